//! Paper §3.2: the line geometry of the linking and merging (design §7.1 and
//! design §8), in integers.
//!
//! * **Line fit** ([`Fit`]): exact integer sums `n, Σx, Σy, Σx², Σy², Σxy`
//!   (`i64`; coordinates < 2^15 and at most 2^16 points, so the centred
//!   moments `n·Σx² - (Σx)²` and the like are below 2^62). Direction
//!   `t = atan2(2·cxy, cxx - cyy) / 2` by the LUT atan2, as a binary angle;
//!   unit vector by the LUT sin/cos in Q30.
//! * **Lines** ([`Line`]) are a binary-angle direction through a rational
//!   point `(px/n, py/n)` (the fit's centroid, or a group centre with
//!   `n = 1`). Distances are compared as `|n·(p - c) × u| > T·n` in Q30;
//!   projections are rounded to the nearest Q8 value (1/256 px).

use core::num::NonZeroU32;

use crate::num::q8::{centroid_q8, div_q8, div_round, div_round_pow2, nearest_from, round_q8};
use crate::num::trig::{Bam, DEG_45, atan2, fold_half, ratio_q32, sin_cos};
use crate::target::{SMALL, WIDE};

/// Exact integer least-squares sums.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fit {
    n: i64,
    sx: i64,
    sy: i64,
    sxx: i64,
    syy: i64,
    sxy: i64,
}

impl Default for Fit {
    /// No points. In a build for size, out of line and with a zero the
    /// optimiser cannot see through (`black_box`): it would otherwise turn
    /// the six stores into a call of an 8-byte-aligned `memset` that
    /// nothing else links (174 bytes).
    #[cfg_attr(aaglsd_small, inline(never))]
    fn default() -> Self {
        let zero = if SMALL { core::hint::black_box(0) } else { 0 };
        Self {
            n: zero,
            sx: zero,
            sy: zero,
            sxx: zero,
            syy: zero,
            sxy: zero,
        }
    }
}

impl Fit {
    /// Adds the point `(x, y)`. The products are 32x32 -> 64-bit
    /// multiply-accumulates (one `SMLAL` each on a Cortex-M4).
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub(crate) fn add(&mut self, x: i32, y: i32) {
        let (x, y) = (i64::from(x), i64::from(y));
        self.n += 1;
        self.sx += x;
        self.sy += y;
        self.sxx += x * x;
        self.syy += y * y;
        self.sxy += x * y;
    }

    /// `(n, Σx, Σy)` (the float reference's fits use these sums).
    #[cfg(feature = "reference")]
    pub(crate) fn sums(&self) -> (i64, i64, i64) {
        (self.n, self.sx, self.sy)
    }

    /// The centred moments `(n·Σx² - (Σx)², n·Σy² - (Σy)², n·Σxy - Σx·Σy)`.
    pub(crate) fn moments(&self) -> (i64, i64, i64) {
        // Each centred moment is bounded by 2^62 (see the module docs); the
        // intermediate products may wrap, the differences are exact.
        let cxx = self
            .n
            .wrapping_mul(self.sxx)
            .wrapping_sub(self.sx.wrapping_mul(self.sx));
        let cyy = self
            .n
            .wrapping_mul(self.syy)
            .wrapping_sub(self.sy.wrapping_mul(self.sy));
        let cxy = self
            .n
            .wrapping_mul(self.sxy)
            .wrapping_sub(self.sx.wrapping_mul(self.sy));
        (cxx, cyy, cxy)
    }

    /// The orthogonal least-squares line through the centroid.
    pub(crate) fn line(&self) -> Line {
        self.line_inline()
    }

