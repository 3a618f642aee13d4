//! Paper §3.1: hierarchical anchors, in integers (design §4-5).
//!
//! One streaming pass over the blurred image computes, row by row, the 2x2
//! gradient and thresholded L1 magnitude into a 3-row ring
//! ([`super::gradient`]), and for each pixel of the middle row:
//! * its **regular-anchor** state, by NMS ([`super::nms`]);
//! * where the NMS's gate allows it, the **static part of the
//!   aligned-anchor-group test** (eqs. 2-3 as the authors' code implements
//!   them): strict maximum across the edge, the T_anchor margin on one side,
//!   the strongest partner on each side along the edge, and the alignment of
//!   the centre with either partner. Only the "not already used" conditions
//!   depend on the processing order, so a pixel passing this test is a
//!   *candidate*, handed with its partners' neighbour codes to the ordering
//!   stage ([`super::order`]).
//!
//! Gradient classes are exact integer tests: the orientation boundaries
//! 22.5° and 67.5° are compared through `tan 22.5° = √2 - 1` in Q22 (an
//! integer gradient never lies within 1e-4° of them, far above the relative
//! error of the constant), and the alignment test `angle(g1, g2) ≤ T` is
//! `|g1 × g2|·cos T ≤ |g1 · g2|·sin T` with Q30 constants. Orientation
//! follows the paper (the official code's -90° bug is fixed, design §2): a
//! gradient with `gy < 0` is flipped, so `(0, -g)` reads 90°.

use crate::invariant::Invariant;
use crate::params::Params;
use crate::spec::{ACROSS, ALONG, Offset, Orientation, code_of};
use crate::target::SMALL;

use super::candidates::CandidateList;
use super::gradient::{Ring, gradient_row};
use super::nms::{Gate, Neighbourhood, OUTSIDE, at, flat, nms_branchy, unflat};
use super::packed::candidate::{self, Partners};
use super::state::{Class, ClassMap};

mod interior;
mod ties;

use ties::{thin_line_inside, wins_ties};

/// `round(tan 22.5° · 2^22)`. In Q22 every product below fits `i32`
/// (|gx|, |gy| <= 510, and 510·2^22 < 2^31), and the constant's error
/// (at most 255 units for |gx| = 510) stays far below the smallest gap an
/// integer gradient leaves to the 22.5° line (about 3,300 units, for
/// 408:169); `classes_match_float_orientation` checks every pair.
const TAN_22_5_Q22: i32 = 1_737_338;

/// The [`Orientation`] class of a gradient.
#[inline]
pub(crate) fn class_of(gx: i32, gy: i32) -> Orientation {
    let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
    let ax = x.abs();
    if (y << 22) <= ax * TAN_22_5_Q22 {
        Orientation::H
    } else if y * TAN_22_5_Q22 > ax << 22 {
        Orientation::V
    } else if x > 0 {
        Orientation::D45
    } else {
        Orientation::D135
    }
}

/// Whether the undirected angle between two gradients is within T.
#[inline]
pub(crate) fn aligned(p: &Params, a: (i32, i32), b: (i32, i32)) -> bool {
    let cross = i64::from(a.0) * i64::from(b.1) - i64::from(a.1) * i64::from(b.0);
    let dot = i64::from(a.0) * i64::from(b.0) + i64::from(a.1) * i64::from(b.1);
    cross.abs() * p.align_cos <= dot.abs() * p.align_sin
}

/// Counters of the anchor pass.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct AnchorStats {
    /// Candidates stored (after any eviction).
    pub candidates: usize,
    /// Candidates dropped for capacity.
    pub dropped: usize,
}

