//! Generated tables for [`super::trig`]; do not edit by hand (but for
//! [`ATAN_D1`], computed at compile time from its formula).
//!
//! Regenerate with the formulas quoted in `super::trig`'s module docs; the
//! unit test `tables_match_libm` recomputes every entry with `libm` (f64)
//! and fails on any difference of more than one unit ([`ATAN_D1`]: on any
//! difference).
//!
//! The generated tables are `const`s: only the step tables derived from
//! them at compile time ([`ATAN_STEPS`], [`SIN_STEPS`], at the end of this
//! file) are stored in flash.

#![allow(clippy::unreadable_literal)]

use crate::invariant::Invariant;

/// `atan(i / 128)` in binary-angle units (2^32 per turn), i = 0..=128.
pub(crate) const ATAN: [u32; 129] = [
    0, 5340245, 10679838, 16018129, 21354465, 26688200, 32018685, 37345276, 42667331, 47984212,
    53295284, 58599915, 63897482, 69187361, 74468939, 79741605, 85004756, 90257796, 95500135,
    100731191, 105950391, 111157167, 116350962, 121531227, 126697423, 131849018, 136985493,
    142106335, 147211045, 152299132, 157370116, 162423527, 167458907, 172475810, 177473799,
    182452450, 187411349, 192350096, 197268300, 202165583, 207041579, 211895933, 216728303,
    221538359, 226325781, 231090262, 235831508, 240549235, 245243172, 249913059, 254558647,
    259179700, 263775993, 268347313, 272893455, 277414230, 281909457, 286378966, 290822599,
    295240206, 299631651, 303996806, 308335554, 312647786, 316933406, 321192324, 325424463,
    329629752, 333808132, 337959550, 342083962, 346181336, 350251643, 354294865, 358310992,
    362300021, 366261957, 370196809, 374104599, 377985350, 381839095, 385665872, 389465727,
    393238710, 396984877, 400704291, 404397019, 408063135, 411702716, 415315845, 418902610,
    422463104, 425997422, 429505665, 432987938, 436444350, 439875013, 443280042, 446659557,
    450013680, 453342536, 456646255, 459924966, 463178803, 466407904, 469612406, 472792449,
    475948178, 479079736, 482187271, 485270931, 488330866, 491367227, 494380167, 497369841,
    500336404, 503280012, 506200824, 509098996, 511974689, 514828063, 517659277, 520468494,
    523255875, 526021581, 528765775, 531488619, 534190278, 536870912,
];

/// `K / (1 + r^2) / 128` with `r = i / 128`, `K = 2^32 / 2π`: the derivative
/// of [`ATAN`] per table step (for cubic Hermite interpolation). Computed
/// here rather than listed: each entry is `128·K / (16384 + i^2)` rounded
/// to the nearest integer, from `128·K` in Q20 (`K_128_Q20`, exact to
/// 2^-21, far closer than any entry comes to a rounding tie;
/// `tables_match_libm` asserts each entry equals `libm`'s rounding).
#[allow(clippy::indexing_slicing)] // compile time: out of range is a compile error
pub(crate) const ATAN_D1: [u32; 129] = {
    const K_128_Q20: u64 = 91_746_578_227_562_544;
    let mut t = [0u32; 129];
    let mut i = 0;
    while i < 129 {
        let den = 16384 + (i * i) as u64;
        t[i] = ((K_128_Q20 + (den << 19)) / (den << 20)) as u32;
        i += 1;
    }
    t
};

/// `sin(i π / 256)` in Q30 (a quarter wave), i = 0..=128.
pub(crate) const SIN_Q30: [u32; 129] = [
    0, 13176464, 26350943, 39521455, 52686014, 65842639, 78989349, 92124163, 105245103, 118350194,
    131437462, 144504935, 157550647, 170572633, 183568930, 196537583, 209476638, 222384147,
    235258165, 248096755, 260897982, 273659918, 286380643, 299058239, 311690799, 324276419,
    336813204, 349299266, 361732726, 374111709, 386434353, 398698801, 410903207, 423045732,
    435124548, 447137835, 459083786, 470960600, 482766489, 494499676, 506158392, 517740883,
    529245404, 540670223, 552013618, 563273883, 574449320, 585538248, 596538995, 607449906,
    618269338, 628995660, 639627258, 650162530, 660599890, 670937767, 681174602, 691308855,
    701339000, 711263525, 721080937, 730789757, 740388522, 749875788, 759250125, 768510122,
    777654384, 786681534, 795590213, 804379079, 813046808, 821592095, 830013654, 838310216,
    846480531, 854523370, 862437520, 870221790, 877875009, 885396022, 892783698, 900036924,
    907154608, 914135678, 920979082, 927683790, 934248793, 940673101, 946955747, 953095785,
    959092290, 964944360, 970651112, 976211688, 981625251, 986890984, 992008094, 996975812,
    1001793390, 1006460100, 1010975242, 1015338134, 1019548121, 1023604567, 1027506862, 1031254418,
    1034846671, 1038283080, 1041563127, 1044686319, 1047652185, 1050460278, 1053110176, 1055601479,
    1057933813, 1060106826, 1062120190, 1063973603, 1065666786, 1067199483, 1068571464, 1069782521,
    1070832474, 1071721163, 1072448455, 1073014240, 1073418433, 1073660973, 1073741824,
];

