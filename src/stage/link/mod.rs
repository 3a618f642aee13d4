//! Paper §3.2: linking hierarchical anchors, in integers (design §7).
//!
//! Seeds are the aligned anchor groups in id order. Each seed walks forward
//! then backward with the skip budgets S_min / S_ra / S_aag, linking regular
//! anchors and aligned groups, refitting its line ([`super::fit`]) after each
//! addition, and ends with its endpoints and the validation
//! ([`super::validate`]). The walk follows the authors' code step by step
//! (design §7, with the deliberate differences listed in
//! `crate::reference`); only the number systems differ: angles (the line
//! classes, the reverse-flag rule, group-vs-line alignment) are compared as
//! binary angles, distances in Q30.

use core::num::NonZeroUsize;

mod bridge;
mod part;
mod step;
mod tuned;

use super::P;
use super::extend::extend;
use super::fit::{Fit, Line};
use super::gradient::magnitude_at;
use super::groups::{Group, Groups};
use super::output::SegQ8;
use super::state::{BitMap, Class, ClassMap};
use super::trim::Longest;
use super::validate::{Verdict, validate};
use super::work::Work;
use crate::invariant::Invariant;
use crate::num::trig::{DEG_45, undirected_diff};
use crate::params::Params;
use crate::spec::WALK;
use crate::target::SMALL;

/// Label of a pixel for the walk (design §6): nothing, a regular anchor, or a
/// group, identified by its centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Label {
    None,
    Regular,
    /// A group: its centre and its record position.
    Group(P, usize),
}

const FWD: usize = 0;
const BWD: usize = 1;

/// Counters of the linking stage.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LinkStats {
    pub truncated: usize,
}

/// The frame the linker walks: parameters, blurred image, size.
#[derive(Clone, Copy)]
pub(crate) struct Frame<'a> {
    pub p: &'a Params,
    pub blur: &'a [u8],
    /// Half the thresholded magnitude of each pixel (`w·h` bytes), or empty.
    pub mags: &'a [u8],
    pub w: NonZeroUsize,
    pub h: usize,
}

impl Frame<'_> {
    /// Whether `(x, y)` is in the image.
    pub(super) fn in_bounds(&self, (x, y): P) -> bool {
        // Negative coordinates wrap to huge unsigned values.
        (x as u32 as usize) < self.w.get() && (y as u32 as usize) < self.h
    }

    /// The thresholded magnitude of the in-image pixel `(x, y)`.
    pub(super) fn mag(&self, (x, y): P) -> u16 {
        magnitude_at(
            self.blur,
            self.w.get(),
            x as usize,
            y as usize,
            self.p.mag_min,
        )
    }
}

/// The linker's borrowed state.
pub(crate) struct Linker<'a> {
    frame: Frame<'a>,
    groups: Groups<'a>,
    classes: ClassMap<'a>,
    visited: BitMap<'a>,
    /// The current linking's visited pixels (byte indices of the visited
    /// map), to clear.
    vlist: &'a mut [u32],
    /// The record positions of the groups linked on the normal route of
    /// the current linking (released if it is weak).
    undo: &'a mut [u32],
    /// The current linking's bridges (design §7.5), two [`point`](super::packed::point)s
    /// each: a pass's end and the centre of the group it bridged to.
    bridges: &'a mut [u32],
    nvis: usize,
    nundo: usize,
    nbridges: usize,
    /// Pixels probed by the current linking's bridges (work units).
    probed: usize,
    full: bool,
    pub stats: LinkStats,
    pub work: Work,
}

/// Per-seed state (design §7.1).
#[derive(Clone, Copy)]
struct Seed {
    /// The seed group's record.
    pos: usize,
    line: Line,
    prev: i32,
    reverse: bool,
    fit: Fit,
    links: u32,
    cur: Label,
    ends: [P; 2],
    /// Each pass's last end on its own line (not a crossing pixel): the
    /// bridge's contrast reference (design §7.5).
    pole: [P; 2],
    /// [`WALK`] table indices for the current line (forward, backward);
    /// stale when `dirty` (the line changed since they were derived).
    walk: [u8; 2],
    dirty: bool,
}

