//! The float reference: a plain, readable transcription of the authors' code
//! (design §1-8) plus the paper's merging
//! stage (paper §3.3), in `f32`/`f64` through `libm`. It is the oracle the
//! fixed-point core is tested against, not a product: it allocates
//! (`alloc::vec::Vec`) and makes no attempt at speed.
//!
//! Pipeline (paper section → module):
//!
//! | stage | paper | here |
//! |---|---|---|
//! | 5x5 Gaussian, 2x2 gradient, L1 magnitude, orientation | paper §3.1 | `stage::smooth` (shared with the core), `Maps` |
//! | pseudo-sort, aligned anchor groups, NMS regular anchors, labels | paper §3.1 | `anchors` |
//! | linking with skip budgets, reverse flag, `extend` | paper §3.2 | `link` |
//! | endpoints, length / group count / density validation | paper §3.3 | `link` |
//! | merging (eqs. 6-7) and the Bresenham re-fit | paper §3.3 | `merge` |
//!
//! # Deliberate differences from the official code
//!
//! 1. **Orientation bug fixed.** The official code maps a gradient with
//!    `gx = 0, gy < 0` to -90° instead of 90° (design §2). Such pixels
//!    then fall in the wrong group class, are never NMS anchors and align
//!    with almost anything, and every perfectly horizontal edge that is
//!    darker below is lost. Here they get 90°.
//! 2. **No sentinel restarts.** Where the official walk finds no pixel it
//!    returns a sentinel at the image corner and keeps walking from there
//!    (design §12). Here a walk that finds no pixel ends; a pass whose first step
//!    finds nothing keeps the seed centre as its endpoint.
//! 3. **Pixel-centre output.** The official output is in the gradient grid
//!    (`(x, y)` is the corner between pixels `x-1` and `x`), which is
//!    +0.5 px on both axes from the 0-based pixel-centre frame of the ground
//!    truth. The output here is shifted by -0.5 px on both axes; the
//!    agreement test measures the offset to the official output
//!    (`tests/official_agreement.rs`).
//! 4. **Merging** (paper §3.3), absent from the released code, is a
//!    [`Config::merge`] switch, on in [`Config::DEFAULT`] and [`Config::PAPER`]. The paper's second
//!    condition (eq. 7: endpoint gap ≤ D_e for disjoint segments) states no
//!    angle or offset test, which would merge the two arms of every corner;
//!    here both conditions also require the angle (D_a) and centre-distance
//!    (D_c) tests of eq. 6, so only near-collinear fragments merge.
//! 5. **Clipping**: segments are clipped to the image rectangle
//!    (`[-0.5, w - 0.5] x [-0.5, h - 0.5]` in pixel centres); projections
//!    onto a fitted line can otherwise leave the image by a pixel or so.
//! 6. **Numerical clean-ups that change no decision in practice**: the line
//!    fit takes its centred moments from exact integer sums (the official
//!    f64 mean formula leaves rounding noise in `dxy`, which makes the sign of
//!    a perfectly vertical fit random); line angles lie in [-90°, 90°) (a
//!    vertical line reads -90°, never +90°); the point-line distance is the
//!    plain perpendicular distance (the official two-point construction
//!    carries a 1e-5 slope bias and is undefined when the fit's mean lies on
//!    row or column 0); `ret_x`/`ret_y` drop the same 1e-5 bias.
//! 7. **Endpoint extension** ([`Config::extend_max_px`], design §8) and
//!    [`Config::reseed`] (every [`crate::Reseed`]) are implemented as in the core. The work
//!    limit ([`Config::work_per_mille`], [`Config::work_budget`]) is not:
//!    the reference runs every linking and compares every candidate pair,
//!    which on natural images is what the core does too.
//! 8. **Positions on the core's grid.** The decisions that hang on a
//!    segment's ends or on a point probed along a line (the end pixels of
//!    the validation trace, the length, the extension, the merging, the
//!    `extend` probe and the bridges) take the float values rounded to
//!    1/256 px, as the fixed core keeps them (design §8 and design §12), before any
//!    rounding to pixels. The output ends stay the float projections where
//!    no extension or merging moves them.
//!
//! Everything else, including the quirks that shape the output (the
//! "either side" group alignment test, the `extend` probe's signed-slope
//! axis choice, the sticky reverse flag, the undo rule for weak candidates),
//! follows the official code.

// The reference is host-side test oracle code on `Vec`s: readable indexing
// is preferred over `get()`; an out-of-range index there is a bug that the
// tests would surface as a panic.
#![allow(clippy::indexing_slicing)]

use alloc::vec;
use alloc::vec::Vec;

use crate::stage::{gradient::gradient_at, smooth};
use crate::{Config, Error, GrayImage, Segment};

mod anchors;
pub(crate) mod link;
mod merge;
mod trace;

#[cfg(feature = "_unstable-hooks")]
pub use trace::{Quirks, Trace};
#[cfg(not(feature = "_unstable-hooks"))]
use trace::{Quirks, Trace};

