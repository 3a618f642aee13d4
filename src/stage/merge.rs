//! Paper §3.3, eqs. 6-7: merging duplicate and collinear fragments, in
//! integers (the authors' released code has no merging; this follows the
//! paper, with the reading documented in `crate::reference`).
//!
//! Two segments merge when the angle between them is at most D_a, the larger
//! perpendicular centre distance is at most D_c, and they overlap along the
//! first one's axis or (eq. 7) their closest endpoints are at most D_e
//! apart. The merged segment is the orthogonal least-squares line through
//! the Bresenham pixels of both, cut at the projections of its two extreme
//! pixels; it replaces the first segment and the second is removed. Which
//! pairs are compared, and in what order, is [`merge_all`]'s: near
//! directions only, a bounded number per segment and of sweeps.
//!
//! Segment coordinates are Q8 (`i32`, within ±2^24: [`SegQ8`]), so their
//! sums and differences fit `i32` and their products `i64` (one widening
//! multiplication each on a 32-bit core). The tests square both sides of
//! each inequality; the squares that exceed 64 bits are exact 128-bit
//! products of 64-bit values; the angle test first
//! shifts both direction vectors below 2^20 (a relative direction error
//! under 2^-19, far below the 5° threshold's sensitivity).

use super::best::swap;
use super::fit::Fit;
use super::output::SegQ8;
use super::raster::Raster;
use super::work::Work;
use crate::Segment;
use crate::num::q8::{div_round_u64, isqrt_u64};
use crate::num::trig;
use crate::params::Params;

/// A segment's direction vector (below 2^25 in each component).
fn dir(s: &SegQ8) -> (i32, i32) {
    (s.x1 - s.x0, s.y1 - s.y0)
}

/// `a · b` in 64 bits.
fn mul(a: i32, b: i32) -> i64 {
    i64::from(a) * i64::from(b)
}

/// Shifts a vector right until both components are below 2^20.
#[cfg_attr(aaglsd_small, inline(never))]
fn shrink((x, y): (i32, i32)) -> (i32, i32) {
    let big = x.unsigned_abs().max(y.unsigned_abs());
    let shift = (32 - big.leading_zeros()).saturating_sub(20);
    (x >> shift, y >> shift)
}

/// `a · b`, exact. The only 128-bit arithmetic in the merging is on these
/// products (squared distances and the angle test); everything else fits
/// 64 bits. Out of line in a build for size: a Cortex-M has no 128-bit
/// registers, and each inlined product is a dozen instructions.
#[cfg_attr(aaglsd_small, inline(never))]
fn wide(a: u64, b: u64) -> u128 {
    u128::from(a) * u128::from(b)
}

/// A necessary condition for [`mergeable`], in cheap `i32` arithmetic: if
/// the two can merge, `b`'s midpoint lies within `max(D_c, D_e) + |b|/2` of
/// segment `a` (in the overlap case its projection falls within `|b|/2` of
/// `a` and its offset is at most D_c; in the gap case an endpoint of `b` is
/// within D_e of one of `a`). The L∞ distance to `a`'s bounding box is at
/// most that Euclidean distance and `|b|` at most its L1 length, so a pair
/// failing this test cannot merge. (Below 2^27 throughout: D_c and D_e are
/// at most 2^20 in Q8.)
fn maybe_mergeable(p: &Params, a: &SegQ8, b: &SegQ8) -> bool {
    // Q9 (doubled Q8) so that the midpoint is an integer.
    let (mx, my) = (b.x0 + b.x1, b.y0 + b.y1);
    let gap = |m: i32, lo: i32, hi: i32| (2 * lo - m).max(m - 2 * hi).max(0);
    let dx = gap(mx, a.x0.min(a.x1), a.x0.max(a.x1));
    let dy = gap(my, a.y0.min(a.y1), a.y0.max(a.y1));
    let half_l1 = (b.x1 - b.x0).abs() + (b.y1 - b.y0).abs(); // |b|_1 in Q9 / 2
    let reach = p.merge_dc_q8.max(p.merge_de_q8).clamp(0, 1 << 20) as i32;
    dx.max(dy) <= 2 * reach + half_l1
}

