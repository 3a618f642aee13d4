//! Design §8: the validation of a linking, its score and the endpoint
//! extension, in floating point.

use alloc::vec;
use alloc::vec::Vec;

use super::{BWD, FWD, Line, Linker, Outcome, Seed};
use crate::Config;
use crate::reference::Maps;
use crate::reference::anchors::NONE;
use crate::reference::{Seg, angle_diff, bresenham, q8, round};
use crate::stage::gradient::gradient_at;
use crate::stage::trim::Longest;

/// What validation counts along a segment (design §8 and design §8.1).
struct Trace {
    /// In-image pixels within T_aligned of the normal.
    aligned: u32,
    /// Pixels at a junction, left out of the aligned density.
    junction: u32,
    /// The gradient across, towards the left of the segment as displayed.
    polarity: f64,
    sums: Sums,
}

impl Linker<'_> {
    /// Design §8: endpoints by projection along the minor axis, then the three
    /// outcomes, decided on the ends as the core keeps them, on the Q8 grid.
    pub(super) fn validate(&mut self, s: &Seed) -> Outcome {
        self.validate_with(s, self.cfg.trim, false)
    }

    /// [`Linker::validate`]; `trim`: a linking that fails ρ2 may keep its
    /// longest passing part (design §8.2); `nested`: a part, validated
    /// without the weak linking's side effects.
    fn validate_with(&mut self, s: &Seed, trim: bool, nested: bool) -> Outcome {
        let l = &s.line;
        let end = |(x, y): (i32, i32)| -> (f64, f64) {
            if l.steep() {
                (l.x_at(f64::from(y)), f64::from(y))
            } else {
                (f64::from(x), l.y_at(f64::from(x)))
            }
        };
        let (b, e) = (end(s.ends[FWD]), end(s.ends[BWD]));
        let exact = Seg::new(b.0, b.1, e.0, e.1);
        let seg = exact.on_q8_grid();
        let (dx, dy) = ((seg.x1 - seg.x0) as f32, (seg.y1 - seg.y0) as f32);
        let length = libm::sqrtf(dx * dx + dy * dy);
        if s.links < 1 || length < self.cfg.min_length_px {
            return Outcome::Discard;
        }
        let few_groups = s.links + 1 < usize::from(self.cfg.min_groups);
        if few_groups && self.cfg.reseed.skips_trace_of_few() {
            return self.weak(s, few_groups, nested);
        }
        let normal = normal_angle(f64::from(dx), f64::from(dy));
        // The parts' stack holds what the core's visited list holds.
        let trim = trim && !few_groups;
        let words = if trim { self.cfg.max_link_pixels } else { 0 };
        let mut stack = vec![0u32; words as usize];
        let mut track = Longest::new(&mut stack, self.rho2_q32, l.steep());
        let t = self.trace(s, &seg, normal, trim.then_some(&mut track));
        let (inside, anchors, aligned) = (t.sums.inside, t.sums.anchors, t.aligned);
        let density = |k: u32, of: u32| {
            if of == 0 {
                0.0
            } else {
                f64::from(k) / f64::from(of)
            }
        };
        if inside == 0 || density(anchors, inside) < f64::from(self.cfg.anchor_density) {
            return Outcome::Discard;
        }
        // Junction pixels count for ρ1 and the score, not for ρ2.
        let judged = inside - t.junction;
        if few_groups || density(aligned, judged) < f64::from(self.cfg.aligned_density) {
            if let Some(part) = track.best()
                && let Some(strong) = self.part(s, part)
            {
                return strong;
            }
            return self.weak(s, few_groups, nested);
        }
        // The brighter side on the left; balanced sides keep the walk's
        // order. Scored as validated (design §8.1).
        let flip = |s: Seg| if t.polarity < 0.0 { s.reversed() } else { s };
        let score = t.sums.score(libm::hypot(seg.x1 - seg.x0, seg.y1 - seg.y0));
        // The authors' float ends when nothing moves them (their code has no
        // extension; the merging puts its input on the grid).
        let out = if self.cfg.extend_max_px == 0 {
            flip(exact)
        } else {
            extend(self.maps, self.cfg, l, flip(seg))
        };
        Outcome::Strong(Seg { score, ..out })
    }

    /// Design §8: what validation counts along `seg` (on the Q8 grid) by
    /// Bresenham, the pixels of a bridge's crossing edge left out.
    fn trace(
        &self,
        s: &Seed,
        seg: &Seg,
        normal: f32,
        mut track: Option<&mut Longest<'_>>,
    ) -> Trace {
        let l = &s.line;
        let (mut inside, mut anchors, mut aligned) = (0u32, 0u32, 0u32);
        let (w, h) = (self.maps.w as i64, self.maps.h as i64);
        let r = |v: f64| round(v) as i64;
        // Within a bridge (design §7.5: strictly between its ends along the
        // final line's major axis) the pixels of the crossing edge, with a
        // nonzero gradient not aligned with the normal, are not counted.
        let steep = l.steep();
        let tol = self.cfg.align_tolerance_deg;
        let crossing = |x: i64, y: i64| {
            let p = (y * w + x) as usize;
            self.maps.m[p] > 0.0
                && angle_diff(self.maps.o[p], normal) > tol
                && s.bridged.iter().any(|&(a, b)| {
                    let (u, ua, ub) = if steep {
                        (y, i64::from(a.1), i64::from(b.1))
                    } else {
                        (x, i64::from(a.0), i64::from(b.0))
                    };
                    u > ua.min(ub) && u < ua.max(ub)
                })
        };
        // The gradient across, towards the left of the segment as
        // displayed (design §8.1).
        let mut polarity = 0.0;
        let (sdx, sdy) = (seg.x1 - seg.x0, seg.y1 - seg.y0);
        // And the score's sums (design §8.1).
        let mut sums = Sums::new(self.cfg);
        // A junction (design §8): at most `bridge_px` pixels in a row not
        // aligned with the normal, between two aligned pixels whose
        // gradients cross the line towards opposite sides, where the
        // line's contrast changes sign. `run` counts the pixels since the
        // last aligned one, `side` is that one's (0: below the magnitude
        // threshold).
        let (mut junction, mut run, mut side) = (0u32, 0u32, 0.0f64);
        let sign = |m: f32, v: f64| if m > 0.0 && v != 0.0 { v.signum() } else { 0.0 };
        bresenham((r(seg.x0), r(seg.y0)), (r(seg.x1), r(seg.y1)), |x, y| {
            if x >= 0 && y >= 0 && x < w && y < h && !crossing(x, y) {
                let p = (y * w + x) as usize;
                inside += 1;
                if self.labels[p] != NONE {
                    anchors += 1;
                }
                let (gx, gy) = gradient_at(&self.maps.blur, self.maps.w, x as usize, y as usize);
                let across = f64::from(gx) * sdy - f64::from(gy) * sdx;
                if angle_diff(self.maps.o[p], normal) <= self.cfg.align_tolerance_deg {
                    aligned += 1;
                    let now = sign(self.maps.m[p], across);
                    if run <= u32::from(self.cfg.bridge_px) && side * now < 0.0 {
                        junction += run;
                    }
                    (run, side) = (0, now);
                    if let Some(track) = track.as_deref_mut() {
                        let (a, j) = (u64::from(aligned - 1), u64::from(inside - 1 - junction));
                        track.aligned((x as i32, y as i32), a, j);
                    }
                } else {
                    run += 1;
                }
                if self.maps.m[p] > 0.0 {
                    polarity += across;
                    sums.add((gx, gy), (sdx, sdy));
                }
            }
        });
        (sums.anchors, sums.inside) = (anchors, inside);
        Trace {
            aligned,
            junction,
            polarity,
            sums,
        }
    }

    /// Design §8.2: the part `(a, b)` of a linking that fails ρ2, validated
    /// on its own with the seed and normal-route groups whose centres it
    /// spans; a strong part releases the normal-route groups outside it.
    fn part(&mut self, s: &Seed, (a, b): ((i32, i32), (i32, i32))) -> Option<Outcome> {
        let steep = s.line.steep();
        let major = |q: (i32, i32)| if steep { q.1 } else { q.0 };
        let (lo, hi) = (major(a).min(major(b)), major(a).max(major(b)));
        let within = |g: usize| (lo..=hi).contains(&major(self.maps.xy(self.groups[g].c)));
        let count = usize::from(within(s.g)) + s.undo.iter().filter(|&&g| within(g)).count();
        if count < usize::from(self.cfg.min_groups) {
            return None;
        }
        let mut t = s.clone();
        (t.ends, t.links) = ([a, b], count - 1);
        let out = self.validate_with(&t, false, true);
        let Outcome::Strong(_) = out else { return None };
        let outside: Vec<usize> = s.undo.iter().copied().filter(|&g| !within(g)).collect();
        for g in outside {
            self.linked[g] = false;
            self.released[g] = true;
        }
        Some(out)
    }

    /// A weak linking: releases its normal-route links, retired when the
    /// rule says so; a `nested` one (a part) changes nothing.
    fn weak(&mut self, s: &Seed, few_groups: bool, nested: bool) -> Outcome {
        if nested {
            return Outcome::Weak;
        }
        let retire = self.cfg.reseed.retires(self.released[s.g], few_groups);
        for &u in &s.undo {
            self.linked[u] = false;
            self.released[u] = true;
            self.retired[u] |= retire;
        }
        Outcome::Weak
    }
}