/// One step of a cubic Hermite table, as a polynomial in the position
/// `t ∈ [0, 1)` within the step: `p0 + t·(m0 + t·(c2 + t·c3))`, with
/// `c2 = 3d - 2m0 - m1`, `c3 = m0 + m1 - 2d`, `d = p1 - p0` from the values
/// `p0`, `p1` and the derivatives per step `m0`, `m1` at its ends. The
/// coefficients are computed at compile time with the same `i32` arithmetic
/// the interpolation used to do at run time, so the results are unchanged.
#[derive(Clone, Copy, Default)]
pub(crate) struct Step<C> {
    pub(crate) p0: i32,
    pub(crate) m0: i32,
    pub(crate) c2: C,
    pub(crate) c3: C,
}

/// The [`ATAN`] / [`ATAN_D1`] steps `i = 0..128` (between nodes `i` and
/// `i + 1`). `c2 ∈ [-13550, -1]` and `c3 ∈ [-110, 28]` fit `i16` (checked at
/// compile time). 128 × 12 = 1,536 bytes.
pub(crate) static ATAN_STEPS: [Step<i16>; 128] = atan_steps();

/// `round(π / 256 · 2^32)`: one sine table step in radians, Q32.
pub(crate) const SIN_STEP_Q32: u64 = 52_707_179;

/// The quarter-wave sine steps `i = 0..=128`: values [`SIN_Q30`] and
/// derivatives per step `(SIN_Q30[128 - i] · SIN_STEP_Q32) >> 32` (the
/// cosine times π/256, in Q30). Step 128 starts at node 128 (1.0) and is
/// only read with `t = 0`, at the angle 90° exactly; it has the shape of
/// the old clamped lookup (both ends node 128), so no index needs a clamp.
/// 129 × 16 = 2,064 bytes.
pub(crate) static SIN_STEPS: [Step<i32>; 129] = sin_steps();

/// `(p0, m0, c2, c3)` of the Hermite step from `(p0, m0)` to `(p1, m1)`.
const fn coefficients(p0: i32, m0: i32, p1: i32, m1: i32) -> (i32, i32, i32, i32) {
    let d = p1 - p0;
    (p0, m0, 3 * d - 2 * m0 - m1, m0 + m1 - 2 * d)
}

// The builders below run at compile time only (static initialisers): an
// out-of-range index there is a compile error, not a run-time panic.

#[allow(clippy::indexing_slicing)]
const fn atan_steps() -> [Step<i16>; 128] {
    let mut out = [Step {
        p0: 0,
        m0: 0,
        c2: 0,
        c3: 0,
    }; 128];
    let mut i = 0;
    while i < 128 {
        let (p0, m0, c2, c3) = coefficients(
            ATAN[i] as i32,
            ATAN_D1[i] as i32,
            ATAN[i + 1] as i32,
            ATAN_D1[i + 1] as i32,
        );
        assert!(c2 == c2 as i16 as i32 && c3 == c3 as i16 as i32);
        out[i] = Step {
            p0,
            m0,
            c2: c2 as i16,
            c3: c3 as i16,
        };
        i += 1;
    }
    out
}

/// The sine's derivative per step at a node whose cosine is `cos_q30`
/// (the node `128 - i` of [`SIN_Q30`] for node `i`): the cosine times the
/// step.
const fn sin_derivative(cos_q30: u32) -> i32 {
    ((cos_q30 as u64 * SIN_STEP_Q32) >> 32) as i32
}

#[allow(clippy::indexing_slicing)]
const fn sin_steps() -> [Step<i32>; 129] {
    const fn derivative(i: usize) -> i32 {
        sin_derivative(SIN_Q30[128 - i])
    }
    let mut out = [Step {
        p0: 0,
        m0: 0,
        c2: 0,
        c3: 0,
    }; 129];
    let mut i = 0;
    while i <= 128 {
        // Node 129 is node 128 again, as the old clamped lookup had it.
        let j = if i < 128 { i + 1 } else { 128 };
        let (p0, m0, c2, c3) = coefficients(
            SIN_Q30[i] as i32,
            derivative(i),
            SIN_Q30[j] as i32,
            derivative(j),
        );
        out[i] = Step { p0, m0, c2, c3 };
        i += 1;
    }
    out
}

