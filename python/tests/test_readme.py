"""The README's "From Python" example: tests/readme_snippets.rs checks that
the README block is made of these lines, in order."""

import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_example(monkeypatch, capsys):
    pytest.importorskip("cv2", reason="opencv-python not installed: README example SKIPPED")
    monkeypatch.chdir(ROOT)
    # --- README: From Python ---
    import aaglsd, cv2, numpy as np

    gray = np.fromfile("testdata/castle1_320x240.gray", np.uint8).reshape(240, 320)
    segments = aaglsd.detect(gray, "paper", min_length_px=20.0)  # (N, 4) float32: x0 y0 x1 y1
    bgr = cv2.imread("testdata/castle1.png")  # OpenCV's BGR order
    from_bgr = aaglsd.detect(bgr, color="bgr")  # gray as cv2.cvtColor(bgr, COLOR_BGR2GRAY)

    detector = aaglsd.Detector(320, 240, "paper", min_length_px=20.0)  # keeps its buffers
    for frame in [gray, gray[::-1], gray[:, ::-1]]:  # any 2-D uint8 layout, or (h, w, 3)
        segments = detector(frame)  # allocates only the returned array
        print(len(segments), detector.summary.dropped_segments)
    scored = aaglsd.detect(gray, scores=True)  # (N, 5): x0 y0 x1 y1 score
    # --- end ---
    assert scored.shape[1] == 5 and np.array_equal(scored[:, :4], aaglsd.detect(gray))
    assert segments.dtype == np.float32 and segments.shape[1] == 4 and len(segments) > 10
    assert np.array_equal(segments, aaglsd.detect(gray[:, ::-1], "paper", min_length_px=20.0))
    assert detector.summary.dropped_segments == 0
    png_gray = cv2.imread("testdata/castle1.png", cv2.IMREAD_GRAYSCALE)
    assert len(from_bgr) > 100 and np.array_equal(from_bgr, aaglsd.detect(png_gray))
    assert len(capsys.readouterr().out.splitlines()) == 3
