//! Paper §3.1: hierarchical anchors, in integers.
//!
//! One streaming pass over the blurred image computes, row by row, the 2x2
//! gradient and thresholded L1 magnitude into a 3-row ring, and for each
//! pixel of the middle row:
//! * the **NMS** test of regular anchors, in exact rational form
//!   (`m·|gx| > |gy|·m(P1) + (|gx| - |gy|)·m(P2)` and the like; the float
//!   reference uses f32 weights, which can differ on exact ties);
//! * the **static part of the aligned-anchor-group test** (eqs. 2-3 as the
//!   authors' code implements them): strict maximum across the edge, the
//!   T_anchor margin on one side, the strongest partner on each side along
//!   the edge, and the alignment of the centre with either partner. Only the
//!   "not already used" conditions depend on the processing order, so a
//!   pixel passing this test is a *candidate*, stored with its partners'
//!   neighbour codes.
//!
//! Candidates are then counting-sorted by `min(m, 255)`, descending, ties in
//! raster order (the paper's pseudo-sort), and extracted greedily: a
//! candidate becomes a group unless its centre or a partner already belongs
//! to one.
//!
//! Gradient classes are exact integer tests: the orientation boundaries
//! 22.5° and 67.5° are compared through `tan 22.5° = √2 - 1` in Q24 (an
//! integer gradient never lies within 1e-4° of them, far above the 3e-8
//! relative error of the constant), and the alignment test
//! `angle(g1, g2) ≤ T` is `|g1 × g2|·cos T ≤ |g1 · g2|·sin T` with Q30
//! constants. Orientation follows the paper (the official code's -90° bug is
//! fixed): a gradient with `gy < 0` is flipped, so `(0, -g)` reads 90°.

use core::num::NonZeroUsize;

use crate::num::trig::atan2;
use crate::params::Params;

/// Pixel state byte: bits 0-1 hold the class.
pub(crate) const CLASS_MASK: u8 = 0b11;
/// Neither an anchor nor in a group.
pub(crate) const NONE: u8 = 0;
/// NMS pixel not in any group (a regular anchor).
pub(crate) const REGULAR: u8 = 1;
/// Centre of an aligned anchor group.
pub(crate) const CENTRE: u8 = 2;
/// Partner of a group; bits 2-4 hold the neighbour code of its centre.
pub(crate) const MEMBER: u8 = 3;
/// On a centre: the group has been linked.
pub(crate) const LINKED: u8 = 1 << 5;
/// In the current linking's visited set.
pub(crate) const VISITED: u8 = 1 << 6;

/// Neighbour codes 0..8: (dx, dy).
pub(crate) const NEIGHBOURS: [(i32, i32); 8] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
];

/// The neighbour code of `(dx, dy)` (both in -1..=1, not both 0).
const fn code_of(dx: i32, dy: i32) -> u8 {
    match (dx, dy) {
        (1, 0) => 0,
        (1, 1) => 1,
        (0, 1) => 2,
        (-1, 1) => 3,
        (-1, 0) => 4,
        (-1, -1) => 5,
        (0, -1) => 6,
        _ => 7,
    }
}

/// Across-edge neighbourhoods by class (D45, V, D135, H): side A, side B.
const ACROSS: [[(i32, i32); 6]; 4] = [
    [(0, -1), (-1, -1), (-1, 0), (0, 1), (1, 1), (1, 0)],
    [(1, -1), (0, -1), (-1, -1), (-1, 1), (0, 1), (1, 1)],
    [(-1, 0), (-1, 1), (0, 1), (1, 0), (1, -1), (0, -1)],
    [(-1, -1), (-1, 0), (-1, 1), (1, 1), (1, 0), (1, -1)],
];

/// Along-edge neighbourhoods by the same classes: side J, side K.
const ALONG: [[(i32, i32); 6]; 4] = [
    [(-1, 0), (-1, 1), (0, 1), (1, 0), (1, -1), (0, -1)],
    [(-1, -1), (-1, 0), (-1, 1), (1, 1), (1, 0), (1, -1)],
    [(0, -1), (-1, -1), (-1, 0), (0, 1), (1, 1), (1, 0)],
    [(1, -1), (0, -1), (-1, -1), (-1, 1), (0, 1), (1, 1)],
];

/// `round(tan 22.5° · 2^22)`. In Q22 every product below fits `i32`
/// (|gx|, |gy| <= 510, and 510·2^22 < 2^31), and the constant's error
/// (at most 255 units for |gx| = 510) stays far below the smallest gap an
/// integer gradient leaves to the 22.5° line (about 3,300 units, for
/// 408:169); `classes_match_float_orientation` checks every pair.
const TAN_22_5_Q22: i32 = 1_737_338;

/// Orientation class of a gradient: 0 = D45 [22.5°, 67.5°), 1 = V
/// [67.5°, 112.5°), 2 = D135 [112.5°, 157.5°), 3 = H (the rest).
#[inline]
pub(crate) fn class_of(gx: i32, gy: i32) -> usize {
    let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
    let ax = x.abs();
    if (y << 22) <= ax * TAN_22_5_Q22 {
        3
    } else if y * TAN_22_5_Q22 > ax << 22 {
        1
    } else if x > 0 {
        0
    } else {
        2
    }
}