/// Whether `a` and `b` can merge (the module docs).
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn mergeable(p: &Params, a: &SegQ8, b: &SegQ8) -> bool {
    if !maybe_mergeable(p, a, b) {
        return false;
    }
    // Sides below 2^25, squared lengths below 2^51.
    let (ax, ay) = dir(a);
    let (bx, by) = dir(b);
    let (la2, lb2) = (mul(ax, ax) + mul(ay, ay), mul(bx, bx) + mul(by, by));
    if la2 == 0 || lb2 == 0 {
        return false;
    }
    // D_a: |a·b| >= cos(D_a)·|a|·|b|, squared: dot² · 2^30 >= cos² · |s|²
    // · |t|² (Q30 cosine squared; below 2^112). `cos² · |s|²` is below
    // 2^71, so the last factor multiplies its two 64-bit halves.
    let ((sx, sy), (tx, ty)) = (shrink((ax, ay)), shrink((bx, by)));
    // Either polarity (design §8.1): the merged segment takes the one of
    // most of its contrast.
    let dot = (mul(sx, tx) + mul(sy, ty)).unsigned_abs(); // below 2^41
    let cos2 = ((p.merge_cos_q30 * p.merge_cos_q30) >> 30).unsigned_abs();
    let (s2, t2) = (
        (mul(sx, sx) + mul(sy, sy)) as u64,
        (mul(tx, tx) + mul(ty, ty)) as u64,
    );
    let cs = wide(cos2, s2);
    let rhs = wide(cs as u64, t2) + (wide((cs >> 64) as u64, t2) << 64);
    if wide(dot, dot) << 30 < rhs {
        return false;
    }
    // D_c: midpoints (Q9) to the other line: cross (Q17, at most 2^52)
    // squared against D_c² (below 2^30) · |v|².
    let dc = (p.merge_dc_q8 * 2).unsigned_abs(); // Q9
    let far = |m: (i32, i32), s: &SegQ8, (vx, vy): (i32, i32), l2: i64| {
        let (ox, oy) = (m.0 - 2 * s.x0, m.1 - 2 * s.y0); // at most 2^26
        let cross = (mul(ox, vy) - mul(oy, vx)).unsigned_abs();
        wide(cross, cross) > wide(dc * dc, l2.unsigned_abs())
    };
    let mid = |s: &SegQ8| (s.x0 + s.x1, s.y0 + s.y1);
    // A loop, not two calls: one copy of the test in a build for size.
    for &(m, s, v, l2) in &[(mid(b), a, (ax, ay), la2), (mid(a), b, (bx, by), lb2)] {
        if far(m, s, v, l2) {
            return false;
        }
    }
    // Overlap of b's projection with a: t in [0, |a|²] (Q16, below 2^51).
    let t = |x: i32, y: i32| mul(x - a.x0, ax) + mul(y - a.y0, ay);
    let (t0, t1) = (t(b.x0, b.y0), t(b.x1, b.y1));
    if t0.max(t1) >= 0 && t0.min(t1) <= la2 {
        return true;
    }
    // Disjoint: closest endpoints within D_e (D_e² below 2^40).
    let de2 = p.merge_de_q8 * p.merge_de_q8;
    let d2 = |x0: i32, y0: i32, x1: i32, y1: i32| {
        let (dx, dy) = (x1 - x0, y1 - y0);
        mul(dx, dx) + mul(dy, dy)
    };
    for &(x, y) in &[(a.x0, a.y0), (a.x1, a.y1)] {
        if d2(x, y, b.x0, b.y0) <= de2 || d2(x, y, b.x1, b.y1) <= de2 {
            return true;
        }
    }
    false
}

fn pixels(s: &SegQ8) -> Raster {
    let (from, to) = s.pixel_ends();
    Raster::new(from, to)
}

