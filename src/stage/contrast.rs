//! Design §8.1: a strong segment's score, from one trace of its pixels.
//!
//! The score is the gradient contrast integrated along the segment: over
//! the Bresenham pixels of the segment inside the image whose thresholded
//! magnitude is nonzero, the sum of `|g · n|`, the gradient component
//! across the segment (`n` its unit normal), in 2x2 gradient levels ×
//! pixels. Long, sharp edges score high; short or faint ones low. Exact in
//! integers: with `d` the segment's Q8 direction, each term is
//! `|gx·dy - gy·dx|` (below 2^35), summed in `i64`, then divided by `|d|`
//! (its integer square root) once, rounded.

use core::num::NonZeroUsize;

use super::gradient::gradient_at;
use super::output::SegQ8;
use super::raster::Raster;
use crate::params::Params;

/// The score of `seg` (its ends in the `w` x `h` blurred image `blur`'s
/// gradient grid), at most [`SegQ8::MAX_SCORE`], and the pixels traced
/// (work units).
pub(crate) fn score(
    p: &Params,
    blur: &[u8],
    w: NonZeroUsize,
    h: usize,
    seg: &SegQ8,
) -> (u32, usize) {
    let (dx, dy) = (
        i64::from(seg.x1) - i64::from(seg.x0),
        i64::from(seg.y1) - i64::from(seg.y0),
    );
    // Below 2^51: the sides are below 2^25.
    let len = (dx * dx + dy * dy).unsigned_abs().isqrt();
    let (from, to) = seg.pixel_ends();
    let (mut sum, mut traced) = (0u64, 0usize);
    for (x, y) in Raster::new(from, to) {
        traced += 1;
        let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else {
            continue;
        };
        if x >= w.get() || y >= h {
            continue;
        }
        let (gx, gy) = gradient_at(blur, w.get(), x, y);
        if gx.unsigned_abs() + gy.unsigned_abs() < u32::from(p.mag_min.max(1)) {
            continue;
        }
        sum += (i64::from(gx) * dy - i64::from(gy) * dx).unsigned_abs();
    }
    let score = (sum + len / 2).checked_div(len).unwrap_or(0);
    (score.min(u64::from(SegQ8::MAX_SCORE)) as u32, traced)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    /// A vertical step edge of contrast `c`: each pixel's gradient across
    /// it is `2c` (the 2x2 mask sums two rows), so a segment along it of
    /// `n` pixels scores `2c·n`; the score does not depend on the
    /// segment's direction, and a segment off the edge scores 0.
    #[test]
    fn a_step_edge_scores_its_contrast_times_its_length() {
        let (w, h) = (40, 30);
        let blur: std::vec::Vec<u8> = (0..w * h)
            .map(|i| if i % w < 20 { 50 } else { 90 })
            .collect();
        let p = Params::new(&Config::DEFAULT);
        let wnz = NonZeroUsize::new(w).unwrap_or(NonZeroUsize::MIN);
        let q = |v: i64| v * 256;
        let along = SegQ8::new(q(20), q(5), q(20), q(24));
        let (s, n) = score(&p, &blur, wnz, h, &along);
        assert_eq!((s, n), (2 * 40 * 20, 20));
        assert_eq!(score(&p, &blur, wnz, h, &along.reversed()).0, s);
        let off = SegQ8::new(q(10), q(5), q(10), q(24));
        assert_eq!(score(&p, &blur, wnz, h, &off).0, 0);
    }
}