    /// [`Fit::line`], inlined: the walk's refit after each regular pixel,
    /// its hottest caller, then keeps the line in registers instead of
    /// reading back a returned struct.
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub(crate) fn line_inline(&self) -> Line {
        let (cxx, cyy, cxy) = self.moments();
        let diff = cxx.wrapping_sub(cyy);
        let double = if cxy.unsigned_abs() < 1 << 61 {
            atan2(cxy * 2, diff)
        } else {
            atan2(cxy, diff >> 1)
        };
        // The exact tie 2t = -45° (`2·cxy = -(cxx - cyy)`, cxy < 0) puts the
        // line at exactly -22.5°, the N45 / Hz walk-class boundary. The
        // official code reaches the angle through f32 (`atan2` rounded to
        // f32, halved, `cosf`/`sinf`, `atanf`), which reads this tie as
        // -22.500002° (N45); one unit less (8e-8°) gives the same class here.
        // Every other double-angle tie (±45°·k, ±90°, 180°) already lands on
        // the same side in both (`fit_ties_classify_like_the_float_chain`).
        let double = if double == DEG_45.wrapping_neg() {
            double - 1
        } else {
            double
        };
        Line::new(double / 2, self.sx, self.sy, self.n.max(1))
    }
}

/// A line: direction `angle` (only its value mod 180° matters) through
/// `(px/n, py/n)`, with its unit vector `(c, s)` in Q30.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line {
    pub angle: Bam,
    c: i64,
    s: i64,
    px: i64,
    py: i64,
    n: i64,
}

impl Line {
    pub(crate) fn new(angle: Bam, px: i64, py: i64, n: i64) -> Self {
        let (c, s) = sin_cos(angle);
        Self {
            angle,
            c: i64::from(c),
            s: i64::from(s),
            px,
            py,
            n,
        }
    }

    /// `*self = *from`; in a build for size ([`SMALL`]) field by field,
    /// as it would otherwise copy the 48 bytes by a call of `memcpy`, and
    /// these copies (the walk's refits) are the only ones that bring that
    /// routine in.
    #[inline(always)]
    pub(crate) fn assign(&mut self, from: &Self) {
        if !SMALL {
            *self = *from;
            return;
        }
        let Self {
            angle,
            c,
            s,
            px,
            py,
            n,
        } = *from;
        (self.angle, self.c, self.s) = (angle, c, s);
        (self.px, self.py, self.n) = (px, py, n);
    }

    /// The line angle in `[-90°, 90°)`.
    pub(crate) fn signed(&self) -> i32 {
        fold_half(self.angle)
    }

    /// Whether the gradient `g` (components below 2^11 in magnitude) lies
    /// strictly within the angle of Q30 cosine `ct` and sine `st` (below
    /// 90°) of the line's direction: `|g × u|·cos < |g · u|·sin`. The
    /// products are shifted below 2^31 first (to 2^-30 of their size, far
    /// below the reference's `f32` angles), so the test fits `i64`.
    pub(crate) fn along(&self, (gx, gy): (i32, i32), ct: i64, st: i64) -> bool {
        let (gx, gy) = (i64::from(gx), i64::from(gy));
        let cross = (gx * self.s - gy * self.c) >> 11;
        let dot = (gx * self.c + gy * self.s) >> 11;
        cross.abs() * ct < dot.abs() * st
    }

    /// `|tan| > 1`.
    pub(crate) fn steep(&self) -> bool {
        self.signed().unsigned_abs() > DEG_45
    }

    /// Perpendicular distance from `(x, y)` exceeds `t_q30` (Q30 pixels).
    #[inline(always)]
    pub(crate) fn farther_than(&self, x: i32, y: i32, t_q30: i64) -> bool {
        // A 64-bit core computes the general form outright: the range tests
        // of the narrow one would cost more than its narrower products save.
        let cross = if cfg!(target_pointer_width = "64") || !self.narrow_at(x, y) {
            self.cross(x, y)
        } else {
            self.cross_narrow(x, y)
        };
        cross.abs() > t_q30 * self.n
    }

