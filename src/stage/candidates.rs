//! The raster-order list of group candidates (design §3), and what it
//! drops when it is full.
//!
//! The anchor pass pushes each candidate with its key `min(m, 255)`; the
//! list keeps the keys in a parallel byte array and their counts in a
//! histogram (the processing order's buckets). When the list is full:
//! * normally the weakest key present is dropped whole, and every later
//!   candidate at or below it: the strongest candidates are kept, as the
//!   processing order would use them first;
//! * but when that key holds more than half the list (sharp synthetic or
//!   printed content, industrial scenes: many edges of one strength),
//!   dropping it would lose most of the image. That key is thinned
//!   instead: first of the candidates the greedy extraction would refuse
//!   anyway (those overlapping an earlier candidate of the same key, found
//!   with a three-row bit ring), which keeps its groups; if the list still
//!   fills, of its later candidates in raster order.
//!
//! [`crate::Summary::dropped_candidates`] counts every candidate dropped.

use super::packed::candidate;
use crate::invariant::Invariant;
use crate::spec::NEIGHBOURS;
use crate::target::SMALL;

/// Bits of three image rows, `y - 1`, `y`, `y + 1` (ring slots `row % 3`),
/// marking the pixels that kept candidates of the thinned key claim (their
/// centre and two partners), as the greedy extraction would.
struct Claims<'a> {
    bits: &'a mut [u32],
    /// Words per row.
    wpr: usize,
    /// The highest row the ring holds (cleared when it entered), if any.
    top: Option<usize>,
}

impl<'a> Claims<'a> {
    /// A ring for rows `w` pixels wide, or `None` when `bits` is too short.
    fn new(bits: &'a mut [u32], w: usize) -> Option<Self> {
        let wpr = w.div_ceil(32);
        let bits = bits.get_mut(..3 * wpr)?;
        Some(Self {
            bits,
            wpr,
            top: None,
        })
    }

    #[cfg_attr(aaglsd_small, inline(never))]
    fn clear_row(&mut self, y: usize) {
        let at = (y % 3) * self.wpr;
        if let Some(r) = self.bits.get_mut(at..at + self.wpr) {
            super::zero_words(r);
        }
    }

    /// Makes the ring hold rows `y - 1 ..= y + 1`, the rows a candidate of
    /// row `y` touches (raster order: `y` never decreases).
    fn reach(&mut self, y: usize) {
        let want = y + 1;
        match self.top {
            Some(top) if top >= want => {}
            Some(top) if want - top < 3 => {
                for r in top + 1..=want {
                    self.clear_row(r);
                }
            }
            _ => {
                super::zero_words(self.bits);
            }
        }
        self.top = Some(self.top.map_or(want, |t| t.max(want)));
    }

    fn bit(&self, x: usize, y: usize) -> (usize, u32) {
        ((y % 3) * self.wpr + x / 32, 1 << (x % 32))
    }

    /// Claims the pixels of candidate `e` (image width `w`) unless one is
    /// claimed already; false then (the extraction would refuse it).
    fn claim(&mut self, e: u32, w: usize) -> bool {
        let idx = candidate::index(e);
        let (x, y) = (idx % w.max(1), idx / w.max(1));
        self.reach(y);
        let [j, k] = candidate::partner_codes(e);
        let mut pixels = [(x, y); 3];
        for (slot, code) in pixels.iter_mut().skip(1).zip([j, k]) {
            let (dx, dy) = NEIGHBOURS.get(code).copied().or_broken((0, 0));
            // Candidates lie inside the image's one-pixel border.
            *slot = (
                x.wrapping_add_signed(dx as isize),
                y.wrapping_add_signed(dy as isize),
            );
        }
        let taken = pixels.iter().any(|&(px, py)| {
            let (word, mask) = self.bit(px, py);
            px < w && self.bits.get(word).is_some_and(|b| b & mask != 0)
        });
        if taken {
            return false;
        }
        for (px, py) in pixels {
            let (word, mask) = self.bit(px, py);
            if px < w
                && let Some(b) = self.bits.get_mut(word)
            {
                *b |= mask;
            }
        }
        true
    }
}

/// How far a full list has thinned its lowest key.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Thin {
    /// Nothing thinned.
    Off,
    /// Overlapping candidates of the key are dropped.
    Overlaps,
    /// Also every later candidate of the key (and below it).
    Later,
}

/// The raster-order candidate list.
pub(crate) struct CandidateList<'a> {
    list: &'a mut [u32],
    keys: &'a mut [u8],
    len: usize,
    hist: &'a mut [u32],
    /// Candidates with key <= floor are dropped.
    floor: i32,
    /// The key being thinned (-1: none) and how far.
    thin_key: i32,
    thin: Thin,
    claims: Option<Claims<'a>>,
    /// Image width.
    w: usize,
    dropped: usize,
}