/// The anchor pass: writes none / regular [`Class`]es into `classes`, the raster-order
/// candidates into `cand`, their key histogram into `hist`, and half of
/// each thresholded magnitude into `mags` when it holds `w·h` bytes (the
/// walk's magnitude cache; empty without one). Returns the
/// number of candidates stored and dropped. `ROW`: the NMS strategy (the
/// detector passes [`crate::target::SIMD`]; the tests run both).
#[allow(clippy::too_many_arguments)]
pub(crate) fn classify<const ROW: bool>(
    p: &Params,
    blur: &[u8],
    w: usize,
    h: usize,
    classes: &mut ClassMap<'_>,
    srow: &mut [u8],
    rows: &mut [u16],
    cand: &mut [u32],
    keys: &mut [u8],
    hist: &mut [u32],
    thin_ring: &mut [u32],
    mags: &mut [u8],
) -> AnchorStats {
    let mut list = CandidateList::new(cand, keys, hist, thin_ring, w);
    let Some(mut ring) = Ring::new(rows, w) else {
        return AnchorStats::default();
    };
    for r in 0..=h {
        if r < h {
            gradient_row(&mut ring, blur, w, r, p.mag_min);
            // Magnitudes are even and at most 510 (`|gx| + |gy|` is twice
            // the larger diagonal difference): the half fits a byte.
            if let (Some(dst), Some(m)) = (mags.get_mut(r * w..(r + 1) * w), ring.m.get(r % 3)) {
                for (d, &v) in dst.iter_mut().zip(m.iter()) {
                    *d = (v >> 1) as u8;
                }
            }
        }
        if r >= 1 {
            let y = r - 1;
            let srow = srow.get_mut(..w).or_broken(&mut []);
            classify_row::<ROW>(p, blur, &ring, w, h, y, srow, &mut list);
            classes.write_row(y, srow);
        }
    }
    AnchorStats {
        candidates: list.len(),
        dropped: list.dropped(),
    }
}

/// A neighbourhood table as flat 3x3 indices (evaluated at compile time only).
#[allow(clippy::indexing_slicing)] // const evaluation: an out-of-range index is a compile error
const fn flatten6(t: &[Offset; 6]) -> [u8; 6] {
    let mut out = [0u8; 6];
    let mut i = 0;
    while i < 6 {
        out[i] = flat(t[i].0, t[i].1) as u8;
        i += 1;
    }
    out
}

const ACROSS_FLAT: [[u8; 6]; 4] = [
    flatten6(&ACROSS[0]),
    flatten6(&ACROSS[1]),
    flatten6(&ACROSS[2]),
    flatten6(&ACROSS[3]),
];
// The flat tables as statics, for [`candidate_any`]'s run-time index (a
// `const` indexed at run time could be emitted once per use).
static ACROSS_TABLES: [[u8; 6]; 4] = ACROSS_FLAT;
static ALONG_TABLES: [[u8; 6]; 4] = ALONG_FLAT;

const ALONG_FLAT: [[u8; 6]; 4] = [
    flatten6(&ALONG[0]),
    flatten6(&ALONG[1]),
    flatten6(&ALONG[2]),
    flatten6(&ALONG[3]),
];

/// Classifies row `y` (rows `y-1..=y+1` are in the ring) into `srow`, one
/// [`Class`] byte per pixel, and pushes its candidates.
#[allow(clippy::too_many_arguments)]
fn classify_row<const ROW: bool>(
    p: &Params,
    blur: &[u8],
    ring: &Ring<'_>,
    w: usize,
    h: usize,
    y: usize,
    srow: &mut [u8],
    list: &mut CandidateList<'_>,
) {
    let slot = |dy: i32| -> Option<usize> {
        let yy = y as i64 + i64::from(dy);
        (yy >= 0 && (yy as usize) < h).then_some(yy as usize % 3)
    };
    fn row<'r>(rows: &'r [&mut [u16]; 3], slot: Option<usize>) -> &'r [u16] {
        slot.and_then(|s| rows.get(s)).map_or(&[], |r| &**r)
    }
    let slots = [slot(-1), slot(0), slot(1)];
    let rows_m = slots.map(|s| row(&ring.m, s));
    let rows_gx = slots.map(|s| row(&ring.gx, s));
    let rows_gy = slots.map(|s| row(&ring.gy, s));
    let ctx = RowCtx {
        p,
        blur,
        w,
        h,
        y,
        rows_m,
        rows_gx,
        rows_gy,
        gate: p.gate(),
    };
    let interior_y = y >= 1 && y + 1 < h;
    super::zero_bytes(srow); // Class::None
    if !interior_y || w < 3 {
        for (x, s) in srow.iter_mut().enumerate() {
            ctx.border(list, x, s);
        }
        return;
    }
    // Interior row: column 0, the interior columns, column w - 1, in that
    // order (candidates are pushed in raster order).
    let Some((first, rest)) = srow.split_first_mut() else {
        return;
    };
    let Some((last, inner)) = rest.split_last_mut() else {
        return;
    };
    ctx.border(list, 0, first);
    if ROW {
        ctx.row_pass(list, inner);
    } else {
        ctx.pixel_pass(list, inner);
    }
    ctx.border(list, w - 1, last);
}

