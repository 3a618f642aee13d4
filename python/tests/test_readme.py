"""The README's "From Python" example (tests/readme_snippets.rs checks that
the README block is made of these lines)."""

import pathlib

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_example():
    gray = np.fromfile(ROOT / "testdata/castle1_320x240.gray", np.uint8).reshape(240, 320)
    # --- README: From Python ---
    import aaglsd

    segments = aaglsd.detect(gray, "paper", min_length_px=20.0)  # (N, 4) float32: x0 y0 x1 y1
    detector = aaglsd.Detector(320, 240, "paper", min_length_px=20.0)
    for frame in [gray, gray[::-1]]:  # any 2-D uint8 views, or (h, w, 3) RGB
        segments = detector(frame)  # reuses its buffers: no allocation but the result
        print(len(segments), detector.summary.dropped_segments)
    # --- end ---
    assert segments.dtype == np.float32 and segments.shape[1] == 4 and len(segments) > 10
    assert detector.summary.dropped_segments == 0
    assert np.array_equal(segments, aaglsd.detect(gray[::-1], "paper", min_length_px=20.0))
