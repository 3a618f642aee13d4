//! The pictures behind the man-made scenes: rectangles of constant gray in a
//! scene frame that may be rotated and shifted against the pixel grid; how
//! they become pixels; and their true lines, read off the picture itself.

use std::collections::BTreeMap;

use super::Look;
use crate::corpus::{SplitMix64, hash3};

/// A rectangle `[u0, u1) x [v0, v1)` of the scene frame, painted `level`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rect {
    pub u0: f64,
    pub v0: f64,
    pub u1: f64,
    pub v1: f64,
    pub level: f64,
}

impl Rect {
    fn contains(&self, u: f64, v: f64) -> bool {
        self.u0 <= u && u < self.u1 && self.v0 <= v && v < self.v1
    }
}

/// Side of the cells of [`Picture`]'s lookup grid, in scene units: a cell
/// holds a handful of rectangles even for the 6-px checkerboards.
const CELL: f64 = 8.0;

/// Rectangles painted in order (a later one covers an earlier one) over a
/// uniform background. The scene frame `(u, v)` maps to the image's
/// pixel-centre frame by `x = ox + u cos - v sin`, `y = oy + u sin + v cos`.
pub(super) struct Picture {
    origin: (f64, f64),
    sin_cos: (f64, f64),
    background: f64,
    rects: Vec<Rect>,
    /// The lookup grid's first corner and size in cells.
    grid_at: (f64, f64),
    grid_size: (usize, usize),
    /// Per cell, the indices of the rectangles that reach into it, in
    /// painting order.
    cells: Vec<Vec<u32>>,
}

impl Picture {
    /// `rects` over `background`, the frame turned by `angle_deg` (towards
    /// +y) about `origin`, the image point of the frame's `(0, 0)`.
    pub fn new(origin: (f64, f64), angle_deg: f64, background: f64, rects: Vec<Rect>) -> Self {
        let lo = rects
            .iter()
            .fold((0f64, 0f64), |(u, v), r| (u.min(r.u0), v.min(r.v0)));
        let hi = rects
            .iter()
            .fold((0f64, 0f64), |(u, v), r| (u.max(r.u1), v.max(r.v1)));
        let span = |a: f64, b: f64| ((b - a) / CELL).floor() as usize + 1;
        let (nu, nv) = (span(lo.0, hi.0), span(lo.1, hi.1));
        let mut cells = vec![Vec::new(); nu * nv];
        let cell = |x: f64, at: f64| ((x - at) / CELL).floor() as usize;
        for (i, r) in rects.iter().enumerate() {
            for cv in cell(r.v0, lo.1)..=cell(r.v1, lo.1).min(nv - 1) {
                for cu in cell(r.u0, lo.0)..=cell(r.u1, lo.0).min(nu - 1) {
                    cells[cv * nu + cu].push(i as u32);
                }
            }
        }
        Self {
            origin,
            sin_cos: angle_deg.to_radians().sin_cos(),
            background,
            rects,
            grid_at: lo,
            grid_size: (nu, nv),
            cells,
        }
    }

    /// The lookup cell of scene point `(u, v)`, if inside the grid.
    fn cell_of(&self, u: f64, v: f64) -> Option<usize> {
        let cu = (u - self.grid_at.0) / CELL;
        let cv = (v - self.grid_at.1) / CELL;
        let (nu, nv) = self.grid_size;
        // Truncation is the floor here, both being >= 0 (and cheaper than
        // `floor`, a libm call on the baseline x86-64).
        (cu >= 0.0 && cv >= 0.0 && cu < nu as f64 && cv < nv as f64)
            .then(|| cv as usize * nu + cu as usize)
    }

    /// The gray level at scene point `(u, v)`.
    fn level_uv(&self, u: f64, v: f64) -> f64 {
        let Some(cell) = self.cell_of(u, v) else {
            return self.background;
        };
        self.cells[cell]
            .iter()
            .rev()
            .map(|&i| &self.rects[i as usize])
            .find(|r| r.contains(u, v))
            .map_or(self.background, |r| r.level)
    }