/// Whether the undirected angle between two gradients is within T.
#[inline]
pub(crate) fn aligned(p: &Params, a: (i32, i32), b: (i32, i32)) -> bool {
    let cross = i64::from(a.0) * i64::from(b.1) - i64::from(a.1) * i64::from(b.0);
    let dot = i64::from(a.0) * i64::from(b.0) + i64::from(a.1) * i64::from(b.1);
    cross.abs() * p.align_cos <= dot.abs() * p.align_sin
}

/// The level-line direction of a gradient: orientation (folded to
/// [0°, 180°]) minus 90°, as a full-turn binary angle.
#[inline]
pub(crate) fn level_line(gx: i32, gy: i32) -> u32 {
    let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
    atan2(i64::from(y), i64::from(x)).wrapping_sub(crate::num::trig::DEG_90)
}

/// The 3-row gradient ring: thresholded magnitude and gradient components
/// of rows `r % 3`.
pub(crate) struct Ring<'a> {
    m: [&'a mut [u16]; 3],
    gx: [&'a mut [u16]; 3],
    gy: [&'a mut [u16]; 3],
}

impl<'a> Ring<'a> {
    /// Splits `rows` (at least `9·w` values) into the ring.
    pub fn new(rows: &'a mut [u16], w: usize) -> Option<Self> {
        let rows = rows.get_mut(..9 * w)?;
        let (m, rest) = rows.split_at_mut_checked(3 * w)?;
        let (gx, gy) = rest.split_at_mut_checked(3 * w)?;
        fn split3(s: &mut [u16], w: usize) -> Option<[&mut [u16]; 3]> {
            let (a, bc) = s.split_at_mut_checked(w)?;
            let (b, c) = bc.split_at_mut_checked(w)?;
            Some([a, b, c])
        }
        Some(Self {
            m: split3(m, w)?,
            gx: split3(gx, w)?,
            gy: split3(gy, w)?,
        })
    }
}

/// Computes gradient row `y` of the `w`-wide blurred image into ring slot
/// `y % 3`, and `min(m, 255)` into `mag8` (that row's slice; may be empty).
fn gradient_row(
    ring: &mut Ring<'_>,
    blur: &[u8],
    w: usize,
    y: usize,
    mag_min: u16,
    mag8: &mut [u8],
) {
    let slot = y % 3;
    let cur = blur.get(y * w..(y + 1) * w).unwrap_or(&[]);
    let prev = blur
        .get(y.saturating_sub(1) * w..(y.saturating_sub(1) + 1) * w)
        .unwrap_or(&[]);
    let (Some(m), Some(gxr), Some(gyr)) = (
        ring.m.get_mut(slot),
        ring.gx.get_mut(slot),
        ring.gy.get_mut(slot),
    ) else {
        return;
    };
    let mut left_c = i32::from(cur.first().copied().unwrap_or(0));
    let mut left_p = i32::from(prev.first().copied().unwrap_or(0));
    for ((((&c, &p), mo), gxo), gyo) in cur
        .iter()
        .zip(prev)
        .zip(m.iter_mut())
        .zip(gxr.iter_mut())
        .zip(gyr.iter_mut())
    {
        let (c, p) = (i32::from(c), i32::from(p));
        let gx = c + p - left_c - left_p;
        let gy = c + left_c - p - left_p;
        let mag = (gx.abs() + gy.abs()) as u16;
        *mo = if mag < mag_min { 0 } else { mag };
        *gxo = gx as u16;
        *gyo = gy as u16;
        left_c = c;
        left_p = p;
    }
    for (o, &v) in mag8.iter_mut().zip(m.iter()) {
        *o = v.min(255) as u8;
    }
}

/// The gradient pass alone (benchmark floor): sum of thresholded magnitudes.
#[cfg(any(test, feature = "_unstable-hooks"))]
pub(crate) fn magnitude_sum(p: &Params, blur: &[u8], w: usize, h: usize, rows: &mut [u16]) -> u64 {
    let Some(mut ring) = Ring::new(rows, w) else {
        return 0;
    };
    let mut sum = 0u64;
    for y in 0..h {
        gradient_row(&mut ring, blur, w, y, p.mag_min, &mut []);
        if let Some(m) = ring.m.get(y % 3) {
            sum += m.iter().map(|&v| u64::from(v)).sum::<u64>();
        }
    }
    sum
}

/// Result of the static group test for one pixel.
#[derive(Clone, Copy)]
struct Partners {
    j: u8,
    k: u8,
}

/// Counters of the anchor pass.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct AnchorStats {
    /// Candidates stored (after any eviction).
    pub candidates: usize,
    /// Candidates dropped for capacity.
    pub dropped: usize,
}

/// The raster-order candidate list with eviction of the weakest key when full.
struct CandidateList<'a> {
    list: &'a mut [u32],
    len: usize,
    hist: &'a mut [u32],
    /// Candidates with key <= floor are dropped.
    floor: i32,
    dropped: usize,
}