impl Seed {
    fn set_end(&mut self, dir: usize, p: P) {
        self.step_over(dir, p);
        if let Some(e) = self.pole.get_mut(dir) {
            *e = p;
        }
    }

    /// The end at a crossing pixel (design §7.5), which is no contrast
    /// reference for a bridge.
    fn step_over(&mut self, dir: usize, p: P) {
        if let Some(e) = self.ends.get_mut(dir) {
            *e = p;
        }
    }

    /// `Lp := L; L := line` (design §7.3).
    fn set_line(&mut self, line: Line) {
        self.prev = self.line.signed();
        self.line.assign(&line);
        self.dirty = true;
    }

    /// Stores a changed walk table. Out of line and cold on purpose: the
    /// caller then tests `walk != self.walk` with a branch, which the CPU
    /// predicts (the class rarely changes), so the next step's loads do not
    /// wait for the refit's `atan2` as they do behind a plain store or a
    /// select. (A core without speculation, such as a Cortex-M4, gains
    /// nothing and pays the call.)
    #[cold]
    #[inline(never)]
    fn set_walk(&mut self, walk: [u8; 2]) {
        self.walk = walk;
    }

    /// `L := line` without touching `Lp` (design §7.4).
    fn refit(&mut self) {
        self.line.assign(&self.fit.line());
        self.dirty = true;
    }
}

impl<'a> Linker<'a> {
    pub fn new(
        frame: Frame<'a>,
        classes: ClassMap<'a>,
        visited: BitMap<'a>,
        lists: &'a mut [u32],
        max_visits: usize,
        groups: Groups<'a>,
        work: Work,
    ) -> Self {
        // The visited list first (`max_visits` words), then the undo list
        // (`V/3 + 1` words) and the bridge list (`Layout::compute`).
        let at = max_visits.min(lists.len());
        let (vlist, rest) = lists.split_at_mut_checked(at).or_broken((&mut [], &mut []));
        let at = (max_visits / 3 + 1).min(rest.len());
        let (undo, bridges) = rest.split_at_mut_checked(at).or_broken((&mut [], &mut []));
        Self {
            frame,
            classes,
            visited,
            vlist,
            undo,
            bridges,
            groups,
            nvis: 0,
            nundo: 0,
            nbridges: 0,
            probed: 0,
            full: false,
            stats: LinkStats::default(),
            work,
        }
    }

    fn in_bounds(&self, p: P) -> bool {
        self.frame.in_bounds(p)
    }

    /// Whether every neighbour of `(x, y)` is in the image with its whole
    /// 2x2 gradient window (columns and rows from 1).
    fn deep_interior(&self, (x, y): P) -> bool {
        (x as u32).wrapping_sub(2) < (self.frame.w.get() as u32).wrapping_sub(3)
            && (y as u32).wrapping_sub(2) < (self.frame.h as u32).wrapping_sub(3)
    }

    /// Raster index of an in-image position.
    fn idx(&self, (x, y): P) -> usize {
        y as usize * self.frame.w.get() + x as usize
    }

    /// The label of the in-image pixel `p`. Inlined into the walk, its
    /// hot caller, except in a build for size.
    #[cfg_attr(not(aaglsd_small), inline(always))]
    fn label(&self, p: P) -> Label {
        match self.classes.get(p.0 as usize, p.1 as usize) {
            Class::None => Label::None,
            Class::Regular => Label::Regular,
            Class::Centre | Class::Member if self.groups.has_index() => {
                match self.groups.indexed(p) {
                    Some((c, pos)) => Label::Group(c, pos),
                    None => Label::None,
                }
            }
            Class::Centre => match self.groups.find(p) {
                Some(pos) => Label::Group(p, pos),
                None => Label::None,
            },
            Class::Member => match self.groups.of_member(&self.classes, self.frame.h, p) {
                Some((c, pos)) => Label::Group(c, pos),
                None => Label::None,
            },
        }
    }