    /// `n·((x, y) - centroid) × u`, in Q30: below 2^62 in magnitude for
    /// points and sums within the module's bounds. The walk's only form on
    /// a 64-bit core; elsewhere its rare fallback, kept out of line so that
    /// the walk loop keeps its registers.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    #[cfg_attr(not(target_pointer_width = "64"), inline(never))]
    fn cross(&self, x: i32, y: i32) -> i64 {
        let dx = self.n * i64::from(x) - self.px;
        let dy = self.n * i64::from(y) - self.py;
        dx.wrapping_mul(self.s)
            .wrapping_sub(dy.wrapping_mul(self.c))
    }

    /// Whether [`Line::cross_narrow`] applies at `(x, y)`: the walk's case,
    /// tested on every visited pixel (coordinates below 2^15, at most 2^16
    /// points, sums below 2^31; a negative value fails as a huge unsigned).
    #[inline(always)]
    fn narrow_at(&self, x: i32, y: i32) -> bool {
        (self.n as u64) <= 1 << 16
            && (self.px as u64) < 1 << 31
            && (self.py as u64) < 1 << 31
            && ((x | y) as u32) < 1 << 15
    }

    /// [`Line::cross`] in 32-bit steps where [`Line::narrow_at`] holds:
    /// `n·x` and `px` then both lie in [0, 2^31), so each offset `n·x - px`
    /// is one 32-bit multiply-subtract (`MLS` on a Cortex-M4) and each cross
    /// term one 32x32 -> 64-bit product (`SMULL`), with no 64-bit product
    /// of the sums.
    #[inline(always)]
    fn cross_narrow(&self, x: i32, y: i32) -> i64 {
        let n = self.n as i32;
        let dx = n * x - self.px as i32;
        let dy = n * y - self.py as i32;
        i64::from(dx) * i64::from(self.s as i32) - i64::from(dy) * i64::from(self.c as i32)
    }

    /// The unit direction in Q30.
    pub(crate) fn unit(&self) -> (i32, i32) {
        (self.c as i32, self.s as i32)
    }

    /// Signed position of `(x, y)` along the line, from the point, scaled
    /// by `n·2^30` (below 2^62 in magnitude).
    #[cfg_attr(aaglsd_small, inline(never))]
    pub(crate) fn projection(&self, x: i64, y: i64) -> i64 {
        (self.n * x - self.px) * self.c + (self.n * y - self.py) * self.s
    }

    /// The point at [`Line::projection`] `t`, in Q8: each coordinate
    /// `p/n + t·u/(n·2^60)` (`p` the centroid sum, `u` the Q30 unit
    /// component) rounded to the nearest Q8 value, ties away from zero, as
    /// the walk's ends (design §9). An estimate in 64-bit arithmetic
    /// (the distance along the line and the centroid rounded to Q8
    /// separately, within two units), then [`nearest_from`] on the exact
    /// residual `p·2^60 + t·u - v·n·2^52`, in 128 bits: one product.
    pub(crate) fn point_at(&self, t: i64) -> (i64, i64) {
        // Distance from the centroid in Q8: t / (n·2^30) · 256.
        let d = div_round(t, self.n << 22).unwrap_or(0); // |d| < 2^24
        let den = i128::from(self.n) << 52;
        let at = |p: i64, u: i64| {
            let v = div_q8(p, self.n).unwrap_or(0) + div_round_pow2(d * u, 30);
            // Below 2^95 in magnitude: `p < 2^32`, `|t| < 2^62`, `|u| <= 2^30`,
            // `|v| < 2^24`, `n <= 2^17`.
            let r = (i128::from(p) << 60) + i128::from(t) * i128::from(u)
                - ((i128::from(v) * i128::from(self.n)) << 52);
            nearest_from(v, r, den)
        };
        (at(self.px, self.c), at(self.py, self.s))
    }

    /// The column of the line's pixel at row `y`: x in Q8 rounded (`None`
    /// for a horizontal line).
    pub(crate) fn x_pixel_at(&self, y: i64) -> Option<i64> {
        self.x_by_row().pixel_at(y)
    }