    /// The gray level at image point `(x, y)`.
    fn level_xy(&self, x: f64, y: f64) -> f64 {
        let (s, c) = self.sin_cos;
        let (dx, dy) = (x - self.origin.0, y - self.origin.1);
        self.level_uv(dx * c + dy * s, dy * c - dx * s)
    }

    /// The image point of scene point `(u, v)`.
    fn to_image(&self, u: f64, v: f64) -> (f64, f64) {
        let (s, c) = self.sin_cos;
        (self.origin.0 + u * c - v * s, self.origin.1 + u * s + v * c)
    }

    /// The mean level over pixel `(x, y)`'s square `[x - 1/2, x + 1/2] x
    /// [y - 1/2, y + 1/2]`. Where a 3 x 3 probe (the square's corners,
    /// side middles and centre) sees one level, that level: every
    /// rectangle of the scenes is at least 1 px across, and an interval
    /// of length 1 that meets `[x - 1/2, x + 1/2]` contains `x - 1/2`,
    /// `x` or `x + 1/2`, so no boundary is missed. Else exactly for an
    /// unturned picture ([`Picture::exact_mean`]), and as the mean of
    /// 16 x 16 samples for a turned one.
    fn pixel_mean(&self, x: usize, y: usize) -> f64 {
        let (x, y) = (x as f64, y as f64);
        let probe = |i: usize| {
            let at = |k: usize| (k as f64 - 1.0) / 2.0;
            self.level_xy(x + at(i % 3), y + at(i / 3))
        };
        let first = probe(0);
        if (1..9).all(|i| probe(i) == first) {
            return first;
        }
        if self.sin_cos == (0.0, 1.0)
            && let Some(m) = self.exact_mean(x - self.origin.0, y - self.origin.1)
        {
            return m;
        }
        let at = |k: usize| (k as f64 + 0.5) / 16.0 - 0.5;
        let sum: f64 = (0..256)
            .map(|i| self.level_xy(x + at(i % 16), y + at(i / 16)))
            .sum();
        sum / 256.0
    }

    /// For an unturned picture, the exact mean over the unit square
    /// centred on scene point `(u, v)`: the rectangles' sides that cross
    /// the square cut it into cells of one level each. `None` when more
    /// sides cross it than the scenes ever have.
    fn exact_mean(&self, u: f64, v: f64) -> Option<f64> {
        let (mut us, mut vs) = (Cuts::new(u - 0.5), Cuts::new(v - 0.5));
        let mut cells = [None; 4];
        for (k, c) in cells.iter_mut().enumerate() {
            *c = self.cell_of(u + [-0.5, 0.5][k % 2], v + [-0.5, 0.5][k / 2]);
        }
        for &i in cells.iter().flatten().flat_map(|&c| &self.cells[c]) {
            let r = &self.rects[i as usize];
            if !(us.add(r.u0) && us.add(r.u1) && vs.add(r.v0) && vs.add(r.v1)) {
                return None;
            }
        }
        let mut sum = 0.0;
        for v in vs.sorted().windows(2) {
            for u in us.sorted().windows(2) {
                let level = self.level_uv((u[0] + u[1]) / 2.0, (v[0] + v[1]) / 2.0);
                sum += (u[1] - u[0]) * (v[1] - v[0]) * level;
            }
        }
        Some(sum)
    }

