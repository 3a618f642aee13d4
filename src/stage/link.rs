//! Paper §3.2: linking hierarchical anchors, in integers (design §7).
//!
//! Seeds are the aligned anchor groups in id order. Each seed walks forward
//! then backward with the skip budgets S_min / S_ra / S_aag, linking regular
//! anchors and aligned groups, refitting its line ([`super::fit`]) after each
//! addition, and ends with its endpoints and the validation
//! ([`super::validate`]). The walk follows the authors' code step by step
//! (design §7, with the deliberate differences listed in
//! [`crate::reference`]); only the number systems differ: angles (the line
//! classes, the reverse-flag rule, group-vs-line alignment) are compared as
//! binary angles, distances in Q30.

use core::num::NonZeroUsize;

use super::P;
use super::extend::extend;
use super::fit::{Fit, Line};
use super::gradient::{gradient_at, magnitude_at};
use super::groups::{Group, Groups};
use super::output::SegQ8;
use super::state::{BitMap, Class, ClassMap};
use super::validate::{Verdict, validate};
use super::work::Work;
use crate::image::MAX_DIMENSION;
use crate::num::SMALL;
use crate::num::trig::{DEG_45, undirected_diff};
use crate::params::Params;
use crate::spec::{WALK, WalkClass, walk_table};

/// An in-image position as one word (sides are below 2^15): `x | y << 16`.
pub(crate) const fn pack((x, y): P) -> u32 {
    (x as u32 & 0xFFFF) | (y as u32) << 16
}

/// The position of a [`pack`]ed word.
pub(crate) const fn unpack(v: u32) -> P {
    ((v & 0xFFFF) as i32, (v >> 16) as i32)
}

/// Label of a pixel for the walk (design §6): nothing, a regular anchor, or a
/// group, identified by its centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Label {
    None,
    Regular,
    /// A group: its centre and its record position.
    Group(P, usize),
}

/// The 22.5° slice `0..8` of a line angle in `[-90°, 90°)`, from -90°: the
/// walk classes and the reverse-flag bands are unions of slices (slice 0
/// is the reverse rule's steep band [-90°, -67.5°), 1 and 2 its diagonal band
/// [-67.5°, -22.5°); `bands_match_the_rules` checks them against comparisons).
#[inline(always)]
fn band(a: i32) -> usize {
    ((a >> 28) + 4) as usize & 7
}

/// The [`WalkClass`] of slice `b` (see [`band`]).
const fn band_class(b: usize) -> WalkClass {
    match b {
        1 | 2 => WalkClass::N45,
        3 | 4 => WalkClass::Hz,
        5 | 6 => WalkClass::P45,
        _ => WalkClass::Vt,
    }
}

/// The walk tables (forward, backward) by reverse flag and slice.
const BAND_WALK: [[[u8; 2]; 8]; 2] = band_walk();

/// [`BAND_WALK`], evaluated at compile time only.
#[allow(clippy::indexing_slicing)] // const evaluation: an out-of-range index is a compile error
const fn band_walk() -> [[[u8; 2]; 8]; 2] {
    let mut t = [[[0u8; 2]; 8]; 2];
    let mut b = 0;
    while b < 8 {
        let class = band_class(b);
        t[0][b] = [
            walk_table(class, true, false),
            walk_table(class, false, false),
        ];
        t[1][b] = [
            walk_table(class, true, true),
            walk_table(class, false, true),
        ];
        b += 1;
    }
    t
}

/// The reverse-flag rule (design §7.2) by slice: bit `now` of entry `prev`
/// is set when a line moving from slice `prev` to slice `now` sets the
/// flag (between [-90°, -67.5°) and [-67.5°, -22.5°), either way).
const REVERSING: [u8; 8] = [0b110, 0b001, 0b001, 0, 0, 0, 0, 0];

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
    /// The current linking's bridges (design §7.5), two [`pack`]ed points
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
    /// [`WALK`] table indices for the current line (forward, backward);
    /// stale when `dirty` (the line changed since they were derived).
    walk: [u8; 2],
    dirty: bool,
}

