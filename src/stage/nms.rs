//! Paper §3.1, regular anchors: Canny-style non-maximum suppression with
//! linear interpolation between the two neighbours that the gradient
//! direction falls between (design §5), in exact rational form.
//!
//! For a gradient whose dominant component is `x` (the other `y`, both
//! folded so that `y >= 0`), the interpolated neighbour on each side is
//! `(num·m(P_diagonal) + (den - num)·m(P_direct)) / den` with `num/den =
//! |y/x|`, and the centre must beat both: `den·(mc - me) > num·(md - me)`.
//! Under [`Maxima::Symmetric`](crate::Maxima::Symmetric) the test against the
//! right side (a gradient closer to horizontal) or the lower side (closer to
//! vertical) allows equality (`>=`, as `> ` with 1 added to the left), so
//! that of two equal pixels across an edge the left or upper one is kept
//! (design §5). The float reference uses `f32` weights (the authors'), or
//! under that rule `f64` differences that are exact on plateaus; both can
//! differ from the rational test on other exact ties (design §14 says how
//! the two are compared).
//!
//! The same pass also computes, for free, a necessary condition of the
//! aligned-anchor-group test (the *gate*), so that the expensive group test
//! runs only where it can succeed.
//!
//! Two strategies give identical results (`branchy_nms_matches`): a
//! branch-free pass over a whole row in 16-bit lanes ([`nms_row`], which the
//! compiler vectorises), and a per-pixel version with one branch per
//! gradient case ([`nms_branchy`]) for targets without SIMD, where skipping
//! zero magnitudes and running only the chosen case's comparisons costs
//! fewer instructions. [`crate::target::SIMD`] picks one by target.

use super::state::Class;

/// The anchor pass's row scratch holds one byte per pixel: its [`Class`]
/// (none or regular) in the low bits, and this bit when the group test must
/// run there (the gate).
pub(crate) const GATE_BIT: u8 = 1 << 7;

/// Flat index of the neighbour `(dx, dy)` in a 3x3 window: `(dy+1)*3 + dx+1`.
pub(crate) const fn flat(dx: i32, dy: i32) -> usize {
    ((dy + 1) * 3 + dx + 1) as usize
}

/// The (dx, dy) of a flat 3x3 index.
pub(crate) const fn unflat(k: usize) -> (i32, i32) {
    ((k % 3) as i32 - 1, (k / 3) as i32 - 1)
}

/// A 3x3 magnitude neighbourhood by flat index `(dy+1)*3 + dx+1`;
/// [`OUTSIDE`] marks pixels beyond the image border.
pub(crate) type Neighbourhood = [u16; 9];

/// What the NMS's gate reads of the parameters: `(tie, margin)`
/// ([`Params::gate`](crate::params::Params::gate)).
pub(crate) type Gate = (u16, u16);

/// Magnitude marker for a neighbour outside the image (magnitudes are at
/// most 1020).
pub(crate) const OUTSIDE: u16 = u16::MAX;

/// Entry `k` of a neighbourhood (`min(k, 8)` is always in range, so this
/// compiles to a plain load; `k` comes from the tables above, all < 9).
#[inline(always)]
#[allow(clippy::indexing_slicing)] // clamped index into a 9-array
pub(crate) fn at(nb: &Neighbourhood, k: u8) -> u16 {
    nb[usize::from(k).min(8)]
}

/// [`nms_i16`] over the interior pixels of one row: `out[i]` is pixel `i + 1`'s
/// state (REGULAR or NONE, [`GATE_BIT`] added when its group test must run;
/// NONE for a zero magnitude). `rows` are the magnitude rows `y-1..=y+1`
/// and `gx`, `gy` row `y`'s gradient, all `out.len() + 2` long. Written
/// without branches or early exits so that it vectorises.
pub(crate) fn nms_row(rows: [&[u16]; 3], gx: &[u16], gy: &[u16], gate: Gate, out: &mut [u8]) {
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
        let g = (i32::from(gx as i16), i32::from(gy as i16));
        let (regular, gated) = nms_i16(c, g, gate, &nb);
        let state = (u8::from(regular) * Class::Regular as u8) | (u8::from(gated) * GATE_BIT);
        *o = if c == 0 { Class::None as u8 } else { state };
    }
}

