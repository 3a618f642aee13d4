//! The tie rules of [`Maxima::Symmetric`](crate::Maxima) (design §4) in
//! the group test: a centre equal to a neighbour across the edge, and a
//! side whose neighbours are all zero (the inside of a thin line).

use super::aligned;
use crate::params::Params;
use crate::stage::nms::{Neighbourhood, OUTSIDE, at};

/// Under [`Maxima::Symmetric`](crate::Maxima) (design §4), for a side of
/// the centre (magnitude `mc`, gradient `gc`) whose neighbours are all zero
/// and whose middle neighbour's gradient is exactly zero: whether the pixel
/// beyond that neighbour, of gradient `beyond`, is the other edge of a thin
/// line (opposite to the centre's within T_aligned, at least half its
/// magnitude). Then the side counts as 0.
// Inlined for speed; one copy in a build for size (flash).
#[cfg_attr(not(aaglsd_small), inline(always))]
#[cfg_attr(aaglsd_small, inline(never))]
pub(super) fn thin_line_inside(
    p: &Params,
    mc: u16,
    gc: (i32, i32),
    beyond: Option<(i32, i32)>,
) -> bool {
    // Beyond the image: a zero gradient, which is never a line's edge.
    let g = beyond.unwrap_or((0, 0));
    let mf = g.0.unsigned_abs() + g.1.unsigned_abs();
    let dot = i64::from(gc.0) * i64::from(g.0) + i64::from(gc.1) * i64::from(g.1);
    dot < 0 && mf >= u32::from(p.mag_min) && 2 * mf >= u32::from(mc) && aligned(p, gc, g)
}

/// Under [`Maxima::Symmetric`](crate::Maxima) (design §4): whether the
/// centre (magnitude `mc`) wins against each neighbour across the edge
/// (`across`, up to the first outside the image) that equals it. Of two
/// equal pixels C and C + e, the one nearer the peak of the profile
/// m(C - e), m, m, m(C + 2e) is the maximum: C when m(C - e) > m(C + 2e),
/// the one on side A (left or upper) when the two are equal. A plateau on
/// a rising slope has no maximum. `far` is [`candidate_with`](super::candidate_with)'s.
// Inlined for speed (ties are frequent at low magnitudes); one copy in a
// build for size (flash), through `dyn`.
#[cfg_attr(not(aaglsd_small), inline(always))]
#[cfg_attr(aaglsd_small, inline(never))]
pub(super) fn wins_ties(
    p: &Params,
    mc: u16,
    across: [u8; 6],
    nb: &Neighbourhood,
    far: &dyn Fn(usize) -> Option<(i32, i32)>,
) -> bool {
    let mag = |g: Option<(i32, i32)>| {
        let m = g.map_or(0, |(x, y)| x.unsigned_abs() + y.unsigned_abs());
        if m < u32::from(p.mag_min) { 0 } else { m }
    };
    for (i, &k) in across.iter().enumerate() {
        let mq = at(nb, k);
        if mq == OUTSIDE {
            break;
        }
        if mq != mc {
            continue;
        }
        let near = at(nb, 8 - k);
        let near = u32::from(if near == OUTSIDE { 0 } else { near });
        let far = mag(far(usize::from(k)));
        let nearer = if i < 3 { near > far } else { near >= far };
        if !nearer || far >= u32::from(mc) {
            return false;
        }
    }
    true
}
