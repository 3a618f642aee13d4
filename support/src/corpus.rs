//! An adversarial corpus: synthetic 8-bit gray images built to make a line
//! segment detector work hard (issue #16).
//!
//! Natural images have a few thousand edge pixels organised into lines; the
//! detector's cost is tuned for those. These patterns instead fill the
//! frame with edges that are short, dense, aliased, oblique, periodic or
//! random, so that anchors, groups and linking attempts multiply: noise,
//! checkerboards, stripes at many angles and periods, rows of dashes,
//! hatching, rings, a star, text-like glyphs, pixel staircases, the tiles of
//! issue #16 (12-px squares with 3-px gaps) and random short strokes.
//!
//! Every pattern is a pure function of its name and the image size: the
//! pseudo-random ones hash the pixel or cell position with a seed taken from
//! the name (no OS randomness, no global state), so a render is the same on
//! every machine and every run. All patterns except [`Kind::Rings`] and
//! [`Kind::Star`] (centred on the image) are also functions of the position
//! alone: a smaller render is the top-left crop of a larger one.
//!
//! Geometric patterns are antialiased by 4x4 supersampling (pixel `(x, y)`
//! covers `[x, x+1) x [y, y+1)`), so oblique edges carry the sub-pixel
//! information a camera would give; boundaries on pixel edges (checkers,
//! tiles, staircases) stay exactly two-level.
//!
//! ```
//! use aaglsd_support::corpus;
//! let tiles = corpus::render("tiles-12-3", 640, 480).unwrap();
//! assert_eq!(tiles.len(), 640 * 480);
//! assert!(corpus::patterns().len() >= 25);
//! ```

/// The dark level of two-level patterns.
pub const DARK: u8 = 40;
/// The bright level of two-level patterns.
pub const BRIGHT: u8 = 200;

/// A named corpus pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pattern {
    /// Stable name (lower case, `-` separated), usable as a file stem.
    pub name: &'static str,
    /// What is drawn.
    pub kind: Kind,
}

/// The pattern families. Lengths are in pixels, angles in degrees from the
/// image's x axis (towards +y, i.e. clockwise on screen).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Every pixel independent and uniform in 0..=255.
    UniformNoise,
    /// Every pixel independent, about normal around 128 with standard
    /// deviation `sigma` (a sum of four uniforms), clamped to 0..=255.
    GaussNoise {
        /// Standard deviation in gray levels.
        sigma: f64,
    },
    /// A checkerboard of `cell` x `cell` squares.
    Checker {
        /// Square side.
        cell: usize,
    },
    /// Straight square-wave stripes (half dark, half bright).
    Stripes {
        /// Direction of the stripes.
        angle: f64,
        /// Distance between successive dark stripes.
        period: f64,
    },
    /// Parallel rows of short dashes; every row is shifted by `shift`
    /// along its direction against the previous one (0: dashes line up
    /// in columns; 0.5: staggered like bricks).
    Dashes {
        /// The rows' direction and spacing.
        rows: Rows,
        /// Dash length.
        len: f64,
        /// Gap between dashes in a row.
        gap: f64,
        /// Dash thickness.
        thick: f64,
        /// Row-to-row shift, as a fraction of `len + gap`.
        shift: f64,
    },
    /// Hatching: dense parallel strokes, each row broken at pseudo-random
    /// places, so stroke ends never line up.
    Hatch {
        /// The strokes' direction and the distance between stroke centres
        /// across.
        rows: Rows,
        /// Stroke length.
        len: f64,
    },
    /// Concentric square-wave rings around the image centre.
    Rings {
        /// Radial period.
        period: f64,
    },
    /// A star of `spokes` dark wedges around the image centre.
    Star {
        /// Number of dark wedges.
        spokes: u32,
    },
    /// Lines of text-like glyphs: each glyph a random 3x5 block bitmap of
    /// `unit`-px blocks, one block between glyphs, random word breaks.
    Glyphs {
        /// Block side.
        unit: usize,
    },
    /// Diagonal bands whose borders are pixel staircases of `dx` x `dy`
    /// steps (1 x 1: the aliased 45-degree edge of a rasteriser).
    Staircase {
        /// Step width.
        dx: usize,
        /// Step height.
        dy: usize,
    },
    /// Bright `cell` x `cell` squares separated by dark `gap`-px lines.
    Tiles {
        /// Square side.
        cell: usize,
        /// Gap width.
        gap: usize,
    },
    /// One random stroke per `cell` x `cell` cell: random angle, length in
    /// `[len / 2, len]`, thickness 1 to 3 px, random gray levels.
    Strokes {
        /// Cell side.
        cell: usize,
        /// Maximum stroke length.
        len: f64,
    },
}

