//! Segments inside the core: endpoints in Q8 (1/256 px) of the gradient
//! grid ([`SegQ8`]), kept in the caller's output slots until the end (as
//! the Q8 integers, which an `f32` holds exactly), clipped to the image, and
//! converted to the public pixel-centre frame ([`SegQ8::to_output`]). The
//! gradient grid is half a pixel off the pixel centres (see
//! [`super::gradient`]).

use fixed::types::I24F8;

use crate::Segment;
use crate::num::q8::{div_round, round_q8};

/// A Q8 value within [`SegQ8`]'s range (or up to half a pixel below it)
/// as an `f32`, exact: `fixed`'s conversion, or in a build for size
/// ([`crate::target::SMALL`]) [`q8_to_f32_by_cast`], with the same results
/// (`q8_conversions_agree`).
fn q8_to_f32(v: i32) -> f32 {
    if crate::target::SMALL {
        q8_to_f32_by_cast(v)
    } else {
        I24F8::from_bits(v).to_num::<f32>()
    }
}

/// [`q8_to_f32`] as a conversion of the integer and a scaling by 2^-8, both
/// exact here (a 25-bit integer, then a power of two): less code than the
/// general bit-level conversion.
#[cfg_attr(not(aaglsd_small), allow(dead_code))]
fn q8_to_f32_by_cast(v: i32) -> f32 {
    v as f32 * (1.0 / 256.0)
}

/// `v` saturated to [`SegQ8`]'s range, a signed 25-bit integer (one `ssat`
/// instruction on a Cortex-M4).
fn saturate_q8(v: i32) -> i32 {
    v.clamp(SegQ8::MIN, SegQ8::MAX)
}

/// A strong segment in the gradient grid, Q8, each coordinate in
/// [[`SegQ8::MIN`], [`SegQ8::MAX`]] (`±2^24`): image sides are below 2^15
/// px, so an image's segments are well inside, an `f32` holds every
/// coordinate exactly, and sums and differences of two coordinates fit
/// `i32` (only their products need 64 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SegQ8 {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
    /// The score ([`Segment::score`]), at most [`SegQ8::MAX_SCORE`]; 0
    /// until measured ([`super::validate::Sums::score`]).
    pub score: u32,
}

impl SegQ8 {
    /// The smallest coordinate, `-2^24`.
    pub const MIN: i32 = -(1 << 24);
    /// The largest coordinate, `2^24 - 1`.
    pub const MAX: i32 = (1 << 24) - 1;
    /// The largest score, `2^24 - 1` (an `f32` holds it exactly).
    pub const MAX_SCORE: u32 = (1 << 24) - 1;

    /// The segment from `(x0, y0)` to `(x1, y1)`, each coordinate saturated
    /// to the range (which no segment of an image leaves).
    pub fn new(x0: i64, y0: i64, x1: i64, y1: i64) -> Self {
        // An `i64` outside `i32` (its high word not the low word's sign)
        // saturates by its sign: `!MAX` is `MIN`.
        let c = |v: i64| {
            let (high, low) = ((v >> 32) as i32, v as i32);
            if high == low >> 31 {
                saturate_q8(low)
            } else {
                (high >> 31) ^ Self::MAX
            }
        };
        Self {
            x0: c(x0),
            y0: c(y0),
            x1: c(x1),
            y1: c(y1),
            score: 0,
        }
    }

    /// The segment with its ends swapped (the same score).
    pub fn reversed(mut self) -> Self {
        (self.x0, self.x1) = (self.x1, self.x0);
        (self.y0, self.y1) = (self.y1, self.y0);
        self
    }

    /// The endpoints rounded to pixels (half away from zero).
    pub fn pixel_ends(&self) -> ((i64, i64), (i64, i64)) {
        let r = |v: i32| round_q8(i64::from(v));
        ((r(self.x0), r(self.y0)), (r(self.x1), r(self.y1)))
    }

    /// The coordinates as kept in a [`Segment`]'s f32 fields between the
    /// stages: the Q8 integers themselves (exact below 2^24 in magnitude),
    /// and the score. Out of line in a build for size: the linking's
    /// output and the merging both store slots.
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn to_slot(self) -> Segment {
        self.to_segment(|v| v as f32)
    }

    /// A [`Segment`] with each coordinate mapped by `f`, and the score.
    #[inline(always)]
    fn to_segment(self, f: impl Fn(i32) -> f32) -> Segment {
        Segment {
            x0: f(self.x0),
            y0: f(self.y0),
            x1: f(self.x1),
            y1: f(self.y1),
            score: self.score.min(Self::MAX_SCORE) as f32,
        }
    }

    /// Reads back what [`SegQ8::to_slot`] wrote. The cast saturates and
    /// maps NaN to 0, and the range check keeps any other value in range,
    /// so no slot value can panic or overflow. The cast is to `i32`: one
    /// instruction on a Cortex-M4F, where a float to `i64` cast is a
    /// library call.
    #[inline]
    pub fn from_slot(s: &Segment) -> Self {
        let f = |v: f32| saturate_q8(v as i32);
        Self {
            x0: f(s.x0),
            y0: f(s.y0),
            x1: f(s.x1),
            y1: f(s.y1),
            score: (s.score as u32).min(Self::MAX_SCORE),
        }
    }