/// Runs the float reference on `img` and returns its segments, in 0-based
/// pixel-centre coordinates, in the order the linking produced them (merged
/// segments take the place of the first fragment).
///
/// # Errors
/// [`Error::InvalidConfig`] when `cfg` fails [`Config::validate`].
pub fn detect(img: &GrayImage<'_>, cfg: &Config) -> Result<Vec<Segment>, Error> {
    run(img, cfg, Quirks::default()).map(|t| t.segments)
}

/// [`detect`] with switches and a trace of intermediate counts, for the
/// agreement tests. Unstable: behind the `_unstable-hooks` feature.
///
/// # Errors
/// As [`detect`].
#[cfg(feature = "_unstable-hooks")]
pub fn detect_traced(img: &GrayImage<'_>, cfg: &Config, quirks: Quirks) -> Result<Trace, Error> {
    run(img, cfg, quirks)
}

/// The pipeline behind [`detect`] and `detect_traced`.
fn run(img: &GrayImage<'_>, cfg: &Config, quirks: Quirks) -> Result<Trace, Error> {
    cfg.validate()?;
    let maps = Maps::compute(img, cfg, quirks);
    let mut trace = Trace {
        blur_sum: maps.blur.iter().map(|&v| u64::from(v)).sum(),
        blur_wsum: maps
            .blur
            .iter()
            .enumerate()
            .map(|(i, &v)| (i as u64 + 1) * u64::from(v))
            .sum(),
        nonzero: maps.m.iter().filter(|&&v| v > 0.0).count(),
        ..Trace::default()
    };
    let groups = anchors::extract_groups(&maps, cfg);
    let nms = anchors::nms(&maps, cfg.maxima);
    trace.nms_pixels = nms.iter().filter(|&&b| b).count();
    trace.nms_index_sum = nms
        .iter()
        .enumerate()
        .filter(|&(_, &b)| b)
        .map(|(i, _)| i as u64)
        .sum();
    let labels = anchors::labels(&maps, &groups, &nms);
    trace.regular = labels.iter().filter(|&&l| l == anchors::REGULAR).count();
    trace.groups = groups
        .iter()
        .map(|g| {
            let p = |i: usize| [(i % maps.w) as u32, (i / maps.w) as u32];
            let (j, c, k) = (p(g.j), p(g.c), p(g.k));
            [j[0], j[1], c[0], c[1], k[0], k[1]]
        })
        .collect();
    let linked = link::link_all(&maps, cfg, &groups, &labels);
    trace.weak = linked.weak;
    let mut segs = linked.segments;
    if cfg.merge {
        trace.merged = merge::merge_all(&mut segs, cfg, maps.w, maps.h);
    }
    let shift = if quirks.official_frame { 0.0 } else { 0.5 };
    trace.segments = segs
        .iter()
        .map(|s| clipped(s, maps.w as f64, maps.h as f64))
        .map(|s| Segment {
            x0: (s.x0 - shift) as f32,
            y0: (s.y0 - shift) as f32,
            x1: (s.x1 - shift) as f32,
            y1: (s.y1 - shift) as f32,
            score: s.score as f32,
        })
        .collect();
    Ok(trace)
}

/// The segment clipped to the image rectangle `[0, w] x [0, h]` of the
/// gradient grid (pixel centres `[-0.5, w - 0.5] x [-0.5, h - 0.5]`): an
/// endpoint outside moves along the segment onto the border. (Not in the
/// official code, whose endpoints can leave the image by a pixel or so.)
fn clipped(s: &Seg, w: f64, h: f64) -> Seg {
    let clip_start = |mut a: (f64, f64), b: (f64, f64)| {
        for (lo, hi, axis) in [(0.0, w, 0), (0.0, h, 1)] {
            let (p, q, dp, dq) = if axis == 0 {
                (a.0, a.1, b.0 - a.0, b.1 - a.1)
            } else {
                (a.1, a.0, b.1 - a.1, b.0 - a.0)
            };
            let target = if p < lo {
                lo
            } else if p > hi {
                hi
            } else {
                continue;
            };
            let q_new = if dp != 0.0 {
                q + (target - p) * dq / dp
            } else {
                q
            };
            a = if axis == 0 {
                (target, q_new)
            } else {
                (q_new, target)
            };
        }
        (a.0.clamp(0.0, w), a.1.clamp(0.0, h))
    };
    let a = clip_start((s.x0, s.y0), (s.x1, s.y1));
    let b = clip_start((s.x1, s.y1), a);
    Seg {
        score: s.score,
        ..Seg::new(a.0, a.1, b.0, b.1)
    }
}

/// A segment in the gradient grid, in f64 (the float pipeline's working form).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Seg {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    /// The score (design §8.1), once measured.
    score: f64,
}

impl Seg {
    /// The segment from `(x0, y0)` to `(x1, y1)`, score 0.
    fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Self {
            x0,
            y0,
            x1,
            y1,
            score: 0.0,
        }
    }

    /// The segment with its ends swapped.
    fn reversed(self) -> Self {
        Self {
            score: self.score,
            ..Self::new(self.x1, self.y1, self.x0, self.y0)
        }
    }
}

