//! The phase views of a carved workspace: each phase of a call borrows its
//! regions through one of these, named by their role in that phase (the
//! roles are [`Region`]'s), so that a region used in the wrong phase is not
//! in scope.

#[allow(unused_imports)] // the docs' links
use super::Region;
use super::{BUCKETS, Layout, as_u16};
use crate::invariant::Invariant;

/// A carved workspace but for the blurred image ([`Workspace::carve`](super::Workspace::carve)
/// returns that apart: every phase reads it): its regions, handed out by
/// role through one phase view at a time.
pub(crate) struct Slab<'a> {
    pub(super) layout: Layout,
    pub(super) classes: &'a mut [u8],
    pub(super) visited: &'a mut [u8],
    pub(super) class_row: &'a mut [u8],
    pub(super) cand: &'a mut [u32],
    pub(super) row_index: &'a mut [u32],
    pub(super) lists: &'a mut [u32],
    pub(super) sort: &'a mut [u32],
    pub(super) rows: &'a mut [u32],
    pub(super) index: &'a mut [u32],
    pub(super) mags: &'a mut [u8],
}

/// The anchor pass's regions (paper §3.1), by role.
pub(crate) struct AnchorPass<'s> {
    /// The gradient ring ([`Region::Rows`]).
    pub ring: &'s mut [u16],
    /// The pixel classes it writes ([`Region::Classes`]).
    pub classes: &'s mut [u8],
    /// The current row of classes and gates ([`Region::ClassRow`]).
    pub class_row: &'s mut [u8],
    /// The candidates, at most [`Layout::push_cap`] ([`Region::Candidates`]).
    pub candidates: &'s mut [u32],
    /// The candidates' keys ([`Region::Visited`]).
    pub keys: &'s mut [u8],
    /// The keys' counts, [`BUCKETS`] words ([`Region::Sort`]).
    pub counts: &'s mut [u32],
    /// The thinning's claim ring ([`Region::Lists`]).
    pub claims: &'s mut [u32],
    /// The magnitude cache it fills, or empty ([`Region::Mags`]).
    pub mags: &'s mut [u8],
}

/// The extraction's regions (paper §3.1, design §4), by role.
pub(crate) struct Extraction<'s> {
    /// The candidates, then the group records ([`Region::Candidates`]).
    pub region: &'s mut [u32],
    /// The candidates' keys ([`Region::Visited`]).
    pub keys: &'s [u8],
    /// The keys' counts, then the order's cursors ([`Region::Sort`]).
    pub counts: &'s mut [u32],
    /// The order's bucket starts ([`Region::Sort`]).
    pub starts: &'s mut [u32],
    /// Where the order's chunks go when longer than the candidate region's
    /// free tail: the longer of [`Region::Index`] and [`Region::Rows`].
    pub spare: &'s mut [u32],
    /// The pixel classes, marked with the groups ([`Region::Classes`]).
    pub classes: &'s mut [u8],
    /// The row index of the records it writes ([`Region::RowIndex`]).
    pub row_index: &'s mut [u32],
}

/// The group tables' regions (paper §3.2), by role: what [`Groups`]
/// borrows for the linking.
///
/// [`Groups`]: crate::stage::groups::Groups
pub(crate) struct GroupTables<'s> {
    /// The group records, then their directions ([`Region::Candidates`]).
    pub records: &'s mut [u32],
    /// The records' row index ([`Region::RowIndex`]).
    pub row_index: &'s [u32],
    /// The group index, or empty ([`Region::Index`]).
    pub index: &'s mut [u16],
}

/// The linking's other regions (paper §3.2-3.3), by role.
pub(crate) struct Linking<'s> {
    /// The pixel classes ([`Region::Classes`]).
    pub classes: &'s mut [u8],
    /// The visited set ([`Region::Visited`]).
    pub visited: &'s mut [u8],
    /// The visited, undo and bridge lists ([`Region::Lists`]), and how
    /// many pixels a linking may visit.
    pub lists: &'s mut [u32],
    /// See `lists`.
    pub max_visits: usize,
    /// The magnitude cache, or empty ([`Region::Mags`]).
    pub mags: &'s [u8],
    /// The seeds' chunks ([`Region::Rows`]).
    pub seeds: &'s mut [u32],
    /// The seeds' bucket starts and cursors ([`Region::Sort`]).
    pub starts: &'s mut [u32],
    /// See `starts`.
    pub cursor: &'s mut [u32],
}

/// The merge's region (paper §3.3), by role.
pub(crate) struct Merge<'s> {
    /// The sort pairs, two words per segment ([`Region::Candidates`]; the
    /// group records are done with).
    pub pairs: &'s mut [u32],
}

impl Slab<'_> {
    /// The smoothing's scratch: 5 rows of horizontal sums
    /// ([`Region::Rows`]).
    #[inline(always)]
    pub fn smoothing(&mut self) -> &mut [u16] {
        as_u16(self.rows)
    }

    /// The anchor pass's regions.
    #[inline(always)]
    pub fn anchor_pass(&mut self) -> AnchorPass<'_> {
        let (counts, _) = split_sort(self.sort);
        AnchorPass {
            ring: as_u16(self.rows),
            classes: self.classes,
            class_row: self.class_row,
            candidates: self.cand.get_mut(..self.layout.push_cap).or_broken(&mut []),
            keys: self.visited,
            counts,
            claims: self.lists,
            mags: self.mags,
        }
    }

    /// The extraction's regions.
    #[inline(always)]
    pub fn extraction(&mut self) -> Extraction<'_> {
        let (counts, starts) = split_sort(self.sort);
        // The longest free region for the order's chunks: the group
        // index's, when there is one (it is built afterwards), so that one
        // pass suffices.
        let spare: &mut [u32] = if self.index.len() > self.rows.len() {
            self.index
        } else {
            self.rows
        };
        Extraction {
            region: self.cand,
            keys: self.visited,
            counts,
            starts,
            spare,
            classes: self.classes,
            row_index: self.row_index,
        }
    }

    /// The linking's regions: the group tables', and the others.
    #[inline(always)]
    pub fn linking(&mut self) -> (GroupTables<'_>, Linking<'_>) {
        let (starts, cursor) = split_sort(self.sort);
        let tables = GroupTables {
            records: self.cand,
            row_index: self.row_index,
            index: as_u16(self.index),
        };
        let linking = Linking {
            classes: self.classes,
            visited: self.visited,
            lists: self.lists,
            max_visits: self.layout.visited,
            mags: self.mags,
            seeds: self.rows,
            starts,
            cursor,
        };
        (tables, linking)
    }

    /// The merge's region.
    #[inline(always)]
    pub fn merge(&mut self) -> Merge<'_> {
        let words = 2 * self.layout.merge_room();
        Merge {
            pairs: self.cand.get_mut(..words).or_broken(&mut []),
        }
    }
}

/// [`Region::Sort`]'s two halves of [`BUCKETS`] words.
#[inline(always)]
fn split_sort(sort: &mut [u32]) -> (&mut [u32], &mut [u32]) {
    sort.split_at_mut(BUCKETS.min(sort.len()))
}