    /// The row of the line's pixel at column `x`: y in Q8 rounded (`None`
    /// for a vertical line).
    pub(crate) fn y_pixel_at(&self, x: i64) -> Option<i64> {
        self.y_by_column().pixel_at(x)
    }

    /// x on the line by row, in Q8 (the shared terms computed once).
    pub(crate) fn x_by_row(&self) -> Minor {
        Minor::new(self.py, self.px, self.n, self.s, self.c)
    }

    /// y on the line by column, in Q8 (the shared terms computed once).
    pub(crate) fn y_by_column(&self) -> Minor {
        Minor::new(self.px, self.py, self.n, self.c, self.s)
    }
}

/// The minor coordinate, in Q8, of the point at major coordinate `t` on the
/// line through `(pu/n, pv/n)` (major, minor) with direction `(du, dv)`
/// (major, minor components, Q30): `pv/n + (t - pu/n)·dv/du`, the exact
/// rational rounded to the nearest Q8 value, ties away from zero
/// (design §8). The float reference takes its decisions on its ends rounded to
/// that grid (design §12): any other rule for the last unit moves a
/// decision near a threshold, such as a merge within a few thousandths of
/// a degree of D_a.
///
/// When `|dv| < |du|` (every line but those at exactly 45°, or the `extend`
/// probe of a steep line) it needs no 64-bit division on a 32-bit target:
/// the centroid in Q8 ([`centroid_q8`]), the slope `|dv|/|du|` in Q32
/// ([`ratio_q32`]), both computed once per line, and one 32x32 -> 64-bit
/// product per point give an estimate within two Q8 units, which
/// [`Minor::nearest`] corrects by the exact residual. Otherwise [`div_q8`]
/// evaluates the exact rational. Both give the same value, on every
/// target.
pub(crate) struct Minor {
    pu: i64,
    pv: i64,
    n: i64,
    du: i64,
    dv: i64,
    /// The centroid `(cu, cv)` in Q8, the slope in Q32 and whether it is
    /// negative, when `|dv| < |du|`, the sums fit 32 bits and the centroid
    /// an `i32`.
    fast: Option<(i32, i32, u32, bool)>,
}

/// The side and the magnitude of [`Minor`]'s offset at major coordinate
/// `t` from the centroid's minor coordinate, in Q8: `d = 256·t - cu` and
/// `|d|·ratio / 2^32` rounded; `None` when the product overflows. `WIDE`
/// (see [`crate::target::WIDE`]): in 64-bit arithmetic; else, for every
/// point of an image (|t| < 2^22), `d` in 32 bits and one 32 x 32 -> 64-bit
/// product, which cannot overflow (a 32-bit core then needs no other 64-bit
/// operation). The same values (`offset_forms_agree`).
#[inline(always)]
fn offset<const WIDE: bool>(t: i64, cu: i32, ratio: u32) -> Option<(bool, i64)> {
    let (negative, product) = match i32::try_from(t) {
        Ok(t) if !WIDE && t.unsigned_abs() < 1 << 22 => {
            let d = (t << 8) - cu;
            (d < 0, u64::from(d.unsigned_abs()) * u64::from(ratio))
        }
        _ => {
            let d = (t << 8) - i64::from(cu);
            (d < 0, d.unsigned_abs().checked_mul(u64::from(ratio))?)
        }
    };
    // Rounded to Q8; the sum wraps only for a product within 2^31 of
    // 2^64, from no point of an image.
    Some((negative, (product.wrapping_add(1 << 31) >> 32) as i64))
}