    /// The `w` x `h` image as `look` says: area-averaged (or point-sampled
    /// when aliased), blurred, with noise seeded by `seed`, rounded to 8
    /// bits.
    pub fn render(&self, w: usize, h: usize, look: &Look, seed: u64) -> Vec<u8> {
        let mut img: Vec<f64> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if look.aliased {
                    self.level_xy(x as f64, y as f64)
                } else {
                    self.pixel_mean(x, y)
                }
            })
            .collect();
        if look.blur > 0.0 {
            gaussian_blur(&mut img, w, h, look.blur);
        }
        img.iter()
            .enumerate()
            .map(|(i, &v)| {
                let n = if look.noise > 0.0 {
                    look.noise * normal(seed, i % w, i / w)
                } else {
                    0.0
                };
                (v + n).round().clamp(0.0, 255.0) as u8
            })
            .collect()
    }

    /// The true lines in a `w` x `h` image: the pieces of the rectangles'
    /// sides (collinear sides joined) along which the picture's level
    /// differs on the two sides, clipped to [`CLIP`] px inside the outer
    /// pixel centres, at least [`MIN_TRUE_LEN`] px long. Reading them off
    /// the picture, not off the layout, keeps a side that is covered by a
    /// later rectangle, or that separates equal levels, out of the truth.
    pub fn true_lines(&self, w: usize, h: usize) -> Vec<[f32; 4]> {
        // (along u?, the other coordinate's bits) -> intervals along.
        let mut sides: BTreeMap<(bool, u64), Vec<(f64, f64)>> = BTreeMap::new();
        for r in &self.rects {
            for (along_u, at, a, b) in [
                (true, r.v0, r.u0, r.u1),
                (true, r.v1, r.u0, r.u1),
                (false, r.u0, r.v0, r.v1),
                (false, r.u1, r.v0, r.v1),
            ] {
                sides
                    .entry((along_u, at.to_bits()))
                    .or_default()
                    .push((a, b));
            }
        }
        let mut out = Vec::new();
        for ((along_u, bits), mut spans) in sides {
            spans.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut merged: Vec<(f64, f64)> = Vec::new();
            for (a, b) in spans {
                match merged.last_mut() {
                    Some(last) if a <= last.1 => last.1 = last.1.max(b),
                    _ => merged.push((a, b)),
                }
            }
            let side = Side {
                pic: self,
                along_u,
                at: f64::from_bits(bits),
                size: (w as f64, h as f64),
            };
            for (a, b) in merged {
                side.trace(a, b, &mut out);
            }
        }
        out
    }
}

/// The places where sides cut a unit interval `[lo, lo + 1]`, its ends
/// included, without repeats.
struct Cuts {
    at: [f64; Cuts::MAX],
    n: usize,
}

impl Cuts {
    /// More than the scenes ever have (features are 1 px or more).
    const MAX: usize = 16;

    fn new(lo: f64) -> Self {
        let mut at = [0.0; Self::MAX];
        (at[0], at[1]) = (lo, lo + 1.0);
        Self { at, n: 2 }
    }

    /// Adds `x` if strictly inside; false when full.
    fn add(&mut self, x: f64) -> bool {
        let (lo, hi) = (self.at[0], self.at[1]);
        if x <= lo || x >= hi || self.at[..self.n].contains(&x) {
            return true;
        }
        if self.n == Self::MAX {
            return false;
        }
        self.at[self.n] = x;
        self.n += 1;
        true
    }

    fn sorted(&self) -> Vec<f64> {
        let mut v = self.at[..self.n].to_vec();
        v.sort_by(f64::total_cmp);
        v
    }
}

/// How far inside the outer pixel centres true lines are clipped: a
/// gradient needs a pixel on each side.
const CLIP: f64 = 1.0;

/// Pieces of true line shorter than this are left out (the ends of rules,
/// corners cut off by the image border): shorter than any detector's
/// minimum segment.
pub(super) const MIN_TRUE_LEN: f64 = 8.0;

/// Sampling step along a side while tracing it; the ends are then refined
/// by bisection.
const TRACE_STEP: f64 = 0.1;

/// One line of the scene frame: `v = at` (along u) or `u = at`.
struct Side<'a> {
    pic: &'a Picture,
    along_u: bool,
    at: f64,
    size: (f64, f64),
}

