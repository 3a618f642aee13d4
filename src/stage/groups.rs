//! Paper §3.2: what the walk needs to know of an aligned anchor group
//! (design §6): its three pixels, its direction (the direction of the sum of
//! the members' level-line unit vectors), its key and whether it has been
//! linked.
//!
//! After the extraction the workspace's candidate region holds one
//! [`record`] per group, in raster order of the centres; a row index gives
//! each row's records, so a lookup is a binary search within one row.
//! [`Groups::build`] puts each group's direction behind the records (the
//! extraction's cap leaves room). A member pixel finds its group by looking
//! up the centres among its eight neighbours: the record of its own centre
//! names it as a partner. With a group index in the workspace
//! ([`Groups::indexed`]), each centre and member names its centre and its
//! rank in that row instead ([`index_entry`]). The seeds, the groups in id
//! order (descending key, ties in raster order), come from the processing
//! order (`Groups::seed_chunk`), so no second copy of the records is kept.

use core::num::NonZeroUsize;

use super::P;
use super::gradient::gradient_at;
use super::order::{Order, bucket_starts, count_keys};
use super::packed::record::{LINKED, RELEASED, RETIRED};
use super::packed::{index_entry, record};
use super::state::{Class, ClassMap};
use crate::invariant::Invariant;
use crate::num::trig::{Bam, atan2, rsqrt_q29};
use crate::spec::NEIGHBOURS;
use crate::target::SMALL;

/// A group: its direction and its three pixels J, C, K.
pub(crate) struct Group {
    pub angle: Bam,
    pub members: [P; 3],
}

/// The group direction: the direction of the sum of the level-line unit
/// vectors of the three `members` (in-image pixels of the `w`-wide blurred
/// image `blur`). The level line of a gradient `(gx, gy)`, folded to
/// `gy >= 0`, is the gradient turned by -90°, so its unit vector is
/// `(gy, -gx) / |g|`: scaled by [`rsqrt_q29`] (2^44 / |g|, to 2^-27), no
/// angle is needed until the sum's.
#[inline]
pub(crate) fn direction_of(blur: &[u8], w: usize, members: [P; 3]) -> Bam {
    // Three calls, not `members.map`: the array map's closure is not
    // always inlined.
    let g = |(x, y): P| gradient_at(blur, w, x as usize, y as usize);
    let [a, b, c] = members;
    direction_of_gradients([g(a), g(b), g(c)])
}

/// [`direction_of`] from the members' gradients.
fn direction_of_gradients(gradients: [(i32, i32); 3]) -> Bam {
    let (mut sx, mut sy) = (0i64, 0i64);
    for (gx, gy) in gradients {
        let (gx, gy) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
        // |gx|, |gy| <= 510: the square sum is below 2^20.
        let (r, e) = rsqrt_q29((gx * gx + gy * gy) as u32);
        if r == 0 {
            // A zero gradient (never a member's: its magnitude is above
            // zero) reads as orientation 0°, level line -90°.
            sy -= 1 << 44;
            continue;
        }
        // Each term at most 2^44 (|gx|, |gy| <= |g|, r << e = 2^44 / |g|).
        // The shift goes on the gradient, not the product: `e <= 14` (the
        // square sum is at least 1) keeps `g << e` below 2^23, and the
        // product is then one 32x32 -> 64-bit multiply, the same value
        // without a 64-bit shift.
        let r = i64::from(r);
        sx += i64::from(gy << e) * r;
        sy -= i64::from(gx << e) * r;
    }
    atan2(sy, sx)
}

/// Writes the index entries of every group's three pixels (`index` holds
/// `w·h` entries; the other entries are never read: a pixel's class says
/// whether it is in a group). An entry holds the record's rank in its
/// centre's row: the row index turns it into the position.
fn fill_index(records: &[u32], rows: &[u32], w: NonZeroUsize, index: &mut [u16]) {
    for (y, span) in rows.windows(2).enumerate() {
        let (Some(&lo), Some(&hi)) = (span.first(), span.get(1)) else {
            continue;
        };
        let Some(recs) = records.get(lo as usize..hi as usize) else {
            continue;
        };
        // A row has at most one centre per column, and the layout gives
        // no index to an image wider than `index_entry::MAX_WIDTH`: every rank
        // fits the entry.
        for (rank, &r) in (0u16..).zip(recs) {
            let x = record::column(r) as usize;
            let at = |(dx, dy): (i32, i32)| {
                (y as isize + dy as isize) as usize * w.get() + (x as isize + dx as isize) as usize
            };
            if let Some(e) = index.get_mut(at((0, 0))) {
                *e = index_entry::centre(rank);
            }
            for code in record::partner_codes(r) {
                let off = NEIGHBOURS.get(code as usize).copied().or_broken((0, 0));
                if let Some(e) = index.get_mut(at(off)) {
                    *e = index_entry::member(rank, code);
                }
            }
        }
    }
}

