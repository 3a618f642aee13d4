//! Paper §3.1, the processing order (the paper's pseudo-sort, design §3):
//! the order in which the extraction takes the candidates and the linking
//! takes its seeds, both through [`Order`].
//!
//! Each item (a candidate, a group) carries an 8-bit key, `min(m, 255)` of
//! its centre's magnitude. The order is by descending key, ties in raster
//! order: exactly the authors' 1024-bin bucket order for integer
//! magnitudes. It is a stable counting sort over [`BUCKETS`] keys, produced
//! in chunks: a pass over the items, which stay in raster order, places
//! each item whose position in the order (its bucket's start plus its rank
//! in the bucket) falls in the chunk. No second array of the items is
//! needed; `n` items take `ceil(n / chunk)` passes.

use crate::invariant::Invariant;
use crate::target::SIMD;

/// Key buckets of the processing order.
pub(crate) const BUCKETS: usize = 256;

/// Counts `keys` into `counts` ([`BUCKETS`] words, cleared first).
pub(crate) fn count_keys(keys: impl Iterator<Item = u8>, counts: &mut [u32]) {
    super::zero_words(counts);
    for k in keys {
        if let Some(c) = counts.get_mut(usize::from(k)) {
            *c += 1;
        }
    }
}

/// The processing order of `len` items, produced chunk by chunk.
pub(crate) struct Order<'a> {
    /// `starts[b]`: the position of the first item of bucket `b` (key
    /// `255 - b`).
    starts: &'a [u32],
    /// Each bucket's next position in the current pass.
    cursor: &'a mut [u32],
    len: usize,
}

/// `starts[b]`: the position in the order of the first item of bucket `b`
/// (key `255 - b`), from the key counts `counts` (both [`BUCKETS`] words).
pub(crate) fn bucket_starts(counts: &[u32], starts: &mut [u32]) {
    super::zero_words(starts);
    let mut acc = 0u32;
    for (b, s) in starts.iter_mut().take(BUCKETS).enumerate() {
        *s = acc;
        acc += counts.get(BUCKETS - 1 - b).copied().or_broken(0);
    }
}

impl<'a> Order<'a> {
    /// The order of `len` items whose keys `counts` holds counted (by key;
    /// the words then serve as the passes' cursors); `starts` receives each
    /// bucket's start. Both hold [`BUCKETS`] words.
    pub fn new(len: usize, counts: &'a mut [u32], starts: &'a mut [u32]) -> Self {
        bucket_starts(counts, starts);
        Self::resume(len, starts, counts)
    }

    /// The order of `len` items whose buckets' starts [`bucket_starts`]
    /// left in `starts`; `cursor` is scratch of [`BUCKETS`] words (each
    /// chunk resets it from `starts`, so an order can be taken up again
    /// between chunks).
    pub fn resume(len: usize, starts: &'a [u32], cursor: &'a mut [u32]) -> Self {
        Self {
            starts,
            cursor,
            len,
        }
    }

    /// Writes the items at positions `lo..` of the order into `chunk`, as
    /// many as it takes (all its words but one, the spare of [`slot`]; at
    /// least one) or up to the end, by one pass over `items`, the
    /// `(value, key)` of each item in raster order. Returns how many it
    /// wrote.
    #[inline(always)]
    pub fn chunk(
        &mut self,
        lo: usize,
        chunk: &mut [u32],
        items: impl Iterator<Item = (u32, u8)>,
    ) -> usize {
        if chunk.is_empty() {
            return 0;
        }
        let span = chunk.len().saturating_sub(1).max(1);
        let len = (lo + span).min(self.len).saturating_sub(lo);
        for (c, &s) in self.cursor.iter_mut().zip(self.starts) {
            *c = s;
        }
        for (value, key) in items {
            if let Some(c) = self.cursor.get_mut(BUCKETS - 1 - usize::from(key)) {
                let at = (*c as usize).wrapping_sub(lo);
                *c += 1;
                if let Some(s) = slot(at, len, span).and_then(|a| chunk.get_mut(a)) {
                    *s = value;
                }
            }
        }
        len
    }
}

/// The word of a chunk that takes the item at position `at` of the chunk,
/// when the chunk holds positions `0..len` and `spare` is a word past them:
/// `at` itself if inside; else, on a core that speculates
/// ([`SIMD`]), the spare word, so that every item is a store: which items
/// fall outside is data-dependent, and a branch on it would mispredict. A
/// core that does not speculate (a Cortex-M) skips the store instead.
#[inline(always)]
fn slot(at: usize, len: usize, spare: usize) -> Option<usize> {
    let inside = at < len;
    if SIMD {
        Some(core::hint::select_unpredictable(inside, at, spare))
    } else {
        inside.then_some(at)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every chunk size gives the stable sort by descending key, ties in
    /// item order, for keys with many ties and for all-equal keys.
    #[test]
    fn chunks_give_the_stable_sort_by_descending_key() {
        let mut next = crate::xorshift64(0x0DDE_5EED);
        // Smaller lists under Miri: a one-word chunk scans every item.
        let (cases, most) = if cfg!(miri) { (4, 60) } else { (60, 300) };
        for case in 0..cases {
            let n = (next() % most) as usize;
            let keys: Vec<u8> = (0..n)
                .map(|_| {
                    if case % 5 == 0 {
                        9
                    } else {
                        (next() % 7) as u8 * 37
                    }
                })
                .collect();
            let mut want: Vec<u32> = (0..n as u32).collect();
            want.sort_by_key(|&i| core::cmp::Reverse(keys[i as usize]));
            for words in [1usize, 2, 3, 17, n + 1, n + 5] {
                let (mut counts, mut starts) = (vec![0u32; BUCKETS], vec![0u32; BUCKETS]);
                count_keys(keys.iter().copied(), &mut counts);
                let mut order = Order::new(n, &mut counts, &mut starts);
                let mut chunk = vec![0u32; words];
                let mut got = Vec::new();
                loop {
                    let items = keys.iter().enumerate().map(|(i, &k)| (i as u32, k));
                    let m = order.chunk(got.len(), &mut chunk, items);
                    if m == 0 {
                        break;
                    }
                    got.extend_from_slice(&chunk[..m]);
                }
                assert_eq!(got, want, "case {case}, {words} words");
            }
        }
    }
}