impl Side<'_> {
    fn point(&self, t: f64) -> (f64, f64) {
        if self.along_u {
            (t, self.at)
        } else {
            (self.at, t)
        }
    }

    /// Whether the point at `t` is on an edge, inside the clip box.
    fn on_edge(&self, t: f64) -> bool {
        // Far below any feature (1 px) and far above rounding.
        const EPS: f64 = 1e-3;
        let (u, v) = self.point(t);
        let (x, y) = self.pic.to_image(u, v);
        let inside = |p: f64, n: f64| (CLIP..=n - 1.0 - CLIP).contains(&p);
        if !inside(x, self.size.0) || !inside(y, self.size.1) {
            return false;
        }
        let (a, b) = if self.along_u {
            (self.pic.level_uv(u, v - EPS), self.pic.level_uv(u, v + EPS))
        } else {
            (self.pic.level_uv(u - EPS, v), self.pic.level_uv(u + EPS, v))
        };
        (a - b).abs() >= 1.0
    }

    /// Where `on_edge` changes between `off` and `on` (one of each), to
    /// 1e-6 px.
    fn boundary(&self, mut off: f64, mut on: f64) -> f64 {
        while (on - off).abs() > 1e-6 {
            let mid = 0.5 * (off + on);
            if self.on_edge(mid) {
                on = mid;
            } else {
                off = mid;
            }
        }
        on
    }

    /// Appends the on-edge pieces of `[a, b]` to `out`, in image
    /// coordinates.
    fn trace(&self, a: f64, b: f64, out: &mut Vec<[f32; 4]>) {
        let n = ((b - a) / TRACE_STEP).ceil().max(1.0) as usize;
        let t = |k: usize| a + (b - a) * k as f64 / n as f64;
        let mut start = None;
        for k in 0..=n + 1 {
            let on = k <= n && self.on_edge(t(k));
            match (start, on) {
                (None, true) => {
                    start = Some(if k == 0 {
                        a
                    } else {
                        self.boundary(t(k - 1), t(k))
                    });
                }
                (Some(s), false) => {
                    let e = if k > n {
                        b
                    } else {
                        self.boundary(t(k), t(k - 1))
                    };
                    start = None;
                    if e - s >= MIN_TRUE_LEN {
                        let (u0, v0) = self.point(s);
                        let (u1, v1) = self.point(e);
                        let (x0, y0) = self.pic.to_image(u0, v0);
                        let (x1, y1) = self.pic.to_image(u1, v1);
                        out.push([x0 as f32, y0 as f32, x1 as f32, y1 as f32]);
                    }
                }
                _ => {}
            }
        }
    }
}

/// About normal, mean 0, standard deviation 1, for pixel `(x, y)`: a sum
/// of four uniforms (as the corpus's Gaussian noise), hashed from the
/// position, so no state and no drawing order.
fn normal(seed: u64, x: usize, y: usize) -> f64 {
    let mut r = SplitMix64(hash3(seed, x as u64, y as u64));
    let s: f64 = (0..4).map(|_| r.next_f64()).sum();
    (s - 2.0) * 3f64.sqrt()
}

/// A Gaussian blur of standard deviation `sigma` px (kernel to 4 sigma,
/// the border pixel repeated), rows then columns.
fn gaussian_blur(img: &mut [f64], w: usize, h: usize, sigma: f64) {
    let r = (4.0 * sigma).ceil() as usize;
    let mut k: Vec<f64> = (0..=2 * r)
        .map(|i| {
            let d = i as f64 - r as f64;
            (-d * d / (2.0 * sigma * sigma)).exp()
        })
        .collect();
    let total: f64 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= total);
    let mut tmp = vec![0.0; img.len()];
    convolve(img, &mut tmp, (w, h), (1, w), &k);
    convolve(&tmp, img, (h, w), (w, 1), &k);
}