/// Design §8.1: what a strong segment's score sums over the pixels
/// validation traces.
struct Sums {
    /// `|g × d|` over the pixels of nonzero magnitude, `d` the direction at
    /// validation.
    contrast: f64,
    anchors: u32,
    /// Pixels of nonzero magnitude within T_aligned/2 of the normal.
    sharp: u32,
    inside: u32,
    /// `K = tan T / tan(T/2)` on the core's Q8 grid, times `cos T` and
    /// `sin T`: within T/2 when `|g · d|·K·cos T ≤ |g × d|·sin T` (the
    /// core's test).
    k_cos: f64,
    sin: f64,
}

impl Sums {
    fn new(cfg: &Config) -> Self {
        let t = f64::from(cfg.align_tolerance_deg).to_radians();
        let h = libm::cos(t / 2.0);
        let k = round(2.0 * h * h / libm::cos(t) * 256.0) / 256.0;
        Self {
            contrast: 0.0,
            anchors: 0,
            sharp: 0,
            inside: 0,
            k_cos: k * libm::cos(t),
            sin: libm::sin(t),
        }
    }

    /// Adds the gradient `g` of a pixel of nonzero magnitude on a segment
    /// of direction `d`.
    fn add(&mut self, (gx, gy): (i32, i32), (dx, dy): (f64, f64)) {
        let (gx, gy) = (f64::from(gx), f64::from(gy));
        let cross = (gx * dy - gy * dx).abs();
        self.contrast += cross;
        // Within T_aligned/2 of the normal `n = (-dy, dx)`.
        if (gx * dx + gy * dy).abs() * self.k_cos <= cross * self.sin {
            self.sharp += 1;
        }
    }

