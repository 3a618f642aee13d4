//! Paper §3.2-3.3: linking one seed group at a time, endpoints and
//! validation (design §7-8).

use alloc::vec;
use alloc::vec::Vec;

mod validate;

use super::anchors::{Group, REGULAR};
use super::{Maps, Seg, angle_diff, q8, round};
use crate::Config;
use crate::spec::{WALK, WalkClass, walk_table};
use crate::stage::gradient::gradient_at;

/// A line `(vx, vy)` through `(x0, y0)`; `(vx, vy)` need not be unit length
/// (group lines are not).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line {
    pub vx: f32,
    pub vy: f32,
    pub x0: f32,
    pub y0: f32,
}

impl Line {
    /// The line angle in degrees, `atan(vy / vx)` in f32, folded into
    /// [-90, 90) (a vertical line reads -90). NaN when `vx = vy = 0`.
    pub fn angle(&self) -> f32 {
        let q = self.vy / self.vx;
        let a = (f64::from(libm::atanf(q)) * 57.295_779_513_082_32) as f32;
        if a >= 90.0 { a - 180.0 } else { a }
    }

    /// `|vy / vx| > 1` in f32 (NaN gives false).
    pub(crate) fn steep(&self) -> bool {
        (self.vy / self.vx).abs() > 1.0
    }

    /// x on the line at row `y` (f64).
    fn x_at(&self, y: f64) -> f64 {
        f64::from(self.vx) / f64::from(self.vy) * (y - f64::from(self.y0)) + f64::from(self.x0)
    }

    /// y on the line at column `x` (f64).
    fn y_at(&self, x: f64) -> f64 {
        f64::from(self.vy) / f64::from(self.vx) * (x - f64::from(self.x0)) + f64::from(self.y0)
    }

    /// Perpendicular distance from `(x, y)`.
    fn dist(&self, x: i32, y: i32) -> f64 {
        let (vx, vy) = (f64::from(self.vx), f64::from(self.vy));
        let (dx, dy) = (
            f64::from(x) - f64::from(self.x0),
            f64::from(y) - f64::from(self.y0),
        );
        (dx * vy - dy * vx).abs() / libm::hypot(vx, vy)
    }
}

/// Orthogonal least-squares line fit over integer points, on the core's
/// exact integer sums (so incremental updates equal a batch fit).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Fit(crate::stage::fit::Fit);

impl Fit {
    pub fn add(&mut self, x: i32, y: i32) {
        self.0.add(x, y);
    }

    /// The total-least-squares line: direction `(cos t, sin t)` with
    /// `t = atan2(2 cxy, cxx - cyy) / 2` (f64 `atan2`, rounded to f32, halved,
    /// `cosf`/`sinf`), through the centroid.
    pub fn line(&self) -> Line {
        let (n, sx, sy) = self.0.sums();
        let n = n.max(1) as f64;
        let (cxx, cyy, cxy) = self.0.moments();
        let t = (libm::atan2(2.0 * cxy as f64, cxx as f64 - cyy as f64) as f32) / 2.0;
        Line {
            vx: libm::cosf(t),
            vy: libm::sinf(t),
            x0: (sx as f64 / n) as f32,
            y0: (sy as f64 / n) as f32,
        }
    }
}

/// The reverse-flag rule's bands (design §7.2): a line angle in `[-90°, -67.5°)`.
pub(crate) fn steep_neg(a: f32) -> bool {
    (-90.0..-67.5).contains(&a)
}

/// The reverse-flag rule's bands (design §7.2): a line angle in `[-67.5°, -22.5°)`.
pub(crate) fn diag_neg(a: f32) -> bool {
    (-67.5..-22.5).contains(&a)
}

/// The [`WalkClass`] of a line angle in degrees (design §7.2).
pub(crate) fn walk_class(a: f32) -> WalkClass {
    if diag_neg(a) {
        WalkClass::N45
    } else if (-22.5..22.5).contains(&a) {
        WalkClass::Hz
    } else if (22.5..67.5).contains(&a) {
        WalkClass::P45
    } else {
        WalkClass::Vt
    }
}

/// Forward and backward candidate offsets of each class (design §7.2).
fn candidates(class: WalkClass, forward: bool, reverse: bool) -> [(i32, i32); 3] {
    WALK[usize::from(walk_table(class, forward, reverse))]
}

/// The result of linking every seed.
pub(super) struct Linked {
    pub segments: Vec<Seg>,
    pub weak: usize,
}

