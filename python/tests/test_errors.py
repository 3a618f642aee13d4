"""Every bad input raises TypeError or ValueError naming the problem; none
reaches Rust as a panic."""

import math

import numpy as np
import pytest

import aaglsd

IMG = np.zeros((16, 16), np.uint8)


def raises(exc, match, fn, *args, **kw):
    with pytest.raises(Exception) as info:
        fn(*args, **kw)
    assert type(info.value) is exc, f"{type(info.value).__name__}: {info.value}"
    assert match in str(info.value), str(info.value)


@pytest.mark.parametrize(
    "image, exc, match",
    [
        ([[0, 1], [2, 3]], TypeError, "numpy.ndarray of uint8, got list"),
        (None, TypeError, "got NoneType"),
        (b"\x00" * 16, TypeError, "got bytes"),
        (np.zeros((8, 8), np.float32), TypeError, "dtype uint8, got float32"),
        (np.zeros((8, 8), np.int16), TypeError, "dtype uint8, got int16"),
        (np.zeros((8, 8), np.int8), TypeError, "dtype uint8, got int8"),
        (np.zeros((8, 8), bool), TypeError, "dtype uint8, got bool"),
        (np.zeros((8, 8), np.uint16), TypeError, "dtype uint8, got uint16"),
        (np.zeros(8, np.uint8), ValueError, "2-D (gray) or 3-D (colour), got 1-D"),
        (np.zeros((), np.uint8), ValueError, "got 0-D"),
        (np.zeros((2, 8, 8, 3), np.uint8), ValueError, "got 4-D"),
        (np.zeros((8, 8, 1), np.uint8), ValueError, "3 (RGB or BGR) or 4 (with alpha) channels, got 1"),
        (np.zeros((8, 8, 2), np.uint8), ValueError, "channels, got 2"),
        (np.zeros((8, 8, 5), np.uint8), ValueError, "channels, got 5"),
        (np.zeros((0, 8), np.uint8), ValueError, "image is empty (height 0, width 8)"),
        (np.zeros((8, 0), np.uint8), ValueError, "image is empty (height 8, width 0)"),
        (np.zeros((0, 0, 3), np.uint8), ValueError, "image is empty"),
        (np.zeros((1, 32768), np.uint8), ValueError, "exceeds the limits"),
        (np.broadcast_to(np.uint8(0), (9000, 9000)), ValueError, "9000x9000 exceeds the limits"),
    ],
)
def test_bad_images(image, exc, match):
    raises(exc, match, aaglsd.detect, image)
    raises(exc, match, aaglsd.Detector(16, 16), image)


# (field, a value out of range); every Config field once.
OUT_OF_RANGE = [
    ("magnitude_threshold", 1021.0),
    ("magnitude_threshold", math.nan),
    ("anchor_margin", 1021),
    ("align_tolerance_deg", 90.0),
    ("dist_tolerance_px", 0.0),
    ("skip_min", 0),
    ("skip_regular", 0),
    ("skip_group", 0),
    ("min_length_px", -1.0),
    ("min_groups", 0),
    ("anchor_density", 1.5),
    ("aligned_density", -0.1),
    ("merge_center_px", 65.0),
    ("merge_angle_deg", 0.0),
    ("merge_gap_px", math.inf),
    ("candidates_per_mille", 1001),
    ("max_link_pixels", 15),
    ("extend_max_px", 1025),
    ("bridge_px", 33),
    ("min_score", 16777216),
    ("work_per_mille", 0),
]


def test_every_field_is_covered():
    assert {f for f, _ in OUT_OF_RANGE} | {"merge", "trim", "reseed", "maxima", "work_budget"} == set(
        aaglsd.FIELDS
    )


@pytest.mark.parametrize("field, value", OUT_OF_RANGE, ids=[f"{f}={v}" for f, v in OUT_OF_RANGE])
def test_field_out_of_range_names_the_field(field, value):
    raises(ValueError, f"{field}=", aaglsd.detect, IMG, **{field: value})
    raises(ValueError, f"{field}=", aaglsd.Detector, 16, 16, **{field: value})
    raises(ValueError, f"{field}=", aaglsd.config, **{field: value})
    raises(ValueError, "config field", aaglsd.config, **{field: value})