/// The three pixels of the group with record `r`, centred at `c`: J, C, K.
fn members_of(c: P, r: u32) -> [P; 3] {
    let partner = |code: u32| {
        let (dx, dy) = NEIGHBOURS.get(code as usize).copied().or_broken((0, 0));
        (c.0 + dx, c.1 + dy)
    };
    let [j, k] = record::partner_codes(r);
    [partner(j), c, partner(k)]
}

/// The groups of one detection (see the module docs).
pub(crate) struct Groups<'a> {
    /// One record per group, in raster order of the centres.
    records: &'a mut [u32],
    /// Each record's direction, or empty (then computed on lookup).
    angles: &'a [u32],
    /// `rows[y]..rows[y + 1]`: the records of row `y`.
    rows: &'a [u32],
    /// The group index ([`Groups::indexed`]), or empty.
    index: &'a [u16],
    w: NonZeroUsize,
}

impl<'a> Groups<'a> {
    /// The `g` records that [`super::extract::extract_groups`] left at the
    /// front of `region`, with their row index `rows` (`h + 1` words); the
    /// directions go behind the records unless `!cache_directions`.
    /// `None` when `region` is shorter than `2·g` or `rows` than `h + 1`
    /// (the extraction's cap and the layout prevent both).
    pub fn build(
        region: &'a mut [u32],
        g: usize,
        blur: &[u8],
        w: NonZeroUsize,
        rows: &'a [u32],
        cache_directions: bool,
        index: &'a mut [u16],
    ) -> Option<Self> {
        let (records, rest) = region.split_at_mut_checked(g)?;
        let angles = rest.get_mut(..if cache_directions { g } else { 0 })?;
        for (y, span) in rows.windows(2).enumerate() {
            let (Some(&lo), Some(&hi)) = (span.first(), span.get(1)) else {
                continue;
            };
            let (lo, hi) = (lo as usize, hi as usize);
            let (Some(recs), Some(dirs)) = (records.get(lo..hi), angles.get_mut(lo..hi)) else {
                continue;
            };
            for (slot, &r) in dirs.iter_mut().zip(recs) {
                let c = (record::column(r) as i32, y as i32);
                *slot = direction_of(blur, w.get(), members_of(c, r));
            }
        }
        let index = if !SMALL
            && !index.is_empty()
            && w.get() <= index_entry::MAX_WIDTH
            && index.len() >= rows.len().saturating_sub(1) * w.get()
        {
            fill_index(records, rows, w, index);
            index
        } else {
            &mut []
        };
        Some(Self {
            records,
            angles,
            rows,
            index,
            w,
        })
    }

    /// Whether [`Groups::indexed`] may be used (never in a build for
    /// size, which leaves the index out).
    #[inline(always)]
    pub fn has_index(&self) -> bool {
        !SMALL && !self.index.is_empty()
    }

    /// The centre and record position of the group of the centre or member
    /// `p` (an in-image pixel whose class says so), from the index: what
    /// [`Groups::find`] and [`Groups::of_member`] search for (each pixel is
    /// in one group at most). Out of line on a 32-bit core, whose
    /// firmware seldom has the memory for the index: inlined, its code
    /// takes registers from the walk even when the index is absent.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    #[cfg_attr(not(target_pointer_width = "64"), inline(never))]
    pub fn indexed(&self, p: P) -> Option<(P, usize)> {
        let v = *self.index.get(p.1 as usize * self.w.get() + p.0 as usize)?;
        let c = match index_entry::member_code(v) {
            None => p,
            Some(code) => {
                let (dx, dy) = NEIGHBOURS.get(code).copied()?;
                (p.0 - dx, p.1 - dy)
            }
        };
        Some((
            c,
            *self.rows.get(c.1 as usize)? as usize + index_entry::rank(v),
        ))
    }

    /// The number of groups.
    pub fn len(&self) -> usize {
        self.records.len()
    }

    /// The record position of the group centred at `c`, if there is one.
    #[inline]
    pub fn find(&self, c: P) -> Option<usize> {
        let y = usize::try_from(c.1).ok()?;
        let (&lo, &hi) = (self.rows.get(y)?, self.rows.get(y + 1)?);
        let x = u32::try_from(c.0).ok()?;
        let row = self.records.get(lo as usize..hi as usize)?;
        let i = row.binary_search_by_key(&x, |&r| record::column(r)).ok()?;
        Some(lo as usize + i)
    }

    /// The centre of the group of record `pos`.
    pub fn centre(&self, pos: usize) -> P {
        // The row whose span holds `pos`: the last start at or before it.
        let y = self.rows.partition_point(|&s| s as usize <= pos).max(1) - 1;
        let x = self.records.get(pos).map_or(0, |&r| record::column(r));
        (x as i32, y as i32)
    }