impl Seed {
    fn set_end(&mut self, dir: usize, p: P) {
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

/// The offset of the first strictly largest thresholded magnitude among
/// the three candidates of walk table `T`, or `None` when none is above
/// zero, from the 4x4 block `rows` of the blurred image around the current
/// pixel (rows y-2..=y+1, one little-endian word each, columns x-2..=x+1;
/// see [`Linker::step`]). `floor` is `max(mag_min, 1)`.
///
/// The threshold is applied to the winner only: a candidate below it is a
/// zero, which cannot beat a winner at or above it, and when every
/// candidate is below it the walk stops either way. So the raw maxima
/// (`|gx| + |gy|` halved: the larger of the two diagonal differences) are
/// compared, and the winner's magnitude against the threshold once.
///
/// Inlined once per walk table by [`best_of_table`], so that the
/// candidates' rows and byte positions are constants; a build for size
/// ([`SMALL`]) inlines it once, with the table read at run time.
#[cfg_attr(not(aaglsd_small), inline(always))]
#[cfg_attr(aaglsd_small, inline(never))]
fn best_of(offsets: [(i32, i32); 3], rows: &[u32; 4], floor: u16) -> Option<(i32, i32)> {
    let half = |(dx, dy): (i32, i32)| {
        // The candidate's row is block row dy + 2, the one above it
        // dy + 1; its column is byte dx + 2, the one left of it dx + 1.
        let r = (dy + 1) as usize & 3;
        let shift = (8 * (dx + 1)) as u32 & 31;
        let up = rows.get(r).copied().unwrap_or(0) >> shift;
        let lo = rows.get((r + 1) & 3).copied().unwrap_or(0) >> shift;
        let (d, u) = ((up & 255) as i32, ((up >> 8) & 255) as i32);
        let (l, a) = ((lo & 255) as i32, ((lo >> 8) & 255) as i32);
        (a - d).abs().max((u - l).abs()) as u16
    };
    first_largest(offsets, half, floor)
}

/// The offset of the first strictly largest of `half` over the three
/// `offsets`, when twice that value reaches `floor`.
#[inline(always)]
fn first_largest(
    offsets: [(i32, i32); 3],
    half: impl Fn((i32, i32)) -> u16,
    floor: u16,
) -> Option<(i32, i32)> {
    let [o0, o1, o2] = offsets;
    let (m0, m1, m2) = (half(o0), half(o1), half(o2));
    // As selects: which candidate wins is data-dependent and a branch
    // would mispredict.
    use core::hint::select_unpredictable as pick;
    let best = pick(m1 > m0, (m1, o1), (m0, o0));
    let (m, off) = pick(m2 > best.0, (m2, o2), best);
    (2 * m >= floor).then_some(off)
}

/// [`best_of`] from the magnitude cache: `win` starts at the current
/// pixel's upper-left neighbour, rows `w` apart, and holds half of each
/// thresholded magnitude. The same offset as [`best_of`]'s (a candidate
/// below the threshold reads 0, which cannot beat a winner at or above
/// it). One copy per walk table `T`, as [`best_of_table`].
#[inline(always)]
fn best_cached<const T: usize>(win: &[u8], w: usize, floor: u16) -> Option<(i32, i32)> {
    let half = |(dx, dy): (i32, i32)| {
        let k = (dy + 1) as usize * w + (dx + 1) as usize;
        u16::from(win.get(k).copied().unwrap_or(0))
    };
    first_largest(WALK.get(T).copied().unwrap_or_default(), half, floor)
}

/// [`best_of`] with walk table `T`: one function per table (a `match`
/// over plain calls with constant tables can be folded back into one body
/// that reads the table).
#[inline(always)]
fn best_of_table<const T: usize>(rows: &[u32; 4], floor: u16) -> Option<(i32, i32)> {
    best_of(WALK.get(T).copied().unwrap_or_default(), rows, floor)
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
        let (vlist, rest) = lists.split_at_mut_checked(at).unwrap_or((&mut [], &mut []));
        let at = (max_visits / 3 + 1).min(rest.len());
        let (undo, bridges) = rest.split_at_mut_checked(at).unwrap_or((&mut [], &mut []));
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

    fn in_bounds(&self, (x, y): P) -> bool {
        // Negative coordinates wrap to huge unsigned values.
        (x as u32 as usize) < self.frame.w.get() && (y as u32 as usize) < self.frame.h
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

    /// The thresholded magnitude of the in-image pixel `p`.
    fn mag(&self, (x, y): P) -> u16 {
        magnitude_at(
            self.frame.blur,
            self.frame.w.get(),
            x as usize,
            y as usize,
            self.frame.p.mag_min,
        )
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
        for &i in self.vlist.get(..self.nvis).unwrap_or(&[]) {
            self.visited.clear_byte(i as usize);
        }
        self.nvis = 0;
    }

    fn absorb_group(&mut self, s: &mut Seed, members: [P; 3]) {
        for q in members {
            s.fit.add(q.0, q.1);
            // A full list stops the linking (`full`); already visited is fine.
            let _ = self.visit_new(q);
        }
    }

    /// Design §7.2: the next pixel, or `None` when no candidate has m > 0.
    ///
    /// The reverse-flag rule and the candidate table depend only on `L` and
    /// `Lp`, so they are re-derived only after the line changed; since `R`
    /// is sticky and every line change is followed by a step before the next
    /// change, this equals evaluating them on every step.
    // Inlined into the walk loop, its hot caller; the other callers share
    // one out-of-line copy, [`Linker::step_once`] (flash).
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    fn step(&self, s: &mut Seed, c: P, dir: usize) -> Option<P> {
        if s.dirty {
            let (prev, now) = (band(s.prev), band(s.line.signed()));
            if (REVERSING.get(prev).copied().unwrap_or(0) >> now) & 1 != 0 {
                s.reverse = true;
            }
            let walk = BAND_WALK
                .get(usize::from(s.reverse))
                .and_then(|t| t.get(now))
                .copied()
                .unwrap_or_default();
            if walk != s.walk {
                s.set_walk(walk);
            }
            s.dirty = false;
        }
        let t = usize::from(if dir == FWD { s.walk[0] } else { s.walk[1] });
        let offsets = WALK.get(t)?;
        // Away from the border, with the magnitude cache (the larger
        // workspace): the three candidates' magnitudes in three loads, one
        // copy per walk table as below.
        if !SMALL && !self.frame.mags.is_empty() && self.deep_interior(c) {
            let w = self.frame.w.get();
            let base = self.idx(c) - w - 1;
            // One bounds test for the 3x3 block, as below.
            let win = match self.frame.mags.get(base..) {
                Some(b) if w <= MAX_DIMENSION && b.len() >= 2 * w + 3 => b,
                _ => &[],
            };
            let floor = self.frame.p.mag_min.max(1);
            let (dx, dy) = match t {
                0 => best_cached::<0>(win, w, floor),
                1 => best_cached::<1>(win, w, floor),
                2 => best_cached::<2>(win, w, floor),
                3 => best_cached::<3>(win, w, floor),
                4 => best_cached::<4>(win, w, floor),
                5 => best_cached::<5>(win, w, floor),
                6 => best_cached::<6>(win, w, floor),
                _ => best_cached::<7>(win, w, floor),
            }?;
            return Some((c.0 + dx, c.1 + dy));
        }
        // Away from the border every candidate has its whole gradient
        // window in the 4x4 block of rows y-2..=y+1, columns x-2..=x+1:
        // four loads of four bytes, then each magnitude from two of them.
        // One copy per walk table, so that the candidates' rows and byte
        // positions are constants (no index arithmetic per candidate).
        if self.deep_interior(c) {
            let w = self.frame.w.get();
            let base = self.idx(c) - 2 * w - 2;
            // One bounds test for the block (its rows start at k·w,
            // k = 0..=3), not one per row: with `w` within MAX_DIMENSION
            // (always: the image was validated) no `k·w + 4` can wrap, so
            // the compiler drops the rows' own tests.
            let block = match self.frame.blur.get(base..) {
                Some(b) if w <= MAX_DIMENSION && b.len() >= 3 * w + 4 => b,
                _ => &[],
            };
            let row = |k: usize| match block.get(k * w..).and_then(|r| r.first_chunk::<4>()) {
                Some(&b) => u32::from_le_bytes(b),
                None => 0,
            };
            let rows = [row(0), row(1), row(2), row(3)];
            let floor = self.frame.p.mag_min.max(1);
            let (dx, dy) = match t {
                _ if SMALL => best_of(*offsets, &rows, floor),
                0 => best_of_table::<0>(&rows, floor),
                1 => best_of_table::<1>(&rows, floor),
                2 => best_of_table::<2>(&rows, floor),
                3 => best_of_table::<3>(&rows, floor),
                4 => best_of_table::<4>(&rows, floor),
                5 => best_of_table::<5>(&rows, floor),
                6 => best_of_table::<6>(&rows, floor),
                _ => best_of_table::<7>(&rows, floor),
            }?;
            return Some((c.0 + dx, c.1 + dy));
        }
        // Near the border: the in-image candidates, in order.
        let mut best = None;
        let mut best_m = 0u16;
        for &(dx, dy) in offsets {
            let q = (c.0 + dx, c.1 + dy);
            if !self.in_bounds(q) {
                continue;
            }
            let m = self.mag(q);
            if m > best_m {
                best_m = m;
                best = Some(q);
            }
        }
        best
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

    /// Design §7.3: one pass, bridging (design §7.5) from each end it
    /// reaches while [`Linker::bridge_target`] finds a group; a bridge
    /// after which the pass links nothing more is undone.
    fn pass(&mut self, s: &mut Seed, dir: usize, start: Option<P>) {
        let Some(mut c) = start else { return };
        let mut steps = self.frame.p.skip_min;
        // The state before the last bridge, and the group it reached.
        let mut tentative: Option<(Seed, bool, usize, P)> = None;
        loop {
            self.walk(s, dir, c, steps);
            if let Some((before, seed_linked, pos, g)) = tentative.take()
                && s.ends.get(dir).copied() == Some(g)
            {
                self.unbridge(s, before, seed_linked, pos);
                return;
            }
            if self.frame.p.bridge == 0 || self.full {
                return;
            }
            let Some((g, pos)) = self.bridge_target(s, dir) else {
                return;
            };
            let from = s.ends.get(dir).copied().unwrap_or(g);
            let (Some(slot), Some(ends)) = (
                self.undo.get_mut(self.nundo),
                self.bridges
                    .get_mut(2 * self.nbridges..2 * self.nbridges + 2),
            ) else {
                // Out of bridge slots: the linking is truncated.
                self.full = true;
                return;
            };
            *slot = pos as u32;
            ends.copy_from_slice(&[pack(from), pack(g)]);
            self.nundo += 1;
            self.nbridges += 1;
            let before = (*s, self.groups.linked(s.pos), pos, g);
            let grp = self.group(g, pos);
            self.absorb_group(s, grp.members);
            s.set_line(s.fit.line());
            if dir == FWD {
                self.groups.set_linked(s.pos, true);
            }
            self.groups.set_linked(pos, true);
            s.set_end(dir, g);
            s.cur = Label::Group(g, pos);
            s.links += 1;
            steps = self.frame.p.skip_group;
            match self.step_once(s, g, dir) {
                Some(q) => {
                    c = q;
                    tentative = Some(before);
                }
                None => {
                    let (before, seed_linked, pos, _) = before;
                    self.unbridge(s, before, seed_linked, pos);
                    return;
                }
            }
        }
    }

    /// Undoes the last bridge, to group record `pos`: the seed's state
    /// `before` it and whether the seed was linked then. The pixels it
    /// visited stay visited (the pass ends).
    fn unbridge(&mut self, s: &mut Seed, before: Seed, seed_linked: bool, pos: usize) {
        *s = before;
        self.groups.set_linked(pos, false);
        self.groups.set_linked(s.pos, seed_linked);
        self.nundo -= 1;
        self.nbridges -= 1;
    }

    /// Design §7.5: the first group that the pass's end bridges to, among
    /// the `bridge` pixels past it, away from the other end, one pixel of
    /// the line's major axis at a time (the minor coordinate on the line,
    /// rounded): not linked yet, its centre within T_dist of the line, its
    /// direction within T_aligned / 2 of the line's, and its gradient
    /// opposite to the one at the end (a line whose contrast changes sign
    /// where it crosses another, as between the squares of a checkerboard).
    fn bridge_target(&mut self, s: &Seed, dir: usize) -> Option<(P, usize)> {
        let [e, o] = if dir == FWD {
            s.ends
        } else {
            [s.ends[1], s.ends[0]]
        };
        let steep = s.line.steep();
        let sign = if steep { e.1 - o.1 } else { e.0 - o.0 }.signum();
        if sign == 0 {
            return None;
        }
        // The minor coordinate along the major axis, its terms computed once.
        let minor = if steep {
            s.line.x_by_row()
        } else {
            s.line.y_by_column()
        };
        let mut end_grad = None;
        for k in 1..=i32::from(self.frame.p.bridge) {
            self.probed += 1;
            let major = if steep { e.1 } else { e.0 } + sign * k;
            let at = i32::try_from(minor.pixel_at(i64::from(major))?).ok()?;
            let q = if steep { (at, major) } else { (major, at) };
            if !self.in_bounds(q) {
                return None;
            }
            if !matches!(
                self.classes.get(q.0 as usize, q.1 as usize),
                Class::Centre | Class::Member
            ) {
                continue;
            }
            if let Label::Group(g, pos) = self.label(q)
                && pos != s.pos
                && !self.groups.linked(pos)
                && !s.line.farther_than(g.0, g.1, self.frame.p.dist_q30)
                && undirected_diff(s.line.angle, self.group(g, pos).angle) <= self.frame.p.align / 2
            {
                let w = self.frame.w.get();
                let grad = |p: P| gradient_at(self.frame.blur, w, p.0 as usize, p.1 as usize);
                let (a, b) = (*end_grad.get_or_insert_with(|| grad(e)), grad(g));
                if i64::from(a.0) * i64::from(b.0) + i64::from(a.1) * i64::from(b.1) < 0 {
                    return Some((g, pos));
                }
            }
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
                        self.absorb_group(s, grp.members);
                        s.set_line(s.fit.line());
                        if dir == FWD {
                            self.groups.set_linked(s.pos, true);
                        }
                        self.groups.set_linked(pos, true);
                        if let Some(slot) = self.undo.get_mut(self.nundo) {
                            *slot = pos as u32;
                            self.nundo += 1;
                        }
                        s.set_end(dir, g);
                        s.cur = lab;
                        s.links += 1;
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
        let centre = self.groups.centre(pos);
        let grp = self.group(centre, pos);
        // The group line: the group direction through the centre.
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
            walk: [0; 2],
            dirty: true,
        };
        self.nundo = 0;
        self.nbridges = 0;
        self.probed = 0;
        self.full = false;
        self.absorb_group(&mut s, grp.members);
        let e_fwd = self.step_once(&mut s, centre, FWD);
        let e_bwd = self.step_once(&mut s, centre, BWD);
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
        let verdict = validate(
            self.frame.p,
            self.frame.blur,
            &self.classes,
            self.frame.w,
            self.frame.h,
            &s.line,
            s.ends,
            s.links,
            self.bridges.get(..2 * self.nbridges).unwrap_or(&[]),
        );
        if verdict == Verdict::Weak {
            // Release the normal-route links, for good when the rule
            // retires them (`Reseed::retires`).
            let p = self.frame.p;
            let few_groups = s.links + 1 < u32::from(p.min_groups);
            let retire = p.reseed.retires(self.groups.released(pos), few_groups);
            for k in 0..self.nundo {
                let u = self.undo.get(k).copied().unwrap_or(0) as usize;
                self.groups.release(u, retire);
            }
        }
        self.clear_visited();
        match verdict {
            Verdict::Strong(valid, sums) => {
                let (seg, tested) = extend(
                    self.frame.p,
                    self.frame.blur,
                    self.frame.w,
                    self.frame.h,
                    s.line.steep(),
                    valid,
                );
                // Scored as validated (design §8.1).
                let seg = SegQ8 {
                    score: sums.score(),
                    ..seg
                };
                self.work.spend(tested);
                Some(seg)
            }
            Verdict::Discard | Verdict::Weak => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::trig::{DEG_22_5, DEG_67_5};

    /// The reverse-flag rule's bands (design §7.2): a line angle in `[-90°, -67.5°)`.
    fn steep_neg(a: i32) -> bool {
        a < -(DEG_67_5 as i32)
    }

    /// The reverse-flag rule's bands (design §7.2): a line angle in `[-67.5°, -22.5°)`.
    fn diag_neg(a: i32) -> bool {
        (-(DEG_67_5 as i32)..-(DEG_22_5 as i32)).contains(&a)
    }

    /// The [`WalkClass`] of a line angle in `[-90°, 90°)`.
    fn walk_class(a: i32) -> WalkClass {
        let (d22, d67) = (DEG_22_5 as i32, DEG_67_5 as i32);
        if diag_neg(a) {
            WalkClass::N45
        } else if (-d22..d22).contains(&a) {
            WalkClass::Hz
        } else if (d22..d67).contains(&a) {
            WalkClass::P45
        } else {
            WalkClass::Vt
        }
    }

    /// A 32-bit xorshift generator from `seed` (nonzero).
    fn xorshift(mut seed: u32) -> impl FnMut() -> u32 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed
        }
    }

    /// The slices give the walk class and the reverse-flag bands of the
    /// comparisons, at every slice boundary, next to it, and in between.
    #[test]
    fn bands_match_the_rules() {
        let mut angles = vec![i32::MIN >> 1, (1 << 30) - 1];
        for k in -4i32..4 {
            let edge = k << 28;
            angles.extend([edge - 1, edge, edge + 1, edge + (1 << 27)]);
        }
        angles.retain(|a| (-(1 << 30)..1 << 30).contains(a));
        for &a in &angles {
            let b = band(a);
            assert_eq!(band_class(b), walk_class(a), "{a}");
            assert_eq!(b == 0, steep_neg(a), "{a}");
            assert_eq!(b == 1 || b == 2, diag_neg(a), "{a}");
            for &p in &angles {
                let rule = (steep_neg(p) && diag_neg(a)) || (diag_neg(p) && steep_neg(a));
                assert_eq!((REVERSING[band(p)] >> b) & 1 != 0, rule, "{p} -> {a}");
            }
            for reverse in [false, true] {
                let class = walk_class(a);
                let want = [
                    walk_table(class, true, reverse),
                    walk_table(class, false, reverse),
                ];
                assert_eq!(BAND_WALK[usize::from(reverse)][b], want);
            }
        }
    }

    /// Each walk table's copy of the step picks what the plain rule picks
    /// (the first strictly largest [`magnitude_at`] of the table's three
    /// candidates, `None` when all are zero) on random 4x4 blocks, with the
    /// threshold at 0, at a typical value and above every magnitude.
    #[test]
    fn best_of_each_table_matches_the_plain_rule() {
        let mut next = xorshift(0x9e37_79b9u32);
        let (w, c) = (4usize, (2i32, 2i32));
        // Fewer under Miri, which interprets every instruction.
        let rounds = if cfg!(miri) { 100 } else { 20_000 };
        for round in 0..rounds {
            // Low-contrast blocks make ties and zero magnitudes common.
            let spread = if round % 2 == 0 { 4 } else { 256 };
            let blur: Vec<u8> = (0..16).map(|_| (next() % spread) as u8).collect();
            let rows: [u32; 4] = core::array::from_fn(|k| {
                u32::from_le_bytes([
                    blur[4 * k],
                    blur[4 * k + 1],
                    blur[4 * k + 2],
                    blur[4 * k + 3],
                ])
            });
            for t_min in [0u16, 1, 2, 5, 6, 7, 1020, 1021] {
                let floor = t_min.max(1);
                let got = WALK.map(|offsets| best_of(offsets, &rows, floor));
                for (t, (&got, table)) in got.iter().zip(&WALK).enumerate() {
                    let mut want = (0u16, None);
                    for &(dx, dy) in table {
                        let (x, y) = ((c.0 + dx) as usize, (c.1 + dy) as usize);
                        let m = magnitude_at(&blur, w, x, y, t_min);
                        if m > want.0 {
                            want = (m, Some((dx, dy)));
                        }
                    }
                    assert_eq!(got, want.1, "table {t}, t_min {t_min}, block {blur:?}");
                }
            }
        }
    }

    /// Fits of 200,000 pseudo-random sets of 3 to 6 points in an 8x8 grid,
    /// among them every kind of exact double-angle tie (`2·cxy = ±(cxx -
    /// cyy)`, each sign pair found over a hundred times), get the same walk
    /// class, steepness and reverse-rule bands as the float reference's f32
    /// chain. A fuzzed scene found the tie that used to differ (2t = -45°).
    #[cfg(feature = "reference")]
    #[test]
    #[cfg_attr(miri, ignore)] // 200k fits through libm
    fn fit_ties_classify_like_the_float_chain() {
        use crate::reference::link as r;
        let mut next = xorshift(0x2545_f491u32);
        let mut ties = [0u32; 4];
        for _ in 0..200_000 {
            let k = 3 + next() % 4;
            let pts: Vec<(i32, i32)> = (0..k)
                .map(|_| ((next() % 8) as i32, (next() % 8) as i32))
                .collect();
            let (mut f, mut rf) = (Fit::default(), r::Fit::default());
            for &(x, y) in &pts {
                f.add(x, y);
                rf.add(x, y);
            }
            let (cxx, cyy, cxy) = f.moments();
            if cxy != 0 && (2 * cxy).abs() == (cxx - cyy).abs() {
                ties[usize::from(cxy > 0) * 2 + usize::from(cxx > cyy)] += 1;
            }
            let (l, rl) = (f.line(), rf.line());
            let (a_fixed, a_ref) = (l.signed(), rl.angle());
            assert_eq!(
                walk_class(a_fixed),
                r::walk_class(a_ref),
                "{pts:?}: {a_fixed} vs {a_ref}"
            );
            assert_eq!(l.steep(), rl.steep(), "{pts:?}");
            assert_eq!(diag_neg(a_fixed), r::diag_neg(a_ref), "{pts:?}");
            assert_eq!(steep_neg(a_fixed), r::steep_neg(a_ref), "{pts:?}");
        }
        assert!(
            ties.iter().all(|&t| t >= 100),
            "ties by sign pair: {ties:?}"
        );
    }
}