impl Minor {
    fn new(pu: i64, pv: i64, n: i64, du: i64, dv: i64) -> Self {
        let (adu, adv) = (du.unsigned_abs(), dv.unsigned_abs());
        let small = |v: i64| u32::try_from(v).ok();
        let fast = match (
            adv < adu,
            small(pu),
            small(pv),
            // The residual of `Minor::nearest` needs `n·|du| < 2^47`.
            small(n).filter(|&n| n <= 1 << 16).and_then(NonZeroU32::new),
            u32::try_from(adu).ok().and_then(NonZeroU32::new),
            u32::try_from(adv).ok(),
        ) {
            // A centroid in Q8 as an `i32`: below 2^23 for the points of an
            // image (coordinates below 2^15); beyond, the exact form.
            (true, Some(pu), Some(pv), Some(n), Some(adu), Some(adv)) => {
                match (
                    i32::try_from(centroid_q8::<WIDE>(pu, n)),
                    i32::try_from(centroid_q8::<WIDE>(pv, n)),
                ) {
                    (Ok(cu), Ok(cv)) => Some((
                        cu,
                        cv,
                        ratio_q32::<WIDE>(adv, adu), // |dv/du| in Q32
                        (du < 0) != (dv < 0),
                    )),
                    _ => None,
                }
            }
            _ => None,
        };
        Self {
            pu,
            pv,
            n,
            du,
            dv,
            fast,
        }
    }

    /// The minor coordinate at major coordinate `t`, in Q8; `None` when the
    /// line runs along the minor axis (or a value overflows).
    pub(crate) fn at(&self, t: i64) -> Option<i64> {
        let (v, exact) = self.estimate(t)?;
        Some(if exact { v } else { self.nearest(v, t) })
    }

    /// The pixel that [`Minor::at`] rounds to (half away from zero, as
    /// [`round_q8`]). The probes of the walk need no more, and their
    /// estimate is rarely near a pixel's rounding boundary, which lies
    /// between the fractions 127 and 128 (of 256) at and above zero, 128
    /// and 129 below: where the estimate's fraction is more than 2 from
    /// 128, every value within two units of it (the nearest among them)
    /// rounds the same way, and the correction is skipped.
    pub(crate) fn pixel_at(&self, t: i64) -> Option<i64> {
        let (v, exact) = self.estimate(t)?;
        let clear = ((v & 0xFF) - 128).abs() > 2;
        Some(round_q8(if exact || clear {
            v
        } else {
            self.nearest(v, t)
        }))
    }

    /// [`Minor::at`] or an estimate within two units of it, and whether it
    /// is the value itself.
    #[inline(always)]
    fn estimate(&self, t: i64) -> Option<(i64, bool)> {
        if let Some((cu, cv, ratio, descending)) = self.fast {
            let (negative, off) = offset::<WIDE>(t, cu, ratio)?;
            let v = if negative != descending {
                i64::from(cv) - off
            } else {
                i64::from(cv) + off
            };
            return Some((v, false));
        }
        // A point count beyond 32 bits (never: at most 2^16) gives `None`.
        u32::try_from(self.n).ok()?;
        let num = self.pv * self.du + (self.n * t - self.pu) * self.dv;
        Some((div_q8(num, self.n * self.du)?, true))
    }