    /// The score of a segment of length `len`: the contrast over `len`,
    /// rounded, times the squares of the two shares in Q16 (rounded), each
    /// product rounded, at most 2^24 - 1 (the core's integer steps).
    fn score(&self, len: f64) -> f64 {
        if len == 0.0 || self.inside == 0 {
            return 0.0;
        }
        let cap = (1u64 << 24) - 1;
        let c = (round(self.contrast / len) as u64).min(cap);
        let n = u64::from(self.inside);
        let share = |k: u32| ((u64::from(k) << 16) + n / 2) / n;
        let (a, s) = (share(self.anchors), share(self.sharp));
        let ca = (c * (a * a) + (1 << 31)) >> 32;
        (((ca * (s * s) + (1 << 31)) >> 32).min(cap)) as f64
    }
}

/// Endpoint extension (design §8): each end moves along the line `l`, one
/// pixel of its major axis at a time, while the pixel under the line has a
/// nonzero magnitude and a gradient within T_aligned of the normal of
/// `seg` and of its polarity, for at most `Config::extend_max_px` pixels.
/// `seg`'s ends are on the Q8 grid, and so is each step's offset along the
/// minor axis.
fn extend(maps: &Maps, cfg: &Config, l: &Line, seg: Seg) -> Seg {
    let (dx, dy) = (seg.x1 - seg.x0, seg.y1 - seg.y0);
    let steep = l.steep();
    let (d_major, d_minor) = if steep { (dy, dx) } else { (dx, dy) };
    if cfg.extend_max_px == 0 || d_major == 0.0 {
        return seg;
    }
    let normal = normal_angle(dx, dy);
    // Aligned with the normal and brighter on the left (design §8.1).
    let supported = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= maps.w as i64 || y >= maps.h as i64 {
            return false;
        }
        let p = y as usize * maps.w + x as usize;
        let (gx, gy) = gradient_at(&maps.blur, maps.w, x as usize, y as usize);
        maps.m[p] > 0.0
            && angle_diff(maps.o[p], normal) <= cfg.align_tolerance_deg
            && f64::from(gx) * dy - f64::from(gy) * dx > 0.0
    };
    let beyond = |(major, minor): (f64, f64), sign: f64, steps: u16| {
        let dm = sign * f64::from(steps);
        (major + dm, minor + q8(dm * d_minor / d_major))
    };
    // (x, y) <-> (major, minor): a swap when steep, its own inverse.
    let axes = |(a, b): (f64, f64)| if steep { (b, a) } else { (a, b) };
    let forward = d_major.signum();
    let mut ends = [(seg.x0, seg.y0), (seg.x1, seg.y1)];
    for (end, sign) in ends.iter_mut().zip([-forward, forward]) {
        let start = axes(*end);
        let mut steps = 0;
        while steps < cfg.extend_max_px {
            let (x, y) = axes(beyond(start, sign, steps + 1));
            if !supported(round(x) as i64, round(y) as i64) {
                break;
            }
            steps += 1;
        }
        *end = axes(beyond(start, sign, steps));
    }
    let [(x0, y0), (x1, y1)] = ends;
    Seg::new(x0, y0, x1, y1)
}

/// The orientation of the normal of a segment with direction `(dx, dy)`, in
/// the degrees of the orientation map (design §8).
fn normal_angle(dx: f64, dy: f64) -> f32 {
    let q = (dy as f32) / (dx as f32);
    let phi = f64::from(libm::atanf(q)) * 180.0 / core::f64::consts::PI;
    (phi + 90.0) as f32
}
