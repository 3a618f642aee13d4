//! Paper §3.2: what the walk needs to know of an aligned anchor group
//! (design §6): its three pixels and its direction, the direction of the sum of the
//! members' level-line unit vectors.
//!
//! Both are computed once per group, before the linking, into the free half
//! of the workspace's sorted-candidate region ([`GroupCache`]): one direction
//! per group centre, keyed by the centres' raster-order candidate entries
//! (which also hold the partners' neighbour codes), plus a row index of
//! those centres when it fits. A lookup is then a binary search within one
//! row. When the cache does not fit, the walk falls back to
//! [`members_by_search`] and [`direction_of`] on each lookup; the results are
//! the same (`group_cache_and_fallback_agree`).

use core::num::NonZeroUsize;

use super::P;
use super::anchors::level_line;
use super::gradient::gradient_at;
use super::order::{INDEX_MASK, partner_codes};
use super::state::PixelState;
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

/// [`PixelState::member`] of each neighbour code (evaluated at compile time
/// only).
#[allow(clippy::indexing_slicing)] // const evaluation: an out-of-range index is a compile error
const fn member_states() -> [PixelState; 8] {
    let mut t = [PixelState::NONE; 8];
    let mut code = 0;
    while code < 8 {
        t[code] = PixelState::member(code);
        code += 1;
    }
    t
}

/// The three pixels of the group centred at `c`, found without the cache:
/// the two neighbours whose state points back to `c`, in neighbour-code
/// order (J, C, K). `state` is the `w` x `h` state image.
pub(crate) fn members_by_search(state: &[u8], w: NonZeroUsize, h: usize, c: P) -> [P; 3] {
    const BACK: [PixelState; 8] = member_states();
    let mut out = [c; 3];
    let mut k = 0;
    // A group has exactly two partners: stop at the second.
    let mut found = |q: P| {
        if let Some(slot) = out.get_mut(k) {
            *slot = q;
        }
        k += 2;
        k > 2
    };
    for (&(dx, dy), &want) in NEIGHBOURS.iter().zip(&BACK) {
        let (x, y) = (c.0 + dx, c.1 + dy);
        // Negative coordinates wrap to huge unsigned values.
        if (x as u32 as usize) >= w.get() || (y as u32 as usize) >= h {
            continue;
        }
        let s = state
            .get(y as usize * w.get() + x as usize)
            .map_or(PixelState::NONE, |&b| PixelState::from_byte(b));
        if s.same_member(want) && found((x, y)) {
            break;
        }
    }
    out
}

/// The group cache (see the module docs). Empty when it did not fit.
#[derive(Default)]
pub(crate) struct GroupCache<'a> {
    /// The group centres' candidate entries, ascending by raster index.
    centres: &'a [u32],
    /// Each centre's direction.
    angles: &'a [u32],
    /// `rows[y]..rows[y + 1]`: the centres in row `y` (empty when there was
    /// no room for it: then a lookup searches all centres).
    rows: &'a [u32],
}

impl<'a> GroupCache<'a> {
    /// Builds the cache for the group centres `centres` (candidate entries
    /// in raster order) of the `w` x `h` blurred image `blur`, in `scratch`:
    /// one direction per centre and, when there is room for `h + 1` more
    /// values, the row index. Empty when `scratch` is too short.
    pub fn build(
        blur: &[u8],
        w: NonZeroUsize,
        h: usize,
        centres: &'a [u32],
        scratch: &'a mut [u32],
    ) -> Self {
        let Some((angles, rest)) = scratch.split_at_mut_checked(centres.len()) else {
            return Self::default();
        };
        for (slot, &e) in angles.iter_mut().zip(centres) {
            let i = (e & INDEX_MASK) as usize;
            let c = ((i % w) as i32, (i / w) as i32);
            *slot = direction_of(blur, w.get(), members_of_entry(c, e));
        }
        let mut rows: &[u32] = &[];
        if let Some(index) = rest.get_mut(..h + 1) {
            // index[y] = the number of centres in rows above y.
            let mut i = 0;
            for (y, slot) in index.iter_mut().enumerate() {
                let row_start = (y * w.get()) as u32;
                while centres.get(i).is_some_and(|&e| e & INDEX_MASK < row_start) {
                    i += 1;
                }
                *slot = i as u32;
            }
            rows = index;
        }
        Self {
            centres,
            angles,
            rows,
        }
    }

    /// The group centred at `c` (raster index `key`), when the cache holds it.
    pub fn get(&self, c: P, key: u32) -> Option<Group> {
        if self.centres.is_empty() {
            return None;
        }
        let y = c.1 as usize;
        let (lo, hi) = match (self.rows.get(y), self.rows.get(y + 1)) {
            (Some(&lo), Some(&hi)) => (lo as usize, hi as usize),
            _ => (0, self.centres.len()),
        };
        let row = self.centres.get(lo..hi)?;
        let i = row.binary_search_by_key(&key, |&e| e & INDEX_MASK).ok()?;
        let (&angle, &e) = (self.angles.get(lo + i)?, row.get(i)?);
        Some(Group {
            angle,
            members: members_of_entry(c, e),
        })
    }
}