impl CandidateList<'_> {
    /// Appends a candidate; when the list is full, evicts (see
    /// [`CandidateList::push_evicting`]).
    #[inline(always)]
    fn push(&mut self, entry: u32, key: u8, keys: impl Fn(u32) -> u8) {
        if i32::from(key) > self.floor && self.append(entry, key) {
            return;
        }
        self.push_evicting(entry, key, keys);
    }

    /// Stores a candidate and counts its key; false when the list is full.
    #[inline(always)]
    fn append(&mut self, entry: u32, key: u8) -> bool {
        let Some(slot) = self.list.get_mut(self.len) else {
            return false;
        };
        *slot = entry;
        self.len += 1;
        if let Some(c) = self.hist.get_mut(usize::from(key)) {
            *c += 1;
        }
        true
    }

    /// [`CandidateList::push`] for a key at or below the floor or a full
    /// list: drops every candidate of the lowest key present until there
    /// is room or the new key is at or below the floor.
    #[cold]
    #[inline(never)]
    fn push_evicting(&mut self, entry: u32, key: u8, keys: impl Fn(u32) -> u8) {
        if i32::from(key) <= self.floor {
            self.dropped += 1;
            return;
        }
        while self.len >= self.list.len() {
            // Full: drop every candidate of the lowest key present.
            let lowest = self
                .hist
                .iter()
                .position(|&c| c > 0)
                .unwrap_or(255)
                .min(255);
            self.floor = lowest as i32;
            if let Some(c) = self.hist.get_mut(lowest) {
                self.dropped += *c as usize;
                *c = 0;
            }
            let mut kept = 0;
            for i in 0..self.len {
                let e = self.list.get(i).copied().unwrap_or(0);
                if i32::from(keys(e)) > self.floor {
                    if let Some(slot) = self.list.get_mut(kept) {
                        *slot = e;
                    }
                    kept += 1;
                }
            }
            self.len = kept;
            if i32::from(key) <= self.floor {
                self.dropped += 1;
                return;
            }
        }
        self.append(entry, key);
    }
}

/// The raster-index bits of a candidate entry.
pub(crate) const INDEX_MASK: u32 = 0x03FF_FFFF;

/// Candidate entry: raster index | J code << 26 | K code << 29.
const fn entry(idx: usize, p: Partners) -> u32 {
    idx as u32 | (p.j as u32) << 26 | (p.k as u32) << 29
}

/// The neighbour codes (indices into [`NEIGHBOURS`]) of the J and K
/// partners of a candidate entry (see [`entry`]).
pub(crate) const fn partner_codes(e: u32) -> [usize; 2] {
    [((e >> 26) & 7) as usize, ((e >> 29) & 7) as usize]
}

/// The state byte of a group partner at neighbour code `code` of its
/// centre: MEMBER with the code pointing back to the centre.
pub(crate) const fn member_state(code: usize) -> u8 {
    MEMBER | (((code + 4) % 8) as u8) << 2
}

/// Whether the anchor pass runs the NMS as a branch-free pass over each row
/// ([`nms_row`], which the compiler vectorises) or pixel by pixel, skipping
/// zero magnitudes (targets without SIMD, such as a Cortex-M4: fewer
/// instructions there). Both give the same result
/// (`row_and_pixel_strategies_agree`).
pub(crate) const ROW_PASS: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "neon",
    target_feature = "simd128"
));

/// The anchor pass: writes NONE / REGULAR into `state`, the raster-order
/// candidates into `cand`, their key histogram into `hist`. Returns the
/// number of candidates stored and dropped. `ROW`: the NMS strategy (the
/// detector passes [`ROW_PASS`]; the tests run both).
#[allow(clippy::too_many_arguments)]
pub(crate) fn classify<const ROW: bool>(
    p: &Params,
    blur: &[u8],
    w: usize,
    h: usize,
    state: &mut [u8],
    mag8: &mut [u8],
    rows: &mut [u16],
    cand: &mut [u32],
    hist: &mut [u32],
) -> AnchorStats {
    hist.iter_mut().for_each(|c| *c = 0);
    let Some(mut ring) = Ring::new(rows, w) else {
        return AnchorStats::default();
    };
    let mut list = CandidateList {
        list: cand,
        len: 0,
        hist,
        floor: 0,
        dropped: 0,
    };
    for r in 0..=h {
        if r < h {
            let m8 = mag8.get_mut(r * w..(r + 1) * w).unwrap_or(&mut []);
            gradient_row(&mut ring, blur, w, r, p.mag_min, m8);
        }
        if r >= 1 {
            let y = r - 1;
            let srow = state.get_mut(y * w..(y + 1) * w).unwrap_or(&mut []);
            // `mag8` holds rows up to `r`: every candidate's key.
            classify_row::<ROW>(p, &ring, mag8, w, h, y, srow, &mut list);
        }
    }
    AnchorStats {
        candidates: list.len,
        dropped: list.dropped,
    }
}

