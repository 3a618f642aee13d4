//! Paper §3.1, the greedy group extraction (design §4): the candidates, in
//! the processing order ([`super::order`]), become aligned anchor groups
//! unless a pixel of theirs already belongs to one.
//!
//! The anchor pass left the candidates ([`candidate`] words) in raster
//! order at the front of their region, their keys in a parallel byte array
//! and the keys' counts. The order is produced in chunks into the free part
//! of the region or into a spare region, whichever is longer; the
//! candidates themselves never move. Afterwards the region starts with one
//! [`record`] per group, in raster order of the centres, and a row index
//! gives each row's records.

use core::num::NonZeroUsize;

use super::order::Order;
use super::packed::{candidate, record};
use super::state::{Class, ClassMap};
use crate::spec::NEIGHBOURS;
use crate::target::WIDE;
use crate::workspace::Extraction;

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

/// The greedy extraction (design §4) of the `n` candidates at the front of
/// `e.region`, in raster order with their keys in `e.keys` and the keys'
/// counts in `e.counts`. A candidate becomes a group unless its centre or a
/// partner already belongs to one; at most `max_groups` are accepted (the
/// strongest come first) and the candidates refused for that cap are
/// counted. Returns the number of groups and of refused candidates; the
/// region then starts with the groups' records, `e.row_index[y]` is the
/// number of records above row `y` and `e.classes` marks the groups.
pub(crate) fn extract_groups(
    e: Extraction<'_>,
    n: usize,
    w: NonZeroUsize,
    h: usize,
    max_groups: usize,
) -> (usize, usize) {
    let n = n.min(e.region.len());
    let Some((list, free)) = e.region.split_at_mut_checked(n) else {
        return (0, 0);
    };
    let free = if free.len() >= e.spare.len() {
        free
    } else {
        e.spare
    };
    let grid = Grid {
        by_width: ByWidth::new(w),
        h,
    };
    let classes = &mut ClassMap::new(e.classes, w.get());
    let order = (e.counts, e.starts);
    let refused = greedy(list, e.keys, free, order, classes, grid, max_groups);
    let kept = keep_records(list, e.keys, classes, e.row_index, grid);
    (kept, refused)
}

/// The image's size as the extraction divides raster indices by it.
#[derive(Clone, Copy)]
struct Grid {
    by_width: ByWidth,
    h: usize,
}

/// The greedy test over the candidates `list` (keys `keys`) in the
/// processing order, produced into `free` with the order's scratch
/// `(counts, starts)`; marks the groups in `classes` and returns how many
/// candidates the cap `max_groups` refused. (Every region a separate
/// argument: the compiler then knows that they do not overlap.)
fn greedy(
    list: &[u32],
    keys: &[u8],
    free: &mut [u32],
    (counts, starts): (&mut [u32], &mut [u32]),
    classes: &mut ClassMap<'_>,
    grid: Grid,
    max_groups: usize,
) -> usize {
    let n = list.len();
    let mut order = Order::new(n, counts, starts);
    let (mut groups, mut refused) = (0, 0);
    let mut lo = 0;
    while lo < n {
        let got = order.chunk(lo, free, list.iter().copied().zip(keys.iter().copied()));
        if got == 0 {
            break;
        }
        for &e in free.iter().take(got) {
            match try_group(e, classes, grid.by_width, grid.h) {
                Some(_) if groups >= max_groups => refused += 1,
                Some([p, j, k]) => {
                    classes.set(p.0, p.1, Class::Centre);
                    classes.set(j.0, j.1, Class::Member);
                    classes.set(k.0, k.1, Class::Member);
                    groups += 1;
                }
                None => {}
            }
        }
        lo += got;
    }
    refused
}

/// Compacts the raster-order candidates `list` to the records of those that
/// became group centres (in `classes`), and writes their row index into
/// `rows`; returns the number of records.
fn keep_records(
    list: &mut [u32],
    keys: &[u8],
    classes: &ClassMap<'_>,
    rows: &mut [u32],
    Grid { by_width, h }: Grid,
) -> usize {
    let mut kept = 0;
    let mut next_row = 0;
    for i in 0..list.len() {
        let (Some(&e), Some(&k)) = (list.get(i), keys.get(i)) else {
            break;
        };
        let (x, y) = by_width.split(candidate::index(e));
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
            *slot = record::new(x, candidate::partner_codes(e), k);
        }
        kept += usize::from(classes.get(x, y) == Class::Centre);
    }
    for r in rows.iter_mut().take(h + 1).skip(next_row) {
        *r = kept as u32;
    }
    kept
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
    let (cx, cy) = by_width.split(candidate::index(e));
    let w = by_width.w;
    let [cj, ck] = candidate::partner_codes(e);
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
    use crate::stage::order::BUCKETS;
    use crate::stage::packed::candidate::Partners;
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
                    list.push(candidate::new(i, p));
                    keys.push((next() % 6) as u8 * 40 + 1);
                }
            }
            let n = list.len();
            let max_groups = if case.is_multiple_of(4) { n / 5 } else { n };
            // The plain version.
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by_key(|&i| (255 - keys[i], candidate::index(list[i])));
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
            by_index.sort_by_key(|&e| candidate::index(e));
            let records: Vec<u32> = by_index
                .iter()
                .map(|&e| {
                    let c = candidate::index(e);
                    record::new(c % w, candidate::partner_codes(e), key_of(e))
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
                let mut hist = vec![0u32; BUCKETS];
                for &key in &keys {
                    hist[usize::from(key)] += 1;
                }
                let mut scratch = vec![0u32; BUCKETS];
                let mut cb = vec![0u8; row_bytes(w, 2) * h];
                let mut rows = vec![0u32; h + 1];
                let regions = Extraction {
                    region: &mut region,
                    keys: &keys,
                    counts: &mut hist,
                    starts: &mut scratch,
                    spare: &mut spare,
                    classes: &mut cb,
                    row_index: &mut rows,
                };
                let got = extract_groups(regions, n, wnz, h, max_groups);
                assert_eq!(got, (g, refused), "case {case}, free {free}");
                assert_eq!(
                    &region[..g],
                    &records[..],
                    "records, case {case}, free {free}"
                );
                assert_eq!(cb, cbytes, "classes, case {case}, free {free}");
                for (y, span) in rows.windows(2).enumerate() {
                    for &e in &by_index[span[0] as usize..span[1] as usize] {
                        assert_eq!(candidate::index(e) / w, y, "row index");
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
                    let c = candidate::index(e);
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
