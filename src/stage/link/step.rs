//! Design §7.2, the plain form of the walk's step: which walk table a line
//! uses (its 22.5° class and the sticky reverse flag), and the next pixel
//! as the rule states it, from each candidate's thresholded magnitude.
//! The walk calls [`best_in_image`] near the border; away from it a tuned
//! form ([`super::tuned`]) computes the same pixel with fewer loads.

use super::{Frame, Seed};
use crate::invariant::Invariant;
use crate::spec::{WalkClass, walk_table};
use crate::stage::P;

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

impl Seed {
    /// Re-derives the reverse flag and the walk tables after the line
    /// changed. Both depend only on `L` and `Lp`; since `R` is sticky and
    /// every line change is followed by a step before the next change,
    /// this equals evaluating them on every step.
    #[inline(always)]
    pub(super) fn update_walk(&mut self) {
        if !self.dirty {
            return;
        }
        let (prev, now) = (band(self.prev), band(self.line.signed()));
        if (REVERSING.get(prev).copied().or_broken(0) >> now) & 1 != 0 {
            self.reverse = true;
        }
        let walk = BAND_WALK
            .get(usize::from(self.reverse))
            .and_then(|t| t.get(now))
            .copied()
            .or_broken([0; 2]);
        if walk != self.walk {
            self.set_walk(walk);
        }
        self.dirty = false;
    }
}

/// The first candidate `c + offset` in the image with the strictly largest
/// thresholded magnitude, `None` when every one is zero or outside.
pub(super) fn best_in_image(frame: &Frame, offsets: &[P; 3], c: P) -> Option<P> {
    let mut best = None;
    let mut best_m = 0u16;
    for &(dx, dy) in offsets {
        let q = (c.0 + dx, c.1 + dy);
        if !frame.in_bounds(q) {
            continue;
        }
        let m = frame.mag(q);
        if m > best_m {
            best_m = m;
            best = Some(q);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::trig::{DEG_22_5, DEG_67_5};
    use crate::stage::fit::Fit;

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
        let mut next = crate::xorshift64(0x2545_f491);
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
