//! Paper §3.3, eqs. 6-7: merging duplicate and collinear fragments, in
//! integers (the authors' released code has no merging; this follows the
//! paper, with the reading documented in [`crate::reference`]).
//!
//! Two segments merge when the angle between them is at most D_a, the larger
//! perpendicular centre distance is at most D_c, and they overlap along the
//! first one's axis or (eq. 7) their closest endpoints are at most D_e
//! apart. The merged segment is the orthogonal least-squares line through
//! the Bresenham pixels of both, cut at the projections of its two extreme
//! pixels; it replaces the first segment and the second is removed. A sweep
//! visits each pair `(i, j > i)` once in order; sweeps repeat until one
//! merges nothing, so no mergeable pair remains.
//!
//! Segment coordinates are Q8 (`i64`, below 2^24 in magnitude). The tests
//! square both sides of each inequality in `i128`; the angle test first
//! shifts both direction vectors below 2^20 (a relative direction error
//! under 2^-19, far below the 5° threshold's sensitivity).

use super::fit::Fit;
use super::output::SegQ8;
use super::raster::Raster;
use crate::Segment;
use crate::num::q8::round_q8;
use crate::params::Params;

fn dir(s: &SegQ8) -> (i128, i128) {
    (i128::from(s.x1 - s.x0), i128::from(s.y1 - s.y0))
}

/// Shifts a vector right until both components are below 2^20.
fn shrink((x, y): (i128, i128)) -> (i128, i128) {
    let big = x.unsigned_abs().max(y.unsigned_abs());
    let shift = (128 - big.leading_zeros()).saturating_sub(20);
    (x >> shift, y >> shift)
}

/// A necessary condition for [`mergeable`], in cheap `i64` arithmetic: if
/// the two can merge, `b`'s midpoint lies within `max(D_c, D_e) + |b|/2` of
/// segment `a` (in the overlap case its projection falls within `|b|/2` of
/// `a` and its offset is at most D_c; in the gap case an endpoint of `b` is
/// within D_e of one of `a`). The L∞ distance to `a`'s bounding box is at
/// most that Euclidean distance and `|b|` at most its L1 length, so a pair
/// failing this test cannot merge.
fn maybe_mergeable(p: &Params, a: &SegQ8, b: &SegQ8) -> bool {
    // Q9 (doubled Q8) so that the midpoint is an integer.
    let (mx, my) = (b.x0 + b.x1, b.y0 + b.y1);
    let gap = |m: i64, lo: i64, hi: i64| (2 * lo - m).max(m - 2 * hi).max(0);
    let dx = gap(mx, a.x0.min(a.x1), a.x0.max(a.x1));
    let dy = gap(my, a.y0.min(a.y1), a.y0.max(a.y1));
    let half_l1 = (b.x1 - b.x0).abs() + (b.y1 - b.y0).abs(); // |b|_1 in Q9 / 2
    let bound = 2 * p.merge_dc_q8.max(p.merge_de_q8) + half_l1;
    dx.max(dy) <= bound
}