/// Flat index of the neighbour `(dx, dy)` in a 3x3 window: `(dy+1)*3 + dx+1`.
const fn flat(dx: i32, dy: i32) -> usize {
    ((dy + 1) * 3 + dx + 1) as usize
}

/// The (dx, dy) of a flat 3x3 index.
const fn unflat(k: usize) -> (i32, i32) {
    ((k % 3) as i32 - 1, (k / 3) as i32 - 1)
}

/// A neighbourhood table as flat 3x3 indices (evaluated at compile time only).
#[allow(clippy::indexing_slicing)] // const evaluation: an out-of-range index is a compile error
const fn flatten6(t: &[(i32, i32); 6]) -> [u8; 6] {
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
const ALONG_FLAT: [[u8; 6]; 4] = [
    flatten6(&ALONG[0]),
    flatten6(&ALONG[1]),
    flatten6(&ALONG[2]),
    flatten6(&ALONG[3]),
];

/// Classifies row `y` (rows `y-1..=y+1` are in the ring; `mag8`, the sort
/// keys, is written up to row `y + 1`).
#[allow(clippy::too_many_arguments)]
fn classify_row<const ROW: bool>(
    p: &Params,
    ring: &Ring<'_>,
    mag8: &[u8],
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
    let [m_up, m_cur, m_dn] = rows_m;
    let [_, gx_cur, _] = rows_gx;
    let [_, gy_cur, _] = rows_gy;
    let ctx = RowCtx {
        p,
        mag8,
        w,
        y,
        rows_m,
        rows_gx,
        rows_gy,
    };
    let interior_y = y >= 1 && y + 1 < h;
    srow.fill(NONE);
    // A pixel with a neighbour beyond the image: OUTSIDE marks those.
    let border = |list: &mut CandidateList<'_>, x: usize, s: &mut u8| {
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
            if xx < 0 || xx as usize >= w {
                return OUTSIDE;
            }
            rows_m
                .get((dy + 1) as usize)
                .and_then(|r| r.get(xx as usize))
                .copied()
                .unwrap_or(OUTSIDE)
        });
        *s = NONE; // no NMS at the border
        ctx.group::<true>(list, x, mc, g, &nb);
    };
    if !interior_y || w < 3 {
        for (x, s) in srow.iter_mut().enumerate() {
            border(list, x, s);
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
    border(list, 0, first);
    if ROW {
        // Pass 1, branch-free over the whole row (the compiler vectorises
        // it): the NMS state of every interior pixel, with the group test's
        // necessary condition in the GATE bit.
        nms_row([m_up, m_cur, m_dn], gx_cur, gy_cur, inner);
        // Pass 2, in raster order: the group test where the gate holds,
        // found eight states at a time (the gate is rare and random: a
        // branch per pixel mispredicts).
        const GATES: u64 = u64::from_le_bytes([GATE; 8]);
        for (c, chunk) in inner.chunks_mut(8).enumerate() {
            let mut word = chunk
                .iter()
                .rev()
                .fold(0u64, |w, &b| (w << 8) | u64::from(b))
                & GATES;
            while word != 0 {
                let i = (word.trailing_zeros() / 8) as usize;
                word &= word - 1;
                if let Some(s) = chunk.get_mut(i) {
                    *s &= !GATE;
                }
                let x = c * 8 + i + 1;
                let (Some(&mc), Some(&gx), Some(&gy)) =
                    (m_cur.get(x), gx_cur.get(x), gy_cur.get(x))
                else {
                    continue;
                };
                ctx.group_at(list, x, mc, (i32::from(gx as i16), i32::from(gy as i16)));
            }
        }
    } else {
        // Pixel by pixel, skipping zero magnitudes; the 3x3 windows come
        // from `array_windows` (no bounds checks).
        let windows = m_up
            .array_windows::<3>()
            .zip(m_cur.array_windows::<3>())
            .zip(m_dn.array_windows::<3>());
        let grads = gx_cur.iter().zip(gy_cur).skip(1);
        for (x0, (((&[a0, a1, a2], &[b0, mc, b2]), &[c0, c1, c2]), ((&gx, &gy), s))) in
            windows.zip(grads.zip(inner.iter_mut())).enumerate()
        {
            if mc == 0 {
                continue;
            }
            let g = (i32::from(gx as i16), i32::from(gy as i16));
            let nb = [a0, a1, a2, b0, mc, b2, c0, c1, c2];
            ctx.interior(list, x0 + 1, s, mc, g, &nb);
        }
    }
    border(list, w - 1, last);
}

/// What [`classify_row`] shares with each pixel.
struct RowCtx<'a> {
    p: &'a Params,
    /// The sort keys written so far (rows up to `y + 1`).
    mag8: &'a [u8],
    w: usize,
    y: usize,
    rows_m: [&'a [u16]; 3],
    rows_gx: [&'a [u16]; 3],
    rows_gy: [&'a [u16]; 3],
}

impl RowCtx<'_> {
    /// Gradient of the neighbour at flat index `k` of `x` (rare: only for
    /// candidates' partners).
    fn grad(&self, x: usize, k: usize) -> (i32, i32) {
        let (dx, dy) = unflat(k);
        let xx = (x as i64 + i64::from(dx)).max(0) as usize;
        let r = (dy + 1) as usize;
        let g = |rows: &[&[u16]; 3]| {
            i32::from(rows.get(r).and_then(|r| r.get(xx)).copied().unwrap_or(0) as i16)
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
        let (regular, may_group) = nms_branchy(mc, g.0, g.1, nb);
        *s = if regular { REGULAR } else { NONE };
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
        if let Some(pt) = group_candidate::<EDGE>(self.p, mc, gx, gy, nb, |k| self.grad(x, k)) {
            let key = mc.min(255) as u8;
            let mag8 = self.mag8;
            list.push(entry(self.y * self.w + x, pt), key, |e| {
                mag8.get((e & INDEX_MASK) as usize).copied().unwrap_or(0)
            });
        }
    }
}

/// A 3x3 magnitude neighbourhood by flat index `(dy+1)*3 + dx+1`;
/// [`OUTSIDE`] marks pixels beyond the image border.
type Neighbourhood = [u16; 9];

/// Magnitude marker for a neighbour outside the image (magnitudes are at
/// most 1020).
const OUTSIDE: u16 = u16::MAX;

/// Entry `k` of a neighbourhood (`min(k, 8)` is always in range, so this
/// compiles to a plain load; `k` comes from the tables above, all < 9).
#[inline(always)]
#[allow(clippy::indexing_slicing)] // clamped index into a 9-array
fn at(nb: &Neighbourhood, k: u8) -> u16 {
    nb[usize::from(k).min(8)]
}

/// Temporary state bit of [`nms_row`]: the pixel passed the group test's
/// necessary condition (see [`nms_i16`]).
const GATE: u8 = 1 << 7;

/// [`nms_i16`] over the interior pixels of one row: `out[i]` is pixel `i + 1`'s
/// state (REGULAR or NONE, [`GATE`] added when its group test must run;
/// NONE for a zero magnitude). `rows` are the magnitude rows `y-1..=y+1`
/// and `gx`, `gy` row `y`'s gradient, all `out.len() + 2` long. Written
/// without branches or early exits so that it vectorises.
fn nms_row(rows: [&[u16]; 3], gx: &[u16], gy: &[u16], out: &mut [u8]) {
    let n = out.len();
    // A row's three column windows (left, centre, right).
    type Cols<'r> = (Option<&'r [u16]>, Option<&'r [u16]>, Option<&'r [u16]>);
    fn cols(r: &[u16], n: usize) -> Cols<'_> {
        (r.get(..n), r.get(1..n + 1), r.get(2..n + 2))
    }
    let [up, cur, dn] = rows;
    let (
        (Some(ul), Some(u), Some(ur)),
        (Some(l), Some(c), Some(r)),
        (Some(dl), Some(d), Some(dr)),
        Some(gx),
        Some(gy),
    ) = (
        cols(up, n),
        cols(cur, n),
        cols(dn, n),
        gx.get(1..n + 1),
        gy.get(1..n + 1),
    )
    else {
        return;
    };
    let top = ul.iter().zip(u).zip(ur);
    let mid = l.iter().zip(c).zip(r);
    let bot = dl.iter().zip(d).zip(dr);
    let grads = gx.iter().zip(gy);
    for ((((o, ((&ul, &u), &ur)), ((&l, &c), &r)), ((&dl, &d), &dr)), (&gx, &gy)) in
        out.iter_mut().zip(top).zip(mid).zip(bot).zip(grads)
    {
        let nb = [ul, u, ur, l, c, r, dl, d, dr];
        let (regular, gate) = nms_i16(c, i32::from(gx as i16), i32::from(gy as i16), &nb);
        let state = (u8::from(regular) * REGULAR) | (u8::from(gate) * GATE);
        *o = if c == 0 { NONE } else { state };
    }
}

/// Regular-anchor NMS in exact rational form (see the module docs), for an
/// interior pixel: `(regular, may_group)`, the second a necessary condition
/// of [`group_candidate`] for the same pixel (`nms_gate_is_necessary_for_a_group`).
///
/// An interior pixel has |gx|, |gy| <= 510 and magnitudes <= 1020 all
/// around (no [`OUTSIDE`] marker), so every value fits `i16`, every
/// difference of two magnitudes is within ±1020 and every product fits
/// `i32`. Computed in `i16` for the row pass ([`nms_row`]), which a SIMD
/// target runs in 16-bit lanes with widening 16x16 -> 32-bit products,
/// twice the lanes of `i32` (callgrind on P1080078: 69.9 M -> 64.6 M
/// instructions for the whole detection). The pixel loop runs
/// [`nms_branchy`], the same test with branches.
#[inline(always)]
fn nms_i16(mc: u16, gx: i32, gy: i32, nb: &Neighbourhood) -> (bool, bool) {
    let (gx, gy) = (gx as i16, gy as i16);
    let (x, y) = if gy < 0 {
        (gx.wrapping_neg(), gy.wrapping_neg())
    } else {
        (gx, gy)
    };
    let a = x.wrapping_abs();
    let m = |dx: i32, dy: i32| at(nb, flat(dx, dy) as u8) as i16;
    let mc = mc as i16;
    // The four cases of the gradient direction (y >= 0 after the flip):
    //   x > 0,  y <  |x|: (P1, P2) = (-1,-1), (-1, 0); (P3, P4) = (1, 1), (1, 0)
    //   x > 0,  y >= |x|: (-1,-1), ( 0,-1);  (1, 1), ( 0, 1)
    //   x <= 0, y >  |x|: ( 1,-1), ( 0,-1); (-1, 1), ( 0, 1)
    //   x <= 0, y <= |x|: (-1, 1), (-1, 0);  (1,-1), ( 1, 0)
    // with w = num/den = |y/x| when x dominates, |x/y| otherwise.
    // Written as selects (the pairs are unordered: both sides must pass).
    let pos = x > 0;
    let x_major = if pos { y < a } else { y <= a };
    let (d1, d2) = if pos {
        (m(-1, -1), m(1, 1))
    } else {
        (m(-1, 1), m(1, -1))
    };
    let (up, down, left, right) = (m(0, -1), m(0, 1), m(-1, 0), m(1, 0));
    let (e1, e2) = if x_major {
        (left, right)
    } else if pos {
        (up, down)
    } else {
        (down, up)
    };
    let (num, den) = if x_major { (y, a) } else { (a, y) };
    // The group test's across-edge set always holds the direct pair
    // (E1, E2): left and right for classes H, D45 and D135, which are all
    // the x-major gradients (below 45°, or exactly 45° with x <= 0); up and
    // down for V, D45 and D135 (the y-major ones). It also holds the
    // diagonal pair (D1, D2): H and V hold all four diagonals, D45 (x > 0)
    // the pair (-1,-1), (1,1) and D135 (x < 0) the pair (-1,1), (1,-1). A
    // group centre is a strict maximum over that set.
    let gate = (mc > e1) & (mc > e2) & (mc > d1) & (mc > d2);
    // The interpolated neighbour `(num·md + (den - num)·me) / den` is below
    // `mc`: `den·(mc - me) > num·(md - me)`, the same inequality with
    // `den·me` moved across.
    let beats = |md: i16, me: i16| {
        i32::from(den) * i32::from(mc - me) > i32::from(num) * i32::from(md - me)
    };
    let regular = (den != 0) & beats(d1, e1) & beats(d2, e2);
    (regular, gate)
}

/// [`nms_i16`] in `i32` with a branch per gradient case and short-circuit
/// tests: the pixel loop's version, for targets without SIMD (a Cortex-M4
/// then executes only the chosen case's loads and comparisons, and needs no
/// sign extensions: 434.7 -> 410.4 instructions per pixel on castle1).
/// Equal to [`nms_i16`] for every interior pixel (`branchy_nms_matches`).
#[inline(always)]
fn nms_branchy(mc: u16, gx: i32, gy: i32, nb: &Neighbourhood) -> (bool, bool) {
    let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
    let a = x.abs();
    let m = |dx: i32, dy: i32| i32::from(at(nb, flat(dx, dy) as u8));
    let mc = i32::from(mc);
    // (num, den, D1, E1, D2, E2) of [`nms_i16`]'s four cases.
    let case = |num: i32, den: i32, d1: i32, e1: i32, d2: i32, e2: i32| {
        let gate = mc > e1 && mc > e2 && mc > d1 && mc > d2;
        let beats = |md: i32, me: i32| den * (mc - me) > num * (md - me);
        (den != 0 && beats(d1, e1) && beats(d2, e2), gate)
    };
    if x > 0 {
        if y < a {
            case(y, a, m(-1, -1), m(-1, 0), m(1, 1), m(1, 0))
        } else {
            case(a, y, m(-1, -1), m(0, -1), m(1, 1), m(0, 1))
        }
    } else if y <= a {
        case(y, a, m(-1, 1), m(-1, 0), m(1, -1), m(1, 0))
    } else {
        case(a, y, m(-1, 1), m(0, 1), m(1, -1), m(0, -1))
    }
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
) -> Option<Partners> {
    match class_of(gx, gy) {
        0 => candidate_of_class::<0, EDGE>(p, mc, (gx, gy), nb, grad),
        1 => candidate_of_class::<1, EDGE>(p, mc, (gx, gy), nb, grad),
        2 => candidate_of_class::<2, EDGE>(p, mc, (gx, gy), nb, grad),
        _ => candidate_of_class::<3, EDGE>(p, mc, (gx, gy), nb, grad),
    }
}

/// [`group_candidate`] for orientation class `C` (0 = D45, 1 = V,
/// 2 = D135, 3 = H).
#[inline(always)]
fn candidate_of_class<const C: usize, const EDGE: bool>(
    p: &Params,
    mc: u16,
    gc: (i32, i32),
    nb: &Neighbourhood,
    grad: impl Fn(usize) -> (i32, i32),
) -> Option<Partners> {
    // Evaluated at compile time: an out-of-range C would not compile.
    #[allow(clippy::indexing_slicing)]
    let (across, along) = const { (ACROSS_FLAT[C], ALONG_FLAT[C]) };
    // Strict maximum across the edge; the walk stops at the image border.
    let (best_a, best_b) = if EDGE {
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
            if mc <= mq {
                return None;
            }
        }
        (best_a, best_b)
    } else {
        // No border: the same test as one comparison with the maximum
        // (fewer unpredictable branches).
        let [a0, a1, a2, b0, b1, b2] = across.map(|k| at(nb, k));
        let (best_a, best_b) = (a0.max(a1).max(a2), b0.max(b1).max(b2));
        if mc <= best_a.max(best_b) {
            return None;
        }
        (best_a, best_b)
    };
    if best_a == 0 || best_b == 0 {
        return None;
    }
    let mci = i32::from(mc);
    if mci - i32::from(best_a) < p.margin && mci - i32::from(best_b) < p.margin {
        return None;
    }
    // Strongest nonzero partner on each side along the edge.
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

/// Stable counting sort of the raster candidates into `sorted`, by
/// descending key. `hist` holds the per-key counts; it is consumed. The key
/// of a candidate is its `mag8` entry, `min(m, 255)` of its thresholded
/// magnitude, which [`classify`] wrote (the candidate list's eviction reads
/// the same entries).
pub(crate) fn sort_candidates(raster: &[u32], sorted: &mut [u32], hist: &mut [u32], mag8: &[u8]) {
    // Start offset of each key, highest key first.
    let mut acc = 0u32;
    for k in (0..hist.len()).rev() {
        if let Some(c) = hist.get_mut(k) {
            let n = *c;
            *c = acc;
            acc += n;
        }
    }
    for &e in raster {
        let key = mag8.get((e & INDEX_MASK) as usize).copied().unwrap_or(0);
        if let Some(pos) = hist.get_mut(usize::from(key)) {
            if let Some(slot) = sorted.get_mut(*pos as usize) {
                *slot = e;
            }
            *pos += 1;
        }
    }
}

/// Greedy extraction in sorted order: writes CENTRE / MEMBER states and
/// compacts the accepted centres (with their partner codes) to the front of
/// `sorted`, in group-id order. Returns the number of groups.
pub(crate) fn extract_groups(
    sorted: &mut [u32],
    n: usize,
    state: &mut [u8],
    w: NonZeroUsize,
) -> usize {
    let mut groups = 0;
    for i in 0..n.min(sorted.len()) {
        let e = sorted.get(i).copied().unwrap_or(0);
        let c = (e & INDEX_MASK) as usize;
        let [cj, ck] = partner_codes(e);
        let partner = |code: usize| -> Option<usize> {
            let (dx, dy) = NEIGHBOURS.get(code).copied()?;
            let x = (c % w) as i64 + i64::from(dx);
            let y = (c / w) as i64 + i64::from(dy);
            (x >= 0 && y >= 0 && (x as usize) < w.get()).then(|| y as usize * w.get() + x as usize)
        };
        let (Some(j), Some(k)) = (partner(cj), partner(ck)) else {
            continue;
        };
        let used = |i: usize| state.get(i).is_none_or(|&s| s & CLASS_MASK >= CENTRE);
        if used(c) || used(j) || used(k) {
            continue;
        }
        if let Some(s) = state.get_mut(c) {
            *s = CENTRE;
        }
        if let Some(s) = state.get_mut(j) {
            *s = member_state(cj);
        }
        if let Some(s) = state.get_mut(k) {
            *s = member_state(ck);
        }
        if let Some(slot) = sorted.get_mut(groups) {
            *slot = e;
        }
        groups += 1;
    }
    groups
}

/// Compacts the raster-order candidate list to the accepted group centres'
/// entries (still in raster order, with their partner codes: see
/// `Linker::cache_directions`). Returns their number.
pub(crate) fn centres_in_raster_order(raster: &mut [u32], n: usize, state: &[u8]) -> usize {
    let mut kept = 0;
    for i in 0..n.min(raster.len()) {
        let e = raster.get(i).copied().unwrap_or(0);
        if state
            .get((e & INDEX_MASK) as usize)
            .is_some_and(|&s| s & CLASS_MASK == CENTRE)
        {
            if let Some(slot) = raster.get_mut(kept) {
                *slot = e;
            }
            kept += 1;
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

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
                assert_eq!(class_of(gx, gy), want, "({gx}, {gy}) o = {o}");
            }
        }
    }

    #[test]
    fn neighbour_codes_round_trip() {
        for (c, &(dx, dy)) in NEIGHBOURS.iter().enumerate() {
            assert_eq!(code_of(dx, dy) as usize, c);
            let back = NEIGHBOURS[(c + 4) % 8];
            assert_eq!(back, (-dx, -dy));
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
            let cfg = if case.is_multiple_of(2) {
                Config::OFFICIAL
            } else {
                Config::PAPER
            };
            let p = Params::new(&cfg);
            let gx = (next() % 1021) as i32 - 510;
            let gy = (next() % 1021) as i32 - 510;
            let mc = (gx.abs() + gy.abs()) as u16;
            if mc == 0 {
                continue;
            }
            // Neighbours mostly below the centre, so that many pass.
            let mut nb: Neighbourhood =
                core::array::from_fn(|_| (next() % (u64::from(mc) + 40)) as u16);
            for v in &mut nb {
                if next().is_multiple_of(5) {
                    *v = 0;
                }
            }
            nb[4] = mc;
            let random_partners = case.is_multiple_of(3);
            let partner = ((next() % 1021) as i32 - 510, (next() % 1021) as i32 - 510);
            let grad = |_k: usize| if random_partners { partner } else { (gx, gy) };
            if group_candidate::<false>(&p, mc, gx, gy, &nb, grad).is_some() {
                accepted += 1;
                let (_, gate16) = nms_i16(mc, gx, gy, &nb);
                let (_, gate_branchy) = nms_branchy(mc, gx, gy, &nb);
                assert!(
                    gate16 && gate_branchy,
                    "gradient ({gx}, {gy}), neighbourhood {nb:?}"
                );
            }
        }
        std::eprintln!("{accepted} group candidates over {cases} neighbourhoods");
        assert!(accepted * 20 >= cases, "too few candidates: {accepted}");
    }

    /// The pixel loop's NMS equals the row pass's, `(regular, gate)`, on
    /// random interior inputs: gradients over the whole range and small
    /// ones (axes, exact diagonals, zero), magnitudes over the whole range
    /// and in narrow bands around the centre's (ties).
    #[test]
    fn branchy_nms_matches() {
        let mut next = crate::xorshift64(0xD1B5_4A32_D192_ED03);
        let cases: u32 = if cfg!(miri) { 500 } else { 1_000_000 };
        let (mut regular, mut gate) = (0u32, 0u32);
        for case in 0..cases {
            // Components in -4..=4 for every fourth case, else -510..=510.
            let span: u64 = if case.is_multiple_of(4) { 9 } else { 1021 };
            let gx = (next() % span) as i32 - (span / 2) as i32;
            let gy = (next() % span) as i32 - (span / 2) as i32;
            let mc = (next() % 1021) as u16;
            let band = 1 + next() % 8;
            let nb: Neighbourhood = core::array::from_fn(|k| {
                if k == 4 {
                    mc
                } else if case.is_multiple_of(2) {
                    (u64::from(mc) + next() % (2 * band + 1))
                        .saturating_sub(band)
                        .min(1020) as u16
                } else {
                    (next() % 1021) as u16
                }
            });
            let want = nms_i16(mc, gx, gy, &nb);
            assert_eq!(
                nms_branchy(mc, gx, gy, &nb),
                want,
                "gradient ({gx}, {gy}), neighbourhood {nb:?}"
            );
            regular += u32::from(want.0);
            gate += u32::from(want.1);
        }
        // Both outcomes of both results occur often.
        assert!(
            regular * 10 > cases && regular * 10 < 9 * cases,
            "{regular}"
        );
        assert!(gate * 20 > cases && gate * 10 < 9 * cases, "{gate}");
    }

    /// The two NMS strategies of the anchor pass (a vectorised pass over
    /// each row, and pixel by pixel skipping zero magnitudes, chosen by
    /// target) give the same states, magnitude cache, candidates (in the
    /// same order, with the same evictions) and counters, on random and
    /// structured images of many shapes and on every profile.
    #[test]
    fn row_and_pixel_strategies_agree() {
        use crate::Config;
        let mut next = crate::xorshift64(0x2545_F491_4F6C_DD1D);
        let cases = if cfg!(miri) { 6 } else { 400 };
        let mut candidates_seen = 0;
        for case in 0..cases {
            let w = 1 + (next() % 40) as usize;
            let h = 1 + (next() % 30) as usize;
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
                let mut state = std::vec![0u8; w * h];
                let mut mag8 = std::vec![0u8; w * h];
                let mut rows = std::vec![0u16; 9 * w];
                let mut cand = std::vec![0u32; cap];
                let mut hist = std::vec![0u32; 256];
                let classify = if row {
                    classify::<true>
                } else {
                    classify::<false>
                };
                let st = classify(
                    &p, &blur, w, h, &mut state, &mut mag8, &mut rows, &mut cand, &mut hist,
                );
                cand.truncate(st.candidates);
                (state, mag8, cand, hist, st.candidates, st.dropped)
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
