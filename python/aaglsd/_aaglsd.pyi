"""Type stubs of the ``aaglsd._aaglsd`` extension module (re-exported by ``aaglsd``).

Input layouts (``image`` of ``detect``, ``frame`` of ``Detector.__call__``):

- read in place, no copy: a 2-D ``uint8`` array whose column stride is 1 and
  whose row stride is at least its width: C-contiguous arrays, crops
  (``img[10:200, 30:300]``), row steps (``img[::2]``), padded rows;
- gathered once into a packed buffer (kept by a ``Detector``, and by
  ``detect`` for its thread's next call): every other 2-D layout, i.e. column steps
  (``img[::2, ::2]``), transposes and Fortran order, negative strides
  (``img[::-1]``), broadcast rows;
- converted to gray into that buffer: 3-D ``uint8`` arrays of shape
  ``(height, width, 3)`` or ``(height, width, 4)`` (the 4th channel, alpha, is
  ignored) in ``color`` order, ``"rgb"`` (numpy, PIL) or ``"bgr"`` (OpenCV), with
  OpenCV's BT.601 integer luma, ``Y = (9798 R + 19235 G + 3735 B + 16384) >> 15``,
  the value ``cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)`` gives (checked against
  OpenCV 4.14 and 5.0). Gray pixels (R = G = B) keep their value.

Output: a ``(N, 4)`` ``float32`` array of ``x0 y0 x1 y1`` rows in 0-based
pixel-centre coordinates, or with ``scores=True`` a ``(N, 5)`` one whose fifth
column is the score: the gradient contrast summed along the segment, an
integer below 2**24 (exact in ``float32``), higher for likelier true lines.
Polarity: going from ``(x0, y0)`` to ``(x1, y1)``, the brighter side lies on
the left as the image is displayed (x right, y down); inverting the image
reverses every segment. When the image holds more than ``max_segments``, the
highest-scoring ones are returned, best first.

Anything else raises ``TypeError`` (not a numpy array, dtype other than
``uint8``, an unknown keyword, a keyword of the wrong type, ``scores`` not a
bool) or ``ValueError``
(other shapes, an empty or too large image, an unknown profile or colour order, a
``Config`` field out of range: the message names the field). The GIL is
released while the pixels are gathered and the segments detected; do not
write to the input array from another thread meanwhile.

Keyword fields (``FIELDS``; Rust ``aaglsd::Config``, whose docs give each
meaning) and their ranges: ``magnitude_threshold`` 0..1020,
``anchor_margin`` int 0..1020, ``align_tolerance_deg`` (0, 90),
``dist_tolerance_px`` (0, 64], ``skip_min``, ``skip_regular``, ``skip_group``
int 1..255, ``min_length_px`` 0..65536, ``min_groups`` int 1..255,
``anchor_density`` 0..1, ``aligned_density`` 0..1, ``min_score`` int 0..16777215,
``maxima`` ``"strict"`` or ``"symmetric"``, ``bridge_px`` int 0..32, ``reseed`` ``"never"``,
``"once"``, ``"misfit"`` or ``"always"`` (a bool: never or always), ``merge`` bool,
``trim`` bool, ``merge_center_px`` (0, 64], ``merge_angle_deg`` (0, 90), ``merge_gap_px``
0..4096, ``candidates_per_mille`` int 1..1000, ``max_link_pixels`` int
16..65535, ``extend_max_px`` int 0..1024, ``work_per_mille`` int 1..100000,
``work_budget`` int (0: none). Floats are rounded to ``float32``, as the Rust fields hold them.
"""

from typing import Any, Final, Literal, Optional, Union, final

import numpy as np
import numpy.typing as npt

__all__ = ["detect", "config", "_input_layout", "Detector", "Summary", "PROFILES", "FIELDS", "__version__"]

__version__: Final[str]
PROFILES: Final[list[str]]
"""``["default", "official", "paper"]``."""
FIELDS: Final[list[str]]
"""The ``Config`` field names, accepted as keyword arguments."""

# Plain str: other values raise ValueError at run time, naming the choices.
_Profile = str  # "default", "official" or "paper"
_Color = str  # "rgb" or "bgr"
_Field = Union[float, int, bool, str]

def detect(
    image: npt.NDArray[np.uint8],
    profile: _Profile = "default",
    *,
    color: _Color = "rgb",
    max_segments: Optional[int] = None,
    scores: bool = False,
    **fields: _Field,
) -> npt.NDArray[np.float32]:
    """Detects line segments; returns a ``(N, 4)`` float32 array of
    ``x0 y0 x1 y1`` rows in 0-based pixel-centre coordinates, the brighter
    side on the left of each; with ``scores=True`` a ``(N, 5)`` one, the
    score in the fifth column.

    At most ``max_segments`` are returned (default: one per 16 pixels, at
    least 64, as the Rust ``detect`` example has; larger values are capped at
    one per pixel, more than any image has): the highest-scoring ones, best
    first, when there are more. ``Summary.dropped_segments`` of a
    ``Detector`` counts the ones that did not fit. The buffers of
    images up to about 4 megapixels (16 MiB) are kept for the calling
    thread's next call, so a loop of ``detect`` calls makes none.

    >>> import numpy as np, aaglsd
    >>> img = np.full((48, 64), 200, np.uint8)
    >>> img[12:36, 16:48] = 40
    >>> aaglsd.detect(img).shape
    (4, 4)
    >>> aaglsd.detect(img, scores=True).shape
    (4, 5)
    """

def config(profile: _Profile = "default", **fields: _Field) -> dict[str, Any]:
    """The validated configuration: every field of the profile, with the
    keyword overrides applied."""

@final
class Summary:
    """What a detection did, including everything it had to drop."""

    segments: int
    dropped_segments: int
    dropped_candidates: int
    truncated_linkings: int
    candidates: int
    groups: int
    merged: int
    work: int
    work_cut: int
    @property
    def is_complete(self) -> bool:
        """True when nothing was dropped, truncated or cut by the work limit."""

@final
class Detector:
    """A detector for frames of one size: keeps its workspace, output and
    gather buffers, so a call allocates only the returned array. One call at
    a time: a concurrent call from another thread raises ``RuntimeError``."""

    def __new__(
        cls,
        width: int,
        height: int,
        profile: _Profile = "default",
        *,
        color: _Color = "rgb",
        max_segments: Optional[int] = None,
        scores: bool = False,
        **fields: _Field,
    ) -> Detector: ...
    def __call__(self, frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float32]:
        """Segments of ``frame`` (``height x width``, gray or colour, any layout),
        ``(N, 4)``, or ``(N, 5)`` with the score when made with ``scores=True``;
        a frame of another size raises ``ValueError``."""
    @property
    def summary(self) -> Optional[Summary]:
        """The ``Summary`` of the last successful call (``None`` before one)."""
    @property
    def _last_detect_ns(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def color(self) -> _Color: ...
    @property
    def scores(self) -> bool:
        """Whether each call returns the score column."""
    @property
    def max_segments(self) -> int: ...
    @property
    def workspace_bytes(self) -> int: ...
    @property
    def config(self) -> dict[str, Any]: ...

def _input_layout(image: npt.NDArray[np.uint8]) -> Literal["direct", "gather", "luma"]:
    """How ``image`` reaches the core: read in place, gathered, or converted from colour."""
