//! Paper §3.1: gradient by the LSD 2x2 mask, unnormalised, placed "backward".
//!
//! With replicate borders (row -1 reads row 0, column -1 reads column 0):
//!
//! ```text
//! gx(x,y) = B(x,y) + B(x,y-1) - B(x-1,y) - B(x-1,y-1)
//! gy(x,y) = B(x,y) + B(x-1,y) - B(x,y-1) - B(x-1,y-1)
//! ```
//!
//! Both are integers in `-510..=510`, so the L1 magnitude `|gx| + |gy|` is in
//! `0..=1020`. The sample at index `(x, y)` measures the change between
//! pixels `x-1` and `x` (and rows `y-1`, `y`): it sits at the pixel corner
//! `(x - 0.5, y - 0.5)` in pixel-centre coordinates. Both implementations
//! work in this "gradient grid" and shift their output by -0.5 px at the end.
//!
//! [`gradient_at`] is exact in integers and shared by the fixed core and the
//! float reference. The fixed core's anchor pass streams the gradient row by
//! row into a three-row [`Ring`] instead of storing it.

use crate::invariant::Invariant;
#[cfg(any(test, feature = "_unstable-hooks"))]
use crate::params::Params;

/// The gradient at `(x, y)` of the `w`-wide blurred image `b`, with
/// replicate borders. Out-of-range reads return 0; callers pass in-image
/// coordinates. Interior pixels take one bounds check (a `w + 2` window).
#[inline]
pub fn gradient_at(b: &[u8], w: usize, x: usize, y: usize) -> (i32, i32) {
    if x > 0 && y > 0 {
        let i = y * w + x;
        if let Some(win) = b.get(i - w - 1..=i) {
            let at = |k: usize| i32::from(win.get(k).copied().or_broken(0));
            let (d, u, l, a) = (at(0), at(1), at(w), at(w + 1));
            return (a + u - l - d, a + l - u - d);
        }
    }
    gradient_at_border(b, w, x, y)
}

/// [`gradient_at`] for row 0 and column 0 (replicate borders).
#[cold]
fn gradient_at_border(b: &[u8], w: usize, x: usize, y: usize) -> (i32, i32) {
    let xm = x.saturating_sub(1);
    let ym = y.saturating_sub(1);
    let px = |xx: usize, yy: usize| i32::from(b.get(yy * w + xx).copied().or_broken(0));
    let a = px(x, y); // B(x, y)
    let l = px(xm, y); // B(x-1, y)
    let u = px(x, ym); // B(x, y-1)
    let d = px(xm, ym); // B(x-1, y-1)
    (a + u - l - d, a + l - u - d)
}

/// The thresholded L1 magnitude at the in-image pixel `(x, y)`: zero below
/// `mag_min`. With `s = B(x,y) - B(x-1,y-1)` and `t = B(x,y-1) - B(x-1,y)`
/// the components are `gx = s + t` and `gy = s - t`, so
/// `|gx| + |gy| = 2·max(|s|, |t|)`: four loads and no multiplication.
#[cfg_attr(not(aaglsd_small), inline(always))]
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn magnitude_at(b: &[u8], w: usize, x: usize, y: usize, mag_min: u16) -> u16 {
    let m = if x > 0 && y > 0 {
        let i = y * w + x;
        match b.get(i - w - 1..=i) {
            Some(win) => {
                let at = |k: usize| i32::from(win.get(k).copied().or_broken(0));
                let (d, u, l, a) = (at(0), at(1), at(w), at(w + 1));
                2 * (a - d).abs().max((u - l).abs())
            }
            None => 0,
        }
    } else {
        let (gx, gy) = gradient_at_border(b, w, x, y);
        gx.abs() + gy.abs()
    } as u16;
    if m < mag_min { 0 } else { m }
}

/// The 3-row gradient ring: thresholded magnitude and gradient components
/// of rows `r % 3`.
pub(crate) struct Ring<'a> {
    pub m: [&'a mut [u16]; 3],
    pub gx: [&'a mut [u16]; 3],
    pub gy: [&'a mut [u16]; 3],
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
/// `y % 3`.
pub(crate) fn gradient_row(ring: &mut Ring<'_>, blur: &[u8], w: usize, y: usize, mag_min: u16) {
    let slot = y % 3;
    let cur = blur.get(y * w..(y + 1) * w).or_broken(&[]);
    let prev = blur
        .get(y.saturating_sub(1) * w..(y.saturating_sub(1) + 1) * w)
        .or_broken(&[]);
    let (Some(m), Some(gxr), Some(gyr)) = (
        ring.m.get_mut(slot),
        ring.gx.get_mut(slot),
        ring.gy.get_mut(slot),
    ) else {
        return;
    };
    let mut left_c = i32::from(cur.first().copied().or_broken(0));
    let mut left_p = i32::from(prev.first().copied().or_broken(0));
    for ((((&c, &p), mo), gxo), gyo) in cur
        .iter()
        .zip(prev)
        .zip(m.iter_mut())
        .zip(gxr.iter_mut())
        .zip(gyr.iter_mut())
    {
        let (c, p) = (i32::from(c), i32::from(p));
        let (gx, gy, mag) = if crate::target::SIMD {
            // In 16-bit lanes, twice as many per SIMD register: every value
            // fits (|gx|, |gy| <= 510, magnitude <= 1020).
            let (c, p, lc, lp) = (c as i16, p as i16, left_c as i16, left_p as i16);
            let gx = c + p - lc - lp;
            let gy = c + lc - p - lp;
            (gx as u16, gy as u16, (gx.abs() + gy.abs()) as u16)
        } else {
            let gx = c + p - left_c - left_p;
            let gy = c + left_c - p - left_p;
            (gx as u16, gy as u16, (gx.abs() + gy.abs()) as u16)
        };
        *mo = if mag < mag_min { 0 } else { mag };
        *gxo = gx;
        *gyo = gy;
        left_c = c;
        left_p = p;
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
        gradient_row(&mut ring, blur, w, y, p.mag_min);
        if let Some(m) = ring.m.get(y % 3) {
            sum += m.iter().map(|&v| u64::from(v)).sum::<u64>();
        }
    }
    sum
}
