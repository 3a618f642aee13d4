"""The wheel's segments equal the Rust CLI's, bit for bit."""

import numpy as np
import pytest

import aaglsd
from conftest import assert_bits_equal, read_pgm, run_cli, shared_images, write_pgm

PROFILES = ["default", "paper"]


@pytest.mark.parametrize("profile", PROFILES)
def test_castle_raw_equals_cli(cli, castle, tmp_path, profile):
    pgm = tmp_path / "castle1.pgm"
    write_pgm(pgm, castle)
    want = run_cli(cli, pgm, profile)
    assert len(want) > 50  # a real scene, not an empty answer
    assert_bits_equal(aaglsd.detect(castle, profile), want)
    det = aaglsd.Detector(320, 240, profile)
    assert_bits_equal(det(castle), want)
    assert det.summary.segments == len(want) and det.summary.is_complete


SHARED = shared_images()


@pytest.mark.skipif(
    not SHARED, reason="!!! ../shared/data/readme-images/gray missing: shared PGMs SKIPPED !!!"
)
@pytest.mark.parametrize("profile", PROFILES)
@pytest.mark.parametrize("pgm", SHARED, ids=[p.name for p in SHARED])
def test_shared_pgms_equal_cli(cli, pgm, profile):
    img = read_pgm(pgm)
    assert_bits_equal(aaglsd.detect(img, profile), run_cli(cli, pgm, profile))


def test_profiles_differ_and_fields_apply(castle):
    default = aaglsd.detect(castle)
    paper = aaglsd.detect(castle, "paper")
    assert len(default) != len(paper)
    # The paper profile is the official one with six fields changed.
    same = aaglsd.detect(
        castle,
        "official",
        min_length_px=9.0,
        min_groups=3,
        anchor_density=0.5,
        aligned_density=0.5,
        maxima="symmetric",
        merge=True,
    )
    assert_bits_equal(same, paper)
    longer = aaglsd.detect(castle, min_length_px=40.0)
    assert 0 < len(longer) < len(default)
    lengths = np.hypot(longer[:, 2] - longer[:, 0], longer[:, 3] - longer[:, 1])
    assert lengths.min() >= 40.0


def test_max_segments_truncates_and_counts(castle):
    full = aaglsd.detect(castle)
    # The ten best by score (test_scores.py checks which), then merged.
    head = aaglsd.detect(castle, max_segments=10)
    assert len(head) == 10
    det = aaglsd.Detector(320, 240, max_segments=10)
    assert_bits_equal(det(castle), head)
    s = det.summary
    # Dropped before merging (which sees only the kept ones): at least as
    # many as the full run's surplus.
    assert (s.segments, s.is_complete) == (10, False)
    assert s.dropped_segments >= len(full) - 10
    # No more segments than pixels can be found: larger capacities are capped.
    assert aaglsd.Detector(16, 8, max_segments=10**15).max_segments == 128
    assert np.array_equal(aaglsd.detect(castle, max_segments=2**62), full)


def test_config_reports_every_field():
    cfg = aaglsd.config("paper", min_length_px=12.5, skip_min=3)
    assert list(cfg) == aaglsd.FIELDS and len(cfg) == 25
    assert (cfg["min_length_px"], cfg["skip_min"], cfg["merge"]) == (12.5, 3, True)
    assert aaglsd.Detector(8, 8, "paper").config == aaglsd.config("paper")
    assert aaglsd.PROFILES == ["default", "official", "paper"]


def test_detect_reuses_its_buffers_across_sizes(castle):
    """detect() keeps its buffers per thread: alternating sizes, profiles and
    a too-large-to-keep image give what fresh Detectors give."""
    rng = np.random.default_rng(9)
    big = np.kron(castle, np.ones((9, 9), np.uint8))[:2100, :2500]  # 5.25 MP: not kept
    big = big // 2 + rng.integers(0, 3, big.shape, dtype=np.uint8)
    small = castle[40:120, 10:200]
    for img, profile in [(castle, "default"), (small, "paper"), (big, "default"),
                         (castle, "paper"), (small, "default"), (castle, "default")]:
        h, w = img.shape
        want = aaglsd.Detector(w, h, profile)(img)
        assert_bits_equal(aaglsd.detect(img, profile), want)