/// `dst = src` convolved with `k` along lines of `n.0` values `step.0`
/// apart; there are `n.1` lines, `step.1` apart.
fn convolve(src: &[f64], dst: &mut [f64], n: (usize, usize), step: (usize, usize), k: &[f64]) {
    let r = k.len() / 2;
    for line in 0..n.1 {
        let at = |i: usize| src[line * step.1 + i * step.0];
        for i in 0..n.0 {
            dst[line * step.1 + i * step.0] = k
                .iter()
                .enumerate()
                .map(|(j, &kj)| kj * at((i + j).saturating_sub(r).min(n.0 - 1)))
                .sum();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar(u0: f64, u1: f64, level: f64) -> Rect {
        Rect {
            u0,
            v0: -10.0,
            u1,
            v1: 10.0,
            level,
        }
    }

    #[test]
    fn pixel_means_are_exact_when_unturned() {
        // A dark bar over [0.3, 2.8) on 100: pixel 0 covers [-0.5, 0.5],
        // 0.2 of it dark; pixel 3 covers [2.5, 3.5], 0.3 of it dark.
        let pic = Picture::new((0.0, 0.0), 0.0, 100.0, vec![bar(0.3, 2.8, 0.0)]);
        let means: Vec<f64> = (0..5).map(|x| pic.pixel_mean(x, 0)).collect();
        let want = [80.0, 0.0, 0.0, 70.0, 100.0];
        for (m, w) in means.iter().zip(want) {
            assert!((m - w).abs() < 1e-9, "{means:?}");
        }
        // Later rectangles cover earlier ones; a side through the pixel
        // centre gives the exact mid level.
        let pic = Picture::new(
            (0.0, 0.0),
            0.0,
            200.0,
            vec![bar(-5.0, 5.0, 40.0), bar(2.0, 8.0, 120.0)],
        );
        assert_eq!(pic.pixel_mean(2, 0), 80.0);
        assert_eq!(pic.pixel_mean(5, 0), 120.0);
        assert_eq!(pic.pixel_mean(8, 0), 160.0);
        // Turned, the 16 x 16 samples come within a level of the area.
        let turned = Picture::new((0.0, 0.0), 30.0, 100.0, vec![bar(0.3, 2.8, 0.0)]);
        let m = turned.pixel_mean(0, 0);
        assert!(m > 60.0 && m < 100.0, "{m}");
        let img = turned.render(
            6,
            6,
            &super::super::Look {
                aliased: false,
                blur: 0.0,
                noise: 0.0,
            },
            1,
        );
        assert_eq!(img.len(), 36);
    }

    #[test]
    fn blur_keeps_the_mean_and_spreads_a_step() {
        let (w, h) = (40, 3);
        let mut img: Vec<f64> = (0..w * h)
            .map(|i| if i % w < 20 { 0.0 } else { 100.0 })
            .collect();
        gaussian_blur(&mut img, w, h, 1.0);
        let row = &img[w..2 * w];
        // Symmetric about the step at 19.5, flat far from it.
        for k in 0..20 {
            assert!((row[19 - k] + row[20 + k] - 100.0).abs() < 1e-9, "{row:?}");
        }
        // Half a pixel from the step, about 100 Phi(-1/2) = 30.9.
        assert!(
            row[0] < 1e-9 && row[5] < 1e-6 && (row[19] - 30.9).abs() < 1.0,
            "{row:?}"
        );
    }

    #[test]
    fn true_lines_skip_covered_and_equal_sides() {
        // A bar half under a later one of the same level: the shared
        // stretch of side is no edge; the image clip cuts the rest.
        let pic = Picture::new(
            (0.0, 0.0),
            0.0,
            200.0,
            vec![
                Rect {
                    u0: 10.0,
                    v0: 10.0,
                    u1: 30.0,
                    v1: 20.0,
                    level: 40.0,
                },
                Rect {
                    u0: 20.0,
                    v0: 10.0,
                    u1: 60.0,
                    v1: 20.0,
                    level: 40.0,
                },
            ],
        );
        let mut lines = pic.true_lines(50, 40);
        lines.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let want = [
            [10.0, 10.0, 10.0, 20.0],
            [10.0, 10.0, 48.0, 10.0],
            [10.0, 20.0, 48.0, 20.0],
        ];
        assert_eq!(lines.len(), want.len(), "{lines:?}");
        for (l, w) in lines.iter().zip(want) {
            for (a, b) in l.iter().zip(w) {
                assert!((a - b).abs() < 1e-4, "{lines:?}");
            }
        }
    }
}
