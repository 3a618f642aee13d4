//! Q8 fixed point (1/256 px), the unit of segment coordinates in the core,
//! and the rounding divisions that produce it. Each helper keeps every
//! intermediate within 64 bits; on a 32-bit target [`centroid_q8`] can avoid
//! 64-bit division altogether.

use core::num::{NonZeroU32, NonZeroU64};
use core::ops::{Add, Neg, Sub};

/// `p / n` in Q8, rounded half up, for `n <= 2^16`. `WIDE` (see
/// [`crate::target::WIDE`]): one 64-bit division; else two 32-bit ones
/// (`r << 8 < 2^24`). Equal, since `p = q·n + r` gives
/// `(256·p + n/2) / n = 256·q + (256·r + n/2) / n`.
pub(crate) fn centroid_q8<const WIDE: bool>(p: u32, n: NonZeroU32) -> i64 {
    if WIDE {
        let num = (u64::from(p) << 8) + u64::from(n.get() / 2);
        (num / NonZeroU64::from(n)) as i64
    } else {
        let (q, r) = (p / n, p % n);
        i64::from(q) * 256 + i64::from(((r << 8) + n.get() / 2) / n)
    }
}

/// `(n / d, n % d)`. A build for size ([`crate::target::SMALL`]) divides by
/// [`long_division`] instead of linking the 64-bit division routine,
/// which on a Cortex-M is about 1 KB of flash; the values are the same.
#[inline]
pub(crate) fn div_rem_u64(n: u64, d: NonZeroU64) -> (u64, u64) {
    if crate::target::SMALL {
        long_division(n, d)
    } else {
        (n / d, n % d)
    }
}

/// `(n / d, n % d)` by shift and subtract, one step per quotient bit,
/// or one 32-bit (hardware) division when both fit 32 bits.
#[cfg_attr(not(aaglsd_small), allow(dead_code))]
fn long_division(n: u64, d: NonZeroU64) -> (u64, u64) {
    let d = d.get();
    if n < d {
        return (0, n);
    }
    if let (Ok(n32), Some(d32)) = (
        u32::try_from(n),
        u32::try_from(d).ok().and_then(NonZeroU32::new),
    ) {
        return (u64::from(n32 / d32), u64::from(n32 % d32));
    }
    // d <= n: the quotient has `shift + 1` bits at most.
    let shift = d.leading_zeros() - n.leading_zeros();
    let (mut q, mut r, mut dd) = (0u64, n, d << shift);
    for _ in 0..=shift {
        q <<= 1;
        if r >= dd {
            r -= dd;
            q |= 1;
        }
        dd >>= 1;
    }
    (q, r)
}

/// `num · 256 / den` rounded half away from zero, for `|den| < 2^47`;
/// `None` for `den == 0`. Splits the quotient so that no intermediate
/// exceeds 64 bits.
pub(crate) fn div_q8(num: i64, den: i64) -> Option<i64> {
    let n = num.unsigned_abs();
    let d = NonZeroU64::new(den.unsigned_abs())?;
    let (q, r) = div_rem_u64(n, d);
    // r < d < 2^47, so r·256 + d/2 < 2^56.
    let v = (q << 8).wrapping_add(div_rem_u64((r << 8) + d.get() / 2, d).0);
    let v = i64::try_from(v).ok()?;
    Some(if (num < 0) != (den < 0) { -v } else { v })
}

/// `num / den` rounded half away from zero; `None` for `den == 0`: the
/// magnitudes through [`div_round_u64`] (one body for both).
pub(crate) fn div_round(num: i64, den: i64) -> Option<i64> {
    let d = den.unsigned_abs();
    if d == 0 {
        return None;
    }
    let q = i64::try_from(div_round_u64(num.unsigned_abs(), d)).ok()?;
    Some(if (num < 0) != (den < 0) { -q } else { q })
}

