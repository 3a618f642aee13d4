//! Paper §3.1, the processing order (the paper's pseudo-sort, design §3)
//! and the greedy group extraction (design §4).
//!
//! The anchor pass pushes every *candidate* (a pixel that passes the
//! order-independent part of the group test) in raster order, packed with
//! its two partners' neighbour codes into one `u32` ([`entry`]), and counts
//! its key `min(m, 255)` in a 256-bin histogram. A stable counting sort then
//! orders the candidates by descending key, ties in raster order, exactly the
//! authors' 1024-bin bucket order for integer magnitudes. The greedy
//! extraction takes them in that order: a candidate becomes a group unless
//! its centre or a partner already belongs to one. Last, the raster-order
//! list is compacted to the accepted centres, the group cache's keys.
//!
//! The list fills in [`super::candidates`], which decides what a full list
//! drops.

use core::num::NonZeroUsize;

use super::groups::record;
use super::nms::ROW_PASS;
use super::state::{Class, ClassMap};
use crate::num::trig::WIDE;
use crate::spec::NEIGHBOURS;

/// Result of the static group test for one pixel.
#[derive(Clone, Copy)]
pub(crate) struct Partners {
    pub j: u8,
    pub k: u8,
}

/// The raster-index bits of a candidate entry.
pub(crate) const INDEX_MASK: u32 = 0x03FF_FFFF;

/// Candidate entry: raster index | J code << 26 | K code << 29.
pub(crate) const fn entry(idx: usize, p: Partners) -> u32 {
    idx as u32 | (p.j as u32) << 26 | (p.k as u32) << 29
}

/// The neighbour codes (indices into [`NEIGHBOURS`]) of the J and K
/// partners of a candidate entry (see [`entry`]).
pub(crate) const fn partner_codes(e: u32) -> [usize; 2] {
    [((e >> 26) & 7) as usize, ((e >> 29) & 7) as usize]
}

/// Division of raster indices by the image width: by a multiplication on
/// a 64-bit core (`m = ceil(2^64 / w)`: for `c, w < 2^32` the error of
/// `c·m / 2^64` is below `2^-32 < 1/w`, so its floor is `c / w`), by the
/// hardware divider elsewhere (a 128-bit product would cost more there).
#[derive(Clone, Copy)]
struct ByWidth {
    w: NonZeroUsize,
    m: u64,
}

impl ByWidth {
    fn new(w: NonZeroUsize) -> Self {
        let m = match u64::try_from(w.get()) {
            Ok(w64 @ 2..=0xFFFF_FFFF) if WIDE => u64::MAX / w64 + 1,
            _ => 0, // w = 1 (or beyond 32 bits, or a 32-bit core): the plain division
        };
        Self { w, m }
    }

    /// `(c % w, c / w)` for a raster index `c < 2^32`.
    #[inline(always)]
    fn split(&self, c: usize) -> (usize, usize) {
        let y = if WIDE && self.m != 0 {
            ((c as u128 * u128::from(self.m)) >> 64) as usize
        } else {
            c / self.w
        };
        (c - y * self.w.get(), y)
    }
}

/// Key buckets of the processing order.
pub(crate) const BUCKETS: usize = 256;

/// How many positions of an order a chunk of `words` words takes at a
/// time: all but its last word, the spare of [`chunk_slot`] (at least one:
/// a one-word chunk has its spare past its end, where nothing is stored).
pub(crate) fn chunk_span(words: usize) -> usize {
    words.saturating_sub(1).max(1)
}

/// The word of a chunk that takes the entry at position `at` of an order,
/// when the chunk holds positions `0..len` and `spare` is a word past
/// them: `at` itself if inside; else, on a core that speculates (the SIMD
/// targets, [`ROW_PASS`]), the spare word (a store either way: which
/// entries fall outside is data-dependent, and a branch on it would
/// mispredict), and on one that does not (a Cortex-M), none.
#[inline(always)]
pub(crate) fn chunk_slot(at: usize, len: usize, spare: usize) -> Option<usize> {
    let inside = at < len;
    if ROW_PASS {
        Some(core::hint::select_unpredictable(inside, at, spare))
    } else {
        inside.then_some(at)
    }
}