pub(crate) fn mergeable(p: &Params, a: &SegQ8, b: &SegQ8) -> bool {
    if !maybe_mergeable(p, a, b) {
        return false;
    }
    let (ax, ay) = dir(a);
    let (bx, by) = dir(b);
    let (la2, lb2) = (ax * ax + ay * ay, bx * bx + by * by);
    if la2 == 0 || lb2 == 0 {
        return false;
    }
    // D_a: |a·b| >= cos(D_a)·|a|·|b|, squared.
    let ((sx, sy), (tx, ty)) = (shrink((ax, ay)), shrink((bx, by)));
    let dot = sx * tx + sy * ty;
    let cos2 = (i128::from(p.merge_cos_q30) * i128::from(p.merge_cos_q30)) >> 30;
    if dot * dot * (1 << 30) < cos2 * (sx * sx + sy * sy) * (tx * tx + ty * ty) {
        return false;
    }
    // D_c: midpoints (Q9) to the other line.
    let dc = i128::from(p.merge_dc_q8) * 2; // Q9
    let far = |m: (i128, i128), s: &SegQ8, (vx, vy): (i128, i128), l2: i128| {
        let (ox, oy) = (m.0 - 2 * i128::from(s.x0), m.1 - 2 * i128::from(s.y0));
        let cross = ox * vy - oy * vx; // Q17
        cross * cross > dc * dc * l2
    };
    let mid = |s: &SegQ8| (i128::from(s.x0 + s.x1), i128::from(s.y0 + s.y1));
    if far(mid(b), a, (ax, ay), la2) || far(mid(a), b, (bx, by), lb2) {
        return false;
    }
    // Overlap of b's projection with a: t in [0, |a|²] (Q16).
    let t = |x: i64, y: i64| i128::from(x - a.x0) * ax + i128::from(y - a.y0) * ay;
    let (t0, t1) = (t(b.x0, b.y0), t(b.x1, b.y1));
    if t0.max(t1) >= 0 && t0.min(t1) <= la2 {
        return true;
    }
    // Disjoint: closest endpoints within D_e.
    let de2 = i128::from(p.merge_de_q8) * i128::from(p.merge_de_q8);
    let d2 = |x0: i64, y0: i64, x1: i64, y1: i64| {
        let (dx, dy) = (i128::from(x1 - x0), i128::from(y1 - y0));
        dx * dx + dy * dy
    };
    [(a.x0, a.y0), (a.x1, a.y1)]
        .iter()
        .any(|&(x, y)| d2(x, y, b.x0, b.y0) <= de2 || d2(x, y, b.x1, b.y1) <= de2)
}

fn pixels(s: &SegQ8) -> Raster {
    Raster::new(
        (round_q8(s.x0), round_q8(s.y0)),
        (round_q8(s.x1), round_q8(s.y1)),
    )
}

pub(crate) fn merged(a: &SegQ8, b: &SegQ8) -> SegQ8 {
    let mut fit = Fit::default();
    for (x, y) in pixels(a).chain(pixels(b)) {
        // Bresenham pixels of in-image segments: far below 2^31.
        fit.add(x as i32, y as i32);
    }
    let line = fit.line();
    let (lo, hi) = pixels(a)
        .chain(pixels(b))
        .map(|(x, y)| line.projection(x, y))
        .fold((i64::MAX, i64::MIN), |(lo, hi), t| (lo.min(t), hi.max(t)));
    let (mut lo, mut hi) = (lo, hi);
    let (ax, ay) = dir(a);
    let (c, s) = line.unit();
    if ax * i128::from(c) + ay * i128::from(s) < 0 {
        core::mem::swap(&mut lo, &mut hi);
    }
    let (x0, y0) = line.point_at(lo);
    let (x1, y1) = line.point_at(hi);
    SegQ8 { x0, y0, x1, y1 }
}

/// Merges the first `count` slots of `out` (holding [`SegQ8::to_slot`]
/// values) in place; returns the new count.
pub(crate) fn merge_all(p: &Params, out: &mut [Segment], count: usize) -> usize {
    let mut len = count.min(out.len());
    loop {
        let mut changed = false;
        let mut i = 0;
        while i < len {
            let mut j = i + 1;
            while j < len {
                let (Some(a), Some(b)) = (out.get(i), out.get(j)) else {
                    break;
                };
                let (a, b) = (SegQ8::from_slot(a), SegQ8::from_slot(b));
                if mergeable(p, &a, &b) {
                    if let Some(s) = out.get_mut(i) {
                        *s = merged(&a, &b).to_slot();
                    }
                    // Remove slot j, keeping the order (a plain loop: no
                    // `rotate_left` length assertion to prove away).
                    for k in j..len - 1 {
                        if let Some(&next) = out.get(k + 1)
                            && let Some(slot) = out.get_mut(k)
                        {
                            *slot = next;
                        }
                    }
                    len -= 1;
                    changed = true;
                    // Continue with the segment that moved into slot j; pairs
                    // the grown segment i now reaches are found by the next
                    // sweep.
                } else {
                    j += 1;
                }
            }
            i += 1;
        }
        if !changed {
            return len;
        }
    }
}
