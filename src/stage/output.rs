//! Segments inside the core: endpoints in Q8 (1/256 px) of the gradient
//! grid ([`SegQ8`]), kept in the caller's output slots until the end (an
//! `f32` holds any Q8 value below 2^24 exactly), clipped to the image, and
//! converted to the public pixel-centre frame ([`SegQ8::to_output`]). The
//! gradient grid is half a pixel off the pixel centres (see
//! [`super::gradient`]).

use fixed::types::I24F8;

use crate::Segment;
use crate::num::q8::div_round;

/// A strong segment in the gradient grid, Q8.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SegQ8 {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
}

impl SegQ8 {
    /// The Q8 values stored in a [`Segment`]'s f32 fields (exact: |v| < 2^24).
    pub fn to_slot(self) -> Segment {
        let f = |v: i64| {
            let v = v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
            I24F8::from_bits(v).to_num::<f32>()
        };
        Segment {
            x0: f(self.x0),
            y0: f(self.y0),
            x1: f(self.x1),
            y1: f(self.y1),
        }
    }

    /// Reads back what [`SegQ8::to_slot`] wrote (a multiple of 2^-8 below
    /// 2^24 in magnitude, so `v · 256` is exact; the cast saturates and
    /// maps NaN to 0, so no slot value can panic). The cast is to `i32`
    /// (`to_slot` clamped to it): one instruction on a Cortex-M4F, where a
    /// float to `i64` cast is a library call.
    #[inline]
    pub fn from_slot(s: &Segment) -> Self {
        let f = |v: f32| i64::from((v * 256.0) as i32);
        Self {
            x0: f(s.x0),
            y0: f(s.y0),
            x1: f(s.x1),
            y1: f(s.y1),
        }
    }

    /// The segment clipped to the image rectangle, which in the gradient
    /// grid is `[0, w] x [0, h]` (in pixel centres `[-0.5, w - 0.5] x
    /// [-0.5, h - 0.5]`): an endpoint outside moves along the segment to the
    /// border. Projections onto a fitted line can leave the image by a pixel
    /// or so; this keeps every output endpoint inside.
    pub fn clipped(self, w: usize, h: usize) -> Self {
        let (wq, hq) = ((w as i64) << 8, (h as i64) << 8);
        let mut s = self;
        for _ in 0..2 {
            s = Self::clip_start(s, wq, hq);
            s = Self {
                x0: s.x1,
                y0: s.y1,
                x1: s.x0,
                y1: s.y0,
            };
        }
        s
    }

    /// Moves `(x0, y0)` onto the rectangle `[0, wq] x [0, hq]` along the
    /// segment (or clamps it when the segment does not reach inside).
    fn clip_start(s: Self, wq: i64, hq: i64) -> Self {
        let mut s = s;
        // x bounds, then y bounds; each move keeps the point on the segment.
        for (lo, hi, horizontal) in [(0, wq, true), (0, hq, false)] {
            let (p, q, dp, dq) = if horizontal {
                (s.x0, s.y0, s.x1 - s.x0, s.y1 - s.y0)
            } else {
                (s.y0, s.x0, s.y1 - s.y0, s.x1 - s.x0)
            };
            let target = if p < lo {
                lo
            } else if p > hi {
                hi
            } else {
                continue;
            };
            // |target - p| and |dq| are below 2^25: the product fits i64.
            let q_new = div_round((target - p) * dq, dp).map_or(q, |d| q + d);
            if horizontal {
                (s.x0, s.y0) = (target, q_new);
            } else {
                (s.y0, s.x0) = (target, q_new);
            }
        }
        s.x0 = s.x0.clamp(0, wq);
        s.y0 = s.y0.clamp(0, hq);
        s
    }

    /// The public segment: pixel-centre coordinates, exact (a Q8 value
    /// below 2^24 in magnitude is an `f32` as is).
    pub fn to_output(self) -> Segment {
        let f = |v: i64| {
            let v = v
                .saturating_sub(128)
                .clamp(i64::from(i32::MIN), i64::from(i32::MAX));
            I24F8::from_bits(v as i32).to_num::<f32>()
        };
        Segment {
            x0: f(self.x0),
            y0: f(self.y0),
            x1: f(self.x1),
            y1: f(self.y1),
        }
    }
}
