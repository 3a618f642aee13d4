"""The score column (``scores=True``) and the polarity convention: the
brighter side of each segment on its left (x right, y down)."""

import numpy as np
import pytest

import aaglsd
from conftest import assert_bits_equal, run_cli, write_pgm


def rectangle(inside=40, outside=200):
    """The README's scene: a 32 x 24 rectangle on a 64 x 48 image."""
    img = np.full((48, 64), outside, np.uint8)
    img[12:36, 16:48] = inside
    return img


def sides(segments, img, at=3.0):
    """The pixels ``at`` px to the left and to the right of each segment's
    middle, left as the image is displayed (x right, y down)."""
    x0, y0, x1, y1 = segments[:, :4].T.astype(np.float64)
    length = np.hypot(x1 - x0, y1 - y0)
    lx, ly = (y1 - y0) / length, -(x1 - x0) / length
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2
    pick = lambda x, y: img[np.rint(y).astype(int), np.rint(x).astype(int)]
    return pick(mx + at * lx, my + at * ly), pick(mx - at * lx, my - at * ly)


def reversed_in(s, segments, tol):
    """Whether ``s`` lies along one of ``segments`` reversed: pointing the
    other way, its middle within ``tol`` px of that segment's line and
    between its ends."""
    s = s[:4].astype(np.float64)
    t = segments[:, :4].astype(np.float64)
    mid = (s[:2] + s[2:]) / 2
    d = t[:, 2:] - t[:, :2]
    length = np.hypot(*d.T)
    rel = mid - t[:, :2]
    along = (rel * d).sum(axis=1) / length
    across = np.abs(rel[:, 0] * d[:, 1] - rel[:, 1] * d[:, 0]) / length
    on = (across <= tol) & (along >= 0) & (along <= length)
    return bool(np.any(on & (d @ (s[2:] - s[:2]) < 0)))


@pytest.mark.parametrize("profile", ["default", "paper"])
def test_scores_equal_the_cli_and_the_plain_columns(cli, castle, tmp_path, profile):
    pgm = tmp_path / "castle1.pgm"
    write_pgm(pgm, castle)
    want = run_cli(cli, pgm, profile, scores=True)
    assert want.shape[1] == 5 and len(want) > 50
    got = aaglsd.detect(castle, profile, scores=True)
    assert_bits_equal(got, want)
    # The first four columns are what scores=False returns.
    plain = aaglsd.detect(castle, profile)
    assert plain.shape == (len(got), 4)
    assert_bits_equal(np.ascontiguousarray(got[:, :4]), plain)
    det = aaglsd.Detector(320, 240, profile, scores=True)
    assert det.scores and "scores=True" in repr(det)
    assert_bits_equal(det(castle), want)
    assert not aaglsd.Detector(320, 240, profile).scores
    # Integers below 2**24, most positive (a segment with no pixel aligned
    # within T_aligned/2 scores 0), and not all the same.
    score = got[:, 4]
    assert np.all(score >= 0) and np.all(score < 2**24) and np.all(score == np.floor(score))
    assert 2 * np.count_nonzero(score) > len(score)
    assert score.max() > 4 * score.min()


def test_scores_follow_contrast():
    """The same rectangle at a quarter of the contrast scores lower."""
    strong = aaglsd.detect(rectangle(40, 200), scores=True)
    weak = aaglsd.detect(rectangle(100, 140), scores=True)
    assert len(strong) == len(weak) == 4
    assert weak[:, 4].max() < strong[:, 4].min() / 2


@pytest.mark.parametrize("profile", ["default", "official", "paper"])
def test_the_brighter_side_is_on_the_left(profile):
    img = rectangle()
    seg = aaglsd.detect(img, profile, scores=True)
    assert len(seg) == 4
    left, right = sides(seg, img)
    assert np.all(left == 200) and np.all(right == 40), seg
    # The inverted image: each side reversed, still with the brighter side
    # on the left. Exactly, scores included, where the maxima are symmetric;
    # the official profile's strict maxima pick the other pixel of an edge
    # between two, so its sides move by one.
    inv_img = 255 - img
    inv = aaglsd.detect(inv_img, profile, scores=True)
    assert len(inv) == 4
    left, right = sides(inv, inv_img)
    assert np.all(left == 215) and np.all(right == 55)
    assert all(reversed_in(s, seg, tol=1.0) for s in inv), (seg, inv)
    if profile != "official":
        flip = seg[:, [2, 3, 0, 1, 4]]
        assert sorted(map(tuple, inv.tolist())) == sorted(map(tuple, flip.tolist()))


def test_an_inverted_photo_reverses_its_segments(castle):
    seg = aaglsd.detect(castle, "official")
    inv = aaglsd.detect(255 - castle, "official")
    assert abs(len(inv) - len(seg)) <= len(seg) // 20
    matched = sum(reversed_in(s, seg, tol=1.0) for s in inv)
    assert matched >= 0.9 * len(inv), f"{matched} of {len(inv)} reversed"
    # None keeps its direction: no segment of the photo runs along the
    # same line the same way in the inverted one.
    same_way = sum(reversed_in(s, inv, tol=0.5) for s in seg[:, [2, 3, 0, 1]])
    assert same_way <= len(seg) // 50, f"{same_way} of {len(seg)} kept their direction"


def test_a_short_output_keeps_the_best_scores(castle):
    # The official profile does not merge: the kept are the best of all.
    full = aaglsd.detect(castle, "official", scores=True)
    det = aaglsd.Detector(320, 240, "official", max_segments=10, scores=True)
    best = det(castle)
    assert len(best) == 10 and det.summary.dropped_segments == len(full) - 10
    rows = {tuple(r) for r in full.view(np.uint32)}
    assert all(tuple(r) in rows for r in best.view(np.uint32)), "segments of the full run"
    assert np.all(np.diff(best[:, 4]) <= 0), "best first"
    assert best[-1, 4] >= np.sort(full[:, 4])[-11], "none left out scores higher"
    assert_bits_equal(aaglsd.detect(castle, "official", max_segments=10, scores=True), best)


@pytest.mark.parametrize("value", [1, 0, None, "yes", 1.0, np.int64(1), [True]])
def test_scores_must_be_a_bool(value):
    img = rectangle()
    name = type(value).__name__
    for call in (lambda: aaglsd.detect(img, scores=value),
                 lambda: aaglsd.Detector(64, 48, scores=value)):
        with pytest.raises(TypeError) as info:
            call()
        assert str(info.value) == f"scores must be a bool, got {name}"


def test_numpy_bools_are_accepted():
    img = rectangle()
    assert aaglsd.detect(img, scores=np.True_).shape == (4, 5)
    assert aaglsd.detect(img, scores=np.False_).shape == (4, 4)
    assert aaglsd.Detector(64, 48, scores=np.True_)(img).shape == (4, 5)
    assert aaglsd.Detector(64, 48)(np.zeros((48, 64), np.uint8)).shape == (0, 4)
    assert aaglsd.Detector(64, 48, scores=True)(np.zeros((48, 64), np.uint8)).shape == (0, 5)
