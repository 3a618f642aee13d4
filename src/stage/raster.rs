//! Integer Bresenham rasterisation (paper §3.3: the validation densities and
//! the merging re-fit walk these pixels).
//!
//! The classic algorithm with the authors' tie rule (`p >= 0` steps the
//! minor axis), both ends included. Coordinates are `i64`; every step is a
//! bounded add, and the iterator yields exactly `max(|dx|, |dy|) + 1` pixels.

/// The number of pixels [`Raster::new`]`(a, b)` yields: `max(|dx|, |dy|) + 1`.
pub fn pixel_count(a: (i64, i64), b: (i64, i64)) -> u64 {
    (b.0.saturating_sub(a.0).unsigned_abs())
        .max(b.1.saturating_sub(a.1).unsigned_abs())
        .saturating_add(1)
}

/// Pixels of the Bresenham line from `a` to `b`, both included.
#[derive(Clone, Debug)]
pub struct Raster {
    x: i64,
    y: i64,
    end: (i64, i64),
    sx: i64,
    sy: i64,
    adx: i64,
    ady: i64,
    p: i64,
    x_major: bool,
    done: bool,
}

impl Raster {
    /// The line from `a` to `b`.
    pub fn new(a: (i64, i64), b: (i64, i64)) -> Self {
        let (dx, dy) = (b.0.saturating_sub(a.0), b.1.saturating_sub(a.1));
        let (adx, ady) = (dx.saturating_abs(), dy.saturating_abs());
        let x_major = adx >= ady;
        let p = if x_major {
            ady.saturating_mul(2).saturating_sub(adx)
        } else {
            adx.saturating_mul(2).saturating_sub(ady)
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
        let here = (self.x, self.y);
        let at_end = if self.x_major {
            self.x == self.end.0
        } else {
            self.y == self.end.1
        };
        if at_end {
            self.done = true;
            return Some(self.end);
        }
        // One step along the major axis; the minor one when `p >= 0`.
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
}