/// Parallel rows, the frame of [`Kind::Dashes`] and [`Kind::Hatch`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rows {
    /// Direction of the rows.
    pub angle: f64,
    /// Distance between row centres.
    pub spacing: f64,
}

use Kind::*;

const fn p(name: &'static str, kind: Kind) -> Pattern {
    Pattern { name, kind }
}

const fn stripes(name: &'static str, angle: f64, period: f64) -> Pattern {
    p(name, Stripes { angle, period })
}

/// `[len, gap, spacing, thick]`, then `shift`: see [`Kind::Dashes`].
const fn dashes(name: &'static str, angle: f64, d: [f64; 4], shift: f64) -> Pattern {
    let [len, gap, spacing, thick] = d;
    p(
        name,
        Dashes {
            rows: Rows { angle, spacing },
            len,
            gap,
            thick,
            shift,
        },
    )
}

const fn hatch(name: &'static str, angle: f64, len: f64, spacing: f64) -> Pattern {
    p(
        name,
        Hatch {
            rows: Rows { angle, spacing },
            len,
        },
    )
}

const fn strokes_in(name: &'static str, cell: usize, len: f64) -> Pattern {
    p(name, Strokes { cell, len })
}

/// The corpus, in a fixed order.
static PATTERNS: [Pattern; 39] = [
    p("noise-uniform", UniformNoise),
    p("noise-gauss-40", GaussNoise { sigma: 40.0 }),
    p("noise-gauss-8", GaussNoise { sigma: 8.0 }),
    p("checker-2", Checker { cell: 2 }),
    p("checker-4", Checker { cell: 4 }),
    p("checker-8", Checker { cell: 8 }),
    p("checker-16", Checker { cell: 16 }),
    stripes("stripes-a00-p3", 0.0, 3.0),
    stripes("stripes-a00-p6", 0.0, 6.0),
    stripes("stripes-a00-p12", 0.0, 12.0),
    stripes("stripes-a07-p3", 7.0, 3.0),
    stripes("stripes-a07-p6", 7.0, 6.0),
    stripes("stripes-a07-p12", 7.0, 12.0),
    stripes("stripes-a30-p3", 30.0, 3.0),
    stripes("stripes-a30-p6", 30.0, 6.0),
    stripes("stripes-a30-p12", 30.0, 12.0),
    stripes("stripes-a45-p3", 45.0, 3.0),
    stripes("stripes-a45-p6", 45.0, 6.0),
    stripes("stripes-a45-p12", 45.0, 12.0),
    stripes("stripes-a63-p3", 63.0, 3.0),
    stripes("stripes-a63-p6", 63.0, 6.0),
    stripes("stripes-a63-p12", 63.0, 12.0),
    dashes("dashes-a20", 20.0, [5.0, 4.0, 7.0, 2.0], 0.5),
    dashes("dashes-a63", 63.0, [5.0, 4.0, 7.0, 2.0], 0.5),
    dashes("dashed-lines-a00", 0.0, [18.0, 6.0, 10.0, 1.5], 0.0),
    dashes("dashed-lines-a37", 37.0, [18.0, 6.0, 10.0, 1.5], 0.0),
    hatch("hatch-a30", 30.0, 12.0, 4.0),
    hatch("hatch-a60", 60.0, 8.0, 3.0),
    p("rings-p6", Rings { period: 6.0 }),
    p("rings-p12", Rings { period: 12.0 }),
    p("star-90", Star { spokes: 90 }),
    p("glyphs-u2", Glyphs { unit: 2 }),
    p("glyphs-u3", Glyphs { unit: 3 }),
    p("staircase-1x1", Staircase { dx: 1, dy: 1 }),
    p("staircase-2x1", Staircase { dx: 2, dy: 1 }),
    p("tiles-12-3", Tiles { cell: 12, gap: 3 }),
    p("tiles-6-2", Tiles { cell: 6, gap: 2 }),
    strokes_in("strokes-c10", 10, 10.0),
    strokes_in("strokes-c20", 20, 18.0),
];

