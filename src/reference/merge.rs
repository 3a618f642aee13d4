//! Paper §3.3, eqs. 6-7: merging duplicate and collinear fragments, with the
//! Bresenham re-fit. Absent from the authors' released code.
//!
//! Two segments `a` and `b` merge when
//! * the angle between them is at most D_a,
//! * the larger of the two perpendicular centre distances (the midpoint of
//!   each to the infinite line of the other) is at most D_c, and
//! * they overlap (eq. 6: the projection of `b` onto the line of `a`
//!   intersects `a`), or they do not and the closest pair of endpoints is
//!   at most D_e apart (eq. 7).
//!
//! The merged segment: rasterise both segments with Bresenham, fit a line to
//! all those pixels by orthogonal least squares, and project the two pixels
//! that lie farthest apart along the fitted line onto it, on the Q8 grid
//! like every end the merging sees. It takes the place of `a`; `b` is
//! removed. Which pairs are compared, and in what order, is
//! [`merge_all`]'s, from the core's own keys.

use alloc::vec::Vec;

use super::{Seg, bresenham, round};
use crate::Config;
use crate::params::Params;
use crate::stage::merge;
use crate::stage::output::SegQ8;

/// Merges in place; returns the number of segments removed. The pairs
/// compared and their order are the fixed core's (`stage::merge`): each
/// sweep puts the segments in direction bins of width W = D_a + 1° (at
/// most 89°), keys each by its midpoint's offset along its bin centre's
/// normal (in quarter pixels, floored), sorts by (bin, offset, position),
/// and takes each segment `a` in that order; its candidates are the later
/// segments of its bin, then those of the next bin (circularly), whose
/// offset is within reach of `a`'s along that bin's normal (D_c plus
/// `sin(W/2)` times `(|a| + |b|_max) / 2 + D_e`, lengths bounded above by
/// `max + min / 2` of the sides), at most `TRIES` of them; a merge grows
/// `a` and removes the candidate; at most `SWEEPS` sweeps.
pub(super) fn merge_all(segs: &mut Vec<Seg>, cfg: &Config, _w: usize, _h: usize) -> usize {
    use crate::stage::merge::SWEEPS;
    let before = segs.len();
    // The fixed core merges Q8 values: on the same grid, the keys, the
    // order and the decisions are the core's.
    for s in segs.iter_mut() {
        *s = s.on_q8_grid();
    }
    let keys = Keys::new(cfg);
    let mut live = alloc::vec![true; segs.len()];
    for _ in 0..SWEEPS {
        if !keys.sweep(segs, &mut live) {
            break;
        }
    }
    let mut k = 0;
    segs.retain(|_| {
        k += 1;
        live[k - 1]
    });
    before - segs.len()
}

/// The merging's thresholds, and the core's parameters for its keys.
struct Keys {
    cos_da: f64,
    dc: f64,
    de: f64,
    p: Params,
}

impl Keys {
    fn new(cfg: &Config) -> Self {
        Self {
            cos_da: libm::cos(f64::from(cfg.merge_angle_deg).to_radians()),
            dc: f64::from(cfg.merge_center_px),
            de: f64::from(cfg.merge_gap_px),
            p: Params::new(cfg),
        }
    }

    /// `s` (on the Q8 grid) as the core holds it, for its keys.
    fn q8(s: &Seg) -> SegQ8 {
        let q = |v: f64| (v * 256.0) as i64;
        SegQ8::new(q(s.x0), q(s.y0), q(s.x1), q(s.y1))
    }

    fn bin_of(&self, s: &Seg) -> u32 {
        merge::bin(&self.p, &Self::q8(s))
    }

    /// The midpoint's offset along the normal of `bin`'s centre, in
    /// quarter pixels, floored.
    fn rho(&self, s: &Seg, bin: u32) -> i64 {
        merge::rho(&self.p, &Self::q8(s), bin)
    }

    /// One sweep; whether it merged anything.
    fn sweep(&self, segs: &mut [Seg], live: &mut [bool]) -> bool {
        use crate::stage::merge::TRIES;
        let mut order: Vec<(u32, i64, usize)> = (0..segs.len())
            .filter(|&i| live[i])
            .map(|i| {
                let bin = self.bin_of(&segs[i]);
                (bin, self.rho(&segs[i], bin), i)
            })
            .collect();
        order.sort_unstable();
        let longest = |bin: u32, segs: &[Seg], live: &[bool]| {
            order
                .iter()
                .filter(|&&(b, _, i)| b == bin && live[i])
                .map(|&(_, _, i)| merge::length_bound(&Self::q8(&segs[i])))
                .fold(0, i64::max)
        };
        let mut changed = false;
        let mut at_bin = u32::MAX;
        let (mut long_same, mut long_next) = (0, 0);
        for k in 0..order.len() {
            let (bin, rho_a, i) = order[k];
            if !live[i] {
                continue;
            }
            let next_bin = (bin + 1) % self.p.merge_bins;
            if bin != at_bin {
                at_bin = bin;
                long_same = longest(bin, segs, live);
                long_next = longest(next_bin, segs, live);
            }
            let la = merge::length_bound(&Self::q8(&segs[i]));
            let rho_next = self.rho(&segs[i], next_bin);
            let r_same = merge::reach(&self.p, la, long_same);
            let same = order[k + 1..]
                .iter()
                .take_while(|&&(b, r, _)| b == bin && r - rho_a <= r_same);
            let r_next = merge::reach(&self.p, la, long_next);
            let next = order
                .iter()
                .filter(|&&(b, r, _)| b == next_bin && (r - rho_next).abs() <= r_next);
            let mut tries = 0;
            for &(_, _, j) in same.chain(next) {
                if !live[j] || j == i {
                    continue;
                }
                if tries == TRIES {
                    break;
                }
                tries += 1;
                if mergeable(&segs[i], &segs[j], self.cos_da, self.dc, self.de) {
                    segs[i] = merged_scored(&segs[i], &segs[j]);
                    live[j] = false;
                    changed = true;
                }
            }
        }
        changed
    }
}

