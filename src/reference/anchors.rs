//! Paper §3.1: processing order, aligned anchor groups (eqs. 2-3 as the
//! code implements them), regular anchors by NMS, and the label map
//! (design §3-6).

use alloc::vec;
use alloc::vec::Vec;

use super::{Maps, angle_diff};
use crate::spec::{ACROSS, ALONG, Orientation};
use crate::stage::gradient::gradient_at;
use crate::{Config, Maxima};

/// Label of a pixel that is neither an anchor nor in a group.
pub(super) const NONE: i32 = -1;
/// Label of an NMS pixel that is not in any group.
pub(super) const REGULAR: i32 = -2;

/// An aligned anchor group: raster indices of its pixels, centre `c` in the
/// middle, and its direction vector (unnormalised sum of the three
/// level-line unit vectors, design §6).
#[derive(Clone, Copy, Debug)]
pub(super) struct Group {
    pub j: usize,
    pub c: usize,
    pub k: usize,
    pub vx: f32,
    pub vy: f32,
}

/// The [`Orientation`] whose across-edge neighbourhood the group test
/// reads (design §4).
fn across_class(o: f32) -> Orientation {
    if (22.5..67.5).contains(&o) {
        Orientation::D45
    } else if (67.5..112.5).contains(&o) {
        Orientation::V
    } else if (112.5..157.5).contains(&o) {
        Orientation::D135
    } else {
        Orientation::H
    }
}

/// The [`Orientation`] whose along-edge neighbourhood the group test reads
/// (design §4: the interval ends differ from [`across_class`]'s).
fn along_class(o: f32) -> Orientation {
    if (22.5..67.5).contains(&o) {
        Orientation::D45
    } else if o > 67.5 && o < 112.5 {
        Orientation::V
    } else if (112.5..=157.5).contains(&o) {
        Orientation::D135
    } else {
        Orientation::H
    }
}

/// Design §3: pixels with `m > 0` in descending `min(m, 255)`, ties in raster order
/// (a stable counting sort with 256 keys).
fn processing_order(maps: &Maps) -> Vec<usize> {
    let key = |v: f32| (v.min(255.0)) as usize;
    let mut count = [0usize; 256];
    for &v in &maps.m {
        if v > 0.0 {
            count[key(v)] += 1;
        }
    }
    let mut start = [0usize; 256];
    let mut acc = 0;
    for k in (1..256).rev() {
        start[k] = acc;
        acc += count[k];
    }
    let mut order = vec![0usize; acc];
    for (i, &v) in maps.m.iter().enumerate() {
        if v > 0.0 {
            let k = key(v);
            order[start[k]] = i;
            start[k] += 1;
        }
    }
    order
}

/// The strongest neighbour of each 3-offset side, walking `offs` in order and
/// stopping at the first offset outside the image. Returns `(best_first,
/// best_second, stopped_early_on)` where each best is `(index, m)` or `None`
/// (zero magnitude never wins; the first strict maximum wins ties).
/// `reject_at` makes the walk stop as soon as a neighbour is `>= m(C)`, or
/// under [`Maxima::Symmetric`] (`equal_ok`) `> m(C)`.
fn best_of_sides(
    maps: &Maps,
    cx: i32,
    cy: i32,
    offs: &[(i32, i32); 6],
    reject_at: Option<f32>,
    equal_ok: bool,
) -> Option<[Option<(usize, f32)>; 2]> {
    let mut best: [Option<(usize, f32)>; 2] = [None, None];
    for (n, &(dx, dy)) in offs.iter().enumerate() {
        let (x, y) = (cx + dx, cy + dy);
        if !maps.in_bounds(x, y) {
            break;
        }
        let q = maps.idx(x, y);
        let mq = maps.m[q];
        let side = &mut best[n / 3];
        if mq > side.map_or(0.0, |b| b.1) {
            *side = Some((q, mq));
        }
        if reject_at.is_some_and(|mc| mc < mq || (mc == mq && !equal_ok)) {
            return None;
        }
    }
    Some(best)
}

/// The magnitude at `(x, y)`, 0 outside the image.
fn m_or_0(maps: &Maps, x: i32, y: i32) -> f32 {
    if maps.in_bounds(x, y) {
        maps.m[maps.idx(x, y)]
    } else {
        0.0
    }
}

