//! Design §8.1: a strong segment's score, from one trace of its pixels.
//!
//! The score is the gradient contrast integrated along the segment,
//! weighted by how well the segment sits on its edge. Over the Bresenham
//! pixels of the segment inside the image, `c = |g · n|` is the gradient
//! component across the segment (`n` its unit normal); the contrast `C` is
//! the sum of `c` over the pixels whose thresholded magnitude is nonzero,
//! in 2x2 gradient levels × pixels. Such a pixel is *on the ridge* when no
//! pixel 1 or 2 steps away along the minor axis has a larger squared
//! gradient magnitude `gx² + gy²` (not `c`: a comparison that does not
//! depend on the segment's direction, so the float reference, whose
//! endpoints differ from these in the last bits, decides it alike). With `k` such pixels of `n` in the image, the score is
//! `C · (k/n)²`: long, sharp edges score high; short or faint ones, and
//! segments that cut across their edge or lie beside it (a curve, a
//! gradient ramp, a texture), low. Exact in integers: with `d` the
//! segment's Q8 direction, each `c·|d|` is `|gx·dy - gy·dx|` (below 2^35),
//! summed in `u64`, divided by `|d|` (its integer square root) once,
//! rounded, then scaled by `k²/n²`, rounded.

use core::num::NonZeroUsize;

use super::gradient::gradient_at;
use super::output::SegQ8;
use super::raster::Raster;
use crate::params::Params;

/// The score of `seg` (its ends in the `w` x `h` blurred image `blur`'s
/// gradient grid), at most [`SegQ8::MAX_SCORE`]; the pixels traced (work
/// units); and the polarity, the sum of the signed cross terms
/// `gx·dy - gy·dx` over the scored pixels (positive: brighter on the left).
pub(crate) fn score(
    p: &Params,
    blur: &[u8],
    w: NonZeroUsize,
    h: usize,
    seg: &SegQ8,
) -> (u32, usize, i64) {
    let (dx, dy) = (
        i64::from(seg.x1) - i64::from(seg.x0),
        i64::from(seg.y1) - i64::from(seg.y0),
    );
    // Below 2^51: the sides are below 2^25.
    let len = (dx * dx + dy * dy).unsigned_abs().isqrt();
    let (from, to) = seg.pixel_ends();
    // The minor axis: the step to the pixels beside the segment.
    let (sx, sy) = if dy.abs() > dx.abs() { (1, 0) } else { (0, 1) };
    let energy = |(gx, gy): (i32, i32)| gx * gx + gy * gy; // below 2^20
    let beside = |x: i64, y: i64| -> i32 {
        let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else {
            return 0;
        };
        if x >= w.get() || y >= h {
            return 0;
        }
        energy(gradient_at(blur, w.get(), x, y))
    };
    let (mut sum, mut traced, mut inside, mut on) = (0u64, 0usize, 0u64, 0u64);
    let mut polarity = 0i64; // below 2^51: 2^16 terms below 2^35
    for (x, y) in Raster::new(from, to) {
        traced += 1;
        let (Ok(ux), Ok(uy)) = (usize::try_from(x), usize::try_from(y)) else {
            continue;
        };
        if ux >= w.get() || uy >= h {
            continue;
        }
        inside += 1;
        let (gx, gy) = gradient_at(blur, w.get(), ux, uy);
        if gx.unsigned_abs() + gy.unsigned_abs() < u32::from(p.mag_min.max(1)) {
            continue;
        }
        let cross = i64::from(gx) * dy - i64::from(gy) * dx;
        polarity += cross;
        sum += cross.unsigned_abs();
        // Nearest first: most pixels off the ridge fail at one step.
        let e = energy((gx, gy));
        if (1..=2)
            .all(|k| e >= beside(x + k * sx, y + k * sy) && e >= beside(x - k * sx, y - k * sy))
        {
            on += 1;
        }
    }
    let contrast = (sum + len / 2).checked_div(len).unwrap_or(0);
    // Below 2^24 · 2^32: `on` and `inside` are below 2^16.
    let n2 = inside * inside;
    let score = (contrast.min(1 << 24) * on * on + n2 / 2)
        .checked_div(n2)
        .unwrap_or(0);
    (
        score.min(u64::from(SegQ8::MAX_SCORE)) as u32,
        traced,
        polarity,
    )
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
        let (s, n, _) = score(&p, &blur, wnz, h, &along);
        assert_eq!((s, n), (2 * 40 * 20, 20));
        assert_eq!(score(&p, &blur, wnz, h, &along.reversed()).0, s);
        let off = SegQ8::new(q(10), q(5), q(10), q(24));
        assert_eq!(score(&p, &blur, wnz, h, &off).0, 0);
    }

    /// A ramp edge, brightest gradient at column 20: a segment along the
    /// peak keeps its whole contrast; one a pixel beside it has contrast
    /// but no pixel on the ridge and scores 0; one crossing from the peak
    /// to the side is scaled by the square of its share on the ridge.
    #[test]
    fn only_pixels_on_the_ridge_count() {
        let (w, h) = (40, 30);
        let ramp = [50u8, 60, 80, 100, 110];
        let blur: std::vec::Vec<u8> = (0..w * h)
            .map(|i| match i % w {
                x if x < 18 => 50,
                x if x > 22 => 110,
                x => ramp.get(x - 18).copied().unwrap_or(0),
            })
            .collect();
        let p = Params::new(&Config::DEFAULT);
        let wnz = NonZeroUsize::new(w).unwrap_or(NonZeroUsize::MIN);
        let q = |v: i64| v * 256;
        // Gradient across columns 19..=22: 2·(60-50), 2·20, 2·20, 2·10;
        // columns 20 and 21 tie at the peak.
        let peak = SegQ8::new(q(20), q(5), q(20), q(24));
        assert_eq!(score(&p, &blur, wnz, h, &peak).0, 2 * 20 * 20);
        let beside = SegQ8::new(q(22), q(5), q(22), q(24));
        assert_eq!(score(&p, &blur, wnz, h, &beside).0, 0);
        // 10 of its 20 pixels at column 21 (on the ridge), 10 at 22.
        let slanted = SegQ8::new(q(21), q(5), q(22), q(24));
        let (s, n, _) = score(&p, &blur, wnz, h, &slanted);
        assert_eq!(n, 20);
        let c = 10 * 40 + 10 * 20; // the contrast, before the scaling
        assert!(s.abs_diff(c / 4) <= c / 50, "{s} vs {}", c / 4);
    }
}
