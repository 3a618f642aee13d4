//! Endpoint extension (design §8; not in the paper or the authors' code).
//!
//! The walk ends a segment at its last anchor, and the endpoints are that
//! anchor projected onto the line: short of where the edge ends, by a few
//! pixels at each end on natural images. Here each end of a strong segment
//! moves on along its line, one pixel of the major axis at a time, while the
//! pixel under the line has a nonzero (thresholded) magnitude and a gradient
//! aligned with the segment normal (the aligned-density test of
//! [`super::validate`]) and of the segment's polarity (brighter on its
//! left), for at most `Config::extend_max_px` pixels. The
//! endpoints stay on the line: only their position along it changes.
//!
//! Coordinates are Q8 in the gradient grid, as everywhere after the walk;
//! the minor coordinate at a major step is an exact rational, rounded to Q8
//! (half away from zero), then to the pixel.

use core::num::NonZeroUsize;

use super::gradient::{gradient_at, magnitude_at};
use super::output::SegQ8;
use super::validate::NormalTest;
use crate::num::q8::{div_round, round_q8};
use crate::params::Params;

/// The strong segment `seg` (endpoints on the major axis `steep` chose:
/// integral `y` when steep, integral `x` otherwise) with both ends extended
/// over the `w` x `h` blurred image `blur`, and the number of pixels tested.
pub(crate) fn extend(
    p: &Params,
    blur: &[u8],
    w: NonZeroUsize,
    h: usize,
    steep: bool,
    seg: SegQ8,
) -> (SegQ8, usize) {
    let max = i64::from(p.extend_max);
    let (x0, y0, x1, y1) = (
        i64::from(seg.x0),
        i64::from(seg.y0),
        i64::from(seg.x1),
        i64::from(seg.y1),
    );
    let (dx, dy) = (x1 - x0, y1 - y0);
    let (d_major, d_minor) = if steep { (dy, dx) } else { (dx, dy) };
    if max == 0 || d_major == 0 {
        return (seg, 0);
    }
    let normal = NormalTest::new(p, dx, dy);
    // Aligned with the normal, and of the segment's polarity: brighter on
    // the left of (dx, dy) (design §8.1).
    let supported = |x: i64, y: i64| -> bool {
        let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else {
            return false;
        };
        if x >= w.get() || y >= h || magnitude_at(blur, w.get(), x, y, p.mag_min) == 0 {
            return false;
        }
        let g = gradient_at(blur, w.get(), x, y);
        normal.aligned(g) && i64::from(g.0) * dy - i64::from(g.1) * dx > 0
    };
    // The point `steps` pixels of the major axis beyond the end at
    // (major, minor), in direction `sign`, as (major, minor) in Q8.
    let beyond = |(major, minor): (i64, i64), sign: i64, steps: i64| {
        let dm = sign * steps * 256;
        (
            major + dm,
            minor + div_round(dm * d_minor, d_major).unwrap_or(0),
        )
    };
    // (x, y) <-> (major, minor): a swap when steep, its own inverse.
    let axes = |(a, b): (i64, i64)| if steep { (b, a) } else { (a, b) };
    let forward = d_major.signum();
    // The first end lies behind the segment's direction, the second ahead.
    let mut ends = [((x0, y0), -forward), ((x1, y1), forward)];
    let mut tested = 0;
    for (end, sign) in &mut ends {
        let sign = *sign;
        let start = axes(*end);
        // The last supported point (none yet: the end itself, `beyond` at
        // 0 steps), so that each step computes one point.
        let mut last = *end;
        let mut steps = 0;
        while steps < max {
            tested += 1;
            let (x, y) = axes(beyond(start, sign, steps + 1));
            if !supported(round_q8(x), round_q8(y)) {
                break;
            }
            last = (x, y);
            steps += 1;
        }
        *end = last;
    }
    let [((x0, y0), _), ((x1, y1), _)] = ends;
    (SegQ8::new(x0, y0, x1, y1), tested)
}