/// State shared by every linking.
struct Linker<'a> {
    maps: &'a Maps,
    cfg: &'a Config,
    groups: &'a [Group],
    labels: &'a [i32],
    linked: Vec<bool>,
    /// Released by a weak linking (see `Config::reseed`).
    released: Vec<bool>,
    /// Released by a weak linking that retires its groups (`Reseed::retires`).
    retired: Vec<bool>,
    /// Visited stamps: pixel `p` is in the current visited set iff
    /// `visited[p] == epoch`.
    visited: Vec<u32>,
    epoch: u32,
    /// ρ2 in Q32, the core's, for the parts' search (design §8.2).
    rho2_q32: u64,
}

/// Per-seed state (design §7.1).
#[derive(Clone)]
struct Seed {
    g: usize,
    line: Line,
    prev: Line,
    reverse: bool,
    fit: Fit,
    links: usize,
    undo: Vec<usize>,
    cur: i32,
    ends: [(i32, i32); 2],
    /// Each pass's last end on its own line (not a crossing pixel): the
    /// bridge's contrast reference (design §7.5).
    pole: [(i32, i32); 2],
    /// The stretches bridged (design §7.5): from a pass's end to the
    /// centre of the group it bridged to.
    bridged: Vec<((i32, i32), (i32, i32))>,
}

const FWD: usize = 0;
const BWD: usize = 1;

pub(super) fn link_all(maps: &Maps, cfg: &Config, groups: &[Group], labels: &[i32]) -> Linked {
    let mut lk = Linker {
        maps,
        cfg,
        groups,
        labels,
        linked: vec![false; groups.len()],
        released: vec![false; groups.len()],
        retired: vec![false; groups.len()],
        visited: vec![0; maps.w * maps.h],
        epoch: 0,
        rho2_q32: crate::params::Params::new(cfg).rho2_q32,
    };
    let mut out = Linked {
        segments: Vec::new(),
        weak: 0,
    };
    for g in 0..groups.len() {
        match lk.link_seed(g) {
            // Below the floor: linked as strong, not reported.
            Outcome::Strong(s) if s.score < f64::from(cfg.min_score) => {}
            Outcome::Strong(s) => out.segments.push(s),
            Outcome::Weak => out.weak += 1,
            Outcome::Discard => {}
        }
    }
    out
}

enum Outcome {
    Discard,
    Weak,
    Strong(Seg),
}