    /// The group of record `pos`, centred at `c`.
    #[inline]
    pub fn get(&self, pos: usize, c: P, blur: &[u8]) -> Group {
        let r = self.records.get(pos).copied().or_broken(0);
        let members = members_of(c, r);
        let angle = match self.angles.get(pos) {
            Some(&a) => a,
            None => direction_of(blur, self.w.get(), members),
        };
        Group { angle, members }
    }

    /// The centre and record of the group whose member is `m`: the
    /// neighbouring centre whose record names `m` as a partner.
    pub fn of_member(&self, classes: &ClassMap<'_>, h: usize, m: P) -> Option<(P, usize)> {
        // By index: iterating the array by value copies it first, which a
        // build for size does by a call of `memcpy`.
        for code in 0..NEIGHBOURS.len() {
            let (dx, dy) = NEIGHBOURS.get(code).copied().or_broken((0, 0));
            let c = (m.0 + dx, m.1 + dy);
            let (Ok(x), Ok(y)) = (usize::try_from(c.0), usize::try_from(c.1)) else {
                continue;
            };
            if x >= self.w.get() || y >= h || classes.get(x, y) != Class::Centre {
                continue;
            }
            let Some(pos) = self.find(c) else { continue };
            let r = self.records.get(pos).copied().or_broken(0);
            // m is the centre's neighbour in the opposite direction: a
            // partner code comparison instead of the partners' coordinates.
            let back = ((code + 4) & 7) as u32;
            let [j, k] = record::partner_codes(r);
            if j == back || k == back {
                return Some((c, pos));
            }
        }
        None
    }

    /// Whether flag `bit` of record `pos` is set.
    #[inline]
    fn has(&self, pos: usize, bit: u32) -> bool {
        self.records.get(pos).is_some_and(|&r| r & bit != 0)
    }

    /// Whether the group of record `pos` has been linked.
    #[inline]
    pub fn linked(&self, pos: usize) -> bool {
        self.has(pos, LINKED)
    }

    /// Whether a weak linking released the group of record `pos`.
    #[inline]
    pub fn released(&self, pos: usize) -> bool {
        self.has(pos, RELEASED)
    }

    /// Whether the group of record `pos` was released by a weak linking
    /// that retires its groups (see [`crate::Reseed::Once`]).
    #[inline]
    pub fn retired(&self, pos: usize) -> bool {
        self.has(pos, RETIRED)
    }

    /// Unlinks the group of record `pos` and marks it released, and retired
    /// if `retire` (a retired group stays retired).
    #[inline]
    pub fn release(&mut self, pos: usize, retire: bool) {
        if let Some(r) = self.records.get_mut(pos) {
            *r = (*r & !LINKED) | RELEASED | if retire { RETIRED } else { 0 };
        }
    }