    fn group(&self, c: P, pos: usize) -> Group {
        self.groups.get(pos, c, self.frame.blur)
    }

    /// Whether a group not linked yet may seed (see [`crate::Reseed`]).
    fn may_seed(&self, pos: usize) -> bool {
        self.frame
            .p
            .reseed
            .permits(self.groups.released(pos), self.groups.retired(pos))
    }

    fn is_visited(&self, (x, y): P) -> bool {
        self.visited.get(x as usize, y as usize)
    }

    /// Adds the in-image pixel `p` to the visited set; false when it was
    /// already visited, or when the visited list is full (and the linking
    /// stops).
    fn visit_new(&mut self, p: P) -> bool {
        let (x, y) = (p.0 as usize, p.1 as usize);
        if self.visited.get(x, y) {
            return false;
        }
        let Some(slot) = self.vlist.get_mut(self.nvis) else {
            self.full = true;
            return false;
        };
        // The map's byte index (the map has fewer than 2^27 bytes): every
        // set bit of the map is on this list, so clearing zeroes the bytes.
        *slot = self.visited.byte_index(x, y) as u32;
        self.nvis += 1;
        self.visited.test_and_set(x, y);
        true
    }

    fn clear_visited(&mut self) {
        // Every set bit of the map belongs to this linking (the map starts
        // cleared, and only `visit_new` sets bits, each one listed).
        for &i in self.vlist.get(..self.nvis).or_broken(&[]) {
            self.visited.clear_byte(i as usize);
        }
        self.nvis = 0;
    }

    /// Links the group of centre `g` and record `pos` at the end `dir` of
    /// the seed's walk (design §7.3): its `members` join the fit, the line
    /// is refitted (`Lp := L`), the group and (forward) the seed are
    /// linked, and the end moves to the centre.
    fn link_group(&mut self, s: &mut Seed, (g, pos): (P, usize), members: [P; 3], dir: usize) {
        self.absorb_group(s, members);
        s.set_line(s.fit.line());
        if dir == FWD {
            self.groups.set_linked(s.pos, true);
        }
        self.groups.set_linked(pos, true);
        s.set_end(dir, g);
        s.cur = Label::Group(g, pos);
        s.links += 1;
    }

    fn absorb_group(&mut self, s: &mut Seed, members: [P; 3]) {
        for q in members {
            s.fit.add(q.0, q.1);
            // A full list stops the linking (`full`); already visited is fine.
            let _ = self.visit_new(q);
        }
    }

    /// Design §7.2: the next pixel, or `None` when no candidate has m > 0:
    /// the first strictly largest thresholded magnitude among the three
    /// candidates of the walk table of the seed's line and pass direction.
    ///
    /// Away from the border a tuned form reads the candidates
    /// ([`tuned`]); near it the plain form ([`step::best_in_image`]). The
    /// two pick the same pixel (`tuned`'s tests).
    // Inlined into the walk loop, its hot caller; the other callers share
    // one out-of-line copy, [`Linker::step_once`] (flash).
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    fn step(&self, s: &mut Seed, c: P, dir: usize) -> Option<P> {
        s.update_walk();
        let t = usize::from(if dir == FWD { s.walk[0] } else { s.walk[1] });
        let offsets = WALK.get(t)?;
        let best = if !self.deep_interior(c) {
            return step::best_in_image(&self.frame, offsets, c);
        } else if !SMALL && !self.frame.mags.is_empty() {
            tuned::from_cache(&self.frame, t, self.idx(c))
        } else {
            tuned::from_block(&self.frame, t, offsets, self.idx(c))
        };
        best.map(|(dx, dy)| (c.0 + dx, c.1 + dy))
    }

    /// [`Linker::step`], out of line.
    #[inline(never)]
    fn step_once(&self, s: &mut Seed, c: P, dir: usize) -> Option<P> {
        self.step(s, c, dir)
    }

    fn aligned_with(&self, line: &Line, g: &Group) -> bool {
        undirected_diff(line.angle, g.angle) <= self.frame.p.align
    }

