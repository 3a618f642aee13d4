//! The output slice as a bounded queue (design §8.1): while it has room,
//! the segments fill it in the order the linking emits them; when it is
//! full, each new segment replaces the worst one kept if it is better, and
//! the rest are dropped and counted. Better: a higher score, and of equal
//! scores the one first in the order of its coordinates `(x0, y0, x1, y1)`
//! (a total order, so the kept set does not depend on the emission order
//! of equal scores). A caller asking for its 32 strongest lines gets them
//! without sizing the output for all.
//!
//! The kept slots form a heap, worst at the root, once the slice is full;
//! the detector orders them best first at the end ([`by_score`]).

use crate::Segment;

/// The output slots and how many are used.
pub(crate) struct Best<'a> {
    out: &'a mut [Segment],
    len: usize,
    dropped: usize,
}

/// Whether `a` is better than `b` (the module docs). The slots hold
/// integers (Q8 coordinates within ±2^24, scores below 2^24) exact in
/// their `f32`s, never NaN, so the floats compare as the integers do: the
/// score, then the coordinates, the first lower in turn the better (the
/// lexicographic order of the score and the negated coordinates).
#[cfg_attr(aaglsd_small, inline(never))]
fn better(a: &Segment, b: &Segment) -> bool {
    if a.score != b.score {
        return a.score > b.score;
    }
    (b.x0, b.y0, b.x1, b.y1) > (a.x0, a.y0, a.x1, a.y1)
}

impl<'a> Best<'a> {
    pub fn new(out: &'a mut [Segment]) -> Self {
        Self {
            out,
            len: 0,
            dropped: 0,
        }
    }

    /// Keeps `s` if there is room or it scores above the lowest kept.
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn push(&mut self, s: Segment) {
        if let Some(slot) = self.out.get_mut(self.len) {
            *slot = s;
            self.len += 1;
            return;
        }
        if self.dropped == 0 {
            // The first segment that does not fit: the slots become a heap.
            heapify(self.out);
        }
        self.dropped += 1;
        if let Some(root) = self.out.first_mut()
            && better(&s, root)
        {
            *root = s;
            sift(self.out, 0, self.len);
        }
    }

    /// The slots used and the segments dropped.
    pub fn finish(self) -> (usize, usize) {
        (self.len, self.dropped)
    }
}

/// Orders `segs` best first (the module docs): heapsort in place, the
/// worst at the heap's root and so at the end.
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn by_score(segs: &mut [Segment]) {
    heapify(segs);
    for end in (1..segs.len()).rev() {
        swap(segs, 0, end);
        sift(segs, 0, end);
    }
}

/// Makes `segs` a heap, the worst at the root.
fn heapify(segs: &mut [Segment]) {
    let n = segs.len();
    for i in (0..n / 2).rev() {
        sift(segs, i, n);
    }
}

/// Swaps slots `a <= b` (no panic path: out of range, nothing happens;
/// `a == b`, nothing moves). Also the merging's compaction. Not
/// `slice::swap`: at opt-level `z` that calls `memmove`, a routine of
/// 1.5 KB of a microcontroller's flash.
pub(crate) fn swap(segs: &mut [Segment], a: usize, b: usize) {
    if let Some((first, rest)) = segs.get_mut(a..=b).and_then(|w| w.split_first_mut())
        && let Some(last) = rest.last_mut()
    {
        core::mem::swap(first, last);
    }
}

/// Moves slot `i` of the heap `segs[..end]` down until no child is worse
/// than it (the worst at the root). One routine, not generic over the
/// order: the queue and the sort share its code.
#[cfg_attr(aaglsd_small, inline(never))]
fn sift(segs: &mut [Segment], mut i: usize, end: usize) {
    loop {
        // The worse of the two children, if worse than slot `i`.
        let mut top = i;
        let mut c = 2 * i + 1;
        while c <= 2 * i + 2 {
            if c < end
                && let (Some(sc), Some(st)) = (segs.get(c), segs.get(top))
                && better(st, sc)
            {
                top = c;
            }
            c += 1;
        }
        if top == i {
            return;
        }
        swap(segs, i, top);
        i = top;
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    /// The score of a slot (an integer below 2^24, exact in the `f32`).
    fn score(s: &Segment) -> u32 {
        s.score as u32
    }

    fn seg(score: u32, x: f32) -> Segment {
        Segment {
            x0: x,
            score: score as f32,
            ..Segment::ZERO
        }
    }

    /// Whatever the order of arrival, the slots keep the best (highest
    /// scores, ties by coordinates), and `by_score` orders them.
    #[test]
    fn keeps_the_best_k() {
        let mut next = crate::xorshift64(0xB357);
        for case in 0..200 {
            let n = 1 + (next() % 60) as usize;
            let k = 1 + (next() % 20) as usize;
            let all: std::vec::Vec<Segment> = (0..n)
                .map(|i| {
                    seg(
                        (next() % if case % 2 == 0 { 8 } else { 1000 }) as u32,
                        i as f32,
                    )
                })
                .collect();
            let mut slots = std::vec![Segment::ZERO; k];
            let mut best = Best::new(&mut slots);
            for s in &all {
                best.push(*s);
            }
            let (len, dropped) = best.finish();
            assert_eq!((len, dropped), (n.min(k), n.saturating_sub(k)));
            // The expected: sorted best first, the first k.
            let mut want = all.clone();
            want.sort_by(|a, b| score(b).cmp(&score(a)).then(a.x0.total_cmp(&b.x0)));
            want.truncate(k);
            let mut got = slots[..len].to_vec();
            by_score(&mut got);
            assert_eq!(got, want, "case {case}");
            assert!(got.windows(2).all(|w| score(&w[0]) >= score(&w[1])));
        }
    }

    /// [`better`]'s float comparisons order as the tuple of the integer
    /// score and the negated integer coordinates, on slot values (scores below 2^24, coordinates within
    /// ±2^24), with many ties.
    #[test]
    fn better_is_the_tuple_order() {
        let tuple = |s: &Segment| {
            let c = [s.x0, s.y0, s.x1, s.y1].map(|v| -(v as i32));
            (score(s), c)
        };
        let mut next = crate::xorshift64(0x0BE7_7E25);
        let mut v = |few: bool| {
            let r = next();
            let m = if few {
                (r >> 8) % 3
            } else {
                (r >> 8) & ((1 << 24) - 1)
            };
            if r & 1 == 0 {
                m as i64
            } else {
                -(m as i64) - i64::from(few)
            }
        };
        for k in 0..if cfg!(miri) { 2_000 } else { 200_000 } {
            let few = k % 2 == 0;
            let mut s = || Segment {
                x0: v(few) as f32,
                y0: v(few) as f32,
                x1: v(few) as f32,
                y1: v(few) as f32,
                score: v(few).unsigned_abs().min((1 << 24) - 1) as f32,
            };
            let (a, b) = (s(), s());
            assert_eq!(better(&a, &b), tuple(&a) > tuple(&b), "{a:?} {b:?}");
        }
    }
}