pub(crate) fn merged(a: &SegQ8, b: &SegQ8) -> SegQ8 {
    // Loops over the two segments rather than chained iterators: one copy
    // of the raster walk each in a build for size.
    let mut fit = Fit::default();
    for &s in &[a, b] {
        for (x, y) in pixels(s) {
            // Bresenham pixels of in-image segments: far below 2^31.
            fit.add(x as i32, y as i32);
        }
    }
    let line = fit.line();
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for &s in &[a, b] {
        for (x, y) in pixels(s) {
            let t = line.projection(x, y);
            (lo, hi) = (lo.min(t), hi.max(t));
        }
    }
    let (ax, ay) = dir(a);
    let (c, s) = line.unit();
    if mul(ax, c) + mul(ay, s) < 0 {
        core::mem::swap(&mut lo, &mut hi);
    }
    let (x0, y0) = line.point_at(lo);
    let (x1, y1) = line.point_at(hi);
    SegQ8::new(x0, y0, x1, y1)
}

/// [`merged`] with its score and polarity (design §8.1): the two parts'
/// score per unit length times the merged length, `(Sa + Sb)·|m| / (|a| +
/// |b|)`, so two parts end to end add their scores and two copies of one
/// line do not; the polarity of the part of the higher score (of equal
/// ones, `a`'s).
fn merged_scored(a: &SegQ8, b: &SegQ8) -> SegQ8 {
    let m = merged(a, b);
    let (ax, ay) = dir(a);
    let (bx, by) = dir(b);
    let m = if b.score > a.score && mul(ax, bx) + mul(ay, by) < 0 {
        m.reversed()
    } else {
        m
    };
    // Q8 lengths below 2^26; scores below 2^24: the product below 2^51.
    let len = |(x, y): (i32, i32)| isqrt_u64((mul(x, x) + mul(y, y)).unsigned_abs());
    let parts = len((ax, ay)) + len((bx, by));
    let sum = u64::from(a.score) + u64::from(b.score);
    let score = if parts == 0 {
        sum
    } else {
        div_round_u64(sum * len(dir(&m)), parts)
    };
    SegQ8 {
        score: score.min(u64::from(SegQ8::MAX_SCORE)) as u32,
        ..m
    }
}

/// Sweeps at most this many times (design §9.2).
pub(crate) const SWEEPS: usize = 3;
/// Compares each segment with at most this many candidates per sweep.
pub(crate) const TRIES: usize = 64;
/// The offset key's unit: a quarter pixel.
const RHO_SHIFT: u32 = 2;
/// The offset key's bias (24 bits: offsets within ±2^21 px).
const RHO_BIAS: i64 = 1 << 23;

/// The undirected direction of `s` as a binary angle of 2^32 per 180°.
fn angle(s: &SegQ8) -> u32 {
    let (dx, dy) = dir(s);
    trig::atan2(dy.into(), dx.into()).wrapping_shl(1)
}

/// The direction bin of `s` (design §9.1).
pub(crate) fn bin(p: &Params, s: &SegQ8) -> u32 {
    (angle(s) / p.merge_window.max(1)).min(p.merge_bins - 1)
}

/// An upper bound of the length of `s` within 12%, in Q8: `max + min / 2`
/// of the two sides (`(M + m/2)² ≥ M² + m²` when `M ≥ m`). Halved by a
/// shift (the sides are not negative): at opt-level `z` a signed 64-bit
/// `/ 2` becomes a call of the 64-bit division routine.
pub(crate) fn length_bound(s: &SegQ8) -> i64 {
    let (dx, dy) = dir(s);
    let (dx, dy) = (dx.abs(), dy.abs());
    (dx.max(dy) + (dx.min(dy) >> 1)).into()
}

/// The longest [`length_bound`] among the live segments of the first `m`
/// sorted entries that lie in `bin`.
fn longest_in(pairs: &[u32], m: usize, bin: u32, out: &[Segment]) -> i64 {
    let mut longest = 0;
    for t in lower_bound(pairs, m, u64::from(bin) << 56)..m {
        let e = entry(pairs, t);
        if bin_of(e) != bin {
            break;
        }
        if let Some(s) = out.get((e as u32) as usize)
            && !dead(s)
        {
            longest = longest.max(length_bound(&SegQ8::from_slot(s)));
        }
    }
    longest
}