    /// Design §7.4: probe one pixel along the line past a misaligned group.
    fn extend(&mut self, s: &mut Seed, n: P, dir: usize) -> Option<P> {
        let horizontal = s.line.signed() <= DEG_45 as i32; // signed slope <= 1
        let sign = if dir == FWD { 1 } else { -1 };
        let q = if horizontal {
            let x = n.0 + sign;
            (x, i32::try_from(s.line.y_pixel_at(i64::from(x))?).ok()?)
        } else {
            let y = n.1 + sign;
            (i32::try_from(s.line.x_pixel_at(i64::from(y))?).ok()?, y)
        };
        if !self.in_bounds(q) || self.is_visited(q) {
            return None;
        }
        if let Label::Group(g, pos) = self.label(q)
            && !self.groups.linked(pos)
            && let grp = self.group(g, pos)
            && self.aligned_with(&s.line, &grp)
        {
            self.groups.set_linked(pos, true);
            self.absorb_group(s, grp.members);
            s.refit(); // Lp is not updated here (design §7.4)
            return self.step_once(s, g, dir);
        }
        None
    }

    /// Design §7.3: the walk of one pass from `c`, with `steps` gap steps.
    fn walk(&mut self, s: &mut Seed, dir: usize, mut c: P, mut steps: u8) {
        // A full visited list (`self.full`, also when a group's members
        // filled it) ends the pass at the next visit, which fails.
        while steps > 0 {
            let Some(n) = self.step(s, c, dir) else { break };
            if !self.visit_new(n) {
                break;
            }
            if s.line.farther_than(n.0, n.1, self.frame.p.dist_q30) {
                break;
            }
            let lab = self.label(n);
            match lab {
                Label::Regular if s.links > 0 && self.crossing(&s.line, n) => {
                    // Walked over, not fitted (design §7.5).
                    c = n;
                    s.step_over(dir, n);
                    s.cur = Label::Regular;
                    steps = self.frame.p.skip_regular;
                }
                Label::Regular => {
                    s.fit.add(n.0, n.1);
                    s.set_line(s.fit.line_inline());
                    c = n;
                    s.set_end(dir, n);
                    s.cur = Label::Regular;
                    steps = self.frame.p.skip_regular;
                }
                Label::Group(g, pos) if lab != s.cur && !self.groups.linked(pos) => {
                    let grp = self.group(g, pos);
                    if self.aligned_with(&s.line, &grp) {
                        self.link_group(s, (g, pos), grp.members, dir);
                        if let Some(slot) = self.undo.get_mut(self.nundo) {
                            *slot = pos as u32;
                            self.nundo += 1;
                        }
                        steps = self.frame.p.skip_group;
                        match self.step_once(s, g, dir) {
                            Some(q) => c = q,
                            None => break,
                        }
                    } else if let Some(r) = self.extend(s, n, dir) {
                        c = r;
                        s.set_end(dir, r);
                        s.cur = self.label(r);
                        steps = self.frame.p.skip_group;
                        s.links += 1;
                    }
                }
                _ => {
                    steps -= 1;
                    c = n;
                    s.cur = lab;
                }
            }
        }
    }

    /// Links every seed, in group-id order (design §7), and passes each
    /// strong segment to `emit`. The seeds are produced in chunks
    /// ([`Groups::seed_chunk`]) into `chunk`; `starts` and `cursor` are
    /// scratch of [`super::order::BUCKETS`] words each.
    pub fn link_all(
        &mut self,
        chunk: &mut [u32],
        starts: &mut [u32],
        cursor: &mut [u32],
        mut emit: impl FnMut(SegQ8),
    ) {
        self.groups.bucket_starts(starts, cursor);
        let g = self.groups.len();
        let mut lo = 0;
        while lo < g {
            let n = self.groups.seed_chunk(lo, chunk, starts, cursor);
            if n == 0 {
                break;
            }
            for &pos in chunk.iter().take(n) {
                let pos = pos as usize;
                if self.groups.linked(pos) || !self.may_seed(pos) {
                    continue;
                }
                if !self.work.left() {
                    self.work.cut += 1;
                    continue;
                }
                if let Some(seg) = self.link_seed(pos) {
                    emit(seg);
                }
            }
            lo += n;
        }
    }

