"""Strided, cropped and non-contiguous inputs, and colour: each equals the
packed gray copy, and the zero-copy layouts are read in place."""

import numpy as np
import pytest

import aaglsd


def bits(a):
    return a.view(np.uint32)


def same_as_packed(view, **kw):
    """detect(view) == detect(packed copy of view); returns the segments."""
    got = aaglsd.detect(view, **kw)
    want = aaglsd.detect(np.ascontiguousarray(view), **kw)
    assert got.shape == want.shape and np.array_equal(bits(got), bits(want))
    return got


@pytest.fixture(scope="module")
def wide(castle):
    """castle1 inside a wider, taller random frame: views of it have
    neighbours whose bytes must not leak in."""
    rng = np.random.default_rng(7)
    big = rng.integers(0, 256, (300, 400), dtype=np.uint8)
    big[30:270, 40:360] = castle
    return big


@pytest.mark.parametrize(
    "name, make, layout",
    [
        ("c-contiguous", lambda c, w: c, "direct"),
        ("crop", lambda c, w: w[30:270, 40:360], "direct"),
        ("crop of a crop", lambda c, w: w[30:270, 40:360][5:200, 7:300], "direct"),
        ("row step", lambda c, w: c[::2], "direct"),
        ("row step 3 of a crop", lambda c, w: w[30:270:3, 40:360], "direct"),
        ("padded rows", lambda c, w: np.lib.stride_tricks.as_strided(
            w[30:, 40:], shape=(240, 320), strides=(400, 1)), "direct"),
        ("one row", lambda c, w: c[100:101], "direct"),
        ("one column", lambda c, w: c[:, 100:101], "direct"),
        ("column step", lambda c, w: c[:, ::2], "gather"),
        ("both steps", lambda c, w: c[::2, ::2], "gather"),
        ("transpose", lambda c, w: c.T, "gather"),
        ("fortran order", lambda c, w: np.asfortranarray(c), "gather"),
        ("rows reversed", lambda c, w: c[::-1], "gather"),
        ("columns reversed", lambda c, w: c[:, ::-1], "gather"),
        ("broadcast row", lambda c, w: np.broadcast_to(c[120], (240, 320)), "gather"),
        ("crop with column step", lambda c, w: w[30:270, 40:360:2], "gather"),
    ],
)
def test_layouts(castle, wide, name, make, layout):
    view = make(castle, wide)
    assert aaglsd._input_layout(view) == layout, name
    same_as_packed(view)
    same_as_packed(view, profile="paper")


def test_crop_equals_the_original(castle, wide):
    """The crop is read in place at the right offset and stride."""
    crop = wide[30:270, 40:360]
    assert not crop.flags.c_contiguous
    assert np.array_equal(bits(aaglsd.detect(crop)), bits(aaglsd.detect(castle)))


def test_views_of_a_detector_frame(castle, wide):
    """A Detector takes every layout too, and reuses its gather buffer."""
    det = aaglsd.Detector(320, 240)
    want = bits(aaglsd.detect(castle))
    for view in (castle, wide[30:270, 40:360], np.asfortranarray(castle), castle[::-1, ::-1][::-1, ::-1]):
        assert np.array_equal(bits(det(view)), want)


def test_readonly_and_foreign_buffers(castle):
    ro = castle.copy()
    ro.flags.writeable = False
    assert np.array_equal(bits(aaglsd.detect(ro)), bits(aaglsd.detect(castle)))
    buf = np.frombuffer(castle.tobytes(), np.uint8).reshape(240, 320)  # bytes-backed, read-only
    assert np.array_equal(bits(aaglsd.detect(buf)), bits(aaglsd.detect(castle)))


def luma_601(rgb):
    """OpenCV's 8-bit BT.601 luma: (9798 R + 19235 G + 3735 B + 16384) >> 15."""
    r, g, b = (rgb[..., i].astype(np.uint32) for i in range(3))
    return ((9798 * r + 19235 * g + 3735 * b + 16384) >> 15).astype(np.uint8)


@pytest.fixture(scope="module")
def colour(castle):
    """A colour image with distinct channels built from castle1."""
    rng = np.random.default_rng(3)
    noise = rng.integers(0, 40, castle.shape, dtype=np.uint8)
    return np.stack([castle, castle // 2 + noise, 255 - castle], axis=-1)


def test_rgb_bgr_rgba(colour):
    gray = luma_601(colour)
    want = bits(aaglsd.detect(gray))
    assert len(want) > 50
    assert aaglsd._input_layout(colour) == "luma"
    assert np.array_equal(bits(aaglsd.detect(colour)), want)
    assert np.array_equal(bits(aaglsd.detect(colour[..., ::-1], color="bgr")), want)
    rgba = np.concatenate([colour, np.full(colour.shape[:2] + (1,), 17, np.uint8)], axis=-1)
    assert np.array_equal(bits(aaglsd.detect(rgba)), want)
    # Non-packed colour layouts: a channel slice of RGBA, a crop, a transpose.
    assert np.array_equal(bits(aaglsd.detect(rgba[..., :3])), want)
    assert np.array_equal(bits(aaglsd.detect(np.asfortranarray(colour))), want)
    det = aaglsd.Detector(320, 240, color="bgr")
    assert np.array_equal(bits(det(np.ascontiguousarray(colour[..., ::-1]))), want)
    # The weights: pure channels and extremes.
    px = np.array([[[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255], [1, 1, 1]]], np.uint8)
    assert luma_601(px).tolist() == [[76, 150, 29, 255, 1]]


def test_luma_matches_opencv(colour):
    cv2 = pytest.importorskip("cv2", reason="opencv-python not installed: cvtColor check SKIPPED")
    rng = np.random.default_rng(11)
    rand = rng.integers(0, 256, (64, 4096, 3), dtype=np.uint8)  # every channel value, many mixes
    assert np.array_equal(cv2.cvtColor(rand, cv2.COLOR_BGR2GRAY), luma_601(rand[..., ::-1]))
    assert np.array_equal(
        bits(aaglsd.detect(rand)), bits(aaglsd.detect(cv2.cvtColor(rand, cv2.COLOR_RGB2GRAY)))
    )
    bgr = np.ascontiguousarray(colour[..., ::-1])
    gray = cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)
    assert np.array_equal(bits(aaglsd.detect(bgr, color="bgr")), bits(aaglsd.detect(gray)))