/// Every corpus pattern, in a fixed order (names are unique).
pub fn patterns() -> &'static [Pattern] {
    &PATTERNS
}

/// The pattern called `name`.
pub fn find(name: &str) -> Option<&'static Pattern> {
    PATTERNS.iter().find(|p| p.name == name)
}

/// The pattern called `name` at `w` x `h` (see [`Pattern::render`]);
/// `None` for an unknown name.
pub fn render(name: &str, w: usize, h: usize) -> Option<Vec<u8>> {
    find(name).map(|p| p.render(w, h))
}

impl Pattern {
    /// The `w` x `h` image, row-major, `w` bytes a row.
    ///
    /// # Panics
    /// For a hand-made [`Kind`] with a zero cell, unit or step size
    /// (the corpus has none).
    pub fn render(&self, w: usize, h: usize) -> Vec<u8> {
        let seed = fnv1a(self.name.as_bytes());
        let (cx, cy) = (w as f64 / 2.0, h as f64 / 2.0);
        match self.kind {
            UniformNoise => per_pixel(w, h, |x, y| hash3(seed, x as u64, y as u64) as u8),
            GaussNoise { sigma } => per_pixel(w, h, |x, y| {
                let mut r = SplitMix64(hash3(seed, x as u64, y as u64));
                // Sum of four U(0, 1): mean 2, variance 1/3.
                let s: f64 = (0..4).map(|_| r.next_f64()).sum();
                (128.0 + sigma * (s - 2.0) * 3f64.sqrt())
                    .round()
                    .clamp(0.0, 255.0) as u8
            }),
            Checker { cell } => two_level(w, h, |x, y| (x / cell + y / cell) % 2 == 0),
            Tiles { cell, gap } => two_level(w, h, |x, y| {
                x % (cell + gap) >= cell || y % (cell + gap) >= cell
            }),
            Staircase { dx, dy } => two_level(w, h, |x, y| (x / dx + y / dy) % 16 < 8),
            Glyphs { unit } => two_level(w, h, |x, y| glyph_ink(seed, x / unit, y / unit)),
            Stripes { angle, period } => {
                let (s, c) = angle.to_radians().sin_cos();
                antialiased(w, h, |x, y| {
                    (y * c - x * s).rem_euclid(period) < period / 2.0
                })
            }
            Dashes {
                rows,
                len,
                gap,
                thick,
                shift,
            } => rows.antialiased(w, h, |u, off, row| {
                let along = u + row * shift * (len + gap);
                off < thick / 2.0 && along.rem_euclid(len + gap) < len
            }),
            Hatch { rows, len } => rows.antialiased(w, h, |u, off, row| {
                let key = row as i64 as u64;
                // Each row's `len` cells start at a random offset; in each
                // cell the stroke is 75% to 100% of the cell, less a 2-px
                // break.
                let along = u + unit_f64(hash3(seed, key, u64::MAX)) * len;
                let cell = (along / len).floor();
                let r = unit_f64(hash3(seed, key, cell as i64 as u64));
                off < 0.6 && along - cell * len < len * (0.75 + 0.25 * r) - 2.0
            }),
            Rings { period } => antialiased(w, h, |x, y| {
                (x - cx).hypot(y - cy).rem_euclid(period) < period / 2.0
            }),
            Star { spokes } => {
                let k = f64::from(spokes) / std::f64::consts::TAU;
                antialiased(w, h, |x, y| {
                    ((y - cy).atan2(x - cx) * k).rem_euclid(1.0) < 0.5
                })
            }
            Strokes { cell, len } => strokes(seed, w, h, cell, len),
        }
    }
}

/// `f(x, y)` at every pixel.
fn per_pixel(w: usize, h: usize, f: impl Fn(usize, usize) -> u8) -> Vec<u8> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| f(x, y))
        .collect()
}

/// [`DARK`] where `ink(x, y)`, else [`BRIGHT`].
fn two_level(w: usize, h: usize, ink: impl Fn(usize, usize) -> bool) -> Vec<u8> {
    per_pixel(w, h, |x, y| if ink(x, y) { DARK } else { BRIGHT })
}

