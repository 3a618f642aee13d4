"""`python -m aaglsd.bench` runs and reports every detector it finds."""

import subprocess
import sys

import pytest

from conftest import write_pgm


def test_bench_runs(castle, tmp_path):
    pgm = tmp_path / "castle1.pgm"
    write_pgm(pgm, castle)
    out = subprocess.run(
        [sys.executable, "-m", "aaglsd.bench", str(pgm), str(pgm), "--runs", "2"],
        check=True, capture_output=True, text=True,
    ).stdout
    assert "2 images (320x240)" in out
    for row in ("| aaglsd.detect |", "| aaglsd Rust core |", "| aaglsd.Detector |",
                "detect overhead over the Rust call", "Detector overhead over the Rust call"):
        assert row in out, out
    try:
        import cv2  # noqa: F401
        has_ximgproc = hasattr(cv2, "ximgproc")
    except ImportError:
        has_ximgproc = False
    if has_ximgproc:
        for row in ("| OpenCV LSD |", "| EDLines (ximgproc) |", "| FastLineDetector (ximgproc) |"):
            assert row in out, out


def test_bench_rejects_bad_arguments(tmp_path):
    bad = tmp_path / "x.pgm"
    bad.write_bytes(b"P6\n1 1\n255\nabc")
    r = subprocess.run([sys.executable, "-m", "aaglsd.bench", str(bad)], capture_output=True, text=True)
    assert r.returncode == 2 and "not an 8-bit binary PGM" in r.stderr
    r = subprocess.run([sys.executable, "-m", "aaglsd.bench", str(bad), "--runs", "0"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--runs must be at least 1" in r.stderr