impl<'a> CandidateList<'a> {
    /// An empty list over `list` (its capacity: as long as `keys`, at the
    /// most), keys in `keys`, counting keys in `hist` (cleared here), for
    /// an image `w` pixels wide; `ring` is scratch for the thinning (three
    /// rows of bits; without it, thinning drops later candidates only).
    pub fn new(
        list: &'a mut [u32],
        keys: &'a mut [u8],
        hist: &'a mut [u32],
        ring: &'a mut [u32],
        w: usize,
    ) -> Self {
        hist.iter_mut().for_each(|c| *c = 0);
        let cap = list.len().min(keys.len());
        let list = list.get_mut(..cap).or_broken(&mut []);
        Self {
            list,
            keys,
            len: 0,
            hist,
            floor: 0,
            thin_key: -1,
            thin: Thin::Off,
            claims: Claims::new(ring, w),
            w,
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

    /// Appends a candidate; when the list is full or the key is thinned,
    /// see [`CandidateList::push_evicting`].
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn push(&mut self, entry: u32, key: u8) {
        let k = i32::from(key);
        if k > self.floor && k != self.thin_key && self.append(entry, key) {
            return;
        }
        self.push_evicting(entry, key);
    }

    /// Stores a candidate and counts its key; false when the list is full.
    #[inline(always)]
    fn append(&mut self, entry: u32, key: u8) -> bool {
        let (Some(slot), Some(k)) = (self.list.get_mut(self.len), self.keys.get_mut(self.len))
        else {
            return false;
        };
        *slot = entry;
        *k = key;
        self.len += 1;
        if let Some(c) = self.hist.get_mut(usize::from(key)) {
            *c += 1;
        }
        true
    }

    /// Removes the stored candidates that `gone(entry, key)` selects (in
    /// raster order), keeping the others in order.
    #[inline(always)]
    fn remove(&mut self, mut gone: impl FnMut(u32, u8) -> bool) {
        if SMALL {
            // One copy for the three callers' tests in a build for size
            // (evictions are rare; the indirect call costs little).
            self.remove_with(&mut gone as &mut dyn FnMut(u32, u8) -> bool);
        } else {
            self.remove_with(gone);
        }
    }

    fn remove_with(&mut self, mut gone: impl FnMut(u32, u8) -> bool) {
        let mut kept = 0;
        for i in 0..self.len {
            let e = self.list.get(i).copied().or_broken(0);
            let k = self.keys.get(i).copied().or_broken(0);
            if gone(e, k) {
                self.dropped += 1;
                if let Some(c) = self.hist.get_mut(usize::from(k)) {
                    *c = c.saturating_sub(1);
                }
            } else {
                if let (Some(slot), Some(ks)) = (self.list.get_mut(kept), self.keys.get_mut(kept)) {
                    *slot = e;
                    *ks = k;
                }
                kept += 1;
            }
        }
        self.len = kept;
    }

    /// Removes the last stored candidates of key `key`, a sixteenth of the
    /// list's capacity at once (so that a run of stronger arrivals costs
    /// one pass per sixteenth, not one per arrival); false if there is
    /// none.
    fn remove_last(&mut self, key: i32) -> bool {
        let want = (self.list.len() / 16).max(1);
        let (mut found, mut cut) = (0, self.len);
        while cut > 0 && found < want {
            cut -= 1;
            if self.keys.get(cut).map(|&x| i32::from(x)) == Some(key) {
                found += 1;
            }
        }
        if found == 0 {
            return false;
        }
        let mut at = 0;
        self.remove(|_, k| {
            at += 1;
            at > cut && i32::from(k) == key
        });
        true
    }

    /// Whether an arriving candidate is refused before any eviction.
    fn refused(&mut self, entry: u32, k: i32) -> bool {
        if k <= self.floor {
            return true;
        }
        if k == self.thin_key && self.thin == Thin::Overlaps {
            let w = self.w;
            return !self.claims.as_mut().is_some_and(|c| c.claim(entry, w));
        }
        false
    }

    /// [`CandidateList::push`] for a key at or below the floor, the key
    /// being thinned, or a full list (see the module docs).
    #[cold]
    #[inline(never)]
    fn push_evicting(&mut self, entry: u32, key: u8) {
        let k = i32::from(key);
        if self.refused(entry, k) {
            self.dropped += 1;
            return;
        }
        while self.len >= self.list.len() {
            let lowest = self
                .hist
                .iter()
                .position(|&c| c > 0)
                // None stored (a list of no room): any key, nothing to drop.
                .unwrap_or(255)
                .min(255) as i32;
            let count = self.hist.get(lowest as usize).copied().or_broken(0) as usize;
            if lowest == self.thin_key && self.thin != Thin::Off {
                // Still full: keep the raster-earliest of the key.
                self.thin = Thin::Later;
                self.floor = lowest;
                if k <= self.floor || !self.remove_last(lowest) {
                    self.dropped += 1;
                    return;
                }
            } else if 2 * count > self.len && self.claims.is_some() {
                self.thin_key = lowest;
                self.thin = Thin::Overlaps;
                self.floor = self.floor.max(lowest - 1);
                let w = self.w;
                let mut claims = self.claims.take();
                if let Some(c) = claims.as_mut() {
                    c.top = None;
                    self.remove(|e, ke| i32::from(ke) == lowest && !c.claim(e, w));
                }
                self.claims = claims;
                if k == lowest && self.refused(entry, k) {
                    self.dropped += 1;
                    return;
                }
            } else {
                self.floor = lowest;
                self.remove(|_, ke| i32::from(ke) <= lowest);
                if k <= self.floor {
                    self.dropped += 1;
                    return;
                }
            }
        }
        self.append(entry, key);
    }
}