impl Rows {
    /// [`antialiased`], with `ink(u, off, row)` in the rows' frame: `row`
    /// the index of the nearest row, `u` the position along it, `off` the
    /// distance from its centre line.
    fn antialiased(self, w: usize, h: usize, ink: impl Fn(f64, f64, f64) -> bool) -> Vec<u8> {
        let Self { angle, spacing } = self;
        let (s, c) = angle.to_radians().sin_cos();
        antialiased(w, h, |x, y| {
            let (u, v) = (x * c + y * s, y * c - x * s);
            let row = (v / spacing).round();
            ink(u, (v - row * spacing).abs(), row)
        })
    }
}

/// The fraction of the 4x4 sub-pixel samples where `ink` holds, from
/// [`BRIGHT`] (none) to [`DARK`] (all).
fn antialiased(w: usize, h: usize, ink: impl Fn(f64, f64) -> bool) -> Vec<u8> {
    per_pixel(w, h, |x, y| {
        let n: u32 = samples(x, y).map(|(sx, sy)| u32::from(ink(sx, sy))).sum();
        let t = f64::from(n) / 16.0;
        (f64::from(BRIGHT) + t * (f64::from(DARK) - f64::from(BRIGHT))).round() as u8
    })
}

/// Whether block `(bx, by)` is inked in the text layout: glyphs 3 blocks
/// wide and 5 high, one blank block between glyphs, three between lines,
/// in columns of 40 glyphs; about one glyph in six is a word space, and
/// each line of a column ends at a random length (12 to 35 glyphs), so the
/// right margins are ragged as in text.
fn glyph_ink(seed: u64, bx: usize, by: usize) -> bool {
    let (line, row) = (by / 8, by % 8);
    let (glyph, col) = (bx / 4, bx % 4);
    if row >= 5 || col >= 3 {
        return false;
    }
    let line_len = 12 + hash3(seed, line as u64, u64::MAX) % 24;
    let g = hash3(seed, line as u64, glyph as u64);
    if glyph as u64 % 40 >= line_len || g.is_multiple_of(6) {
        return false;
    }
    // A random 3x5 bitmap whose middle column is always inked: a stem, as
    // most letters have, so glyphs are connected strokes, not speckle.
    let bits = (g >> 8) | 0b010_010_010_010_010;
    bits >> (row * 3 + col) & 1 == 1
}

/// A stroke: the points within `half` of the segment `a`-`b`, painted in
/// `level`.
struct Stroke {
    a: (f64, f64),
    b: (f64, f64),
    half: f64,
    level: f64,
}

impl Stroke {
    /// The random stroke of cell `(cx, cy)`: centred in the cell, any
    /// direction, length in `[len / 2, len]`, 1 to 3 px thick, dark or
    /// bright.
    fn of_cell(seed: u64, cx: usize, cy: usize, cell: usize, len: f64) -> Self {
        let mut r = SplitMix64(hash3(seed, cx as u64, cy as u64));
        let mx = (cx as f64 + r.next_f64()) * cell as f64;
        let my = (cy as f64 + r.next_f64()) * cell as f64;
        let (s, c) = (r.next_f64() * std::f64::consts::PI).sin_cos();
        let l = len * (0.5 + 0.5 * r.next_f64()) / 2.0;
        Self {
            a: (mx - l * c, my - l * s),
            b: (mx + l * c, my + l * s),
            half: 0.5 + r.next_f64(),
            level: if r.next_f64() < 0.5 { 20.0 } else { 235.0 },
        }
    }

    /// Whether `(x, y)` is on the stroke.
    fn covers(&self, x: f64, y: f64) -> bool {
        let (dx, dy) = (self.b.0 - self.a.0, self.b.1 - self.a.1);
        let (ex, ey) = (x - self.a.0, y - self.a.1);
        let t = ((ex * dx + ey * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        (ex - t * dx).hypot(ey - t * dy) < self.half
    }
}

/// One random antialiased stroke per cell (see [`Stroke::of_cell`]) over a
/// mid-gray background. A stroke reaches at most one cell beyond its own,
/// so each pixel paints the strokes of its own and the eight neighbouring
/// cells, in a fixed order.
fn strokes(seed: u64, w: usize, h: usize, cell: usize, len: f64) -> Vec<u8> {
    let cw = w.div_ceil(cell) + 1;
    let all: Vec<Stroke> = (0..h.div_ceil(cell) + 1)
        .flat_map(|y| (0..cw).map(move |x| (x, y)))
        .map(|(x, y)| Stroke::of_cell(seed, x, y, cell, len))
        .collect();
    per_pixel(w, h, |x, y| {
        let (gx, gy) = (x / cell, y / cell);
        let mut v = 128.0;
        for ny in gy.saturating_sub(1)..=gy + 1 {
            for nx in gx.saturating_sub(1)..=gx + 1 {
                let s = &all[ny * cw + nx];
                let n: u32 = samples(x, y)
                    .map(|(px, py)| u32::from(s.covers(px, py)))
                    .sum();
                v += f64::from(n) / 16.0 * (s.level - v);
            }
        }
        v.round() as u8
    })
}

/// The 4x4 sub-pixel sample positions of pixel `(x, y)`.
fn samples(x: usize, y: usize) -> impl Iterator<Item = (f64, f64)> {
    (0..16).map(move |k| {
        let sub = |i: i32| (f64::from(i) + 0.5) / 4.0;
        (x as f64 + sub(k % 4), y as f64 + sub(k / 4))
    })
}

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny generator whose output
/// function is also a good 64-bit mixer, which [`hash3`] reuses.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix(self.0)
    }