/// `starts[b]`: the position in the processing order of the first candidate
/// of bucket `b` (key `255 - b`), from the key counts `hist`.
pub(crate) fn bucket_starts(hist: &[u32], starts: &mut [u32]) {
    super::zero_words(starts);
    let mut acc = 0u32;
    for (b, s) in starts.iter_mut().take(BUCKETS).enumerate() {
        *s = acc;
        acc += hist.get(BUCKETS - 1 - b).copied().unwrap_or(0);
    }
}

/// The greedy extraction (design §4) over the first `n` candidates of
/// `region`, kept in raster order, taken in the processing order
/// (descending key, ties in raster order: design §3). `keys` holds their keys and
/// `hist` their key counts (as [`super::candidates::CandidateList`] left them; `hist` is reused
/// as scratch), and `scratch` has [`BUCKETS`] words.
///
/// The processing order is produced in chunks, into the free part of
/// `region` or into `spare`, whichever is longer: a pass over the
/// raster-order list places each candidate whose position in the order (its
/// bucket's start plus its rank in the bucket) falls in the current chunk.
/// The list itself is never reordered, so no second array is needed; there
/// are `n / chunk` passes, rounded up.
///
/// A candidate becomes a group unless its centre or a partner already
/// belongs to one; at most `max_groups` are accepted (the strongest come
/// first) and the candidates refused for that cap are counted. Afterwards
/// `region` starts with the groups' records
/// ([`record`](super::groups::record)), in raster order, and `rows` (`h + 1`
/// words) holds their row index. Returns the number of groups and of
/// refused candidates.
#[allow(clippy::too_many_arguments)]
pub(crate) fn extract_groups(
    region: &mut [u32],
    n: usize,
    spare: &mut [u32],
    keys: &mut [u8],
    hist: &mut [u32],
    scratch: &mut [u32],
    classes: &mut ClassMap<'_>,
    rows: &mut [u32],
    w: NonZeroUsize,
    h: usize,
    max_groups: usize,
) -> (usize, usize) {
    let (mut groups, mut refused) = (0, 0);
    let by_width = ByWidth::new(w);
    let n = n.min(region.len());
    // `scratch`: each bucket's start; `hist` then holds the pass's cursors.
    bucket_starts(hist, scratch);
    let (starts, cursor) = (&*scratch, hist);
    let Some((list, free)) = region.split_at_mut_checked(n) else {
        return (0, 0);
    };
    let free = if free.len() >= spare.len() {
        free
    } else {
        spare
    };
    let chunk = chunk_span(free.len());
    let mut lo = 0;
    while lo < n {
        let hi = (lo + chunk).min(n);
        for (c, &s) in cursor.iter_mut().zip(starts) {
            *c = s;
        }
        for (&e, &k) in list.iter().zip(keys.iter()) {
            let b = BUCKETS - 1 - usize::from(k);
            if let Some(c) = cursor.get_mut(b) {
                let at = (*c as usize).wrapping_sub(lo);
                *c += 1;
                if let Some(slot) = chunk_slot(at, hi - lo, chunk).and_then(|a| free.get_mut(a)) {
                    *slot = e;
                }
            }
        }
        for &e in free.iter().take(hi - lo) {
            match try_group(e, classes, by_width, h) {
                Some(_) if groups >= max_groups => refused += 1,
                Some([c, j, k]) => {
                    classes.set(c.0, c.1, Class::Centre);
                    classes.set(j.0, j.1, Class::Member);
                    classes.set(k.0, k.1, Class::Member);
                    groups += 1;
                }
                None => {}
            }
        }
        lo = hi;
    }
    // The records (`super::groups::record`): the accepted entries, still
    // in raster order, and the row index: rows[y] = the records above row y.
    let mut kept = 0;
    let mut next_row = 0;
    for i in 0..n {
        let (Some(&e), Some(&k)) = (list.get(i), keys.get(i)) else {
            break;
        };
        let c = (e & INDEX_MASK) as usize;
        let (x, y) = by_width.split(c);
        // Row y's first candidate: the records so far are those above it.
        while next_row <= y {
            if let Some(r) = rows.get_mut(next_row) {
                *r = kept as u32;
            }
            next_row += 1;
        }
        // Written whether accepted or not (`kept <= i`: entry i has been
        // read), kept only if accepted: the outcome is random, a branch on
        // it would mispredict.
        if let Some(slot) = list.get_mut(kept) {
            *slot = record(x, partner_codes(e), k);
        }
        kept += usize::from(classes.get(x, y) == Class::Centre);
    }
    for r in rows.iter_mut().take(h + 1).skip(next_row) {
        *r = kept as u32;
    }
    (kept, refused)
}

