"""Shared fixtures: the repository's test images and the Rust CLI.

The CLI is the `detect` example of the root crate. `bash .ci/run python`
builds it and passes its path in AAGLSD_CLI; without that, the fixture
builds it with cargo.
"""

import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED_GRAY = ROOT.parent / "shared" / "data" / "readme-images" / "gray"
CASTLE_RAW = ROOT / "testdata" / "castle1_320x240.gray"


def read_pgm(path):
    """An 8-bit binary PGM (P5) as a 2-D uint8 array."""
    data = pathlib.Path(path).read_bytes()
    fields = []
    pos = 0
    while len(fields) < 4:
        while data[pos : pos + 1].isspace():
            pos += 1
        if data[pos : pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end : end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    magic, w, h, maxval = fields[0], int(fields[1]), int(fields[2]), int(fields[3])
    assert magic == b"P5" and maxval == 255, f"{path}: not an 8-bit P5 PGM"
    pos += 1  # the single whitespace after maxval
    return np.frombuffer(data, np.uint8, w * h, pos).reshape(h, w)


def write_pgm(path, img):
    h, w = img.shape
    pathlib.Path(path).write_bytes(b"P5\n%d %d\n255\n" % (w, h) + np.ascontiguousarray(img).tobytes())


@pytest.fixture(scope="session")
def castle():
    """The committed 320x240 gray test image."""
    return np.fromfile(CASTLE_RAW, np.uint8).reshape(240, 320)


def shared_images():
    """The exact gray PGMs beside the repository, or [] (reported as a skip)."""
    return sorted(SHARED_GRAY.glob("*.pgm")) if SHARED_GRAY.is_dir() else []


@pytest.fixture(scope="session")
def cli():
    """Path of the Rust `detect` example."""
    path = os.environ.get("AAGLSD_CLI")
    if not path:
        subprocess.run(
            ["cargo", "build", "--quiet", "--release", "--example", "detect"], cwd=ROOT, check=True
        )
        path = ROOT / "target" / "release" / "examples" / "detect"
    return pathlib.Path(path)


def run_cli(cli, pgm, profile, scores=False):
    """The CLI's segments for a PGM, parsed as float32: its output is Rust's
    shortest round-trip f32 text, so the parse is exact. With ``scores``, its
    ``--scores`` output: the score as a fifth column."""
    args = [str(cli), str(pgm), "--profile", profile] + (["--scores"] if scores else [])
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    rows = [line.split() for line in out.splitlines() if line.strip()]
    return np.array(rows, dtype=np.float32).reshape(-1, 5 if scores else 4)


def assert_bits_equal(got, want):
    """Equal float32 arrays, bit for bit."""
    assert got.dtype == np.float32 and got.shape == want.shape, (got.shape, want.shape)
    assert np.array_equal(got.view(np.uint32), want.view(np.uint32))
