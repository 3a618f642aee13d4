"""AAGLSD line segment detector (Li & Shu, PRCV 2025): the fixed-point Rust
core of the ``aaglsd`` crate, bit for bit the segments its firmware build
finds.

>>> import numpy as np, aaglsd
>>> img = np.full((48, 64), 200, np.uint8)
>>> img[12:36, 16:48] = 40
>>> aaglsd.detect(img).shape
(4, 4)

``detect(image)`` for one image, ``Detector(width, height)`` for video
(it keeps its buffers across frames). Segments are ``float32`` rows
``x0 y0 x1 y1`` in 0-based pixel-centre coordinates, the brighter side on
the left of each (x right, y down); ``scores=True`` adds a fifth column, the
score (the gradient contrast summed along the segment). See the docstrings of
``detect`` and ``Detector`` for the input layouts that are read in place and
the ones that are copied once.
"""

from ._aaglsd import (
    FIELDS,
    PROFILES,
    Detector,
    Summary,
    __version__,
    _input_layout,
    config,
    detect,
)

__all__ = ["Detector", "FIELDS", "PROFILES", "Summary", "config", "detect", "__version__"]