/// Design §4 under [`Maxima::Symmetric`]: whether the centre `(cx, cy)` wins
/// against each across-edge neighbour of equal magnitude, walking `offs`
/// in order up to the first one outside the image (the first three are
/// side A, the left or upper one). Of two equal pixels C and C + e, C wins
/// when the profile `m(C - e), m, m, m(C + 2e)` peaks nearer it (the near
/// end is higher), or, with equal ends, when C is the left or upper one;
/// a plateau whose far end is not lower is a step, not a peak.
fn wins_ties(maps: &Maps, cx: i32, cy: i32, offs: &[(i32, i32); 6]) -> bool {
    let mc = maps.m[maps.idx(cx, cy)];
    for (n, &(dx, dy)) in offs.iter().enumerate() {
        if !maps.in_bounds(cx + dx, cy + dy) {
            break;
        }
        if maps.m[maps.idx(cx + dx, cy + dy)] != mc {
            continue;
        }
        let near = m_or_0(maps, cx - dx, cy - dy);
        let far = m_or_0(maps, cx + 2 * dx, cy + 2 * dy);
        let nearer = if n < 3 { near > far } else { near >= far };
        if !nearer || far >= mc {
            return false;
        }
    }
    true
}

/// Design §4 under [`Maxima::Symmetric`]: whether a side of the centre
/// `(cx, cy)` whose neighbours are all zero is the inside of a thin line:
/// the gradient at the side's middle offset `mid` is exactly zero (the two
/// edges of a line symmetric about it cancel there), and the pixel at
/// twice `mid` has a gradient opposite to the centre's, within T_aligned
/// of antiparallel, with at least half its magnitude (the line's other
/// edge). Only for a centre whose six across-edge neighbours are all in
/// the image.
fn thin_line_inside(maps: &Maps, cfg: &Config, cx: i32, cy: i32, mid: (i32, i32)) -> bool {
    let (fx, fy) = (cx + 2 * mid.0, cy + 2 * mid.1);
    if !maps.in_bounds(cx + mid.0, cy + mid.1) || !maps.in_bounds(fx, fy) {
        return false;
    }
    let g = |x: i32, y: i32| gradient_at(&maps.blur, maps.w, x as usize, y as usize);
    if g(cx + mid.0, cy + mid.1) != (0, 0) {
        return false;
    }
    let mc = maps.m[maps.idx(cx, cy)];
    let mf = maps.m[maps.idx(fx, fy)];
    let ((ax, ay), (bx, by)) = (g(cx, cy), g(fx, fy));
    let (ax, ay, bx, by) = (f64::from(ax), f64::from(ay), f64::from(bx), f64::from(by));
    let dot = ax * bx + ay * by;
    let cross = (ax * by - ay * bx).abs();
    let tol = f64::from(cfg.align_tolerance_deg).to_radians();
    2.0 * mf >= mc && dot < 0.0 && cross <= -dot * libm::tan(tol)
}

/// Design §4: aligned anchor groups in id order.
pub(super) fn extract_groups(maps: &Maps, cfg: &Config) -> Vec<Group> {
    let tol = cfg.align_tolerance_deg;
    let margin = f32::from(cfg.anchor_margin);
    let mut used = vec![false; maps.w * maps.h];
    let mut groups = Vec::new();
    for c in processing_order(maps) {
        if used[c] {
            continue;
        }
        let (cx, cy) = maps.xy(c);
        let (mc, oc) = (maps.m[c], maps.o[c]);
        // Steps 2-5: maximum across the edge, margin on one side (design §4:
        // strict, or under `Maxima::Symmetric` winning each equal
        // neighbour, with a side allowed to be the inside of a thin line).
        let symmetric = cfg.maxima == Maxima::Symmetric;
        let offs = &ACROSS[across_class(oc) as usize];
        let Some(bests) = best_of_sides(maps, cx, cy, offs, Some(mc), symmetric) else {
            continue;
        };
        let interior = offs
            .iter()
            .all(|&(dx, dy)| maps.in_bounds(cx + dx, cy + dy));
        let side = |k: usize| match bests[k] {
            Some((_, m)) => Some(m),
            None if symmetric
                && interior
                && thin_line_inside(maps, cfg, cx, cy, offs[3 * k + 1]) =>
            {
                Some(0.0)
            }
            None => None,
        };
        let (Some(a), Some(b)) = (side(0), side(1)) else {
            continue;
        };
        if symmetric && !wins_ties(maps, cx, cy, offs) {
            continue;
        }
        if mc - a < margin && mc - b < margin {
            continue;
        }
        // Steps 6-8: strongest nonzero partner on each side along the edge.
        let Some([Some((j, _)), Some((k, _))]) =
            best_of_sides(maps, cx, cy, &ALONG[along_class(oc) as usize], None, false)
        else {
            continue;
        };
        if used[j] || used[k] {
            continue;
        }
        // Step 9: either partner aligned.
        if angle_diff(oc, maps.o[j]) <= tol || angle_diff(oc, maps.o[k]) <= tol {
            used[j] = true;
            used[c] = true;
            used[k] = true;
            groups.push(group(maps, j, c, k));
        }
    }
    groups
}

