//! Integer Bresenham rasterisation (paper §3.3: the validation densities and
//! the merging re-fit walk these pixels).
//!
//! The classic algorithm with the authors' tie rule (`p >= 0` steps the
//! minor axis), both ends included. The ends are clamped to `±2^28` (no
//! segment of an image has a coordinate anywhere near: sides are at most
//! 32,767 px), so the state fits `i32` and no step can overflow (`|2·d| <
//! 2^30`); a 32-bit core then walks in single registers (a 64-bit one
//! keeps 64-bit state, which saves it the widening of each pixel). The
//! iterator yields exactly [`pixel_count`] pixels.

/// The walk's integer: the target's register width.
#[cfg(target_pointer_width = "64")]
type C = i64;
#[cfg(not(target_pointer_width = "64"))]
type C = i32;

/// The largest coordinate magnitude [`Raster`] walks.
const LIMIT: i64 = 1 << 28;

/// `v` as `i64` (the same type on a 64-bit target).
#[allow(clippy::useless_conversion)]
#[inline(always)]
fn wide(v: C) -> i64 {
    i64::from(v)
}

#[cfg_attr(aaglsd_small, inline(never))]
fn clamped((x, y): (i64, i64)) -> (C, C) {
    (x.clamp(-LIMIT, LIMIT) as C, y.clamp(-LIMIT, LIMIT) as C)
}

/// The number of pixels [`Raster::new`]`(a, b)` yields: `max(|dx|, |dy|) + 1`
/// of the clamped ends.
pub fn pixel_count(a: (i64, i64), b: (i64, i64)) -> u64 {
    let ((ax, ay), (bx, by)) = (clamped(a), clamped(b));
    let (dx, dy) = (wide(bx) - wide(ax), wide(by) - wide(ay));
    dx.unsigned_abs().max(dy.unsigned_abs()) + 1
}

/// Pixels of the Bresenham line from `a` to `b`, both included.
#[derive(Clone, Debug)]
pub struct Raster {
    x: C,
    y: C,
    end: (C, C),
    sx: C,
    sy: C,
    adx: C,
    ady: C,
    p: C,
    x_major: bool,
    done: bool,
}

impl Raster {
    /// The line from `a` to `b`.
    pub fn new(a: (i64, i64), b: (i64, i64)) -> Self {
        let (a, b) = (clamped(a), clamped(b));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1); // below 2^29 in magnitude
        let (adx, ady) = (dx.abs(), dy.abs());
        let x_major = adx >= ady;
        let p = if x_major {
            2 * ady - adx
        } else {
            2 * adx - ady
        };
        Self {
            x: a.0,
            y: a.1,
            end: b,
            sx: if dx < 0 { -1 } else { 1 },
            sy: if dy < 0 { -1 } else { 1 },
            adx,
            ady,
            p,
            x_major,
            done: false,
        }
    }
}

impl Iterator for Raster {
    type Item = (i64, i64);

    fn next(&mut self) -> Option<(i64, i64)> {
        if self.done {
            return None;
        }
        let here = (wide(self.x), wide(self.y));
        let at_end = if self.x_major {
            self.x == self.end.0
        } else {
            self.y == self.end.1
        };
        if at_end {
            self.done = true;
            return Some((wide(self.end.0), wide(self.end.1)));
        }
        let (major, minor, s_major, s_minor, d_major, d_minor) = if self.x_major {
            (
                &mut self.x,
                &mut self.y,
                self.sx,
                self.sy,
                self.adx,
                self.ady,
            )
        } else {
            (
                &mut self.y,
                &mut self.x,
                self.sy,
                self.sx,
                self.ady,
                self.adx,
            )
        };
        if self.p >= 0 {
            *minor += s_minor;
            self.p += 2 * d_minor - 2 * d_major;
        } else {
            self.p += 2 * d_minor;
        }
        *major += s_major;
        Some(here)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shallow_and_steep() {
        let v: Vec<_> = Raster::new((0, 0), (4, 2)).collect();
        assert_eq!(v, [(0, 0), (1, 1), (2, 1), (3, 2), (4, 2)]); // tie p = 0 steps
        let v: Vec<_> = Raster::new((0, 0), (-1, -3)).collect();
        assert_eq!(v, [(0, 0), (0, -1), (-1, -2), (-1, -3)]);
        let v: Vec<_> = Raster::new((2, 2), (2, 2)).collect();
        assert_eq!(v, [(2, 2)]);
    }

    #[test]
    fn length_is_chebyshev_plus_one() {
        for &(a, b) in &[((0, 0), (7, -3)), ((5, 1), (-2, 9)), ((3, 3), (3, -4))] {
            let n = Raster::new(a, b).count() as i64;
            let (dx, dy) = ((b.0 - a.0).abs(), (b.1 - a.1).abs());
            assert_eq!(n, dx.max(dy) + 1);
            assert_eq!(pixel_count(a, b), n as u64);
            assert_eq!(Raster::new(a, b).last(), Some(b));
        }
    }

    /// The walk in `i64` with no clamp (the plain algorithm), for the
    /// comparison below.
    fn plain(a: (i64, i64), b: (i64, i64)) -> Vec<(i64, i64)> {
        // In (major, minor) coordinates; `swap` is its own inverse.
        let steep = (b.1 - a.1).abs() > (b.0 - a.0).abs();
        let swap = |(x, y): (i64, i64)| if steep { (y, x) } else { (x, y) };
        let ((u0, v0), (u1, v1)) = (swap(a), swap(b));
        let (du, dv) = ((u1 - u0).abs(), (v1 - v0).abs());
        let (mut u, mut v, mut p, mut out) = (u0, v0, 2 * dv - du, vec![]);
        while u != u1 {
            out.push(swap((u, v)));
            if p >= 0 {
                v += (v1 - v0).signum();
                p += 2 * dv - 2 * du;
            } else {
                p += 2 * dv;
            }
            u += (u1 - u0).signum();
        }
        out.push(b);
        out
    }

    /// Within the clamp, the `i32` walk is the plain `i64` one; beyond it
    /// (no image has such coordinates) it walks the clamped ends and
    /// yields `pixel_count` pixels.
    #[test]
    fn i32_walk_is_the_plain_walk() {
        let mut next = crate::xorshift64(0x6A09_E667_F3BC_C908);
        // Miri looks for undefined behaviour, not coverage: fewer and
        // shorter walks (its interpretation of the long ones dominated).
        let (walks, widths) = if cfg!(miri) {
            (200, [4, 6, 8])
        } else {
            (20_000, [4, 8, 12])
        };
        for k in 0..walks {
            // Now and then a walk of up to 2^20 pixels (never under Miri).
            let bits = if k % 1000 == 999 { 19 } else { widths[k % 3] };
            let mut c = || {
                let v = (next() % (1 << bits)) as i64;
                if next() & 1 == 0 { v } else { -v }
            };
            let (a, b) = ((c(), c()), (c(), c()));
            assert_eq!(
                Raster::new(a, b).collect::<Vec<_>>(),
                plain(a, b),
                "{a:?} {b:?}"
            );
            assert_eq!(pixel_count(a, b), plain(a, b).len() as u64);
        }
        let far = (i64::MAX, i64::MIN);
        let mut r = Raster::new(far, (0, 0));
        assert_eq!(r.next(), Some((LIMIT, -LIMIT)));
        assert_eq!(pixel_count(far, (0, 0)), LIMIT as u64 + 1);
    }
}