/// Whether `a` and `b` merge. Their ends are on the fixed core's Q8 grid
/// ([`merge_all`] and [`merged`] put them there), as the core's are: a
/// float end a few ulps off an exact value (1.4999995 for 1.5), or one
/// unit off the core's, would break a tie such as a gap of exactly D_e, or
/// an angle within a few thousandths of a degree of D_a, the other way.
fn mergeable(a: &Seg, b: &Seg, cos_da: f64, dc: f64, de: f64) -> bool {
    let (ax, ay) = (a.x1 - a.x0, a.y1 - a.y0);
    let (bx, by) = (b.x1 - b.x0, b.y1 - b.y0);
    let (la, lb) = (libm::hypot(ax, ay), libm::hypot(bx, by));
    if la == 0.0 || lb == 0.0 {
        return false;
    }
    // D_a: undirected angle, either polarity (design §8.1).
    if (ax * bx + ay * by).abs() < cos_da * la * lb {
        return false;
    }
    // D_c: both midpoints to the other line.
    let dist = |px: f64, py: f64, s: &Seg, vx: f64, vy: f64, l: f64| {
        ((px - s.x0) * vy - (py - s.y0) * vx).abs() / l
    };
    let (max, may) = ((a.x0 + a.x1) / 2.0, (a.y0 + a.y1) / 2.0);
    let (mbx, mby) = ((b.x0 + b.x1) / 2.0, (b.y0 + b.y1) / 2.0);
    if dist(mbx, mby, a, ax, ay, la) > dc || dist(max, may, b, bx, by, lb) > dc {
        return false;
    }
    // Overlap of b's projection onto a's axis with [0, la].
    let t = |px: f64, py: f64| ((px - a.x0) * ax + (py - a.y0) * ay) / la;
    let (t0, t1) = (t(b.x0, b.y0), t(b.x1, b.y1));
    if t0.max(t1) >= 0.0 && t0.min(t1) <= la {
        return true;
    }
    // Disjoint: closest endpoints within D_e.
    let d = |p: (f64, f64), q: (f64, f64)| libm::hypot(p.0 - q.0, p.1 - q.1);
    let ends_a = [(a.x0, a.y0), (a.x1, a.y1)];
    let ends_b = [(b.x0, b.y0), (b.x1, b.y1)];
    ends_a
        .iter()
        .flat_map(|&p| ends_b.iter().map(move |&q| d(p, q)))
        .any(|v| v <= de)
}

fn merged(a: &Seg, b: &Seg) -> Seg {
    let mut pts: Vec<(i64, i64)> = Vec::new();
    for s in [a, b] {
        let r = |v: f64| round(v) as i64;
        bresenham((r(s.x0), r(s.y0)), (r(s.x1), r(s.y1)), |x, y| {
            pts.push((x, y))
        });
    }
    // The core's exact sums (in-image pixels: coordinates below 2^15, at
    // most 2^16 of them).
    let mut fit = crate::stage::fit::Fit::default();
    for &(x, y) in &pts {
        fit.add(x as i32, y as i32);
    }
    let (n, sx, sy) = fit.sums();
    let (cxx, cyy, cxy) = fit.moments();
    let t = libm::atan2(2.0 * cxy as f64, cxx as f64 - cyy as f64) / 2.0;
    let (ux, uy) = (libm::cos(t), libm::sin(t));
    let (mx, my) = (sx as f64 / n as f64, sy as f64 / n as f64);
    let proj = |&(x, y): &(i64, i64)| (x as f64 - mx) * ux + (y as f64 - my) * uy;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &pts {
        let v = proj(p);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    // Keep a's direction so the merged segment reads the same way.
    let (ax, ay) = (a.x1 - a.x0, a.y1 - a.y0);
    if ax * ux + ay * uy < 0.0 {
        core::mem::swap(&mut lo, &mut hi);
    }
    Seg::new(mx + lo * ux, my + lo * uy, mx + hi * ux, my + hi * uy).on_q8_grid()
}

/// [`merged`] with its score and polarity (design §8.1): the parts' score
/// per unit length times the merged length, rounded; the polarity of the
/// part of the higher score (of equal ones, `a`'s).
fn merged_scored(a: &Seg, b: &Seg) -> Seg {
    let m = merged(a, b);
    let dot = (a.x1 - a.x0) * (b.x1 - b.x0) + (a.y1 - a.y0) * (b.y1 - b.y0);
    let m = if b.score > a.score && dot < 0.0 {
        m.reversed()
    } else {
        m
    };
    let len = |s: &Seg| libm::hypot(s.x1 - s.x0, s.y1 - s.y0);
    let parts = len(a) + len(b);
    let sum = a.score + b.score;
    let score = if parts > 0.0 {
        round(sum * len(&m) / parts)
    } else {
        sum
    };
    Seg {
        score: score.min(f64::from((1u32 << 24) - 1)),
        ..m
    }
}