impl Linker<'_> {
    fn group_line(&self, g: usize) -> Line {
        let gr = &self.groups[g];
        let (x0, y0) = self.maps.xy(gr.c);
        Line {
            vx: gr.vx,
            vy: gr.vy,
            x0: x0 as f32,
            y0: y0 as f32,
        }
    }

    fn is_visited(&self, p: usize) -> bool {
        self.visited[p] == self.epoch
    }

    fn visit(&mut self, p: usize) {
        self.visited[p] = self.epoch;
    }

    fn label(&self, (x, y): (i32, i32)) -> i32 {
        self.labels[self.maps.idx(x, y)]
    }

    /// Adds the three pixels of group `g` to the fit (J, C, K) and to V.
    fn absorb_group(&mut self, s: &mut Seed, g: usize) {
        let gr = self.groups[g];
        for p in [gr.j, gr.c, gr.k] {
            let (x, y) = self.maps.xy(p);
            s.fit.add(x, y);
            self.visit(p);
        }
    }

    /// Design §7.2: the next pixel from `c`, or `None` when no candidate has m > 0.
    fn step(&self, s: &mut Seed, c: (i32, i32), dir: usize) -> Option<(i32, i32)> {
        let a_prev = s.prev.angle();
        let a = s.line.angle();
        if (steep_neg(a_prev) && diag_neg(a)) || (diag_neg(a_prev) && steep_neg(a)) {
            s.reverse = true;
        }
        let mut best = None;
        let mut best_m = 0.0f32;
        for (dx, dy) in candidates(walk_class(a), dir == FWD, s.reverse) {
            let (x, y) = (c.0 + dx, c.1 + dy);
            if !self.maps.in_bounds(x, y) {
                continue;
            }
            let mq = self.maps.m[self.maps.idx(x, y)];
            if mq > best_m {
                best_m = mq;
                best = Some((x, y));
            }
        }
        best
    }

    /// Design §7.5, with bridging: whether the gradient at raster index `i`
    /// lies within T_aligned of `line`'s direction (strictly), as a crossing
    /// edge's does where it meets the line.
    fn crossing(&self, line: &Line, i: usize) -> bool {
        if self.cfg.bridge_px == 0 {
            return false;
        }
        // The angle between the gradient and the line's normal, folded.
        let r = libm::fmod(
            f64::from(self.maps.o[i]) - f64::from(line.angle()) - 90.0,
            180.0,
        );
        let d = if r < 0.0 { r + 180.0 } else { r };
        d.min(180.0 - d) > 90.0 - f64::from(self.cfg.align_tolerance_deg)
    }

    fn aligned_with_line(&self, line: &Line, g: usize) -> bool {
        angle_diff(line.angle(), self.group_line(g).angle()) <= self.cfg.align_tolerance_deg
    }

    /// Design §7.4: probe one pixel along the line past a misaligned group.
    fn extend(&mut self, s: &mut Seed, n: (i32, i32), dir: usize) -> Option<(i32, i32)> {
        let horizontal = s.line.vy / s.line.vx <= 1.0; // signed, as in the official code
        let sign = if dir == FWD { 1.0 } else { -1.0 };
        let (mut qx, mut qy) = (f64::from(n.0), f64::from(n.1));
        if horizontal {
            qx += sign;
            qy = s.line.y_at(qx);
        } else {
            qy += sign;
            qx = s.line.x_at(qy);
        }
        let (qx, qy) = (round(q8(qx)), round(q8(qy)));
        if !(qx >= 0.0 && qy >= 0.0 && qx < self.maps.w as f64 && qy < self.maps.h as f64) {
            return None;
        }
        let q = (qx as i32, qy as i32);
        if self.is_visited(self.maps.idx(q.0, q.1)) {
            return None;
        }
        let lab = self.label(q);
        if lab >= 0 && !self.linked[lab as usize] && self.aligned_with_line(&s.line, lab as usize) {
            let g = lab as usize;
            self.linked[g] = true;
            self.absorb_group(s, g);
            s.line = s.fit.line();
            let centre = self.maps.xy(self.groups[g].c);
            return self.step(s, centre, dir);
        }
        None
    }

    /// Links group `g` at the end `dir` of the seed's walk (design §7.3):
    /// its members join the fit, the line is refitted (`Lp := L`), the
    /// group and (forward) the seed are linked, and the end moves to the
    /// group's centre, which is returned.
    fn link_group(&mut self, s: &mut Seed, g: usize, dir: usize) -> (i32, i32) {
        self.absorb_group(s, g);
        s.prev = s.line;
        s.line = s.fit.line();
        if dir == FWD {
            self.linked[s.g] = true;
        }
        self.linked[g] = true;
        s.undo.push(g);
        let centre = self.maps.xy(self.groups[g].c);
        (s.ends[dir], s.pole[dir]) = (centre, centre);
        s.cur = g as i32;
        s.links += 1;
        centre
    }

    /// Design §7.3: one pass in direction `dir`, bridging (design §7.5)
    /// from each end it reaches while `Config::bridge_px` finds a group; a
    /// bridge after which the pass links nothing more is undone.
    fn pass(&mut self, s: &mut Seed, dir: usize, start: Option<(i32, i32)>) {
        let Some(mut c) = start else { return };
        let mut steps = self.cfg.skip_min;
        // The seed before the last bridge, whether it was linked, and the
        // group bridged to.
        let mut tentative: Option<(Seed, bool, usize)> = None;
        loop {
            self.walk(s, dir, c, steps);
            if let Some((before, seed_linked, g)) = tentative.take()
                && s.ends[dir] == self.maps.xy(self.groups[g].c)
            {
                self.unbridge(s, before, seed_linked, g);
                return;
            }
            let Some(g) = self.bridge_target(s, dir) else {
                return;
            };
            let before = (s.clone(), self.linked[s.g], g);
            let from = s.ends[dir];
            let centre = self.link_group(s, g, dir);
            s.bridged.push((from, centre));
            steps = self.cfg.skip_group;
            match self.step(s, centre, dir) {
                Some(p) => {
                    c = p;
                    tentative = Some(before);
                }
                None => {
                    let (before, seed_linked, g) = before;
                    self.unbridge(s, before, seed_linked, g);
                    return;
                }
            }
        }
    }

    /// Undoes the last bridge, to group `g`: the seed as it was `before`
    /// it, and whether it was linked then.
    fn unbridge(&mut self, s: &mut Seed, before: Seed, seed_linked: bool, g: usize) {
        *s = before;
        self.linked[g] = false;
        self.linked[s.g] = seed_linked;
    }

    /// Design §7.5: the first group that the pass's end bridges to, among
    /// the `bridge_px` pixels past it, away from the other end, one pixel of
    /// the line's major axis at a time (the minor coordinate on the line,
    /// rounded): not linked yet, its centre within T_dist of the line, its
    /// direction within T_aligned / 2 of the line's, and its gradient
    /// opposite to the one at the end.
    fn bridge_target(&self, s: &Seed, dir: usize) -> Option<usize> {
        let ((ex, ey), (ox, oy)) = (s.ends[dir], s.ends[1 - dir]);
        let steep = s.line.steep();
        let sign = if steep { ey - oy } else { ex - ox }.signum();
        if sign == 0 {
            return None;
        }
        let grad = |(x, y): (i32, i32)| {
            let (gx, gy) = gradient_at(&self.maps.blur, self.maps.w, x as usize, y as usize);
            (f64::from(gx), f64::from(gy))
        };
        let end_grad = grad(s.pole[dir]);
        for k in 1..=i32::from(self.cfg.bridge_px) {
            let q = if steep {
                let y = ey + sign * k;
                (round(q8(s.line.x_at(f64::from(y)))) as i32, y)
            } else {
                let x = ex + sign * k;
                (x, round(q8(s.line.y_at(f64::from(x)))) as i32)
            };
            if !self.maps.in_bounds(q.0, q.1) {
                return None;
            }
            let lab = self.label(q);
            if lab < 0 || lab == s.g as i32 || self.linked[lab as usize] {
                continue;
            }
            let g = lab as usize;
            let centre = self.maps.xy(self.groups[g].c);
            let cg = grad(centre);
            if s.line.dist(centre.0, centre.1) <= f64::from(self.cfg.dist_tolerance_px)
                && angle_diff(s.line.angle(), self.group_line(g).angle())
                    <= self.cfg.align_tolerance_deg / 2.0
                && end_grad.0 * cg.0 + end_grad.1 * cg.1 < 0.0
            {
                return Some(g);
            }
        }
        None
    }

    /// Design §7.3: the walk of one pass from `c` with `steps` gap steps
    /// left.
    fn walk(&mut self, s: &mut Seed, dir: usize, mut c: (i32, i32), mut steps: u8) {
        while steps > 0 {
            let Some(n) = self.step(s, c, dir) else { break };
            let ni = self.maps.idx(n.0, n.1);
            if self.is_visited(ni) {
                break;
            }
            self.visit(ni);
            if s.line.dist(n.0, n.1) > f64::from(self.cfg.dist_tolerance_px) {
                break;
            }
            let lab = self.label(n);
            if lab == REGULAR && s.links > 0 && self.crossing(&s.line, ni) {
                // Walked over, not fitted (design §7.5).
                c = n;
                s.ends[dir] = n;
                s.cur = REGULAR;
                steps = self.cfg.skip_regular;
            } else if lab == REGULAR {
                s.fit.add(n.0, n.1);
                s.prev = s.line;
                s.line = s.fit.line();
                c = n;
                (s.ends[dir], s.pole[dir]) = (n, n);
                s.cur = REGULAR;
                steps = self.cfg.skip_regular;
            } else if lab >= 0 && lab != s.cur && !self.linked[lab as usize] {
                let g = lab as usize;
                if self.aligned_with_line(&s.line, g) {
                    let centre = self.link_group(s, g, dir);
                    steps = self.cfg.skip_group;
                    match self.step(s, centre, dir) {
                        Some(p) => c = p,
                        None => break,
                    }
                } else if let Some(r) = self.extend(s, n, dir) {
                    c = r;
                    (s.ends[dir], s.pole[dir]) = (r, r);
                    s.cur = self.label(r);
                    steps = self.cfg.skip_group;
                    s.links += 1;
                }
            } else {
                steps -= 1;
                c = n;
                s.cur = lab;
            }
        }
    }

    fn link_seed(&mut self, g: usize) -> Outcome {
        if self.linked[g] || !self.cfg.reseed.permits(self.released[g], self.retired[g]) {
            return Outcome::Discard;
        }
        self.epoch += 1;
        let gl = self.group_line(g);
        let centre = self.maps.xy(self.groups[g].c);
        let mut s = Seed {
            g,
            line: gl,
            prev: gl,
            reverse: false,
            fit: Fit::default(),
            links: 0,
            undo: Vec::new(),
            cur: g as i32,
            ends: [centre, centre],
            pole: [centre, centre],
            bridged: Vec::new(),
        };
        self.absorb_group(&mut s, g);
        let e_fwd = self.step(&mut s, centre, FWD);
        let e_bwd = self.step(&mut s, centre, BWD);
        if let Some(e) = e_fwd {
            (s.ends[FWD], s.pole[FWD]) = (e, e);
        }
        if let Some(e) = e_bwd {
            (s.ends[BWD], s.pole[BWD]) = (e, e);
        }
        self.pass(&mut s, FWD, e_fwd);
        let start_bwd = e_bwd.map(|_| s.ends[BWD]);
        self.pass(&mut s, BWD, start_bwd);
        self.validate(&s)
    }
}