/// `floor(2^39 / 2π)`: [`ATAN_D1`]'s `K · 128`.
const ATAN_D1_NUMERATOR: u64 = 87_496_355_273;

/// [`ATAN_D1`]`[k]` (`k <= 128`; clamped there) computed:
/// `round(K · 128 / (16384 + k²))`, a 37-bit numerator over a 15-bit
/// divisor, as two 32-bit divisions (16 bits of quotient each). Equal to
/// the table at every node: checked at compile time below.
const fn atan_derivative(k: usize) -> i32 {
    let k = if k < 128 { k as u32 } else { 128 };
    let d = 16384 + k * k;
    let n = ATAN_D1_NUMERATOR + (d / 2) as u64;
    let hi = (n >> 16) as u32;
    let lo = (n & 0xFFFF) as u32;
    let (q1, r1) = (hi / d, hi % d);
    ((q1 << 16) + (((r1 << 16) | lo) / d)) as i32
}

// Compile-time indexing: an out-of-range index fails the build.
#[allow(clippy::indexing_slicing)]
const _: () = {
    let mut k = 0;
    while k <= 128 {
        assert!(atan_derivative(k) == ATAN_D1[k] as i32);
        k += 1;
    }
};

// The node tables as statics: a `const` indexed at run time could be
// emitted once per use. Only a `SMALL` build links them (the `atan`
// derivatives it computes: [`atan_derivative`]).
static ATAN_NODES: [u32; 129] = ATAN;
static SIN_NODES: [u32; 129] = SIN_Q30;

/// Step `i` of the `atan` table (`i < 128`; a zero step otherwise, never
/// asked for): [`ATAN_STEPS`]`[i]`, or with `SMALL` (a build for size:
/// 1,032 bytes of node tables instead of 3,600 of step tables, a few
/// multiplications more per `atan2` and `sin_cos`, four divisions more
/// per `atan2`) the
/// same coefficients computed from the nodes `i` and `i + 1`, with the
/// same `i32` arithmetic as the step tables' compile-time builders.
#[inline(always)]
pub(crate) fn atan_step<const SMALL: bool>(i: usize) -> Step<i32> {
    if SMALL {
        let node = |k: usize| {
            let p = ATAN_NODES.get(k).copied().or_broken(0);
            (p as i32, atan_derivative(k))
        };
        if i >= 128 {
            return Step::default();
        }
        let ((p0, m0), (p1, m1)) = (node(i), node(i + 1));
        let (p0, m0, c2, c3) = coefficients(p0, m0, p1, m1);
        Step { p0, m0, c2, c3 }
    } else {
        // Past the table: the documented zero step, as the `SMALL` form's.
        let s = ATAN_STEPS.get(i).copied().unwrap_or_default();
        Step {
            p0: s.p0,
            m0: s.m0,
            c2: s.c2.into(),
            c3: s.c3.into(),
        }
    }
}

/// Step `i` of the quarter-wave sine table (`i <= 128`; a zero step
/// otherwise, never asked for): [`SIN_STEPS`]`[i]`, or with `SMALL` the
/// same coefficients computed from the nodes `i`, `i + 1` (node 128 for
/// the padding step 128) and their cosines.
#[inline(always)]
pub(crate) fn sin_step<const SMALL: bool>(i: usize) -> Step<i32> {
    if SMALL {
        let node = |k: usize| {
            let p = SIN_NODES.get(k).copied().or_broken(0);
            let c = 128usize
                .checked_sub(k)
                .and_then(|c| SIN_NODES.get(c))
                .copied()
                .or_broken(0);
            (p as i32, sin_derivative(c))
        };
        if i > 128 {
            return Step::default();
        }
        let j = if i < 128 { i + 1 } else { 128 };
        let ((p0, m0), (p1, m1)) = (node(i), node(j));
        let (p0, m0, c2, c3) = coefficients(p0, m0, p1, m1);
        Step { p0, m0, c2, c3 }
    } else {
        // Past the table: the documented zero step, as the `SMALL` form's.
        SIN_STEPS.get(i).copied().unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both forms of every step are equal, coefficient by coefficient.
    #[test]
    fn computed_steps_equal_stored_steps() {
        let same =
            |a: Step<i32>, b: Step<i32>| (a.p0, a.m0, a.c2, a.c3) == (b.p0, b.m0, b.c2, b.c3);
        for i in 0..130 {
            assert!(
                same(atan_step::<true>(i), atan_step::<false>(i)),
                "atan step {i}"
            );
            assert!(
                same(sin_step::<true>(i), sin_step::<false>(i)),
                "sin step {i}"
            );
        }
        // Not vacuous: the steps differ from one another.
        assert!(!same(atan_step::<true>(3), atan_step::<true>(4)));
        assert!(!same(sin_step::<true>(3), sin_step::<true>(4)));
    }
}