/// Regular-anchor NMS in exact rational form (see the module docs), for an
/// interior pixel: `(regular, may_group)`, the second a necessary condition
/// of the anchor pass's group test for the same pixel (`nms_gate_is_necessary_for_a_group`).
/// `tie` is [`Params::tie`](crate::params::Params::tie): 1 allows equality
/// towards the right or lower side.
///
/// An interior pixel has |gx|, |gy| <= 510 and magnitudes <= 1020 all
/// around (no [`OUTSIDE`] marker), so every value fits `i16`, every
/// difference of two magnitudes is within ±1020 and every product fits
/// `i32`. Computed in `i16` for the row pass ([`nms_row`]), which a SIMD
/// target runs in 16-bit lanes with widening 16x16 -> 32-bit products,
/// twice the lanes of `i32`. The pixel loop runs
/// [`nms_branchy`], the same test with branches.
#[inline(always)]
pub(crate) fn nms_i16(mc: u16, g: (i32, i32), gate: Gate, nb: &Neighbourhood) -> (bool, bool) {
    let ((gx, gy), (tie, margin)) = ((g.0 as i16, g.1 as i16), gate);
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
    let tie = tie as i16;
    // Side 1 (D1, E1) is the left or upper side in every case but the
    // y-major one with x <= 0, where it is the lower side (the pairs were
    // chosen for their symmetry, not their side).
    let lower1 = !pos & !x_major;
    let (t1, t2) = if lower1 { (tie, 0) } else { (0, tie) };
    // The group test's across-edge set always holds the direct pair
    // (E1, E2): left and right for classes H, D45 and D135, which are all
    // the x-major gradients (below 45°, or exactly 45° with x <= 0); up and
    // down for V, D45 and D135 (the y-major ones). It also holds the
    // diagonal pair (D1, D2): H and V hold all four diagonals, D45 (x > 0)
    // the pair (-1,-1), (1,1) and D135 (x < 0) the pair (-1,1), (1,-1). A
    // group centre is a maximum over that set: strict, or under the tie
    // rule at least equal (an equal neighbour is settled by the group test).
    //
    // The group test's margin (`mc` above the largest neighbour across the
    // edge by `margin` on at least one side) holds on the pairs too: (D1,
    // E1) lie on one side of the group test's across set and (D2, E2) on
    // the other, in every case, so each pair's maximum is at most its
    // side's.
    let margin = margin as i16;
    let gate = (mc + tie > e1)
        & (mc + tie > e2)
        & (mc + tie > d1)
        & (mc + tie > d2)
        & ((mc - e1.max(d1) >= margin) | (mc - e2.max(d2) >= margin));
    // The interpolated neighbour `(num·md + (den - num)·me) / den` is below
    // `mc`: `den·(mc - me) > num·(md - me)`, the same inequality with
    // `den·me` moved across; `t` turns it into `>=`.
    let beats = |md: i16, me: i16, t: i16| {
        i32::from(den) * i32::from(mc - me) + i32::from(t) > i32::from(num) * i32::from(md - me)
    };
    let regular = (den != 0) & beats(d1, e1, t1) & beats(d2, e2, t2);
    (regular, gate)
}

/// [`nms_i16`] in `i32` with a branch per gradient case and short-circuit
/// tests: the pixel loop's version, for targets without SIMD (a Cortex-M4
/// then executes only the chosen case's loads and comparisons, and needs no
/// sign extensions).
/// Equal to [`nms_i16`] for every interior pixel (`branchy_nms_matches`).
#[inline(always)]
pub(crate) fn nms_branchy(mc: u16, g: (i32, i32), gate: Gate, nb: &Neighbourhood) -> (bool, bool) {
    let ((gx, gy), (tie, margin)) = (g, gate);
    let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
    let a = x.abs();
    let m = |dx: i32, dy: i32| i32::from(at(nb, flat(dx, dy) as u8));
    let (mc, tie, margin) = (i32::from(mc), i32::from(tie), i32::from(margin));
    // (num, den, D1, E1, D2, E2) of [`nms_i16`]'s four cases, the strict
    // side (left or upper) first; the gate as [`nms_i16`]'s.
    let case = |num: i32, den: i32, d1: i32, e1: i32, d2: i32, e2: i32| {
        let gate = branchy_gate(mc, tie, margin, [d1, e1, d2, e2]);
        let beats = |md: i32, me: i32, t: i32| den * (mc - me) + t > num * (md - me);
        (den != 0 && beats(d1, e1, 0) && beats(d2, e2, tie), gate)
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
        // The upper side first.
        let (d1, e1, d2, e2) = (m(1, -1), m(0, -1), m(-1, 1), m(0, 1));
        let gate = branchy_gate(mc, tie, margin, [d1, e1, d2, e2]);
        let beats = |md: i32, me: i32, t: i32| y * (mc - me) + t > a * (md - me);
        (y != 0 && beats(d1, e1, 0) && beats(d2, e2, tie), gate)
    }
}

/// [`nms_branchy`]'s gate, as [`nms_i16`]'s (a function inlined in every
/// build, where a closure called from two places ran more instructions
/// in a build for size).
#[inline(always)]
fn branchy_gate(mc: i32, tie: i32, margin: i32, [d1, e1, d2, e2]: [i32; 4]) -> bool {
    mc + tie > e1
        && mc + tie > e2
        && mc + tie > d1
        && mc + tie > d2
        && (mc - e1.max(d1) >= margin || mc - e2.max(d2) >= margin)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

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
            let tie = (case / 4 % 2) as u16;
            // The default margin, none, or a wide one.
            let margin = [3, 0, 3, 12][(case / 8 % 4) as usize];
            let want = nms_i16(mc, (gx, gy), (tie, margin), &nb);
            assert_eq!(
                nms_branchy(mc, (gx, gy), (tie, margin), &nb),
                want,
                "gradient ({gx}, {gy}), tie {tie}, margin {margin}, neighbourhood {nb:?}"
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
}
