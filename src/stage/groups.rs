//! Paper §3.2: what the walk needs to know of an aligned anchor group
//! (design §6): its three pixels, its direction (the direction of the sum of
//! the members' level-line unit vectors) and whether it has been linked.
//!
//! After the extraction the workspace's candidate region holds the groups'
//! entries in raster order (the records, which a lookup finds by binary
//! search within one row, through a row index), then in group-id order (the
//! seeds). [`Groups::build`] puts each group's direction behind them, as
//! many as fit. A member pixel finds its group by looking up the centres
//! among its eight neighbours: the record of its own centre names it as a
//! partner. A lookup of a group whose direction did not fit computes it; the
//! results are the same (`group_cache_and_fallback_agree`).

use core::num::NonZeroUsize;

use super::P;
use super::anchors::level_line;
use super::gradient::gradient_at;
use super::order::{INDEX_MASK, partner_codes};
use super::state::{Class, ClassMap};
use crate::num::trig::{Bam, atan2, sin_cos};
use crate::spec::NEIGHBOURS;

/// A group: its direction and its three pixels J, C, K.
pub(crate) struct Group {
    pub angle: Bam,
    pub members: [P; 3],
}

/// The group direction: the direction of the sum of the level-line unit
/// vectors of the three `members` (in-image pixels of the `w`-wide blurred
/// image `blur`).
pub(crate) fn direction_of(blur: &[u8], w: usize, members: [P; 3]) -> Bam {
    let (mut sx, mut sy) = (0i64, 0i64);
    for (x, y) in members {
        let (gx, gy) = gradient_at(blur, w, x as usize, y as usize);
        let (cs, sn) = sin_cos(level_line(gx, gy));
        sx += i64::from(cs);
        sy += i64::from(sn);
    }
    atan2(sy, sx)
}

/// The three pixels of the group whose candidate entry `e` (raster index and
/// partner codes, see [`partner_codes`]) is centred at `c`: J, C, K.
pub(crate) fn members_of_entry(c: P, e: u32) -> [P; 3] {
    let partner = |code: usize| {
        let (dx, dy) = NEIGHBOURS.get(code).copied().unwrap_or((0, 0));
        (c.0 + dx, c.1 + dy)
    };
    // Not `array::map`: opt-level z does not inline it.
    let [j, k] = partner_codes(e);
    [partner(j), c, partner(k)]
}

/// The groups of one detection (see the module docs).
pub(crate) struct Groups<'a> {
    /// The groups' entries, ascending by raster index.
    by_index: &'a [u32],
    /// Each record's direction, or empty (then computed on lookup).
    angles: &'a [u32],
    /// `rows[y]..rows[y + 1]`: the records of row `y`.
    rows: &'a [u32],
    /// One linked bit per record.
    linked: &'a mut [u32],
    w: NonZeroUsize,
}

/// Words of linked bits for `groups` groups.
pub(crate) const fn linked_words(groups: usize) -> usize {
    groups.div_ceil(32)
}

impl<'a> Groups<'a> {
    /// The records of the `g` groups that [`super::order::extract_groups`]
    /// left in `region` (the entries in raster order, then in id order): the
    /// directions of as many records as fit go behind them (all of them
    /// when `3·g <= region.len()`; none unless `cache_directions`), `rows`
    /// (at least `h + 1` words) receives the row index and `linked` (at
    /// least [`linked_words`]`(g)` words) is cleared. Returns the seeds (the
    /// id-order entries) and the records; `None` when `region` is shorter
    /// than `2·g` (the extraction's cap prevents it).
    #[allow(clippy::too_many_arguments)]
    pub fn build(
        region: &'a mut [u32],
        g: usize,
        blur: &[u8],
        w: NonZeroUsize,
        h: usize,
        rows: &'a mut [u32],
        linked: &'a mut [u32],
        cache_directions: bool,
    ) -> Option<(&'a [u32], Self)> {
        let (by_index, rest) = region.split_at_mut_checked(g)?;
        let (seeds, rest) = rest.split_at_mut_checked(g)?;
        let rows = rows.get_mut(..h + 1)?;
        // rows[y] = the number of records in rows above y.
        let mut i = 0;
        for (y, slot) in rows.iter_mut().enumerate() {
            let row_start = (y * w.get()) as u32;
            while by_index.get(i).is_some_and(|&e| e & INDEX_MASK < row_start) {
                i += 1;
            }
            *slot = i as u32;
        }
        let linked = linked.get_mut(..linked_words(g))?;
        linked.fill(0);
        let cached = if cache_directions {
            g.min(rest.len())
        } else {
            0
        };
        let angles = rest.get_mut(..cached).unwrap_or(&mut []);
        for (slot, &e) in angles.iter_mut().zip(by_index.iter()) {
            *slot = direction_of(blur, w.get(), members_of_entry(centre_of(e, w), e));
        }
        Some((
            seeds,
            Self {
                by_index,
                angles,
                rows,
                linked,
                w,
            },
        ))
    }

    /// The record position of the group centred at `c`, if there is one.
    #[inline]
    pub fn find(&self, c: P) -> Option<usize> {
        let y = usize::try_from(c.1).ok()?;
        let (&lo, &hi) = (self.rows.get(y)?, self.rows.get(y + 1)?);
        let key = (y * self.w.get() + usize::try_from(c.0).ok()?) as u32;
        let row = self.by_index.get(lo as usize..hi as usize)?;
        let i = row.binary_search_by_key(&key, |&e| e & INDEX_MASK).ok()?;
        Some(lo as usize + i)
    }

    /// The group of record `pos`, centred at `c`.
    #[inline]
    pub fn get(&self, pos: usize, c: P, blur: &[u8]) -> Group {
        let e = self.by_index.get(pos).copied().unwrap_or(0);
        let members = members_of_entry(c, e);
        let angle = match self.angles.get(pos) {
            Some(&a) => a,
            None => direction_of(blur, self.w.get(), members),
        };
        Group { angle, members }
    }

    /// The centre and record of the group whose member is `m`: the
    /// neighbouring centre whose record names `m` as a partner.
    pub fn of_member(&self, classes: &ClassMap<'_>, h: usize, m: P) -> Option<(P, usize)> {
        for (dx, dy) in NEIGHBOURS {
            let c = (m.0 + dx, m.1 + dy);
            let (Ok(x), Ok(y)) = (usize::try_from(c.0), usize::try_from(c.1)) else {
                continue;
            };
            if x >= self.w.get() || y >= h || classes.get(x, y) != Class::Centre {
                continue;
            }
            let Some(pos) = self.find(c) else { continue };
            let e = self.by_index.get(pos).copied().unwrap_or(0);
            let [j, _, k] = members_of_entry(c, e);
            if j == m || k == m {
                return Some((c, pos));
            }
        }
        None
    }

    /// Whether the group of record `pos` has been linked.
    #[inline]
    pub fn linked(&self, pos: usize) -> bool {
        self.linked
            .get(pos / 32)
            .is_some_and(|&w| w & (1 << (pos % 32)) != 0)
    }

    /// Marks the group of record `pos` linked or not.
    #[inline]
    pub fn set_linked(&mut self, pos: usize, on: bool) {
        if let Some(w) = self.linked.get_mut(pos / 32) {
            let bit = 1 << (pos % 32);
            if on {
                *w |= bit;
            } else {
                *w &= !bit;
            }
        }
    }
}

/// The centre pixel of a candidate entry.
pub(crate) fn centre_of(e: u32, w: NonZeroUsize) -> P {
    let i = (e & INDEX_MASK) as usize;
    ((i % w) as i32, (i / w) as i32)
}