impl RowCtx<'_> {
    /// The pixel `x` of a border row or column, with a neighbour beyond the
    /// image (`OUTSIDE` marks those): no NMS, only the group test.
    #[inline]
    fn border(&self, list: &mut CandidateList<'_>, x: usize, s: &mut u8) {
        let ([_, m_cur, _], [_, gx_cur, _], [_, gy_cur, _]) =
            (self.rows_m, self.rows_gx, self.rows_gy);
        let (Some(&mc), Some(&gx), Some(&gy)) = (m_cur.get(x), gx_cur.get(x), gy_cur.get(x)) else {
            return;
        };
        if mc == 0 {
            return;
        }
        let g = (i32::from(gx as i16), i32::from(gy as i16));
        let nb: Neighbourhood = core::array::from_fn(|k| {
            let (dx, dy) = unflat(k);
            let xx = x as i64 + i64::from(dx);
            if xx < 0 || xx as usize >= self.w {
                return OUTSIDE;
            }
            self.rows_m
                .get((dy + 1) as usize)
                .and_then(|r| r.get(xx as usize))
                .copied()
                // A row outside the image is empty: outside.
                .unwrap_or(OUTSIDE)
        });
        *s = Class::None as u8; // no NMS at the border
        self.group::<true>(list, x, mc, g, &nb);
    }
}

