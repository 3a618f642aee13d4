#!/usr/bin/env python3
"""OpenCV LSD and EDLines on the man-made scenes, for `cargo run --example manmade`.

Usage: python3 examples/manmade_peers.py DIR

For every DIR/<stem>.pgm, writes DIR/<stem>.lsd.txt and DIR/<stem>.edlines.txt,
one segment `x0 y0 x1 y1` a line, exactly as the detector returns it: the
example, not this script, moves each method to its best frame shift. LSD is
`cv2.createLineSegmentDetector()` with OpenCV's defaults; EDLines is
`cv2.ximgproc.createEdgeDrawing()` with its defaults, `detectEdges` then
`detectLines`: the calls benches/opencv_speed.py times.

EDLines is run in a forked child per image: OpenCV's `detectLines()` overruns
a buffer when one edge chain is longer than 8 (width + height) pixels, as a
chain winding along a checkerboard's squares can be (opencv_contrib issue
3429), and the process dies. An image where the child dies gets an empty
EDLines file: the method gave nothing there.

Prints one JSON line: the OpenCV version, the number of images, and the
images where EDLines crashed. Exit status 3 when cv2 or its ximgproc module
cannot be imported, so that the example can say the peers were skipped
rather than failing.
"""
import json
import os
import sys

try:
    import cv2

    cv2.ximgproc.createEdgeDrawing  # noqa: B018  (contrib present?)
except (ImportError, AttributeError) as err:
    print(f"manmade_peers: OpenCV with ximgproc is not available: {err}", file=sys.stderr)
    sys.exit(3)


def write_segments(path, lines):
    """`lines` (None or N x 1 x 4) as text; repr keeps every float32 exact."""
    rows = [] if lines is None else lines.reshape(-1, 4).tolist()
    with open(path, "w") as f:
        for row in rows:
            f.write(" ".join(repr(v) for v in row) + "\n")


def edlines_apart(ed, img, path):
    """EDLines on `img` into `path` in a child process; False if it died."""
    if not hasattr(os, "fork"):
        ed.detectEdges(img)
        write_segments(path, ed.detectLines())
        return True
    pid = os.fork()
    if pid == 0:
        ed.detectEdges(img)
        write_segments(path, ed.detectLines())
        os._exit(0)
    _, status = os.waitpid(pid, 0)
    if status == 0:
        return True
    write_segments(path, None)
    return False


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    folder = sys.argv[1]
    cv2.setNumThreads(1)
    stems = sorted(n[:-4] for n in os.listdir(folder) if n.endswith(".pgm"))
    lsd = cv2.createLineSegmentDetector()
    ed = cv2.ximgproc.createEdgeDrawing()
    crashed = []
    for stem in stems:
        img = cv2.imread(os.path.join(folder, stem + ".pgm"), cv2.IMREAD_GRAYSCALE)
        if img is None:
            print(f"manmade_peers: cannot read {stem}.pgm", file=sys.stderr)
            return 1
        write_segments(os.path.join(folder, stem + ".lsd.txt"), lsd.detect(img)[0])
        if not edlines_apart(ed, img, os.path.join(folder, stem + ".edlines.txt")):
            crashed.append(stem)
    print(json.dumps({"opencv": cv2.__version__, "images": len(stems), "edlines_crashed": crashed}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
