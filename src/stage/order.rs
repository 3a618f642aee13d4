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
//! When the candidate list fills, [`CandidateList`] evicts the weakest key
//! present (and every later candidate at or below it), so the strongest
//! candidates are the ones kept; [`crate::Summary::dropped_candidates`]
//! counts the loss.

use core::num::NonZeroUsize;

use super::state::{Class, PixelState};
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

/// The raster-order candidate list with eviction of the weakest key when full.
pub(crate) struct CandidateList<'a> {
    list: &'a mut [u32],
    len: usize,
    hist: &'a mut [u32],
    /// Candidates with key <= floor are dropped.
    floor: i32,
    dropped: usize,
}

impl<'a> CandidateList<'a> {
    /// An empty list over `list`, counting keys in `hist` (cleared here).
    pub fn new(list: &'a mut [u32], hist: &'a mut [u32]) -> Self {
        hist.iter_mut().for_each(|c| *c = 0);
        Self {
            list,
            len: 0,
            hist,
            floor: 0,
            dropped: 0,
        }
    }

    /// Candidates stored (after any eviction).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Candidates dropped for capacity.
    pub fn dropped(&self) -> usize {
        self.dropped
    }

    /// Appends a candidate; when the list is full, evicts (see
    /// [`CandidateList::push_evicting`]).
    #[inline(always)]
    pub fn push(&mut self, entry: u32, key: u8, keys: impl Fn(u32) -> u8) {
        if i32::from(key) > self.floor && self.append(entry, key) {
            return;
        }
        self.push_evicting(entry, key, keys);
    }

    /// Stores a candidate and counts its key; false when the list is full.
    #[inline(always)]
    fn append(&mut self, entry: u32, key: u8) -> bool {
        let Some(slot) = self.list.get_mut(self.len) else {
            return false;
        };
        *slot = entry;
        self.len += 1;
        if let Some(c) = self.hist.get_mut(usize::from(key)) {
            *c += 1;
        }
        true
    }

    /// [`CandidateList::push`] for a key at or below the floor or a full
    /// list: drops every candidate of the lowest key present until there
    /// is room or the new key is at or below the floor.
    #[cold]
    #[inline(never)]
    fn push_evicting(&mut self, entry: u32, key: u8, keys: impl Fn(u32) -> u8) {
        if i32::from(key) <= self.floor {
            self.dropped += 1;
            return;
        }
        while self.len >= self.list.len() {
            // Full: drop every candidate of the lowest key present.
            let lowest = self
                .hist
                .iter()
                .position(|&c| c > 0)
                .unwrap_or(255)
                .min(255);
            self.floor = lowest as i32;
            if let Some(c) = self.hist.get_mut(lowest) {
                self.dropped += *c as usize;
                *c = 0;
            }
            let mut kept = 0;
            for i in 0..self.len {
                let e = self.list.get(i).copied().unwrap_or(0);
                if i32::from(keys(e)) > self.floor {
                    if let Some(slot) = self.list.get_mut(kept) {
                        *slot = e;
                    }
                    kept += 1;
                }
            }
            self.len = kept;
            if i32::from(key) <= self.floor {
                self.dropped += 1;
                return;
            }
        }
        self.append(entry, key);
    }
}

/// Stable counting sort of the raster candidates into `sorted`, by
/// descending key. `hist` holds the per-key counts; it is consumed. The key
/// of a candidate is its `mag8` entry, `min(m, 255)` of its thresholded
/// magnitude, which [`classify`] wrote (the candidate list's eviction reads
/// the same entries).
pub(crate) fn sort_candidates(raster: &[u32], sorted: &mut [u32], hist: &mut [u32], mag8: &[u8]) {
    // Start offset of each key, highest key first.
    let mut acc = 0u32;
    for k in (0..hist.len()).rev() {
        if let Some(c) = hist.get_mut(k) {
            let n = *c;
            *c = acc;
            acc += n;
        }
    }
    for &e in raster {
        let key = mag8.get((e & INDEX_MASK) as usize).copied().unwrap_or(0);
        if let Some(pos) = hist.get_mut(usize::from(key)) {
            if let Some(slot) = sorted.get_mut(*pos as usize) {
                *slot = e;
            }
            *pos += 1;
        }
    }
}

/// Greedy extraction in sorted order: writes CENTRE / MEMBER states and
/// compacts the accepted centres (with their partner codes) to the front of
/// `sorted`, in group-id order. Returns the number of groups.
pub(crate) fn extract_groups(
    sorted: &mut [u32],
    n: usize,
    state: &mut [u8],
    w: NonZeroUsize,
) -> usize {
    let mut groups = 0;
    for i in 0..n.min(sorted.len()) {
        let e = sorted.get(i).copied().unwrap_or(0);
        let c = (e & INDEX_MASK) as usize;
        let [cj, ck] = partner_codes(e);
        let partner = |code: usize| -> Option<usize> {
            let (dx, dy) = NEIGHBOURS.get(code).copied()?;
            let x = (c % w) as i64 + i64::from(dx);
            let y = (c / w) as i64 + i64::from(dy);
            (x >= 0 && y >= 0 && (x as usize) < w.get()).then(|| y as usize * w.get() + x as usize)
        };
        let (Some(j), Some(k)) = (partner(cj), partner(ck)) else {
            continue;
        };
        let used = |i: usize| {
            state
                .get(i)
                .is_none_or(|&s| PixelState::from_byte(s).in_group())
        };
        if used(c) || used(j) || used(k) {
            continue;
        }
        if let Some(s) = state.get_mut(c) {
            *s = PixelState::CENTRE.byte();
        }
        if let Some(s) = state.get_mut(j) {
            *s = PixelState::member(cj).byte();
        }
        if let Some(s) = state.get_mut(k) {
            *s = PixelState::member(ck).byte();
        }
        if let Some(slot) = sorted.get_mut(groups) {
            *slot = e;
        }
        groups += 1;
    }
    groups
}

/// Compacts the raster-order candidate list to the accepted group centres'
/// entries (still in raster order, with their partner codes: see
/// `Linker::cache_directions`). Returns their number.
pub(crate) fn centres_in_raster_order(raster: &mut [u32], n: usize, state: &[u8]) -> usize {
    let mut kept = 0;
    for i in 0..n.min(raster.len()) {
        let e = raster.get(i).copied().unwrap_or(0);
        if state
            .get((e & INDEX_MASK) as usize)
            .is_some_and(|&s| PixelState::from_byte(s).class() == Class::Centre)
        {
            if let Some(slot) = raster.get_mut(kept) {
                *slot = e;
            }
            kept += 1;
        }
    }
    kept
}