@pytest.mark.parametrize(
    "field, value, exc, match",
    [
        ("skip_min", 256, ValueError, "config field skip_min out of range: 256"),
        ("skip_min", -1, ValueError, "config field skip_min out of range: -1"),
        ("anchor_margin", 70000, ValueError, "anchor_margin out of range: 70000"),
        ("max_link_pixels", 2**40, ValueError, "max_link_pixels out of range"),
        ("max_link_pixels", 2**70, ValueError, f"max_link_pixels out of range: {2**70}"),
        ("skip_min", 7.0, TypeError, "skip_min must be an int, got float"),
        ("skip_min", True, TypeError, "skip_min must be an int, got bool"),
        ("skip_min", "7", TypeError, "skip_min must be an int, got str"),
        ("min_length_px", "9", TypeError, "min_length_px must be a number, got str"),
        ("min_length_px", None, TypeError, "min_length_px must be a number, got NoneType"),
        ("min_length_px", True, TypeError, "min_length_px must be a number, got bool"),
        ("merge", 1, TypeError, "merge must be a bool, got int"),
        ("merge", "yes", TypeError, "merge must be a bool, got str"),
        ("reseed", 2, TypeError, "reseed must be a str or a bool, got int"),
        ("reseed", "twice", ValueError, 'reseed must be never, once, misfit or always, got "twice"'),
        ("maxima", True, TypeError, "maxima must be a str, got bool"),
        ("maxima", "loose", ValueError, 'maxima must be strict or symmetric, got "loose"'),
        ("min_lenght_px", 9.0, TypeError, "unknown config field 'min_lenght_px'"),
    ],
)
def test_field_types(field, value, exc, match):
    raises(exc, match, aaglsd.detect, IMG, **{field: value})
    raises(exc, match, aaglsd.Detector, 16, 16, **{field: value})


def test_numpy_scalars_are_accepted():
    cfg = aaglsd.config(min_length_px=np.float32(12.5), skip_min=np.int64(3), merge=np.True_)
    assert (cfg["min_length_px"], cfg["skip_min"], cfg["merge"]) == (12.5, 3, True)


def test_reseed_takes_a_name_or_a_bool():
    assert aaglsd.config()["reseed"] == "misfit"
    assert aaglsd.config("official")["reseed"] == "always"
    assert aaglsd.config(reseed="never")["reseed"] == "never"
    assert aaglsd.config(reseed="once")["reseed"] == "once"
    assert aaglsd.config(reseed=True)["reseed"] == "always"
    assert aaglsd.config(reseed=np.False_)["reseed"] == "never"


def test_maxima_takes_a_name():
    assert aaglsd.config()["maxima"] == "symmetric"
    assert aaglsd.config("official")["maxima"] == "strict"
    assert aaglsd.config(maxima="strict")["maxima"] == "strict"
    assert aaglsd.config()["bridge_px"] == 6
    assert aaglsd.config("paper")["bridge_px"] == 0
    assert aaglsd.config()["min_score"] == 150
    assert aaglsd.config()["trim"] is True
    assert aaglsd.config("official")["trim"] is False
    assert aaglsd.config("official")["min_score"] == 0


def test_other_arguments():
    raises(ValueError, "unknown profile 'fast': expected one of default, official, paper",
           aaglsd.detect, IMG, "fast")
    raises(TypeError, "", aaglsd.detect, IMG, 3)
    raises(ValueError, "color must be 'rgb' or 'bgr', got 'BGR'", aaglsd.detect, IMG, color="BGR")
    raises(ValueError, "max_segments must be at least 1", aaglsd.detect, IMG, max_segments=0)
    raises(ValueError, "max_segments out of range: -1", aaglsd.detect, IMG, max_segments=-1)
    raises(TypeError, "max_segments must be an int, got float", aaglsd.detect, IMG, max_segments=2.0)
    raises(ValueError, f"max_segments out of range: {-(2**70)}", aaglsd.detect, IMG, max_segments=-(2**70))
    raises(TypeError, "", aaglsd.detect)
    raises(ValueError, "unknown profile", aaglsd.Detector, 16, 16, "Paper")
    raises(ValueError, "zero dimension (0x16)", aaglsd.Detector, 0, 16)
    raises(ValueError, "zero dimension (16x0)", aaglsd.Detector, 16, 0)
    raises(ValueError, "40000x1 exceeds the limits", aaglsd.Detector, 40000, 1)
    raises(ValueError, "9000x9000 exceeds the limits", aaglsd.Detector, 9000, 9000)
    raises(ValueError, "width out of range: -1", aaglsd.Detector, -1, 16)
    raises(ValueError, f"height out of range: {2**64}", aaglsd.Detector, 16, 2**64)
    raises(TypeError, "width must be an int, got float", aaglsd.Detector, 16.0, 16)
    raises(TypeError, "height must be an int, got str", aaglsd.Detector, 16, "16")
    raises(ValueError, "max_segments must be at least 1", aaglsd.Detector, 16, 16, max_segments=0)


def test_detector_frame_size():
    det = aaglsd.Detector(16, 12)
    raises(ValueError, "frame is 12x16 (width x height); this Detector takes 16x12", det,
           np.zeros((16, 12), np.uint8))
    raises(ValueError, "frame is 17x12 (width x height); this Detector takes 16x12", det,
           np.zeros((12, 17, 3), np.uint8))
    assert det.summary is None
    assert det(np.zeros((12, 16), np.uint8)).shape == (0, 4)
    assert det.summary.segments == 0 and det.summary.candidates == 0
