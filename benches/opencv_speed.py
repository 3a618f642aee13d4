#!/usr/bin/env python3
"""OpenCV LSD and EdgeDrawing/EDLines (and ELSED) timing for `cargo bench --bench speed`.

Usage: python3 benches/opencv_speed.py DIR [MAX_IMAGES] [REPS] [--serve]

Decodes the JPEG/PNG/PGM files of DIR (sorted by name, the first MAX_IMAGES
if > 0) to 8-bit gray with cv2.imread first (not timed), then times,
single-threaded (cv2.setNumThreads(1)), per image: `lsd.detect(img)` and
`ed.detectEdges(img); ed.detectLines()`, each with one warm-up call then
REPS (default 7) timed calls (time.perf_counter), keeping the median.

ELSED (Suarez et al. 2022) is timed the same way, as `pyelsed.detect(img)`
with its default parameters, when its Python module `pyelsed` can be
imported (AAGLSD_BENCH_ELSED_PY=DIR puts DIR first on the module path);
the OpenCV it links (not cv2's) is set to one thread too. Otherwise one
line on stderr says so and nothing else changes.

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


def load_elsed():
    """(pyelsed, header fields) if ELSED's Python module imports, else None.

    pyelsed links a system OpenCV of its own, whose thread count
    cv2.setNumThreads does not reach: find its core library among the
    process's mappings and set it to one thread (threads None if not found).
    """
    extra = os.environ.get("AAGLSD_BENCH_ELSED_PY")
    if extra:
        sys.path.insert(0, extra)
    try:
        import pyelsed
    except ImportError as e:
        print(f"opencv_speed.py: no ELSED row ({e})", file=sys.stderr)
        return None
    version, threads = "?", None
    try:
        import ctypes
        with open("/proc/self/maps") as f:
            libs = sorted({l.split()[-1] for l in f if "/libopencv_core.so" in l})
        for path in libs:
            core = ctypes.CDLL(path)
            core._ZN2cv13setNumThreadsEi(1)
            threads = max(threads or 0, core._ZN2cv13getNumThreadsEv())
            version = path.rsplit(".so.", 1)[-1]
    except (OSError, AttributeError) as e:
        print(f"opencv_speed.py: ELSED's OpenCV threads not set ({e})", file=sys.stderr)
    return pyelsed, {"elsed_opencv": version, "elsed_threads": threads}


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

    methods = [("lsd", run_lsd), ("edlines", run_edlines)]

    elsed = load_elsed()
    if elsed is not None:
        pyelsed = elsed[0]

        def run_elsed(img):
            return len(pyelsed.detect(img)[0])

        methods.append(("elsed", run_elsed))

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
        **(elsed[1] if elsed is not None else {}),
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