/// Design §6: the group direction, the unnormalised sum of the level-line unit
/// vectors of J, C, K (level line = orientation - 90°), in that order.
fn group(maps: &Maps, j: usize, c: usize, k: usize) -> Group {
    let (mut vx, mut vy) = (0f32, 0f32);
    for p in [j, c, k] {
        let a = f64::from(maps.o[p]) - 90.0;
        let r = a * core::f64::consts::PI / 180.0;
        vx = (f64::from(vx) + libm::cos(r)) as f32;
        vy = (f64::from(vy) + libm::sin(r)) as f32;
    }
    Group { j, c, k, vx, vy }
}

/// Design §5: interpolated Canny NMS on interior pixels. Under
/// [`Maxima::Strict`] with the authors' `f32` weights `w = num/den`; under
/// [`Maxima::Symmetric`], where equality decides, without rounding: the
/// interpolation `t = p_e + w·(p_d - p_e)` is compared as
/// `den·(m - p_e) > num·(p_d - p_e)` (integers, exact in `f64`), allowing
/// equality on the second side (right or lower: each row of the table
/// below lists the left or upper side first).
pub(super) fn nms(maps: &Maps, maxima: Maxima) -> Vec<bool> {
    let (w, h) = (maps.w, maps.h);
    let mut out = vec![false; w * h];
    if w < 3 || h < 3 {
        return out;
    }
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = y * w + x;
            let (gx, gy) = crate::stage::gradient::gradient_at(&maps.blur, w, x, y);
            let (ax, ay) = ((gx as f32).abs(), (gy as f32).abs());
            let o = maps.o[i];
            let m = |dx: isize, dy: isize| {
                maps.m[((y as isize + dy) as usize) * w + (x as isize + dx) as usize]
            };
            let (p1, p2, p3, p4, (num, den)) = if o < 45.0 {
                (m(-1, -1), m(-1, 0), m(1, 1), m(1, 0), (ay, ax))
            } else if o < 90.0 {
                (m(-1, -1), m(0, -1), m(1, 1), m(0, 1), (ax, ay))
            } else if o < 135.0 {
                (m(1, -1), m(0, -1), m(-1, 1), m(0, 1), (ax, ay))
            } else {
                (m(-1, 1), m(-1, 0), m(1, -1), m(1, 0), (ay, ax))
            };
            let mc = maps.m[i];
            out[i] = match maxima {
                Maxima::Strict => {
                    let wgt = num / den;
                    let t1 = wgt * p1 + (1.0 - wgt) * p2;
                    let t2 = wgt * p3 + (1.0 - wgt) * p4;
                    mc > t1 && mc > t2 // NaN (0/0, x/0) never passes
                }
                Maxima::Symmetric => {
                    let side = |pd: f32, pe: f32| {
                        f64::from(den) * f64::from(mc - pe) - f64::from(num) * f64::from(pd - pe)
                    };
                    den > 0.0 && side(p1, p2) > 0.0 && side(p3, p4) >= 0.0
                }
            };
        }
    }
    out
}

/// Design §6: NONE everywhere, REGULAR on NMS pixels, the group id on group pixels.
pub(super) fn labels(maps: &Maps, groups: &[Group], nms: &[bool]) -> Vec<i32> {
    let mut lab: Vec<i32> = nms
        .iter()
        .map(|&b| if b { REGULAR } else { NONE })
        .collect();
    debug_assert_eq!(lab.len(), maps.w * maps.h);
    for (id, g) in groups.iter().enumerate() {
        for p in [g.j, g.c, g.k] {
            lab[p] = id as i32;
        }
    }
    lab
}
