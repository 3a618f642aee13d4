"""Milliseconds per image: ``python -m aaglsd.bench IMAGES... [--runs N]``.

Times ``aaglsd.detect`` (a call that sizes its buffers), a reused
``aaglsd.Detector``, and, when ``opencv-contrib-python`` (or its headless
build) is installed, OpenCV's LSD, EdgeDrawing/EDLines and FastLineDetector
on the same gray pixels. Each figure is the median of ``--runs`` calls per
image, then the median over the images. Decoding (cv2, else Pillow, else
binary PGM only) is not timed.

The wrapper's overhead is a call's time over the Rust core's own time
(``Detector._last_detect_ns``, the ``aaglsd::detect`` call on the Detector's
warm workspace): for ``Detector`` the argument checks, the GIL hand-over
and the result array; for ``detect`` also making (and faulting in) the
workspace and output buffers.
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import sys
import time
from typing import Callable, Optional

import numpy as np

import aaglsd

try:  # optional: decoding and the OpenCV detectors
    import cv2
except ImportError:  # pragma: no cover - depends on the environment
    cv2 = None  # type: ignore[assignment]


def read_pgm(path: pathlib.Path) -> np.ndarray:
    """A binary 8-bit PGM (P5) as a 2-D uint8 array."""
    data = path.read_bytes()
    parts = data.split(maxsplit=4)
    if len(parts) < 5 or parts[0] != b"P5" or parts[3] != b"255":
        raise ValueError(f"{path}: not an 8-bit binary PGM (install opencv-python or Pillow)")
    w, h = int(parts[1]), int(parts[2])
    return np.frombuffer(parts[4], np.uint8, w * h).reshape(h, w)


def load_gray(path: pathlib.Path) -> np.ndarray:
    """Decodes an image to 8-bit gray with whatever is installed."""
    if path.suffix.lower() == ".pgm":
        return read_pgm(path)
    if cv2 is not None:
        img = cv2.imread(str(path), cv2.IMREAD_COLOR)
        if img is None:
            raise ValueError(f"{path}: cv2 cannot decode it")
        return cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    try:
        from PIL import Image  # type: ignore[import-not-found, unused-ignore]
    except ImportError:
        raise ValueError(f"{path}: only PGM without opencv-python or Pillow") from None
    rgb = np.asarray(Image.open(path).convert("RGB"))
    return aaglsd_luma(rgb)


def aaglsd_luma(rgb: np.ndarray) -> np.ndarray:
    """OpenCV's BT.601 8-bit luma, as ``aaglsd`` converts colour input.

    >>> aaglsd_luma(np.array([[[255, 0, 0], [0, 255, 0], [0, 0, 255]]], np.uint8)).tolist()
    [[76, 150, 29]]
    """
    r, g, b = (rgb[..., i].astype(np.uint32) for i in range(3))
    return ((9798 * r + 19235 * g + 3735 * b + 16384) >> 15).astype(np.uint8)


def overhead(total_ns: float, core_ns: float) -> float:
    """The wrapper's share over the core's time, in percent.

    >>> overhead(10_500, 10_000)
    5.0
    """
    return 100.0 * (total_ns - core_ns) / core_ns


def opencv_detectors() -> dict[str, Callable[[np.ndarray], int]]:
    """The OpenCV detectors available here, each returning its segment count."""
    if cv2 is None:
        return {}
    found: dict[str, Callable[[np.ndarray], int]] = {}
    if hasattr(cv2, "createLineSegmentDetector"):
        lsd = cv2.createLineSegmentDetector()
        found["OpenCV LSD"] = lambda g: _count(lsd.detect(g)[0])
    xi = getattr(cv2, "ximgproc", None)
    if xi is not None:
        ed = xi.createEdgeDrawing()

        def edlines(g: np.ndarray) -> int:
            ed.detectEdges(g)
            return _count(ed.detectLines())

        found["EDLines (ximgproc)"] = edlines
        fld = xi.createFastLineDetector()
        found["FastLineDetector (ximgproc)"] = lambda g: _count(fld.detect(g))
    return found


def _count(lines: Optional[np.ndarray]) -> int:
    return 0 if lines is None else len(lines)


def time_ns(fn: Callable[[], object], runs: int) -> float:
    """Median wall time of ``fn()`` in ns, after one warm-up call."""
    fn()
    samples = []
    for _ in range(runs):
        t = time.perf_counter_ns()
        fn()
        samples.append(time.perf_counter_ns() - t)
    return statistics.median(samples)


def bench(images: list[np.ndarray], runs: int, profile: str, with_opencv: bool) -> list[dict]:
    """Per image: name -> (median ms, segments), and the overheads in percent."""
    rows = []
    for img in images:
        h, w = img.shape
        row: dict = {"size": f"{w}x{h}"}
        det = aaglsd.Detector(w, h, profile)
        n = len(det(img))
        aaglsd.detect(img, profile)
        # Interleaved, so that a change in the machine's load hits both alike.
        calls, core, detects = [], [], []
        for _ in range(runs):
            t = time.perf_counter_ns()
            det(img)
            calls.append(time.perf_counter_ns() - t)
            core.append(det._last_detect_ns)
            t = time.perf_counter_ns()
            aaglsd.detect(img, profile)
            detects.append(time.perf_counter_ns() - t)
        # The Rust call alone, on the Detector's warm workspace: the baseline.
        row["aaglsd Rust core"] = (statistics.median(core) / 1e6, n)
        row["aaglsd.Detector"] = (statistics.median(calls) / 1e6, n)
        row["aaglsd.detect"] = (statistics.median(detects) / 1e6, n)
        row["Detector overhead %"] = statistics.median(map(overhead, calls, core))
        row["detect overhead %"] = statistics.median(map(overhead, detects, core))
        if with_opencv:
            for name, fn in opencv_detectors().items():
                count = fn(img)
                row[name] = (time_ns(lambda: fn(img), runs) / 1e6, count)
        rows.append(row)
    return rows


def report(rows: list[dict], out=sys.stdout) -> None:
    """Prints the table: median and mean over the images."""
    sizes = sorted({r["size"] for r in rows})
    names = [k for k in rows[0] if isinstance(rows[0][k], tuple)]
    print(f"{len(rows)} images ({', '.join(sizes)}); median of the per-image medians", file=out)
    print("| detector | ms/image (median) | ms/image (mean) | segments/image |", file=out)
    print("|---|---:|---:|---:|", file=out)
    for name in names:
        ms = [r[name][0] for r in rows if name in r]
        segs = [r[name][1] for r in rows if name in r]
        print(
            f"| {name} | {statistics.median(ms):.3f} | {statistics.mean(ms):.3f} "
            f"| {statistics.mean(segs):.1f} |",
            file=out,
        )
    for key in ("Detector overhead %", "detect overhead %"):
        vals = [r[key] for r in rows]
        print(
            f"{key[:-2]} over the Rust call: median {statistics.median(vals):.2f}%, "
            f"max {max(vals):.2f}%",
            file=out,
        )


def main(argv: Optional[list[str]] = None) -> int:
    p = argparse.ArgumentParser(prog="python -m aaglsd.bench", description=__doc__.split("\n")[0])
    p.add_argument("images", nargs="+", type=pathlib.Path, help="image files (PGM, or any cv2/Pillow reads)")
    p.add_argument("--runs", type=int, default=11, help="timed calls per image (default 11)")
    p.add_argument("--profile", default="default", choices=aaglsd.PROFILES)
    p.add_argument("--no-opencv", action="store_true", help="time aaglsd only")
    a = p.parse_args(argv)
    if a.runs < 1:
        p.error("--runs must be at least 1")
    try:
        images = [load_gray(path) for path in a.images]
    except (OSError, ValueError) as e:
        print(f"aaglsd.bench: {e}", file=sys.stderr)
        return 2
    with_opencv = not a.no_opencv
    if with_opencv and not opencv_detectors():
        print("(OpenCV detectors not available: pip install opencv-contrib-python-headless)")
    report(bench(images, a.runs, a.profile, with_opencv))
    return 0


if __name__ == "__main__":
    sys.exit(main())
