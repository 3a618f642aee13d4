"""A Detector reused over 100 frames keeps a constant RSS."""

import os

import numpy as np
import pytest

import aaglsd

PAGE = os.sysconf("SC_PAGE_SIZE")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


@pytest.mark.parametrize("layout", ["direct", "gather", "luma"])
def test_detector_rss_is_constant_over_100_frames(castle, layout):
    frames = {
        "direct": castle,
        "gather": np.asfortranarray(castle),
        "luma": np.stack([castle] * 3, axis=-1),
    }[layout]
    assert aaglsd._input_layout(frames) == layout
    det = aaglsd.Detector(320, 240, "paper")
    per_frame = det(frames).nbytes  # warm-up: the gather buffer is made here, once
    for _ in range(5):
        det(frames)
    before = rss_bytes()
    for _ in range(100):
        seg = det(frames)
    after = rss_bytes()
    allowance = 16 * PAGE  # the allocator's own bookkeeping
    # Leaking only the result array (16 bytes a segment) would exceed it
    # several times over; leaking a workspace (300 KB) far more.
    assert seg.nbytes == per_frame and 100 * per_frame > 4 * allowance
    assert after - before <= allowance, (before, after, per_frame)