/// The offset of `s`'s midpoint along the normal of direction bin `bin`
/// (the bin's centre), in quarter pixels, floored.
pub(crate) fn rho(p: &Params, s: &SegQ8, bin: u32) -> i64 {
    let centre = bin
        .wrapping_mul(p.merge_window)
        .wrapping_add(p.merge_window / 2);
    let (c, sn) = trig::sin_cos(centre >> 1);
    // Q9 midpoint times Q30 trig: Q39.
    let (mx, my) = (s.x0 + s.x1, s.y0 + s.y1);
    (mul(my, c) - mul(mx, sn)) >> (39 - RHO_SHIFT)
}

/// How far (in quarter pixels, rounded up) the offset of a segment `b` of
/// a bin, at most `lb` long, can be from the offset of a segment `a`, at
/// most `la` long, that can merge with it, both along the normal of `b`'s
/// bin: `a`'s midpoint is within D_c of `b`'s line and within `(|a| +
/// |b|) / 2 + D_e` of `b`'s midpoint along it, and `b`'s direction is
/// within W/2 of its bin's centre.
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn reach(p: &Params, la: i64, lb: i64) -> i64 {
    let along = ((la + lb) >> 1) + p.merge_de_q8; // Q8; both lengths >= 0
    let r = p.merge_dc_q8 + ((along * p.merge_sin_half_q30) >> 30) + 1; // Q8
    (r >> (8 - RHO_SHIFT)) + 1
}

/// Entry `k` of the sort array: `(bin << 56) | (offset << 32) | slot`.
fn entry(pairs: &[u32], k: usize) -> u64 {
    let at = |i: usize| u64::from(pairs.get(i).copied().unwrap_or(0));
    (at(2 * k) << 32) | at(2 * k + 1)
}

fn set_entry(pairs: &mut [u32], k: usize, v: u64) {
    if let Some(e) = pairs.get_mut(2 * k..2 * k + 2) {
        e.copy_from_slice(&[(v >> 32) as u32, v as u32]);
    }
}

#[cfg_attr(aaglsd_small, inline(never))]
fn make_entry(bin: u32, rho: i64, slot: usize) -> u64 {
    let r = (rho + RHO_BIAS).clamp(0, (1 << 24) - 1) as u64;
    (u64::from(bin) << 56) | (r << 32) | slot as u64
}

fn bin_of(e: u64) -> u32 {
    (e >> 56) as u32
}

fn rho_of(e: u64) -> i64 {
    ((e >> 32) & 0xFF_FFFF) as i64 - RHO_BIAS
}

/// Sorts the first `n` entries ascending: heapsort, in place, O(n log n)
/// whatever the order (the keys can come from adversarial content).
fn heapsort(pairs: &mut [u32], n: usize) {
    let sift = |pairs: &mut [u32], mut root: usize, end: usize| {
        loop {
            let mut child = 2 * root + 1;
            if child >= end {
                return;
            }
            if child + 1 < end && entry(pairs, child + 1) > entry(pairs, child) {
                child += 1;
            }
            let (r, c) = (entry(pairs, root), entry(pairs, child));
            if r >= c {
                return;
            }
            set_entry(pairs, root, c);
            set_entry(pairs, child, r);
            root = child;
        }
    };
    for root in (0..n / 2).rev() {
        sift(pairs, root, n);
    }
    for end in (1..n).rev() {
        let (first, last) = (entry(pairs, 0), entry(pairs, end));
        set_entry(pairs, 0, last);
        set_entry(pairs, end, first);
        sift(pairs, 0, end);
    }
}