    /// Marks the group of record `pos` linked or not.
    #[cfg_attr(not(aaglsd_small), inline)]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn set_linked(&mut self, pos: usize, on: bool) {
        if let Some(r) = self.records.get_mut(pos) {
            if on {
                *r |= LINKED;
            } else {
                *r &= !LINKED;
            }
        }
    }

    /// `starts[b]`: the id of the first group of key `255 - b` (see
    /// [`Groups::seed_chunk`]); `counts` is scratch of
    /// [`BUCKETS`](super::order::BUCKETS) words.
    pub fn bucket_starts(&self, starts: &mut [u32], counts: &mut [u32]) {
        count_keys(self.records.iter().map(|&r| record::key(r)), counts);
        bucket_starts(counts, starts);
    }

    /// The seeds `lo..lo + chunk.len() - 1` (or fewer, at the end): the
    /// record positions of the groups in id order (descending key, ties in
    /// raster order) written to `chunk`, by one pass over the records
    /// ([`Order::chunk`]). `starts` must hold [`Groups::bucket_starts`];
    /// `cursor` is scratch of the same size. Returns how many were written.
    #[inline]
    pub fn seed_chunk(
        &self,
        lo: usize,
        chunk: &mut [u32],
        starts: &[u32],
        cursor: &mut [u32],
    ) -> usize {
        Order::resume(self.records.len(), starts, cursor).chunk(lo, chunk, self.keyed())
    }

    /// Each group's record position and key, in raster order: the items of
    /// [`Groups::seed_chunk`].
    pub fn keyed(&self) -> impl Iterator<Item = (u32, u8)> + '_ {
        let key = |(p, &r): (usize, &u32)| (p as u32, record::key(r));
        self.records.iter().enumerate().map(key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direction by normalised gradients is the one by angles (the
    /// level line's LUT `atan2`, its LUT `sin_cos` in Q30, summed) within
    /// 16 binary-angle units (1.3e-6°; 7 measured), on random member
    /// gradients over the whole range and small ones; both are far more
    /// precise than the float reference's `f32` sums.
    #[test]
    fn direction_matches_the_angle_chain() {
        use crate::num::trig::{DEG_90, sin_cos};
        let by_angles = |gradients: [(i32, i32); 3]| {
            let (mut sx, mut sy) = (0i64, 0i64);
            for (gx, gy) in gradients {
                let (x, y) = if gy < 0 { (-gx, -gy) } else { (gx, gy) };
                let level = atan2(i64::from(y), i64::from(x)).wrapping_sub(DEG_90);
                let (c, s) = sin_cos(level);
                sx += i64::from(c);
                sy += i64::from(s);
            }
            // A sum shorter than one unit vector (members in opposite
            // directions; never in a group, whose centre is aligned with a
            // partner) leaves the angle to rounding: not compared.
            let long = (sx as f64).hypot(sy as f64) >= f64::from(1u32 << 30);
            (atan2(sy, sx), long)
        };
        let mut next = crate::xorshift64(0x000D_1EC7);
        let mut worst = 0u32;
        for round in 0..if cfg!(miri) { 500 } else { 300_000 } {
            let span = if round % 3 == 0 { 9 } else { 1021 };
            let mut g = || {
                let v = |r: u64| (r % span) as i32 - (span / 2) as i32;
                (v(next()), v(next()))
            };
            let gradients = [g(), g(), g()];
            let (want, long) = by_angles(gradients);
            if gradients.contains(&(0, 0)) || !long {
                continue;
            }
            let d = direction_of_gradients(gradients).wrapping_sub(want);
            worst = worst.max(d.min(d.wrapping_neg()));
        }
        assert!(worst <= 16, "{worst} units");
    }

    /// The index names every pixel's group, also with the most records a
    /// row can hold: one centre in every column of the widest indexed
    /// image, each with its partners above and below.
    #[test]
    fn index_names_every_member_of_a_full_row() {
        use crate::spec::code_of;
        let w = index_entry::MAX_WIDTH;
        let wnz = NonZeroUsize::new(w).unwrap_or(NonZeroUsize::MIN);
        let codes = [code_of(0, -1) as usize, code_of(0, 1) as usize];
        let mut region: Vec<u32> = (0..w).map(|x| record::new(x, codes, 7)).collect();
        let rows = [0, 0, w as u32, w as u32];
        let mut index = vec![0xFFFFu16; 3 * w];
        let blur = vec![0u8; 3 * w];
        let Some(g) = Groups::build(&mut region, w, &blur, wnz, &rows, false, &mut index) else {
            panic!("the records fit");
        };
        // A build for size leaves the index out.
        assert_eq!(g.has_index(), !SMALL);
        if SMALL {
            return;
        }
        for x in 0..w as i32 {
            for y in 0..3 {
                assert_eq!(g.indexed((x, y)), Some(((x, 1), x as usize)), "({x}, {y})");
            }
        }
        // One column more: no index (the ranks would not fit).
        let wide = NonZeroUsize::new(w + 1).unwrap_or(NonZeroUsize::MIN);
        let mut region: Vec<u32> = (0..w + 1).map(|x| record::new(x, codes, 7)).collect();
        let rows = [0, 0, w as u32 + 1, w as u32 + 1];
        let mut index = vec![0u16; 3 * (w + 1)];
        let blur = vec![0u8; 3 * (w + 1)];
        let g = Groups::build(&mut region, w + 1, &blur, wide, &rows, false, &mut index);
        assert!(g.is_some_and(|g| !g.has_index()));
    }

    #[test]
    fn release_keeps_the_record_and_sets_the_flags() {
        let mut region = [record::new(5, [0, 4], 9), record::new(7, [1, 5], 3), 0, 0];
        let rows = [0, 2];
        let w = NonZeroUsize::new(16).unwrap_or(NonZeroUsize::MIN);
        let Some(mut g) = Groups::build(&mut region, 2, &[0; 16], w, &rows, false, &mut []) else {
            panic!("two records fit");
        };
        g.set_linked(0, true);
        g.release(0, false);
        assert!(!g.linked(0) && g.released(0) && !g.retired(0));
        g.set_linked(1, true);
        g.release(1, true);
        assert!(!g.linked(1) && g.released(1) && g.retired(1));
        // Released again without retiring: once retired, always retired.
        g.release(1, false);
        assert!(g.retired(1));
        // The centre, key and partners are untouched.
        assert_eq!(g.find((7, 0)), Some(1));
        assert_eq!(g.centre(1), (7, 0));
        assert_eq!(record::key(g.records.get(1).copied().unwrap_or(0)), 3);
    }
}