    /// Uniform in `[0, 1)`, 53 bits.
    pub(crate) fn next_f64(&mut self) -> f64 {
        unit_f64(self.next_u64())
    }
}

/// The SplitMix64 finaliser.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A random 64-bit value for position `(a, b)` of the stream `seed`:
/// random access, so a pattern needs no state and no drawing order.
pub(crate) fn hash3(seed: u64, a: u64, b: u64) -> u64 {
    mix(mix(mix(seed ^ a).wrapping_add(b)) ^ seed)
}

/// The top 53 bits as a value in `[0, 1)`.
fn unit_f64(r: u64) -> f64 {
    (r >> 11) as f64 / (1u64 << 53) as f64
}

/// FNV-1a, 64 bit: each pattern's seed, from its name (also the man-made
/// scenes' noise seeds).
pub(crate) fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xCBF2_9CE4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_file_safe() {
        let mut names: Vec<_> = patterns().iter().map(|p| p.name).collect();
        assert!((25..=40).contains(&names.len()));
        assert!(names.iter().all(|n| {
            n.bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-')
        }));
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), patterns().len());
        assert!(find("tiles-12-3").is_some() && find("no-such").is_none());
    }

    #[test]
    fn deterministic_sized_and_not_constant() {
        for &(w, h) in &[(64, 48), (37, 23), (1, 1), (160, 120)] {
            for p in patterns() {
                let img = p.render(w, h);
                assert_eq!(img.len(), w * h, "{} at {w}x{h}", p.name);
                assert_eq!(img, p.render(w, h), "{} at {w}x{h}", p.name);
                if w * h >= 64 * 48 {
                    let (lo, hi) = (img.iter().min(), img.iter().max());
                    assert!(hi.unwrap() - lo.unwrap() >= 32, "{} is nearly flat", p.name);
                }
            }
        }
        assert_eq!(render("noise-uniform", 8, 8), render("noise-uniform", 8, 8));
        assert_eq!(render("no-such", 8, 8), None);
    }

    #[test]
    fn fixed_values_and_crops() {
        // Pinned so that a change of the generator shows as a test failure,
        // not as a silent change of every worst-case number.
        let tiles = render("tiles-12-3", 640, 480).unwrap();
        assert_eq!(
            (tiles[0], tiles[11], tiles[12], tiles[14], tiles[15]),
            (BRIGHT, BRIGHT, DARK, DARK, BRIGHT)
        );
        assert_eq!(tiles[12 * 640], DARK);
        let noise = render("noise-uniform", 4, 1).unwrap();
        assert_eq!(noise, [62, 100, 36, 186]);
        // Position-only patterns: a small render is a crop of a large one.
        for p in patterns()
            .iter()
            .filter(|p| !matches!(p.kind, Rings { .. } | Star { .. }))
        {
            let big = p.render(50, 40);
            let small = p.render(20, 10);
            for y in 0..10 {
                assert_eq!(small[y * 20..][..20], big[y * 50..][..20], "{}", p.name);
            }
        }
    }

    #[test]
    fn noise_statistics() {
        let n = render("noise-gauss-40", 200, 200).unwrap();
        let mean = n.iter().map(|&v| f64::from(v)).sum::<f64>() / n.len() as f64;
        let var = n
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / n.len() as f64;
        assert!((mean - 128.0).abs() < 1.0, "{mean}");
        assert!((var.sqrt() - 40.0).abs() < 1.5, "{}", var.sqrt());
    }
}