/// What [`classify_row`] shares with each pixel.
struct RowCtx<'a> {
    p: &'a Params,
    blur: &'a [u8],
    w: usize,
    h: usize,
    y: usize,
    rows_m: [&'a [u16]; 3],
    rows_gx: [&'a [u16]; 3],
    rows_gy: [&'a [u16]; 3],
    /// [`Params::gate`], once per row.
    gate: Gate,
}

impl RowCtx<'_> {
    /// The gradient twice as far from `x` as the neighbour at flat index
    /// `k`, `None` outside the image (rare: only for a centre equal to a
    /// neighbour, or with a side all zero, under `Maxima::Symmetric`).
    fn far(&self, x: usize, k: usize) -> Option<(i32, i32)> {
        let (dx, dy) = unflat(k);
        let xx = x as i64 + 2 * i64::from(dx);
        let yy = self.y as i64 + 2 * i64::from(dy);
        if xx < 0 || yy < 0 || xx as usize >= self.w || yy as usize >= self.h {
            return None;
        }
        Some(super::gradient::gradient_at(
            self.blur,
            self.w,
            xx as usize,
            yy as usize,
        ))
    }

    /// Gradient of the neighbour at flat index `k` of `x` (rare: only for
    /// candidates' partners).
    fn grad(&self, x: usize, k: usize) -> (i32, i32) {
        let (dx, dy) = unflat(k);
        let xx = (x as i64 + i64::from(dx)).max(0) as usize;
        let r = (dy + 1) as usize;
        let g = |rows: &[&[u16]; 3]| {
            i32::from(rows.get(r).and_then(|r| r.get(xx)).copied().or_broken(0) as i16)
        };
        (g(&self.rows_gx), g(&self.rows_gy))
    }

    /// NMS state of the interior pixel `x` (magnitude `mc > 0`), and its
    /// group-candidate test when a necessary condition of that test holds
    /// (most pixels stop there).
    #[inline(always)]
    fn interior(
        &self,
        list: &mut CandidateList<'_>,
        x: usize,
        s: &mut u8,
        mc: u16,
        g: (i32, i32),
        nb: &Neighbourhood,
    ) {
        let (regular, may_group) = nms_branchy(mc, g, self.gate, nb);
        *s = u8::from(regular) * Class::Regular as u8;
        if may_group {
            self.group_interior(list, x, mc, g);
        }
    }

    /// The group-candidate test of the interior pixel `x`. Out of line: it
    /// re-reads the neighbourhood, so the NMS loop keeps only what it needs
    /// in registers.
    #[inline(never)]
    fn group_interior(&self, list: &mut CandidateList<'_>, x: usize, mc: u16, g: (i32, i32)) {
        self.group_at(list, x, mc, g);
    }

    /// [`RowCtx::group_interior`], inlined (the row strategy's second pass
    /// has nothing else live).
    #[inline(always)]
    fn group_at(&self, list: &mut CandidateList<'_>, x: usize, mc: u16, g: (i32, i32)) {
        let span = x.wrapping_sub(1)..x.wrapping_add(2);
        let [up, cur, down] = self.rows_m;
        if let (Some(&[a0, a1, a2]), Some(&[b0, _, b2]), Some(&[c0, c1, c2])) =
            (up.get(span.clone()), cur.get(span.clone()), down.get(span))
        {
            let nb = [a0, a1, a2, b0, mc, b2, c0, c1, c2];
            self.group::<false>(list, x, mc, g, &nb);
        }
    }

    /// The group-candidate test of pixel `x`; pushes a candidate. `EDGE`
    /// as in [`group_candidate`].
    #[inline(always)]
    fn group<const EDGE: bool>(
        &self,
        list: &mut CandidateList<'_>,
        x: usize,
        mc: u16,
        (gx, gy): (i32, i32),
        nb: &Neighbourhood,
    ) {
        let found = if SMALL {
            self.candidate_small(x, mc, (gx, gy), nb)
        } else {
            group_candidate::<EDGE>(
                self.p,
                mc,
                gx,
                gy,
                nb,
                |k| self.grad(x, k),
                |k| self.far(x, k),
            )
        };
        if let Some(pt) = found {
            list.push(candidate::new(self.y * self.w + x, pt), mc.min(255) as u8);
        }
    }

    /// The group test in a build for size ([`SMALL`]): one out-of-line
    /// copy for every position and class ([`candidate_any`]).
    #[inline(never)]
    fn candidate_small(
        &self,
        x: usize,
        mc: u16,
        g: (i32, i32),
        nb: &Neighbourhood,
    ) -> Option<Partners> {
        candidate_any(self.p, mc, g, nb, |k| self.grad(x, k), |k| self.far(x, k))
    }
}

/// [`group_candidate`] with the class's tables read at run time and the
/// border-safe test: the same result for an interior pixel, which has no
/// [`OUTSIDE`] neighbour (`EDGE` only skips that check, and takes the
/// maximum across the edge in one comparison, which is the same test).
/// Checked against both forms by `candidate_any_equals_the_per_class_forms`.
fn candidate_any(
    p: &Params,
    mc: u16,
    (gx, gy): (i32, i32),
    nb: &Neighbourhood,
    grad: impl Fn(usize) -> (i32, i32),
    far: impl Fn(usize) -> Option<(i32, i32)>,
) -> Option<Partners> {
    let c = class_of(gx, gy) as usize;
    let tables = (
        ACROSS_TABLES.get(c).copied().or_broken([0; 6]),
        ALONG_TABLES.get(c).copied().or_broken([0; 6]),
    );
    candidate_with::<true>(p, mc, tables, (gx, gy), nb, grad, far)
}

/// The order-independent part of the group test for a pixel with
/// magnitude `mc > 0` and gradient `(gx, gy)`; `grad` gives a neighbour's
/// gradient by flat index. Dispatches on the orientation class so that each
/// class's neighbour tables are compile-time constants. `EDGE`: the pixel
/// may have [`OUTSIDE`] neighbours (false for interior pixels, whose tests
/// then skip that check).
#[inline(always)]
fn group_candidate<const EDGE: bool>(
    p: &Params,
    mc: u16,
    gx: i32,
    gy: i32,
    nb: &Neighbourhood,
    grad: impl Fn(usize) -> (i32, i32),
    far: impl Fn(usize) -> Option<(i32, i32)>,
) -> Option<Partners> {
    use Orientation as O;
    const D45: usize = O::D45 as usize;
    const V: usize = O::V as usize;
    const D135: usize = O::D135 as usize;
    const H: usize = O::H as usize;
    match class_of(gx, gy) {
        O::D45 => candidate_of_class::<D45, EDGE>(p, mc, (gx, gy), nb, grad, far),
        O::V => candidate_of_class::<V, EDGE>(p, mc, (gx, gy), nb, grad, far),
        O::D135 => candidate_of_class::<D135, EDGE>(p, mc, (gx, gy), nb, grad, far),
        O::H => candidate_of_class::<H, EDGE>(p, mc, (gx, gy), nb, grad, far),
    }
}

/// [`group_candidate`] for the orientation class `C` (an [`Orientation`]
/// as `usize`, so that its tables are constants).
#[inline(always)]
fn candidate_of_class<const C: usize, const EDGE: bool>(
    p: &Params,
    mc: u16,
    gc: (i32, i32),
    nb: &Neighbourhood,
    grad: impl Fn(usize) -> (i32, i32),
    far: impl Fn(usize) -> Option<(i32, i32)>,
) -> Option<Partners> {
    // Evaluated at compile time: an out-of-range C would not compile.
    #[allow(clippy::indexing_slicing)]
    let tables = const { (ACROSS_FLAT[C], ALONG_FLAT[C]) };
    candidate_with::<EDGE>(p, mc, tables, gc, nb, grad, far)
}

/// The body of [`candidate_of_class`], for the class whose flat neighbour
/// tables (across, along) are `tables`.
#[inline(always)]
fn candidate_with<const EDGE: bool>(
    p: &Params,
    mc: u16,
    (across, along): ([u8; 6], [u8; 6]),
    gc: (i32, i32),
    nb: &Neighbourhood,
    grad: impl Fn(usize) -> (i32, i32),
    far: impl Fn(usize) -> Option<(i32, i32)>,
) -> Option<Partners> {
    let (best_a, best_b) = across_maxima::<EDGE>(p, mc, across, nb)?;
    // A side with no nonzero neighbour: the authors' test refuses it;
    // under `Maxima::Symmetric` it may be the exactly-zero inside of a thin
    // line (`thin_line_inside`). Only where all six neighbours exist.
    if best_a == 0 || best_b == 0 {
        let interior = !EDGE || across.iter().all(|&k| at(nb, k) != OUTSIDE);
        let [_, a_mid, _, _, b_mid, _] = across;
        let thin = |mid: u8| {
            interior
                && p.tie != 0
                && grad(usize::from(mid)) == (0, 0)
                && thin_line_inside(p, mc, gc, far(usize::from(mid)))
        };
        if (best_a == 0 && !thin(a_mid)) || (best_b == 0 && !thin(b_mid)) {
            return None;
        }
    }
    // A neighbour equal to the centre: settled by `wins_ties`.
    if p.tie != 0 && (best_a == mc || best_b == mc) && !wins_ties(p, mc, across, nb, &far) {
        return None;
    }
    let mci = i32::from(mc);
    if mci - i32::from(best_a) < p.margin && mci - i32::from(best_b) < p.margin {
        return None;
    }
    let (j, k) = strongest_along::<EDGE>(along, nb)?;
    if aligned(p, gc, grad(usize::from(j.1))) || aligned(p, gc, grad(usize::from(k.1))) {
        let code = |k: u8| {
            let (dx, dy) = unflat(usize::from(k));
            code_of(dx, dy)
        };
        Some(Partners {
            j: code(j.1),
            k: code(k.1),
        })
    } else {
        None
    }
}

/// The largest neighbour magnitude on each side across the edge
/// (neighbours `across`, three a side), or `None` when the centre `mc` is
/// not a maximum across the edge: strict, or under `Maxima::Symmetric` at
/// least equal to every neighbour (then winning each equal one is
/// [`candidate_with`]'s test). `EDGE`: the walk stops at the image border.
#[inline(always)]
fn across_maxima<const EDGE: bool>(
    p: &Params,
    mc: u16,
    across: [u8; 6],
    nb: &Neighbourhood,
) -> Option<(u16, u16)> {
    if EDGE {
        let (mut best_a, mut best_b) = (0u16, 0u16);
        for (i, &k) in across.iter().enumerate() {
            let mq = at(nb, k);
            if mq == OUTSIDE {
                break;
            }
            let b = if i < 3 { &mut best_a } else { &mut best_b };
            if mq > *b {
                *b = mq;
            }
            if mc + p.tie <= mq {
                return None;
            }
        }
        Some((best_a, best_b))
    } else {
        // No border: the same test as one comparison with the maximum
        // (fewer unpredictable branches).
        let [a0, a1, a2, b0, b1, b2] = across.map(|k| at(nb, k));
        let (best_a, best_b) = (a0.max(a1).max(a2), b0.max(b1).max(b2));
        if mc + p.tie <= best_a.max(best_b) {
            return None;
        }
        Some((best_a, best_b))
    }
}

/// The strongest nonzero partner on each side along the edge (neighbours
/// `along`, three a side), as (magnitude, flat index); `None` when a side
/// has none. `EDGE`: the walk stops at the image border.
#[inline(always)]
fn strongest_along<const EDGE: bool>(
    along: [u8; 6],
    nb: &Neighbourhood,
) -> Option<((u16, u8), (u16, u8))> {
    let (mut j, mut k) = ((0u16, 0u8), (0u16, 0u8));
    for (i, &q) in along.iter().enumerate() {
        let mq = at(nb, q);
        if EDGE && mq == OUTSIDE {
            break;
        }
        let b = if i < 3 { &mut j } else { &mut k };
        if mq > b.0 {
            *b = (mq, q);
        }
    }
    if j.0 == 0 || k.0 == 0 {
        return None;
    }
    Some((j, k))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;
    use crate::stage::nms::nms_i16;

    /// The integer classes equal the float classes of the reference
    /// orientation (f32 `atan2f`, f64 scaling) for every gradient pair.
    #[test]
    #[cfg_attr(miri, ignore = "exhaustive sweep; too slow under Miri")]
    fn classes_match_float_orientation() {
        for gy in -510i32..=510 {
            for gx in -510i32..=510 {
                let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
                let o = (f64::from(libm::atan2f(y as f32, x as f32)) * 180.0
                    / core::f64::consts::PI) as f32;
                let want = if (22.5..67.5).contains(&o) {
                    0
                } else if (67.5..112.5).contains(&o) {
                    1
                } else if (112.5..157.5).contains(&o) {
                    2
                } else {
                    3
                };
                assert_eq!(class_of(gx, gy) as usize, want, "({gx}, {gy}) o = {o}");
            }
        }
    }

    /// The NMS's gate is a necessary condition of the group test: every
    /// interior pixel that [`group_candidate`] accepts has the gate set by
    /// both NMS instances (the anchor pass runs the group test only there).
    /// Random 3x3 magnitude neighbourhoods and gradients, with partners'
    /// gradients equal to the centre's (always aligned) or random.
    #[test]
    fn nms_gate_is_necessary_for_a_group() {
        use crate::Config;
        let mut next = crate::xorshift64(0x9E37_79B9_7F4A_7C15);
        let cases: u32 = if cfg!(miri) { 200 } else { 400_000 };
        let mut accepted = 0;
        for case in 0..cases {
            let mut cfg = [Config::OFFICIAL, Config::PAPER, Config::DEFAULT][case as usize % 3];
            // The default margin, none, or a wide one.
            cfg.anchor_margin = [3, 0, 3, 12][(case / 3 % 4) as usize];
            let p = Params::new(&cfg);
            let Some((gx, gy, mc, nb)) = random_pixel(&mut next) else {
                continue;
            };
            let random_partners = case.is_multiple_of(3);
            let partner = ((next() % 1021) as i32 - 510, (next() % 1021) as i32 - 510);
            let grad = |_k: usize| if random_partners { partner } else { (gx, gy) };
            // The pixels two steps away: below the centre (plateaus win),
            // or the far edge of a thin line (opposite gradient).
            let far_g = ((next() % 1021) as i32 - 510, (next() % 1021) as i32 - 510);
            let far = |k: usize| {
                Some(if k.is_multiple_of(2) {
                    (-gx, -gy)
                } else {
                    far_g
                })
            };
            if group_candidate::<false>(&p, mc, gx, gy, &nb, grad, far).is_some() {
                accepted += 1;
                let (_, gate16) = nms_i16(mc, (gx, gy), p.gate(), &nb);
                let (_, gate_branchy) = nms_branchy(mc, (gx, gy), p.gate(), &nb);
                assert!(
                    gate16 && gate_branchy,
                    "gradient ({gx}, {gy}), neighbourhood {nb:?}"
                );
            }
        }
        std::eprintln!("{accepted} group candidates over {cases} neighbourhoods");
        assert!(accepted * 20 >= cases, "too few candidates: {accepted}");
    }

    /// A random gradient `(gx, gy)` with its magnitude and a neighbourhood
    /// mostly below it (so that many pixels pass the group test); `None`
    /// for a zero gradient.
    fn random_pixel(next: &mut impl FnMut() -> u64) -> Option<(i32, i32, u16, Neighbourhood)> {
        let gx = (next() % 1021) as i32 - 510;
        let gy = (next() % 1021) as i32 - 510;
        let mc = (gx.abs() + gy.abs()) as u16;
        if mc == 0 {
            return None;
        }
        let mut nb: Neighbourhood =
            core::array::from_fn(|_| (next() % (u64::from(mc) + 40)) as u16);
        for v in &mut nb {
            match next() % 10 {
                0 | 1 => *v = 0,
                // Equal neighbours, for the tie rules.
                2 => *v = mc,
                _ => {}
            }
        }
        nb[4] = mc;
        Some((gx, gy, mc, nb))
    }

    /// The size build's single form of the group test ([`candidate_any`])
    /// gives the per-class forms' results: `group_candidate::<false>` on
    /// interior neighbourhoods, `::<true>` on ones with pixels outside the
    /// image, with partner gradients that depend on the neighbour.
    #[test]
    fn candidate_any_equals_the_per_class_forms() {
        use crate::Config;
        let mut next = crate::xorshift64(0xA076_1D64_78BD_642F);
        let cases: u32 = if cfg!(miri) { 200 } else { 400_000 };
        let (mut found, mut edges) = (0, 0);
        for case in 0..cases {
            let cfg = [Config::OFFICIAL, Config::PAPER, Config::DEFAULT][(case % 3) as usize];
            let p = Params::new(&cfg);
            let Some((gx, gy, mc, mut nb)) = random_pixel(&mut next) else {
                continue;
            };
            let edge = case.is_multiple_of(4);
            if edge {
                // One side of the 3x3 block outside the image, or (to
                // reach the tests beyond the first outside neighbour) one
                // neighbour.
                let side = (next() % 12) as usize;
                for (k, v) in nb.iter_mut().enumerate() {
                    let (col, row) = (k % 3, k / 3);
                    let out = match side {
                        0..4 => [col == 0, col == 2, row == 0, row == 2][side],
                        _ => k != 4 && k == side - 4 + usize::from(side - 4 >= 4),
                    };
                    if out {
                        *v = OUTSIDE;
                    }
                }
            }
            let partners: [(i32, i32); 9] = core::array::from_fn(|_| {
                ((next() % 1021) as i32 - 510, (next() % 1021) as i32 - 510)
            });
            let grad = |k: usize| {
                if k.is_multiple_of(2) {
                    (gx, gy)
                } else {
                    partners[k]
                }
            };
            let fars: [Option<(i32, i32)>; 9] = core::array::from_fn(|k| match k % 3 {
                0 => None,
                1 => Some((-gx, -gy)),
                _ => Some(((next() % 41) as i32 - 20, (next() % 41) as i32 - 20)),
            });
            let far = |k: usize| fars[k];
            let code = |r: Option<Partners>| r.map(|pt| (pt.j, pt.k));
            let want = if edge {
                code(group_candidate::<true>(&p, mc, gx, gy, &nb, grad, far))
            } else {
                code(group_candidate::<false>(&p, mc, gx, gy, &nb, grad, far))
            };
            let got = code(candidate_any(&p, mc, (gx, gy), &nb, grad, far));
            assert_eq!(
                got, want,
                "gradient ({gx}, {gy}), neighbourhood {nb:?}, edge {edge}"
            );
            if got.is_some() {
                found += 1;
                edges += usize::from(edge);
            }
        }
        // Under Miri (200 cases) too few reach an edge candidate to count.
        let edges_seen = cfg!(miri) || edges > 100;
        assert!(
            found * 20 >= cases && edges_seen,
            "{found} candidates, {edges} at an edge"
        );
    }

    /// The two NMS strategies of the anchor pass (a vectorised pass over
    /// each row, and pixel by pixel skipping zero magnitudes, chosen by
    /// target) give the same classes, candidates (in the
    /// same order, with the same evictions) and counters, on random and
    /// structured images of many shapes and on every profile.
    #[test]
    fn row_and_pixel_strategies_agree() {
        use crate::Config;
        let mut next = crate::xorshift64(0x2545_F491_4F6C_DD1D);
        let cases = if cfg!(miri) { 6 } else { 400 };
        let mut candidates_seen = 0;
        for case in 0..cases {
            // Every eighth image wider than the row pass's gate spans.
            let (w, h) = if case % 8 == 7 {
                (250 + (next() % 400) as usize, 1 + (next() % 6) as usize)
            } else {
                (1 + (next() % 40) as usize, 1 + (next() % 30) as usize)
            };
            let kind = next() % 3;
            let blur: std::vec::Vec<u8> = (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as u64, (i / w) as u64);
                    match kind {
                        0 => next() as u8,
                        // Edges: a ramp plus noise, so many pixels tie.
                        1 => ((x * 37 + y * 11) % 256) as u8 ^ (next() % 4) as u8,
                        _ => {
                            if (x + 2 * y) % 7 < 3 {
                                200
                            } else {
                                40
                            }
                        }
                    }
                })
                .collect();
            let cfg = match case % 3 {
                0 => Config::OFFICIAL,
                1 => Config::PAPER,
                _ => Config {
                    magnitude_threshold: 0.0,
                    ..Config::OFFICIAL
                },
            };
            let p = Params::new(&cfg);
            // A small candidate capacity now and then exercises eviction.
            let cap = if case % 4 == 0 { 1 + w * h / 20 } else { w * h };
            let run = |row: bool| {
                let mut classes = std::vec![0u8; crate::stage::state::row_bytes(w, 2) * h];
                let mut srow = std::vec![0u8; w];
                let mut rows = std::vec![0u16; 9 * w];
                let mut cand = std::vec![0u32; cap];
                let mut keys = std::vec![0u8; cap];
                let mut hist = std::vec![0u32; 256];
                let mut ring = std::vec![0u32; 3 * w.div_ceil(32)];
                let classify = if row {
                    classify::<true>
                } else {
                    classify::<false>
                };
                let st = classify(
                    &p,
                    &blur,
                    w,
                    h,
                    &mut ClassMap::new(&mut classes, w),
                    &mut srow,
                    &mut rows,
                    &mut cand,
                    &mut keys,
                    &mut hist,
                    &mut ring,
                    &mut [],
                );
                cand.truncate(st.candidates);
                keys.truncate(st.candidates);
                (classes, cand, keys, hist, st.candidates, st.dropped)
            };
            let (a, b) = (run(true), run(false));
            assert_eq!(a, b, "case {case}: {w}x{h}, kind {kind}");
            candidates_seen += a.4;
        }
        // The comparison means something only if candidates were produced:
        // on average at least five per image (Miri runs fewer images).
        std::eprintln!("{candidates_seen} candidates over {cases} images");
        assert!(
            candidates_seen >= 5 * cases,
            "too few candidates to compare: {candidates_seen} over {cases} images"
        );
    }
}
