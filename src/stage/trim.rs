//! Design §8.2: the longest part of a linking that passes the aligned
//! density ρ2, found in validation's own trace (the core and the float
//! reference feed it the same pixels, each with its own decisions).
//!
//! A linking that fails ρ2 often runs past the end of its line: a pane's
//! edge across the muntin of a window, a building's edge across a pole. Its
//! longest part between two aligned pixels whose aligned share is at least
//! ρ2 is then validated on its own (`Config::trim`).
//!
//! With `a` and `j` the aligned and judged pixels before a pixel (a
//! junction's pixels are not judged), the key `a·2^32 − ρ2·j` (ρ2 in Q32)
//! turns "a part passes ρ2" into "its end's key after it is at least its
//! start's key before it". The starts worth keeping are the aligned pixels
//! whose key is below every earlier start's (a stack of strictly falling
//! keys), and each aligned pixel, as an end, pairs with the first of them
//! whose key is at most its own: one binary search per aligned pixel, no
//! second trace, and exact integers on both sides.

use super::P;
use super::packed::point::{pack, unpack};

/// The words of one start on the stack: its packed point and its key.
const ENTRY: usize = 3;

/// The longest part found so far of a trace, on caller-provided scratch.
pub(crate) struct Longest<'a> {
    /// Starts, [`ENTRY`] words each, their keys strictly falling.
    stack: &'a mut [u32],
    len: usize,
    rho: u64,
    steep: bool,
    best: Option<(P, P)>,
    /// The major-axis span of `best` (0 without one), kept because every
    /// aligned pixel of a tracked trace compares with it.
    width: i32,
    /// The stack overflowed: no part is reported.
    full: bool,
}

impl<'a> Longest<'a> {
    /// A tracker for a segment whose major axis is y when `steep`, with ρ2
    /// in Q32, keeping at most `stack.len() / 3` starts.
    pub(crate) fn new(stack: &'a mut [u32], rho_q32: u64, steep: bool) -> Self {
        Self {
            stack,
            len: 0,
            rho: rho_q32,
            steep,
            best: None,
            width: 0,
            full: false,
        }
    }

    /// The key of a prefix of `aligned` aligned and `judged` judged pixels
    /// (both below 2^17, ρ2 at most 2^32: within ±2^49).
    fn key(&self, aligned: u64, judged: u64) -> i64 {
        ((aligned << 32) as i64).wrapping_sub((self.rho * judged) as i64)
    }

    fn entry(&self, i: usize) -> Option<(P, i64)> {
        let &[point, lo, hi] = self.stack.get(ENTRY * i..ENTRY * i + ENTRY)? else {
            return None;
        };
        Some((unpack(point), (u64::from(hi) << 32 | u64::from(lo)) as i64))
    }

    fn major(&self, p: P) -> i32 {
        if self.steep { p.1 } else { p.0 }
    }

    /// The aligned pixel `at`, after `aligned` aligned and `judged` judged
    /// pixels of the trace (the run of pixels before it settled).
    pub(crate) fn aligned(&mut self, at: P, aligned: u64, judged: u64) {
        let before = self.key(aligned, judged);
        let below = match self.len.checked_sub(1).and_then(|t| self.entry(t)) {
            Some((_, top)) => before < top,
            None => true,
        };
        if below {
            match self
                .stack
                .get_mut(ENTRY * self.len..ENTRY * self.len + ENTRY)
            {
                Some(w) => {
                    let k = before as u64;
                    w.copy_from_slice(&[pack(at), k as u32, (k >> 32) as u32]);
                    self.len += 1;
                }
                None => self.full = true,
            }
        }
        // The first start whose key is at most the key after `at` (the
        // keys fall along the stack).
        let after = self.key(aligned + 1, judged + 1);
        let (mut lo, mut hi) = (0, self.len);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            match self.entry(mid) {
                Some((_, k)) if k > after => lo = mid + 1,
                _ => hi = mid,
            }
        }
        if let Some((start, _)) = self.entry(lo) {
            let width = (self.major(at) - self.major(start)).abs();
            if width > self.width {
                (self.best, self.width) = (Some((start, at)), width);
            }
        }
    }

    /// The longest part's first and last pixels, in trace order; `None`
    /// when no part spans two pixels or the stack overflowed.
    pub(crate) fn best(&self) -> Option<(P, P)> {
        if self.full { None } else { self.best }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    /// Feeds a trace of aligned (`true`) and judged unaligned pixels along
    /// a row, ρ2 = 0.9.
    fn longest(trace: &[bool]) -> Option<(P, P)> {
        let mut stack = [0u32; 3 * 64];
        let mut t = Longest::new(&mut stack, 3_865_470_464, false);
        let (mut a, mut j) = (0u64, 0u64);
        for (x, &ok) in trace.iter().enumerate() {
            if ok {
                t.aligned((x as i32, 0), a, j);
                a += 1;
            }
            j += 1;
        }
        t.best()
    }

    /// The longest part passing ρ2 between two aligned pixels, by brute
    /// force: the same part as the tracker's (the first of the longest).
    #[test]
    fn the_tracker_finds_the_first_longest_passing_part() {
        let mut next = crate::xorshift64(0x7219_0A11);
        // Fewer under Miri, where the brute force is slow.
        for _ in 0..if cfg!(miri) { 30 } else { 2_000 } {
            let n = 1 + (next() % 60) as usize;
            let miss = 2 + next() % 12;
            let trace: std::vec::Vec<bool> = (0..n).map(|_| !next().is_multiple_of(miss)).collect();
            let mut want: Option<(usize, usize)> = None;
            for i in 0..n {
                for k in i + 1..n {
                    if !(trace[i] && trace[k]) {
                        continue;
                    }
                    let a = trace[i..=k].iter().filter(|&&b| b).count() as u64;
                    let len = (k - i + 1) as u64;
                    let passes = (a << 32) >= 3_865_470_464 * len;
                    if passes && want.is_none_or(|(wi, wk)| k - i > wk - wi) {
                        want = Some((i, k));
                    }
                }
            }
            let got = longest(&trace).map(|(a, b)| (a.0 as usize, b.0 as usize));
            assert_eq!(got, want, "{trace:?}");
        }
    }

    /// A line across a gap: the longer side is the part; an overflowing
    /// stack reports none.
    #[test]
    fn a_gap_splits_the_line_and_a_full_stack_gives_none() {
        let mut trace = [true; 30];
        trace[12..16].fill(false);
        assert_eq!(longest(&trace), Some(((16, 0), (29, 0))));
        let mut stack = [0u32; 2];
        let mut t = Longest::new(&mut stack, 3_865_470_464, false);
        t.aligned((0, 0), 0, 0);
        t.aligned((1, 0), 1, 1);
        assert_eq!(t.best(), None);
    }
}
