//! What the reference can be asked to replicate of the official code, and
//! what it reports of its intermediate stages: test hooks for the agreement
//! tests (exported only with the `_unstable-hooks` feature).

use alloc::vec::Vec;

use crate::Segment;

/// Switches that make the reference reproduce official-code behaviour that
/// the product deliberately changes. Test-only: not part of the API.
#[derive(Clone, Copy, Debug, Default)]
pub struct Quirks {
    /// Replicate the official orientation bug (`gx = 0, gy < 0` → -90°).
    pub orientation_bug: bool,
    /// Leave the output in the gradient grid (the official frame) instead of
    /// shifting it to pixel centres.
    pub official_frame: bool,
}

/// Everything the reference computed, for agreement tests. Not part of the API.
#[derive(Clone, Debug, Default)]
pub struct Trace {
    /// The output segments.
    pub segments: Vec<Segment>,
    /// Aligned anchor groups in id order: `[Jx, Jy, Cx, Cy, Kx, Ky]`.
    pub groups: Vec<[u32; 6]>,
    /// Pixels with nonzero thresholded magnitude.
    pub nonzero: usize,
    /// NMS pixels (before removing group pixels).
    pub nms_pixels: usize,
    /// Sum of the raster indices of the NMS pixels.
    pub nms_index_sum: u64,
    /// NMS pixels that are not in any group.
    pub regular: usize,
    /// Sum of the blurred image.
    pub blur_sum: u64,
    /// Sum of `(raster index + 1) * blurred value`.
    pub blur_wsum: u64,
    /// Weak candidates (segments that failed the group count or ρ2).
    pub weak: usize,
    /// Segments removed by merging.
    pub merged: usize,
}