    /// Links the seed group of record `pos` (not linked yet); `Some` for a
    /// strong segment.
    fn link_seed(&mut self, pos: usize) -> Option<SegQ8> {
        let mut s = self.start(pos);
        let c = s.ends[0];
        let e_fwd = self.step_once(&mut s, c, FWD);
        let e_bwd = self.step_once(&mut s, c, BWD);
        if let Some(e) = e_fwd {
            s.set_end(FWD, e);
        }
        if let Some(e) = e_bwd {
            s.set_end(BWD, e);
        }
        self.pass(&mut s, FWD, e_fwd);
        self.pass(&mut s, BWD, e_bwd);
        if self.full {
            self.stats.truncated += 1;
        }
        // The visits, and about the pixels the validation traces.
        let [(x0, y0), (x1, y1)] = s.ends;
        let span = (x1 - x0).unsigned_abs().max((y1 - y0).unsigned_abs()) as usize + 1;
        self.work.spend(self.nvis + span + self.probed);
        let p = self.frame.p;
        let trim = p.trim && !p.few_groups(s.links);
        // Validation does not read the visited map: its list is free for
        // the trace's parts (design §8.2).
        self.clear_visited();
        let mut track = Longest::new(self.vlist, p.rho2_q32, s.line.steep());
        let mut verdict = validate(
            p,
            self.frame.blur,
            &self.classes,
            self.frame.w,
            self.frame.h,
            &s.line,
            s.ends,
            s.links,
            self.bridges.get(..2 * self.nbridges).or_broken(&[]),
            trim.then_some(&mut track),
        );
        if verdict == Verdict::Weak
            && let Some(part) = track.best()
            && let Some(strong) = self.part(&s, pos, part)
        {
            verdict = strong;
        }
        if verdict == Verdict::Weak {
            self.release_links(&s, pos);
        }
        match verdict {
            // Below the floor: linked as strong, not reported (`Config::min_score`).
            Verdict::Strong(valid, sums) => {
                let score = sums.score();
                (score >= self.frame.p.min_score).then(|| self.finish(&s, valid, score))
            }
            Verdict::Discard | Verdict::Weak => None,
        }
    }

    /// The seed of group record `pos`: its group's members fitted, its
    /// line the group direction through the centre, the linking's lists
    /// empty.
    fn start(&mut self, pos: usize) -> Seed {
        let centre = self.groups.centre(pos);
        let grp = self.group(centre, pos);
        let gl = Line::new(grp.angle, i64::from(centre.0), i64::from(centre.1), 1);
        let mut s = Seed {
            pos,
            line: gl,
            prev: gl.signed(),
            reverse: false,
            fit: Fit::default(),
            links: 0,
            cur: Label::Group(centre, pos),
            ends: [centre, centre],
            pole: [centre, centre],
            walk: [0; 2],
            dirty: true,
        };
        self.nundo = 0;
        self.nbridges = 0;
        self.probed = 0;
        self.full = false;
        self.absorb_group(&mut s, grp.members);
        s
    }

    /// Releases a weak linking's normal-route links, for good when the
    /// rule retires them (`Reseed::retires`).
    fn release_links(&mut self, s: &Seed, pos: usize) {
        let p = self.frame.p;
        let retire = p
            .reseed
            .retires(self.groups.released(pos), p.few_groups(s.links));
        for &u in self.undo.get(..self.nundo).or_broken(&[]) {
            self.groups.release(u as usize, retire);
        }
    }

    /// The strong segment of seed `s`: its `valid` part extended, scored
    /// as validated (design §8.1).
    fn finish(&mut self, s: &Seed, valid: SegQ8, score: u32) -> SegQ8 {
        let (seg, tested) = extend(
            self.frame.p,
            self.frame.blur,
            self.frame.w,
            self.frame.h,
            s.line.steep(),
            valid,
        );
        self.work.spend(tested);
        SegQ8 { score, ..seg }
    }
}
