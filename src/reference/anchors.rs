//! Paper §3.1: processing order, aligned anchor groups (eqs. 2-3 as the
//! code implements them), regular anchors by NMS, and the label map
//! (design §3-6).

use alloc::vec;
use alloc::vec::Vec;

use super::{Maps, angle_diff};
use crate::Config;
use crate::spec::{ACROSS, ALONG, Orientation};

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
/// `reject_at` makes the walk stop as soon as a neighbour is `>= m(C)`.
fn best_of_sides(
    maps: &Maps,
    cx: i32,
    cy: i32,
    offs: &[(i32, i32); 6],
    reject_at: Option<f32>,
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
        if reject_at.is_some_and(|mc| mc <= mq) {
            return None;
        }
    }
    Some(best)
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
        // Steps 2-5: strict maximum across the edge, margin on one side.
        let Some([Some(a), Some(b)]) =
            best_of_sides(maps, cx, cy, &ACROSS[across_class(oc) as usize], Some(mc))
        else {
            continue;
        };
        if mc - a.1 < margin && mc - b.1 < margin {
            continue;
        }
        // Steps 6-8: strongest nonzero partner on each side along the edge.
        let Some([Some((j, _)), Some((k, _))]) =
            best_of_sides(maps, cx, cy, &ALONG[along_class(oc) as usize], None)
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

/// Design §5: interpolated Canny NMS on interior pixels (f32 weights).
pub(super) fn nms(maps: &Maps) -> Vec<bool> {
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
            let (p1, p2, p3, p4, wgt) = if o < 45.0 {
                (m(-1, -1), m(-1, 0), m(1, 1), m(1, 0), ay / ax)
            } else if o < 90.0 {
                (m(-1, -1), m(0, -1), m(1, 1), m(0, 1), ax / ay)
            } else if o < 135.0 {
                (m(1, -1), m(0, -1), m(-1, 1), m(0, 1), ax / ay)
            } else {
                (m(-1, 1), m(-1, 0), m(1, -1), m(1, 0), ay / ax)
            };
            let t1 = wgt * p1 + (1.0 - wgt) * p2;
            let t2 = wgt * p3 + (1.0 - wgt) * p4;
            let mc = maps.m[i];
            out[i] = mc > t1 && mc > t2; // NaN (0/0, x/0) never passes
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