/// The greedy test of one candidate entry: its centre and partners when
/// none of the three is in a group yet (and both partners are in the
/// image).
#[inline]
fn try_group(
    e: u32,
    classes: &ClassMap<'_>,
    by_width: ByWidth,
    h: usize,
) -> Option<[(usize, usize); 3]> {
    let c = (e & INDEX_MASK) as usize;
    let (cx, cy) = by_width.split(c);
    let w = by_width.w;
    let [cj, ck] = partner_codes(e);
    let partner = |code: usize| -> Option<(usize, usize)> {
        let (dx, dy) = NEIGHBOURS.get(code).copied()?;
        let x = cx.checked_add_signed(dx as isize)?;
        let y = cy.checked_add_signed(dy as isize)?;
        (x < w.get() && y < h).then_some((x, y))
    };
    let (j, k) = (partner(cj)?, partner(ck)?);
    let used = |(x, y): (usize, usize)| classes.get(x, y).in_group();
    if used((cx, cy)) || used(j) || used(k) {
        return None;
    }
    Some([(cx, cy), j, k])
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;
    use crate::stage::state::row_bytes;

    /// `ByWidth::split` is the division, for every width up to 2^16 and
    /// the largest ones, at indices over the whole 32-bit range.
    #[test]
    fn division_by_width_is_exact() {
        let mut next = crate::xorshift64(0x0D1F_1DE5);
        let widths = (1..=if cfg!(miri) { 300 } else { 65_536 }).chain([
            0x7FFF_FFFF,
            0xFFFF_FFFE,
            0xFFFF_FFFF,
        ]);
        for w in widths {
            let by = ByWidth::new(NonZeroUsize::new(w).unwrap());
            for k in 0..if cfg!(miri) { 4 } else { 64 } {
                let c = match k {
                    0 => 0,
                    1 => 0xFFFF_FFFF,
                    2 => w - 1,
                    3 => (0xFFFF_FFFF / w) * w - 1,
                    _ => (next() as u32 >> (k % 32)) as usize,
                };
                assert_eq!(by.split(c), (c % w, c / w), "{c} / {w}");
            }
        }
    }

    /// The chunked extraction equals a plain one (sort by key, then index;
    /// then greedy) for every size of the free part, from one entry (a
    /// pass per candidate) to all of them (one pass), and with the group
    /// cap biting.
    #[test]
    fn chunked_extraction_equals_sort_then_greedy() {
        let mut next = crate::xorshift64(0xC0FF_EE00);
        let (w, h) = (23usize, 17usize);
        let wnz = NonZeroUsize::new(w).unwrap();
        let mut total_groups = 0;
        for case in 0..if cfg!(miri) { 4u32 } else { 120 } {
            // Distinct pixels in raster order, random partners and keys
            // (few distinct keys, so that ties are common).
            let mut list = Vec::new();
            let mut keys = Vec::new();
            for i in 0..w * h {
                if next().is_multiple_of(3) {
                    let p = Partners {
                        j: (next() % 8) as u8,
                        k: (next() % 8) as u8,
                    };
                    list.push(entry(i, p));
                    keys.push((next() % 6) as u8 * 40 + 1);
                }
            }
            let n = list.len();
            let max_groups = if case.is_multiple_of(4) { n / 5 } else { n };
            // The plain version.
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by_key(|&i| (255 - keys[i], list[i] & INDEX_MASK));
            let mut cbytes = vec![0u8; row_bytes(w, 2) * h];
            let mut classes = ClassMap::new(&mut cbytes, w);
            let (mut seeds, mut refused) = (Vec::new(), 0);
            for &i in &order {
                if let Some([c, j, k]) = try_group(list[i], &classes, ByWidth::new(wnz), h) {
                    if seeds.len() >= max_groups {
                        refused += 1;
                        continue;
                    }
                    classes.set(c.0, c.1, Class::Centre);
                    classes.set(j.0, j.1, Class::Member);
                    classes.set(k.0, k.1, Class::Member);
                    seeds.push(list[i]);
                }
            }
            // The expected records, in raster order, and the seeds as
            // positions among them (the group ids).
            let key_of = |e: u32| keys[list.iter().position(|&x| x == e).unwrap()];
            let mut by_index = seeds.clone();
            by_index.sort_by_key(|&e| e & INDEX_MASK);
            let records: Vec<u32> = by_index
                .iter()
                .map(|&e| {
                    let c = (e & INDEX_MASK) as usize;
                    record(c % w, partner_codes(e), key_of(e))
                })
                .collect();
            let seed_pos: Vec<u32> = seeds
                .iter()
                .map(|e| by_index.iter().position(|x| x == e).unwrap() as u32)
                .collect();
            total_groups += seeds.len();
            let g = seeds.len();
            // Miri: fewer and larger sizes, one odd and one even (a pass
            // per candidate is quadratic under the interpreter).
            let frees = if cfg!(miri) {
                vec![7, 8, n]
            } else {
                vec![1, 2, 7, n / 3 + 1, n]
            };
            for free in frees {
                // The chunk goes to the longer of the region's free part and
                // the spare: odd sizes use the region, even ones the spare.
                let mut region = list.clone();
                let spare_len = if free % 2 == 0 { free } else { 0 };
                region.resize((n + free - spare_len).max(2 * g), 0);
                let mut spare = vec![0u32; spare_len];
                let mut k = keys.clone();
                let mut hist = vec![0u32; BUCKETS];
                for &key in &keys {
                    hist[usize::from(key)] += 1;
                }
                let mut scratch = vec![0u32; BUCKETS];
                let mut cb = vec![0u8; row_bytes(w, 2) * h];
                let mut cl = ClassMap::new(&mut cb, w);
                let mut rows = vec![0u32; h + 1];
                let got = extract_groups(
                    &mut region,
                    n,
                    &mut spare,
                    &mut k,
                    &mut hist,
                    &mut scratch,
                    &mut cl,
                    &mut rows,
                    wnz,
                    h,
                    max_groups,
                );
                assert_eq!(got, (g, refused), "case {case}, free {free}");
                assert_eq!(
                    &region[..g],
                    &records[..],
                    "records, case {case}, free {free}"
                );
                assert_eq!(cb, cbytes, "classes, case {case}, free {free}");
                for (y, span) in rows.windows(2).enumerate() {
                    for &e in &by_index[span[0] as usize..span[1] as usize] {
                        assert_eq!((e & INDEX_MASK) as usize / w, y, "row index");
                    }
                }
                // The seeds in id order, in chunks of any size.
                let blur = vec![0u8; w * h];
                let groups = crate::stage::groups::Groups::build(
                    &mut region,
                    g,
                    &blur,
                    wnz,
                    &rows,
                    false,
                    &mut [],
                )
                .unwrap();
                let (mut starts, mut cursor) = (vec![0u32; BUCKETS], vec![0u32; BUCKETS]);
                groups.bucket_starts(&mut starts, &mut cursor);
                let mut chunk = vec![0u32; free];
                let mut order = Vec::new();
                while order.len() < g {
                    let got = groups.seed_chunk(order.len(), &mut chunk, &starts, &mut cursor);
                    order.extend_from_slice(&chunk[..got]);
                }
                assert_eq!(order, seed_pos, "seeds, case {case}, free {free}");
                for (p, &e) in by_index.iter().enumerate() {
                    let c = (e & INDEX_MASK) as usize;
                    let (x, y) = ((c % w) as i32, (c / w) as i32);
                    assert_eq!(groups.centre(p), (x, y));
                    assert_eq!(groups.find((x, y)), Some(p));
                }
            }
        }
        // A few hundred groups per case: the cases are not degenerate.
        assert!(
            total_groups > if cfg!(miri) { 100 } else { 500 },
            "{total_groups}"
        );
    }
}