/// The first of the `m` sorted entries at or above `key`.
fn lower_bound(pairs: &[u32], m: usize, key: u64) -> usize {
    let (mut lo, mut hi) = (0, m);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if entry(pairs, mid) < key {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo
}

/// A removed segment's slot holds NaN until the final compaction.
fn dead(s: &Segment) -> bool {
    s.x0.is_nan()
}

/// Merges the first `count` slots of `out` (holding [`SegQ8::to_slot`]
/// values) in place; returns the new count, live slots kept in order.
///
/// A sweep puts each live segment in a direction bin of width W = D_a + 1°
/// (at most 89°) and keys it by its midpoint's offset along the bin
/// centre's normal; it sorts by (bin, offset, slot) and takes each segment
/// `a` in that order. Its candidates are, nearest offset first, the later
/// segments of its bin within [`reach`] of its offset, then the segments
/// of the next bin (circularly) within reach of `a`'s offset along that
/// bin's normal: every pair within D_a of each other that can merge is
/// among them. At most [`TRIES`] are compared. A mergeable `b` is folded
/// into `a` (which keeps its keys for the sweep) and removed. Sweeps repeat
/// while one merges something, at most [`SWEEPS`] times. `pairs` holds two
/// words per segment (the caller's group records are done with); segments
/// beyond its room are not merged (never the case: a frame has fewer
/// strong segments than group records).
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn merge_all(
    p: &Params,
    out: &mut [Segment],
    count: usize,
    pairs: &mut [u32],
    work: &mut Work,
) -> usize {
    let len = count.min(out.len());
    let n = len.min(pairs.len() / 2);
    for _ in 0..SWEEPS {
        let m = sort_keys(p, out, n, pairs);
        if !sweep(p, out, pairs, m, work) {
            break;
        }
    }
    compact(out, len)
}

/// Writes the sort key of each live segment among the first `n` slots
/// into `pairs` and sorts them; the number of keys.
fn sort_keys(p: &Params, out: &[Segment], n: usize, pairs: &mut [u32]) -> usize {
    let mut m = 0;
    for slot in 0..n {
        if let Some(s) = out.get(slot)
            && !dead(s)
        {
            let q = SegQ8::from_slot(s);
            let bin = bin(p, &q);
            set_entry(pairs, m, make_entry(bin, rho(p, &q, bin), slot));
            m += 1;
        }
    }
    heapsort(pairs, m);
    m
}

/// One sweep over the `m` sorted keys; whether it merged anything.
fn sweep(p: &Params, out: &mut [Segment], pairs: &[u32], m: usize, work: &mut Work) -> bool {
    let bins = p.merge_bins;
    let mut changed = false;
    // The longest segments of the current bin and of the next, taken
    // when the sweep enters the bin: the later segments of the bin have
    // not grown yet, nor has the next bin (but for the wrap, whose bin
    // 0 is done and measured as it is).
    let (mut at_bin, mut long_same, mut long_next) = (u32::MAX, 0, 0);
    for k in 0..m {
        let e = entry(pairs, k);
        let i = (e as u32) as usize;
        let Some(sa) = out.get(i) else { continue };
        if dead(sa) {
            continue;
        }
        let a = SegQ8::from_slot(sa);
        let bin = bin_of(e);
        let next_bin = if bin + 1 == bins { 0 } else { bin + 1 };
        if bin != at_bin {
            at_bin = bin;
            long_same = longest_in(pairs, m, bin, out);
            long_next = longest_in(pairs, m, next_bin, out);
        }
        let la = length_bound(&a);
        let r_same = rho_of(e) + reach(p, la, long_same);
        let rho_next = rho(p, &a, next_bin);
        let r_next = reach(p, la, long_next);
        // The later entries of the bin up to `r_same`, then the next
        // bin's within `rho_next ± r_next`.
        let first_next = lower_bound(pairs, m, make_entry(next_bin, rho_next - r_next, 0));
        let ranges = [
            (k + 1, bin, r_same),
            (first_next, next_bin, rho_next + r_next),
        ];
        changed |= merge_into(p, out, pairs, m, (i, a), ranges, work);
    }
    changed
}

/// Folds into segment `a` (slot `i`) each mergeable segment of the key
/// `ranges` (first key, bin, largest rho), at most [`TRIES`] compared;
/// whether one merged.
fn merge_into(
    p: &Params,
    out: &mut [Segment],
    pairs: &[u32],
    m: usize,
    (i, mut a): (usize, SegQ8),
    ranges: [(usize, u32, i64); 2],
    work: &mut Work,
) -> bool {
    let mut changed = false;
    let mut tries = 0;
    for &(start, in_bin, rho_max) in &ranges {
        for t in start..m {
            let eb = entry(pairs, t);
            if bin_of(eb) != in_bin || rho_of(eb) > rho_max {
                break;
            }
            let j = (eb as u32) as usize;
            if j == i {
                continue;
            }
            let Some(sb) = out.get(j) else { continue };
            if dead(sb) {
                continue;
            }
            if tries == TRIES || !work.left() {
                work.cut += 1;
                return changed;
            }
            tries += 1;
            work.spend(1);
            let b = SegQ8::from_slot(sb);
            if mergeable(p, &a, &b) {
                a = merged_scored(&a, &b);
                if let Some(s) = out.get_mut(i) {
                    *s = a.to_slot();
                }
                if let Some(s) = out.get_mut(j) {
                    s.x0 = f32::NAN;
                }
                changed = true;
            }
        }
    }
    changed
}

/// Moves the live segments among the first `len` slots to the front, in
/// slot order, and zeroes the rest; the number kept.
fn compact(out: &mut [Segment], len: usize) -> usize {
    // A swap, not a copy: the compiler turns the copy between two slots of
    // one slice into a `memmove` call, and that routine alone is 1.5 KB of
    // a microcontroller's flash. What the swaps leave past `kept` is
    // zeroed below.
    let mut kept = 0;
    for i in 0..len {
        let Some(s) = out.get(i) else { break };
        if !dead(s) {
            // Slots `kept..=i` trade their first and last (nothing moves
            // when `kept == i`).
            swap(out, kept, i);
            kept += 1;
        }
    }
    // The freed slots hold zeros, not the removal marks: a zero the
    // optimiser cannot see through (as `super::zero_bytes`), or the loop
    // of whole-slot stores becomes a call of the memory-clearing routine.
    let zero = core::hint::black_box(0.0);
    for i in kept..len {
        let Some(s) = out.get_mut(i) else { break };
        *s = Segment {
            x0: zero,
            y0: zero,
            x1: zero,
            y1: zero,
            score: zero,
        };
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    /// A [`SegQ8`] widened to `i64`, for the oracle.
    struct Wide {
        x0: i64,
        y0: i64,
        x1: i64,
        y1: i64,
    }

    impl Wide {
        fn of(s: &SegQ8) -> Self {
            Self {
                x0: s.x0.into(),
                y0: s.y0.into(),
                x1: s.x1.into(),
                y1: s.y1.into(),
            }
        }
    }

    /// [`mergeable`] with every product in `i128`: the plain form of the
    /// tests, the oracle for the 32/64-bit one.
    fn mergeable_i128(p: &Params, a: &SegQ8, b: &SegQ8) -> bool {
        let (a, b) = (&Wide::of(a), &Wide::of(b));
        // The bounding-box pretest, in i64.
        let (mx, my) = (b.x0 + b.x1, b.y0 + b.y1);
        let gap = |m: i64, lo: i64, hi: i64| (2 * lo - m).max(m - 2 * hi).max(0);
        let dx = gap(mx, a.x0.min(a.x1), a.x0.max(a.x1));
        let dy = gap(my, a.y0.min(a.y1), a.y0.max(a.y1));
        let half_l1 = (b.x1 - b.x0).abs() + (b.y1 - b.y0).abs();
        if dx.max(dy) > 2 * p.merge_dc_q8.max(p.merge_de_q8) + half_l1 {
            return false;
        }
        let w = |s: &Wide| (i128::from(s.x1 - s.x0), i128::from(s.y1 - s.y0));
        let shrink = |(x, y): (i128, i128)| {
            let big = x.unsigned_abs().max(y.unsigned_abs());
            let shift = (128 - big.leading_zeros()).saturating_sub(20);
            (x >> shift, y >> shift)
        };
        let ((ax, ay), (bx, by)) = (w(a), w(b));
        let (la2, lb2) = (ax * ax + ay * ay, bx * bx + by * by);
        if la2 == 0 || lb2 == 0 {
            return false;
        }
        let ((sx, sy), (tx, ty)) = (shrink((ax, ay)), shrink((bx, by)));
        let dot = sx * tx + sy * ty;
        let cos2 = (i128::from(p.merge_cos_q30) * i128::from(p.merge_cos_q30)) >> 30;
        if dot * dot * (1 << 30) < cos2 * (sx * sx + sy * sy) * (tx * tx + ty * ty) {
            return false;
        }
        let dc = i128::from(p.merge_dc_q8) * 2;
        let far = |m: (i128, i128), s: &Wide, (vx, vy): (i128, i128), l2: i128| {
            let (ox, oy) = (m.0 - 2 * i128::from(s.x0), m.1 - 2 * i128::from(s.y0));
            let cross = ox * vy - oy * vx;
            cross * cross > dc * dc * l2
        };
        let mid = |s: &Wide| (i128::from(s.x0 + s.x1), i128::from(s.y0 + s.y1));
        if far(mid(b), a, (ax, ay), la2) || far(mid(a), b, (bx, by), lb2) {
            return false;
        }
        let t = |x: i64, y: i64| i128::from(x - a.x0) * ax + i128::from(y - a.y0) * ay;
        let (t0, t1) = (t(b.x0, b.y0), t(b.x1, b.y1));
        if t0.max(t1) >= 0 && t0.min(t1) <= la2 {
            return true;
        }
        let de2 = i128::from(p.merge_de_q8) * i128::from(p.merge_de_q8);
        let d2 = |x0: i64, y0: i64, x1: i64, y1: i64| {
            let (dx, dy) = (i128::from(x1 - x0), i128::from(y1 - y0));
            dx * dx + dy * dy
        };
        [(a.x0, a.y0), (a.x1, a.y1)]
            .iter()
            .any(|&(x, y)| d2(x, y, b.x0, b.y0) <= de2 || d2(x, y, b.x1, b.y1) <= de2)
    }

    /// The 32/64-bit form agrees with the `i128` one: on near-mergeable
    /// pairs (a segment and a perturbed copy, both anywhere in the
    /// coordinate range) under the default and the widest
    /// tolerances, a mix that both merges and does not.
    #[test]
    fn narrow_tests_equal_the_i128_form() {
        let widest = Config {
            merge_center_px: 64.0,
            merge_angle_deg: 89.0,
            merge_gap_px: 4096.0,
            ..Config::DEFAULT
        };
        let mut next = crate::xorshift64(0x2545_F491_4F6C_DD1D);
        let mut coord = |bits: u32| {
            let v = next();
            let m = (v >> 8) & ((1u64 << bits) - 1);
            if v & 1 == 0 { m as i64 } else { -(m as i64) }
        };
        let (mut yes, mut no) = (0, 0);
        for cfg in [Config::DEFAULT, widest] {
            let p = Params::new(&cfg);
            for k in 0..if cfg!(miri) { 200 } else { 200_000 } {
                let scale = 8 + (k % 17) as u32; // 2^8 .. 2^24
                let a = SegQ8::new(coord(scale), coord(scale), coord(scale), coord(scale));
                let jitter = scale.saturating_sub(6).max(4);
                let mut b = |v: i32| i64::from(v) + coord(jitter);
                let b = SegQ8::new(b(a.x0), b(a.y0), b(a.x1), b(a.y1));
                let got = mergeable(&p, &a, &b);
                assert_eq!(got, mergeable_i128(&p, &a, &b), "{a:?} {b:?}");
                if got {
                    yes += 1;
                } else {
                    no += 1;
                }
            }
        }
        let floor = if cfg!(miri) { 10 } else { 10_000 };
        assert!(yes > floor && no > floor, "merged {yes}, not {no}");
    }
}
