//! Output types: segments and the run summary.

/// A detected line segment, in 0-based pixel-centre coordinates: pixel
/// `(col, row)` is centred at `x = col`, `y = row`.
///
/// **Polarity**: going from `(x0, y0)` to `(x1, y1)`, the brighter side
/// lies on the left as the image is displayed (x to the right, y down): a
/// segment running right has the brighter pixels above it (OpenCV LSD's
/// convention). Inverting the image reverses every segment.
///
/// **Score**: the gradient contrast integrated along the segment, the sum
/// over its pixels of the gradient component across it (2x2 gradient
/// levels × pixels, design §8.1); higher is likelier a true line. An
/// integer, below 2^24.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(C)]
pub struct Segment {
    /// First endpoint, x (column).
    pub x0: f32,
    /// First endpoint, y (row).
    pub y0: f32,
    /// Second endpoint, x (column).
    pub x1: f32,
    /// Second endpoint, y (row).
    pub y1: f32,
    /// The segment's score (see above).
    pub score: f32,
}

impl Segment {
    /// The segment with every coordinate and the score 0: a `const`
    /// initialiser for output arrays (`[Segment::ZERO; N]` in a `static`).
    pub const ZERO: Self = Self {
        x0: 0.0,
        y0: 0.0,
        x1: 0.0,
        y1: 0.0,
        score: 0.0,
    };

    /// Squared length in pixels².
    pub fn length_squared(&self) -> f32 {
        let dx = self.x1 - self.x0;
        let dy = self.y1 - self.y0;
        dx * dx + dy * dy
    }

    /// Length in pixels (`libm::sqrtf`, correctly rounded).
    pub fn length(&self) -> f32 {
        libm::sqrtf(self.length_squared())
    }

    /// The segment with its endpoints swapped (the same score; the
    /// brighter side then on the right).
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self {
            x0: self.x1,
            y0: self.y1,
            x1: self.x0,
            y1: self.y0,
            score: self.score,
        }
    }
}

/// What a [`detect`](crate::detect()) call did, including everything it had to drop.
///
/// `#[non_exhaustive]`: new counters may come in a minor release; read the
/// fields, or start from `Summary::default()`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct Summary {
    /// Segments written to the front of the output slice.
    pub segments: usize,
    /// Segments found but not written because the output slice was full:
    /// the slice keeps the highest-scoring ones (counted as the linking
    /// emits them, before the merging, which sees only the kept ones).
    pub dropped_segments: usize,
    /// Aligned-anchor-group candidates dropped (the weakest first) because
    /// the candidate list was full. Zero in normal operation.
    pub dropped_candidates: usize,
    /// Linkings stopped early because the visited list was full, or that
    /// stopped bridging because their bridge list was
    /// ([`Config::bridge_px`](crate::Config::bridge_px)).
    pub truncated_linkings: usize,
    /// Aligned-anchor-group candidates kept for extraction (pixels passing
    /// the order-independent part of the group test).
    pub candidates: usize,
    /// Aligned anchor groups extracted.
    pub groups: usize,
    /// Segments that merging removed (paper §3.3); 0 when merging is off.
    pub merged: usize,
    /// Work units spent by the linking, validation, extension and merging
    /// (see [`Config::work_per_mille`](crate::Config::work_per_mille)).
    pub work: usize,
    /// Seeds left unlinked and segment pairs left uncompared because the
    /// work limit or budget was reached. Zero on natural images at the
    /// default limit.
    pub work_cut: usize,
}

impl Summary {
    /// True when nothing was dropped or truncated.
    pub const fn is_complete(&self) -> bool {
        self.dropped_segments == 0
            && self.dropped_candidates == 0
            && self.truncated_linkings == 0
            && self.work_cut == 0
    }
}
