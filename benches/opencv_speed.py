#!/usr/bin/env python3
"""OpenCV LSD and EdgeDrawing/EDLines timing for `cargo bench --bench speed`.

Usage: python3 benches/opencv_speed.py DIR [MAX_IMAGES] [REPS] [--serve]

Decodes the JPEG/PNG/PGM files of DIR (sorted by name, the first MAX_IMAGES
if > 0) to 8-bit gray with cv2.imread first (not timed), then times,
single-threaded (cv2.setNumThreads(1)), per image: `lsd.detect(img)` and
`ed.detectEdges(img); ed.detectLines()`, each with one warm-up call then
REPS (default 7) timed calls (time.perf_counter), keeping the median.

Standalone, it times every image and prints one JSON object on stdout with
the median over images per method. With --serve (used by the Rust bench so
that the Rust and OpenCV timings of each image are interleaved), it prints
one JSON line `{"ready": ...}` after decoding, then answers each image index
read from stdin with one JSON line of that image's medians. Diagnostics go
to stderr.
"""
import json
import os
import statistics
import sys
import time

import cv2


def load(folder, max_images):
    names = sorted(
        n for n in os.listdir(folder)
        if n.lower().endswith((".jpg", ".jpeg", ".png", ".pgm"))
    )
    if max_images > 0:
        names = names[:max_images]
    images = []
    for n in names:
        img = cv2.imread(os.path.join(folder, n), cv2.IMREAD_GRAYSCALE)
        if img is None:
            raise SystemExit(f"cannot decode {n}")
        images.append(img)
    return images


def main():
    args = [a for a in sys.argv[1:] if a != "--serve"]
    serve = len(args) != len(sys.argv) - 1
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    folder = args[0]
    max_images = int(args[1]) if len(args) > 1 else 0
    reps = max(1, int(args[2])) if len(args) > 2 else 7
    cv2.setNumThreads(1)
    images = load(folder, max_images)

    lsd = cv2.createLineSegmentDetector()
    ed = cv2.ximgproc.createEdgeDrawing()

    def run_lsd(img):
        lines = lsd.detect(img)[0]
        return 0 if lines is None else len(lines)

    def run_edlines(img):
        ed.detectEdges(img)
        lines = ed.detectLines()
        return 0 if lines is None else len(lines)

    methods = (("lsd", run_lsd), ("edlines", run_edlines))

    def time_image(img):
        """{method: (median ms, segments)} for one image."""
        res = {}
        for name, fn in methods:
            n = fn(img)  # warm-up
            times = []
            for _ in range(reps):
                t0 = time.perf_counter()
                fn(img)
                times.append(time.perf_counter() - t0)
            res[name] = (statistics.median(times) * 1e3, n)
        return res

    header = {
        "opencv": cv2.__version__,
        "threads": cv2.getNumThreads(),
        "images": len(images),
        "reps": reps,
    }
    if serve:
        print(json.dumps({"ready": True, **header}), flush=True)
        for line in sys.stdin:
            line = line.strip()
            if not line:
                continue
            i = int(line)
            r = time_image(images[i])
            out = {"i": i}
            for name, (ms, n) in r.items():
                out[f"{name}_ms"] = ms
                out[f"{name}_segments"] = n
            print(json.dumps(out), flush=True)
        return 0

    per = [time_image(img) for img in images]
    result = dict(header)
    for name, _ in methods:
        result[f"{name}_ms"] = statistics.median(p[name][0] for p in per) if per else None
        result[f"{name}_segments"] = sum(p[name][1] for p in per)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