    /// The segment clipped to the image rectangle, which in the gradient
    /// grid is `[0, w] x [0, h]` (in pixel centres `[-0.5, w - 0.5] x
    /// [-0.5, h - 0.5]`): an endpoint outside moves along the segment to the
    /// border. Projections onto a fitted line can leave the image by a pixel
    /// or so; this keeps every output endpoint inside.
    pub fn clipped(self, w: usize, h: usize) -> Self {
        let (wq, hq) = ((w as i64) << 8, (h as i64) << 8);
        let w64 = i64::from;
        let mut s = (w64(self.x0), w64(self.y0), w64(self.x1), w64(self.y1));
        for _ in 0..2 {
            let (x0, y0, x1, y1) = Self::clip_start(s, wq, hq);
            s = (x1, y1, x0, y0);
        }
        Self {
            score: self.score,
            ..Self::new(s.0, s.1, s.2, s.3)
        }
    }

    /// Moves `(x0, y0)` of `(x0, y0, x1, y1)` onto the rectangle
    /// `[0, wq] x [0, hq]` along the segment (or clamps it when the segment
    /// does not reach inside).
    fn clip_start(s: (i64, i64, i64, i64), wq: i64, hq: i64) -> (i64, i64, i64, i64) {
        let (x0, y0, x1, y1) = s;
        // x bounds, then y bounds; each move keeps the point on the segment.
        let (x0, y0) = Self::into_band(x0, y0, x1 - x0, y1 - y0, wq);
        let (y0, x0) = Self::into_band(y0, x0, y1 - y0, x1 - x0, hq);
        (x0.clamp(0, wq), y0.clamp(0, hq), x1, y1)
    }

    /// The point `(p, q)` moved along the direction `(dp, dq)` to `p`'s
    /// nearest bound in `[0, hi]` when it lies outside (unmoved along `q`
    /// when `dp` is 0). One body for both axes: out of line in a build for
    /// size.
    #[cfg_attr(aaglsd_small, inline(never))]
    fn into_band(p: i64, q: i64, dp: i64, dq: i64, hi: i64) -> (i64, i64) {
        let target = p.clamp(0, hi);
        if target == p {
            return (p, q);
        }
        // |target - p| and |dq| are below 2^25: the product fits i64.
        (
            target,
            div_round((target - p) * dq, dp).map_or(q, |d| q + d),
        )
    }

    /// The public segment: pixel-centre coordinates, exact (a Q8 value
    /// below 2^24 in magnitude is an `f32` as is), and the score.
    pub fn to_output(self) -> Segment {
        self.to_segment(|v| q8_to_f32(v - 128))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both forms of [`q8_to_f32`] give the same bits on the whole range
    /// and half a pixel below it ([`SegQ8::to_output`]'s shift).
    #[test]
    fn q8_conversions_agree() {
        let step = if cfg!(miri) { 9_973 } else { 1 };
        for v in (SegQ8::MIN - 128..=SegQ8::MAX).step_by(step) {
            let exact = I24F8::from_bits(v).to_num::<f32>();
            assert_eq!(q8_to_f32_by_cast(v).to_bits(), exact.to_bits(), "{v}");
        }
    }

    /// [`SegQ8::new`] keeps values in range and saturates the rest by their
    /// sign, including those outside `i32`.
    #[test]
    fn construction_saturates() {
        let (min, max) = (i64::from(SegQ8::MIN), i64::from(SegQ8::MAX));
        let cases = [
            (0, 0),
            (-5, -5),
            (min, min),
            (max, max),
            (min - 1, min),
            (max + 1, max),
            (i64::from(i32::MIN), min),
            (i64::from(i32::MAX), max),
            (1 << 32, max),
            ((1 << 32) + 7, max),
            (-(1 << 32), min),
            (-(1 << 32) + 7, min),
            (i64::MIN, min),
            (i64::MAX, max),
        ];
        for (v, want) in cases {
            let s = SegQ8::new(v, -v.saturating_add(1), 3, v);
            let want = want as i32;
            assert_eq!((s.x0, s.x1, s.y1), (want, 3, want), "{v}");
            let neg = SegQ8::new(-v.saturating_add(1), 0, 0, 0).x0;
            assert_eq!(
                i64::from(neg),
                (-v.saturating_add(1)).clamp(min, max),
                "{v}"
            );
        }
    }

    /// A slot round-trips every in-range value, and any other slot value
    /// (NaN, infinities, huge) reads back in range.
    #[test]
    fn slots_round_trip_and_read_back_in_range() {
        for v in [SegQ8::MIN, -1, 0, 1, 12_345, SegQ8::MAX] {
            let s = SegQ8 {
                x0: v,
                y0: -v - 1,
                x1: v / 2,
                y1: 7,
                score: v.unsigned_abs().min(SegQ8::MAX_SCORE),
            };
            assert_eq!(SegQ8::from_slot(&s.to_slot()), s);
        }
        for (f, want) in [
            (f32::NAN, 0),
            (f32::INFINITY, SegQ8::MAX),
            (f32::NEG_INFINITY, SegQ8::MIN),
            (1e30, SegQ8::MAX),
            (-1e30, SegQ8::MIN),
            (2.5e7, SegQ8::MAX),
        ] {
            let slot = Segment {
                x0: f,
                y0: f,
                x1: f,
                y1: f,
                score: f,
            };
            assert_eq!(SegQ8::from_slot(&slot).x0, want, "{f}");
        }
    }
}