impl Seg {
    /// The segment with its ends on the fixed core's Q8 grid ([`q8`]).
    fn on_q8_grid(&self) -> Self {
        Self {
            score: self.score,
            ..Self::new(q8(self.x0), q8(self.y0), q8(self.x1), q8(self.y1))
        }
    }
}

/// Per-pixel maps of design §1-2: blurred image, integer gradient, thresholded L1
/// magnitude `m` (f32, integer-valued) and orientation `o` (f32 degrees).
pub(crate) struct Maps {
    w: usize,
    h: usize,
    blur: Vec<u8>,
    m: Vec<f32>,
    o: Vec<f32>,
}

impl Maps {
    fn compute(img: &GrayImage<'_>, cfg: &Config, quirks: Quirks) -> Self {
        let (w, h) = (img.width(), img.height());
        let mut blur = vec![0u8; w * h];
        let mut scratch = vec![0u16; smooth::SCRATCH_ROWS * w];
        smooth::blur_into(img, &mut blur, &mut scratch);
        let mut m = vec![0f32; w * h];
        let mut o = vec![0f32; w * h];
        for y in 0..h {
            for x in 0..w {
                let (gx, gy) = gradient_at(&blur, w, x, y);
                let mag = (gx.abs() + gy.abs()) as f32;
                m[y * w + x] = if mag < cfg.magnitude_threshold {
                    0.0
                } else {
                    mag
                };
                o[y * w + x] = orientation(gx, gy, quirks.orientation_bug);
            }
        }
        Self { w, h, blur, m, o }
    }

    fn in_bounds(&self, x: i32, y: i32) -> bool {
        x >= 0 && y >= 0 && (x as usize) < self.w && (y as usize) < self.h
    }

    fn idx(&self, x: i32, y: i32) -> usize {
        y as usize * self.w + x as usize
    }

    fn xy(&self, i: usize) -> (i32, i32) {
        ((i % self.w) as i32, (i / self.w) as i32)
    }
}

/// Gradient orientation in degrees, the gradient direction modulo 180°:
/// `gy < 0` flips the vector, then `atan2f`, then the f64 scaling of design §2.
/// Values lie in [0, 180]; `gy = 0, gx < 0` gives 180.
///
/// With `bug`, a gradient `(0, gy < 0)` is not flipped and reads -90° as in
/// the official code.
fn orientation(gx: i32, gy: i32, bug: bool) -> f32 {
    let flip = gy < 0 && (gx != 0 || !bug);
    let (x, y) = if flip { (-gx, -gy) } else { (gx, gy) };
    let a = libm::atan2f(y as f32, x as f32);
    (f64::from(a) * 180.0 / core::f64::consts::PI) as f32
}

/// Difference of two orientations in degrees, folded once at 90° as the authors' code does (design §4).
fn angle_diff(a: f32, b: f32) -> f32 {
    let d = (a - b).abs();
    if d > 90.0 {
        (180.0 - f64::from(d)) as f32
    } else {
        d
    }
}

/// Round half away from zero (C `roundf`).
fn round(v: f64) -> f64 {
    libm::round(v)
}

/// `v` on the fixed core's Q8 grid (1/256 px), rounded half away from
/// zero. The core keeps segment ends and the points it probes along a line
/// there (design §8) and rounds those to pixels; on the same values the
/// reference takes the same decisions: the pixel an end or a probe rounds
/// to (a float 0.499 px past a pixel centre is 0.5 on the grid), a step of
/// the extension, a merge within a few thousandths of a degree of D_a.
fn q8(v: f64) -> f64 {
    round(v * 256.0) / 256.0
}

/// The classic integer Bresenham line from `a` to `b`, both ends included,
/// tie rule `p >= 0` (design §8): the core's rasteriser, an integer spec
/// both implementations share (like the blur).
fn bresenham(a: (i64, i64), b: (i64, i64), mut emit: impl FnMut(i64, i64)) {
    for (x, y) in crate::stage::raster::Raster::new(a, b) {
        emit(x, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_fix_and_bug() {
        assert_eq!(orientation(0, -5, false), 90.0);
        assert_eq!(orientation(0, -5, true), -90.0);
        assert_eq!(orientation(0, 5, false), 90.0);
        assert_eq!(orientation(-5, 0, false), 180.0);
        assert_eq!(orientation(5, 0, false), 0.0);
        assert!((orientation(3, -3, false) - 135.0).abs() < 1e-4);
    }

    #[test]
    fn bresenham_includes_both_ends() {
        let mut pts = Vec::new();
        bresenham((0, 0), (4, 2), |x, y| pts.push((x, y)));
        assert_eq!(pts, [(0, 0), (1, 1), (2, 1), (3, 2), (4, 2)]); // tie p = 0 steps
        pts.clear();
        bresenham((2, 3), (2, 3), |x, y| pts.push((x, y)));
        assert_eq!(pts, [(2, 3)]);
    }

    #[test]
    fn angle_diff_folds() {
        assert_eq!(angle_diff(10.0, 170.0), 20.0);
        assert_eq!(angle_diff(0.0, 90.0), 90.0);
        assert_eq!(angle_diff(45.0, 30.0), 15.0);
    }
}
