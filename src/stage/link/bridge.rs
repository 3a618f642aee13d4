//! Design §7.3 and design §7.5: a linking pass, and the bridges by which
//! it continues past the end of its walk (a junction where the line's
//! contrast changes sign, as between the squares of a checkerboard).

use super::{FWD, Label, Linker, Seed};
use crate::invariant::Invariant;
use crate::num::trig::undirected_diff;
use crate::stage::P;
use crate::stage::fit::Line;
use crate::stage::gradient::gradient_at;
use crate::stage::packed::point::pack;
use crate::stage::state::Class;

impl Linker<'_> {
    /// Design §7.3: one pass, bridging (design §7.5) from each end it
    /// reaches while [`Linker::bridge_target`] finds a group; a bridge
    /// after which the pass links nothing more is undone.
    pub(super) fn pass(&mut self, s: &mut Seed, dir: usize, start: Option<P>) {
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
            let from = s.ends.get(dir).copied().or_broken(g);
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
            self.link_group(s, (g, pos), grp.members, dir);
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

    /// Design §7.5, with bridging: whether the gradient at `n` (in the
    /// image) lies within T_aligned of `line`'s direction (strictly), as a
    /// crossing edge's does where it meets the line. The walk then steps
    /// over `n` without fitting it.
    pub(super) fn crossing(&self, line: &Line, n: P) -> bool {
        let p = self.frame.p;
        p.bridge != 0 && {
            let g = gradient_at(
                self.frame.blur,
                self.frame.w.get(),
                n.0 as usize,
                n.1 as usize,
            );
            line.along(g, p.align_cos, p.align_sin)
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
                let pole = s.pole.get(dir).copied().or_broken(e);
                let (a, b) = (*end_grad.get_or_insert_with(|| grad(pole)), grad(g));
                if i64::from(a.0) * i64::from(b.0) + i64::from(a.1) * i64::from(b.1) < 0 {
                    return Some((g, pos));
                }
            }
        }
        None
    }
}