/// `n / d` rounded half up, `(n + d/2) / d` without overflow; 0 for
/// `d == 0`. Through [`div_rem_u64`] (no 64-bit division routine in a
/// build for size).
pub(crate) fn div_round_u64(n: u64, d: u64) -> u64 {
    NonZeroU64::new(d).map_or(0, |d| {
        let (q, r) = div_rem_u64(n, d);
        // Rounds up when `r >= d - d/2` (`d/2` rounded up): no overflow,
        // as `q` is below `u64::MAX` when `r > 0`.
        q + u64::from(r >= d.get() - d.get() / 2)
    })
}

/// `floor(sqrt(n))`: the standard library's, or in a build for size
/// ([`crate::target::SMALL`]) bit by bit, a dozen instructions of code where the
/// library's links half a kilobyte on a Cortex-M; the same values.
pub(crate) fn isqrt_u64(n: u64) -> u64 {
    if crate::target::SMALL {
        isqrt_bitwise(n)
    } else {
        n.isqrt()
    }
}

/// [`isqrt_u64`] one result bit per step.
#[cfg_attr(not(aaglsd_small), allow(dead_code))]
fn isqrt_bitwise(n: u64) -> u64 {
    let (mut rem, mut root) = (n, 0u64);
    // The largest power of four at most `n`.
    let mut bit = if n == 0 {
        0
    } else {
        1u64 << ((63 - n.leading_zeros()) & !1)
    };
    while bit != 0 {
        if rem >= root + bit {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// `num / 2^shift` rounded half away from zero: [`div_round`] by a power
/// of two, without a division. `shift` in `1..=62`.
pub(crate) fn div_round_pow2(num: i64, shift: u32) -> i64 {
    // At most 2^63 + 2^61: no overflow.
    let q = ((num.unsigned_abs() + (1 << (shift - 1))) >> shift) as i64;
    if num < 0 { -q } else { q }
}

/// The bits of `v` as a Q32 number (`I32F32`): exact for every `f32` with
/// a magnitude of at least 2^-32, the rest rounded to nearest (ties to
/// even); `None` for NaN, the infinities and magnitudes beyond the range
/// (`[-2^31, 2^31)`). The `fixed` crate's `I32F32::checked_from_num`; a
/// build for size ([`crate::target::SMALL`]) decodes the float itself
/// ([`decode_q32`], less code than the general conversion), with the same
/// results (`decoded_q32_is_fixed`).
#[inline]
pub(crate) fn q32_of(v: f32) -> Option<i64> {
    if crate::target::SMALL {
        decode_q32(v)
    } else {
        fixed::types::I32F32::checked_from_num(v).map(fixed::types::I32F32::to_bits)
    }
}

/// [`q32_of`] from the float's fields: `m · 2^(e - 150)` with the 24-bit
/// significand `m`, shifted to Q32.
#[cfg_attr(not(aaglsd_small), allow(dead_code))]
#[inline(never)]
fn decode_q32(v: f32) -> Option<i64> {
    let bits = v.to_bits();
    let e = (bits >> 23) & 0xFF;
    if e == 0xFF {
        return None; // NaN, infinities
    }
    if e == 0 {
        return Some(0); // zero and subnormals (below 2^-126)
    }
    let m = u64::from((bits & 0x7F_FFFF) | 0x80_0000);
    // Q32 bits: m · 2^(e - 150 + 32) = m · 2^(e - 118).
    let mag = if e >= 118 {
        let s = e - 118;
        if s > 40 {
            return None;
        }
        m << s // at most 2^64 - 2^40: no overflow
    } else {
        let s = 118 - e;
        if s > 25 {
            0 // below a quarter of the last unit
        } else {
            // In 32 bits (`m` has 24): no 64-bit shift routine.
            let m = m as u32;
            let (q, r, half) = (m >> s, m & ((1 << s) - 1), 1 << (s - 1));
            u64::from(q + u32::from(r > half || (r == half && q & 1 == 1)))
        }
    };
    if bits >> 31 == 0 {
        i64::try_from(mag).ok()
    } else if mag <= 1 << 63 {
        Some(0i64.wrapping_sub_unsigned(mag))
    } else {
        None
    }
}

/// The integer nearest `num / den` (`den > 0`), ties away from zero (as
/// [`div_round`]), from an `estimate` within two of it and the exact
/// residual `r = num - estimate·den`: the last step of a quotient that is
/// estimated rather than divided (its terms exceed 64 bits, or a 32-bit
/// target would need its 64-bit division routine). Additions and
/// comparisons only, in `i64` or, where the residual needs them, `i128`.
pub(crate) fn nearest_from<T>(estimate: i64, r: T, den: T) -> i64
where
    T: Copy + PartialOrd + Add<Output = T> + Sub<Output = T> + Neg<Output = T>,
{
    let (mut v, mut r) = (estimate, r);
    // `v` is the nearest integer when `-den <= 2r < den` (for a quotient
    // at or above zero) or `-den < 2r <= den` (below zero).
    for _ in 0..2 {
        let twice = r + r;
        if twice > den || (twice == den && v >= 0) {
            v += 1;
            r = r - den;
        } else if twice < -den || (twice == -den && v <= 0) {
            v -= 1;
            r = r + den;
        }
    }
    v
}

/// Round a Q8 value to an integer, half away from zero.
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn round_q8(v: i64) -> i64 {
    if v >= 0 {
        (v + 128) >> 8
    } else {
        -((-v + 128) >> 8)
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn isqrt_and_rounded_division_are_exact() {
        let mut next = crate::xorshift64(0x5157);
        for k in 0..20_000u64 {
            let n = match k {
                0..=300 => k,
                301 => u64::MAX,
                _ => next() >> (k % 64),
            };
            assert_eq!(isqrt_bitwise(n), n.isqrt(), "{n}");
            let d = next() >> (k % 64);
            let want = if d == 0 {
                0
            } else {
                (u128::from(n) + u128::from(d / 2)) / u128::from(d)
            };
            assert_eq!(u128::from(div_round_u64(n, d)), want, "{n} / {d}");
        }
    }

    use super::*;

    /// The float decoding gives `fixed`'s conversion for every exponent
    /// and sign, on random significands and the edges.
    #[test]
    fn decoded_q32_is_fixed() {
        let fixed =
            |v: f32| fixed::types::I32F32::checked_from_num(v).map(fixed::types::I32F32::to_bits);
        let mut next = crate::xorshift64(0xBB67_AE85_84CA_A73B);
        let check = |bits: u32| {
            let v = f32::from_bits(bits);
            assert_eq!(decode_q32(v), fixed(v), "{v:e} ({bits:#010x})");
        };
        for sign in [0u32, 1 << 31] {
            for e in 0..=255u32 {
                for m in [0u32, 1, 0x40_0000, 0x7F_FFFF, 0x3F_FFFF, 0x40_0001] {
                    check(sign | e << 23 | m);
                }
                for _ in 0..if cfg!(miri) { 2 } else { 200 } {
                    check(sign | e << 23 | (next() as u32 & 0x7F_FFFF));
                }
            }
        }
        for v in [
            -2147483648.0f32,
            2147483648.0,
            2147483520.0,
            -2147483520.0,
            0.5,
            -0.0,
        ] {
            check(v.to_bits());
        }
    }

    /// The shift rounds as the division does.
    #[test]
    fn power_of_two_rounding_is_div_round() {
        let mut next = crate::xorshift64(0xD1B5_4A32_D192_ED03);
        for shift in 1..=62u32 {
            let half = 1i64 << (shift - 1);
            let edges = [
                0,
                1,
                -1,
                half,
                -half,
                half - 1,
                1 - half,
                3 * half,
                -3 * half,
                i64::MAX,
                i64::MIN,
            ];
            for num in edges.into_iter().chain(
                (0..if cfg!(miri) { 5 } else { 200 }).map(|_| next() as i64 >> (next() % 64)),
            ) {
                assert_eq!(
                    Some(div_round_pow2(num, shift)),
                    div_round(num, 1 << shift),
                    "{num} >> {shift}"
                );
            }
        }
    }

    /// The long division gives the quotient and remainder of `u64`
    /// division: random operands of every pair of widths, and the edges.
    #[test]
    fn long_division_is_exact() {
        let mut next = crate::xorshift64(0x9E37_79B9_7F4A_7C15);
        let check = |n: u64, d: u64| {
            let Some(nz) = NonZeroU64::new(d) else { return };
            assert_eq!(long_division(n, nz), (n / d, n % d), "{n} / {d}");
        };
        for bits_n in 0..=64u32 {
            for bits_d in 1..=64u32 {
                for _ in 0..if cfg!(miri) { 1 } else { 20 } {
                    let mask = |b: u32| if b == 64 { u64::MAX } else { (1u64 << b) - 1 };
                    check(next() & mask(bits_n), next() & mask(bits_d));
                }
            }
        }
        for (n, d) in [
            (u64::MAX, 1),
            (u64::MAX, u64::MAX),
            (u64::MAX - 1, u64::MAX),
            (0, 7),
            (1 << 63, 3),
            (u64::MAX, 1 << 32),
            (u32::MAX as u64, u32::MAX as u64 + 1),
        ] {
            check(n, d);
        }
    }
    use crate::num::trig::ratio_q32;

    #[test]
    fn wide_and_narrow_divisions_agree() {
        let mut next = crate::xorshift64(0x853C_49E6_748F_EA9B);
        let cases = if cfg!(miri) { 2_000 } else { 2_000_000 };
        for k in 0..cases {
            let n = NonZeroU32::new(1 + (next() % (1 << 16)) as u32).unwrap();
            // Any u32 sum, biased towards small ones and the top of the range.
            let p = match k % 3 {
                0 => next() as u32,
                1 => (next() % 4096) as u32,
                _ => u32::MAX - (next() % 4096) as u32,
            };
            assert_eq!(
                centroid_q8::<true>(p, n),
                centroid_q8::<false>(p, n),
                "{p}/{n}"
            );
            let den = (next() as u32 >> (next() % 32)).max(1);
            let num = (next() as u32) % den;
            assert_eq!(
                ratio_q32::<true>(num, NonZeroU32::new(den).unwrap()),
                ratio_q32::<false>(num, NonZeroU32::new(den).unwrap()),
                "{num}/{den}"
            );
        }
        for (num, den) in [(0, 1), (u32::MAX - 1, u32::MAX), (1, 2), (5, 5), (7, 3)] {
            assert_eq!(
                ratio_q32::<true>(num, NonZeroU32::new(den).unwrap()),
                ratio_q32::<false>(num, NonZeroU32::new(den).unwrap()),
                "{num}/{den}"
            );
        }
        for p in [0, 1, u32::MAX] {
            for n in [1, 2, 3, 65_535, 65_536] {
                let n = NonZeroU32::new(n).unwrap();
                assert_eq!(
                    centroid_q8::<true>(p, n),
                    centroid_q8::<false>(p, n),
                    "{p}/{n}"
                );
            }
        }
    }

    #[test]
    fn rounding() {
        assert_eq!(round_q8(128), 1);
        assert_eq!(round_q8(127), 0);
        assert_eq!(round_q8(-128), -1);
        assert_eq!(round_q8(-127), 0);
        assert_eq!(div_round(5, 2), Some(3));
        assert_eq!(div_round(-5, 2), Some(-3));
        assert_eq!(div_round(1, 0), None);
        assert_eq!(div_q8(1, 2), Some(128));
        assert_eq!(div_q8(-3, 512), Some(-2)); // -1.5/256 -> -2 (half away)
        assert_eq!(div_q8(5, 3), Some(427)); // 426.67
        assert_eq!(div_q8(1, 0), None);
        let (n, d) = (4_611_686_018_427_387_903i64, 140_737_488_355_327i64);
        let exact = (i128::from(n) * 256 + i128::from(d) / 2) / i128::from(d);
        assert_eq!(div_q8(n, d), Some(exact as i64));
    }
}
