//! Q8 fixed point (1/256 px), the unit of segment coordinates in the core,
//! and the rounding divisions that produce it. Each helper keeps every
//! intermediate within 64 bits; on a 32-bit target [`centroid_q8`] can avoid
//! 64-bit division altogether.

use core::num::{NonZeroU32, NonZeroU64};

/// `p / n` in Q8, rounded half up, for `n <= 2^16`. `WIDE` (see
/// [`crate::num::trig::WIDE`]): one 64-bit division; else two 32-bit ones
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

/// `num · 256 / den` rounded half away from zero, for `|den| < 2^47`;
/// `None` for `den == 0`. Splits the quotient so that no intermediate
/// exceeds 64 bits.
pub(crate) fn div_q8(num: i64, den: i64) -> Option<i64> {
    let n = num.unsigned_abs();
    let d = core::num::NonZeroU64::new(den.unsigned_abs())?;
    let (q, r) = (n / d, n % d);
    // r < d < 2^47, so r·256 + d/2 < 2^56.
    let v = (q << 8).wrapping_add(((r << 8) + d.get() / 2) / d);
    let v = i64::try_from(v).ok()?;
    Some(if (num < 0) != (den < 0) { -v } else { v })
}

/// `num / den` rounded half away from zero; `None` for `den == 0`.
pub(crate) fn div_round(num: i64, den: i64) -> Option<i64> {
    let n = num.unsigned_abs();
    let d = core::num::NonZeroU64::new(den.unsigned_abs())?;
    let q = (n / d).wrapping_add(u64::from(n % d >= d.get() - d.get() / 2));
    let q = i64::try_from(q).ok()?;
    Some(if (num < 0) != (den < 0) { -q } else { q })
}

/// Round a Q8 value to an integer, half away from zero.
pub(crate) fn round_q8(v: i64) -> i64 {
    if v >= 0 {
        (v + 128) >> 8
    } else {
        -((-v + 128) >> 8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
