//! Design §8.2: the longest passing part of a linking that fails ρ2,
//! validated as a linking of its own.

use super::{Linker, Seed};
use crate::invariant::Invariant;
use crate::stage::P;
use crate::stage::groups::Groups;
use crate::stage::validate::{Verdict, validate};

impl Linker<'_> {
    /// Design §8.2: the part `(a, b)` of a linking that fails ρ2 (first and
    /// last pixel in the trace's order), validated on its own with the
    /// seed and normal-route groups whose centres it spans. A strong part
    /// releases the normal-route groups outside it, which may link again.
    pub(super) fn part(&mut self, s: &Seed, pos: usize, (a, b): (P, P)) -> Option<Verdict> {
        let p = self.frame.p;
        let steep = s.line.steep();
        let major = |q: P| if steep { q.1 } else { q.0 };
        let (lo, hi) = (major(a).min(major(b)), major(a).max(major(b)));
        // Whether the part spans the centre of the group of record `u`.
        let within = |groups: &Groups<'_>, u: usize| (lo..=hi).contains(&major(groups.centre(u)));
        let undo = self.undo.get(..self.nundo).or_broken(&[]);
        let spanned = undo.iter().filter(|&&u| within(&self.groups, u as usize));
        let count = usize::from(within(&self.groups, pos)) + spanned.count();
        if count < usize::from(p.min_groups) {
            return None;
        }
        self.work.spend((hi - lo) as usize + 1);
        let verdict = validate(
            p,
            self.frame.blur,
            &self.classes,
            self.frame.w,
            self.frame.h,
            &s.line,
            [a, b],
            count as u32 - 1,
            self.bridges.get(..2 * self.nbridges).or_broken(&[]),
            None,
        );
        if !matches!(verdict, Verdict::Strong(..)) {
            return None;
        }
        for &u in self.undo.get(..self.nundo).or_broken(&[]) {
            if !within(&self.groups, u as usize) {
                self.groups.release(u as usize, false);
            }
        }
        Some(verdict)
    }
}