    /// The Q8 value nearest `256·num/den` (ties away from zero, as
    /// [`div_q8`]), where `num = pv·du + (n·t - pu)·dv` and `den = n·du`
    /// are the exact rational's terms, from an `estimate` within two units
    /// of it. The estimate rounds the centroid, the distance along the
    /// major axis and the offset separately, so it can miss by one unit.
    /// The residual `256·num - estimate·den` is then below `2·den <= 2^47`
    /// in magnitude (`n <= 2^16`, `|du| <= 2^30`): wrapping 64-bit
    /// arithmetic computes it exactly, although `256·num` itself may not
    /// fit; no division, no 128 bits.
    fn nearest(&self, estimate: i64, t: i64) -> i64 {
        let num = self.pv.wrapping_mul(self.du).wrapping_add(
            self.n
                .wrapping_mul(t)
                .wrapping_sub(self.pu)
                .wrapping_mul(self.dv),
        );
        let den = self.n.wrapping_mul(self.du);
        let (num, den) = if den < 0 {
            (num.wrapping_neg(), den.wrapping_neg())
        } else {
            (num, den)
        };
        let r = num
            .wrapping_mul(256)
            .wrapping_sub(estimate.wrapping_mul(den));
        nearest_from(estimate, r, den)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::trig::DEG_90;

    #[test]
    fn fit_directions() {
        let mut f = Fit::default();
        for x in 0..10 {
            f.add(x, 5);
        }
        assert_eq!(f.line().signed(), 0);
        let mut f = Fit::default();
        for y in 0..10 {
            f.add(3, y);
        }
        assert_eq!(f.line().signed(), -(DEG_90 as i32));
        let mut f = Fit::default();
        for k in 0..10 {
            f.add(k, k);
        }
        let a = f.line().signed();
        assert!((a - DEG_45 as i32).abs() < 64, "{a}");
    }

    /// Both forms of [`offset`] give the same value for points of an image,
    /// at its limits and beyond, for random centroids and slopes.
    #[test]
    fn offset_forms_agree() {
        let mut next = crate::xorshift64(0x000F_F5E7);
        let ts = [
            0i64,
            1,
            -1,
            (1 << 22) - 1,
            1 << 22,
            -(1 << 22),
            32_767,
            i64::MAX >> 9,
        ];
        for round in 0..if cfg!(miri) { 200 } else { 200_000 } {
            let cu = (next() % (1 << 24)) as i32;
            let ratio = if round % 7 == 0 {
                u32::MAX
            } else {
                next() as u32
            };
            let t = if round % 3 == 0 {
                ts[round % ts.len()]
            } else {
                (next() % (1 << 24)) as i64 - (1 << 23)
            };
            assert_eq!(
                offset::<true>(t, cu, ratio),
                offset::<false>(t, cu, ratio),
                "{t} {cu} {ratio}"
            );
        }
    }

    #[test]
    fn along_is_the_angle_to_the_direction() {
        // Random lines and gradients against the angle between them in
        // `f64`, away from the threshold (T = 22.5°).
        let mut next = crate::xorshift64(0x0A10_9E55);
        let (ct, st) = sin_cos(crate::num::trig::bam_from_degrees(22.5));
        let (ct, st) = (i64::from(ct), i64::from(st));
        let (mut near, mut within, mut total) = (0, 0, 0);
        for _ in 0..if cfg!(miri) { 500 } else { 100_000 } {
            let angle = next() as u32;
            let line = Line::new(angle, 0, 0, 1);
            let g = ((next() % 1021) as i32 - 510, (next() % 1021) as i32 - 510);
            if g == (0, 0) {
                continue;
            }
            let t = f64::from(angle) / 2f64.powi(32) * core::f64::consts::TAU;
            let (u, v) = (libm::cos(t), libm::sin(t));
            let (gx, gy) = (f64::from(g.0), f64::from(g.1));
            let between = libm::atan2((gx * v - gy * u).abs(), (gx * u + gy * v).abs());
            let off = between.to_degrees() - 22.5;
            if off.abs() < 1e-3 {
                near += 1;
                continue;
            }
            within += usize::from(off < 0.0);
            total += 1;
            assert_eq!(line.along(g, ct, st), off < 0.0, "{angle} {g:?} {off}");
        }
        // Both answers were asked for (a quarter of the directions are
        // within 22.5°), and few cases were skipped.
        assert!(
            8 * within > total && 8 * within < 7 * total,
            "{within} {total}"
        );
        assert!(100 * near < total, "{near} {total}");
    }

    #[test]
    fn narrow_cross_equals_the_general_form() {
        // Every target must compute the same distance test, whichever form
        // it takes: random lines and points around the narrow form's bounds.
        let mut seed = 11u64;
        let (mut narrow, rounds) = (0, if cfg!(miri) { 1_000 } else { 50_000 });
        for _ in 0..rounds {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let n = 1 + (seed >> 47) as i64 % if seed & 2 == 0 { 1 << 17 } else { 500 };
            let big = if seed & 1 == 0 { 1 << 15 } else { 700 };
            let px = n * ((seed >> 8) as i64 % big) + (seed >> 20) as i64 % n;
            let py = n * ((seed >> 30) as i64 % big) + (seed >> 40) as i64 % n;
            let line = Line::new((seed >> 3) as u32, px, py, n);
            let x = ((seed >> 13) as i32 % (big as i32 + 8)) - 4;
            let y = ((seed >> 23) as i32 % (big as i32 + 8)) - 4;
            if line.narrow_at(x, y) {
                narrow += 1;
                let c = line.cross_narrow(x, y);
                assert_eq!(c, line.cross(x, y), "n {n} p ({px}, {py}) at ({x}, {y})");
            }
        }
        assert!(narrow * 10 > rounds, "the narrow form ran {narrow} times");
    }

    #[test]
    fn point_at_is_the_nearest_q8_value() {
        // Points projected onto lines through (px/n, py/n): each
        // coordinate `(p·2^60 + t·u) / (n·2^52)` rounded half away from
        // zero, by a 128-bit division.
        let nearest = |num: i128, den: i128| {
            let q = (2 * num.abs() + den) / (2 * den);
            if num < 0 { -q } else { q }
        };
        let mut seed = 5u64;
        for _ in 0..if cfg!(miri) { 1_000 } else { 50_000 } {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let n = 1 + (seed >> 47) as i64 % if seed & 1 == 0 { 1 << 16 } else { 300 };
            let px = n * ((seed >> 8) as i64 % 1200) + (seed >> 20) as i64 % n;
            let py = n * ((seed >> 30) as i64 % 900) + (seed >> 40) as i64 % n;
            let line = Line::new((seed >> 3) as u32, px, py, n);
            let (x, y) = ((seed >> 13) as i64 % 1300, (seed >> 23) as i64 % 1000);
            let t = line.projection(x, y);
            let exact = |p: i64, u: i64| {
                nearest(
                    (i128::from(p) << 60) + i128::from(t) * i128::from(u),
                    i128::from(n) << 52,
                ) as i64
            };
            assert_eq!(
                line.point_at(t),
                (exact(px, line.c), exact(py, line.s)),
                "n {n} p ({px}, {py}) angle {} at ({x}, {y})",
                line.angle
            );
        }
    }

    #[test]
    fn minor_axis_projection_matches_the_exact_rational() {
        // Lines through (px/n, py/n) in several directions; every result
        // the exact rational rounded to the nearest Q8 value.
        let mut seed = 7u64;
        for _ in 0..if cfg!(miri) { 1_000 } else { 20_000 } {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let n = 1 + (seed >> 48) as i64 % 500;
            let px = n * ((seed >> 8) as i64 % 600) + (seed >> 20) as i64 % n;
            let py = n * ((seed >> 30) as i64 % 400) + (seed >> 40) as i64 % n;
            let a = (seed >> 3) as u32;
            let line = Line::new(a, px, py, n);
            let t = (seed >> 12) as i64 % 700;
            let exact_x = div_q8(
                line.px * line.s + (line.n * t - line.py) * line.c,
                line.n * line.s,
            );
            let exact_y = div_q8(
                line.py * line.c + (line.n * t - line.px) * line.s,
                line.n * line.c,
            );
            let (by_row, by_column) = (line.x_by_row(), line.y_by_column());
            if let (Some(e), Some(g)) = (exact_x, by_row.at(t)) {
                assert_eq!(e, g, "x");
                assert_eq!(by_row.pixel_at(t), Some(round_q8(e)), "x pixel");
            }
            if let (Some(e), Some(g)) = (exact_y, by_column.at(t)) {
                assert_eq!(e, g, "y");
                assert_eq!(by_column.pixel_at(t), Some(round_q8(e)), "y pixel");
            }
        }
    }
}
