//! The caller-provided scratch memory, sized by a `const fn`.
//!
//! One `&mut [u8]` slab holds every per-call region. [`Layout::compute`]
//! decides the regions with checked arithmetic; [`Workspace::bytes_needed`]
//! returns its total and [`detect`](crate::detect) carves the slab with the
//! same function, so sizing and carving cannot disagree.
//!
//! | region | type | count | why that many |
//! |---|---|---|---|
//! | blurred image | `u8` | `w·h` | every later stage recomputes gradients from it |
//! | pixel classes | 2 bits | `w·h` | none / regular anchor / group centre / member |
//! | visited set (before it: the candidates' keys) | 1 bit | `w·h` | the current linking's visited pixels (at least `C - 64` bytes) |
//! | candidates, then the group records and their directions, then the merging's sort | `u32` | `C` | a record replaces its candidate; the directions are cached when groups ≤ `C/2` (always on natural images); the merge needs 2 words per segment, and segments < groups |
//! | row index of the records | `u32` | `h + 1` | a lookup searches one row |
//! | visited, undo and bridge lists (before them: the thinning's claim ring) | `u32` | `V + V/3 + 1 + 2·(V/6)` | one linking: a group adds 3 visited pixels, so links ≤ V/3; bridges, 2 words each, half as many (a linking bridges no more) |
//! | row scratch | `u16` | `9·w` | blur: 5 rows; gradient ring: 3 rows of m, gx, gy; then the ordering buffer of the extraction and of the seeds |
//! | class row | `u8` | `w` | the anchor pass's row of classes and gates |
//! | sort scratch | `u32` | 512 | key counts and bucket ends |
//! | group index (only in the larger layout, [`Workspace::bytes_needed_fast`], up to 4096 columns) | `u16` | `w·h`, rounded up to even | a group centre or member names its group's record within its row: one load per lookup (before it is built: the extraction's ordering buffer, one pass) |
//! | magnitude cache (only in the larger layout, with the index) | `u8` | `w·h` | half of each pixel's thresholded gradient magnitude (at most 255): a walk step reads its three candidates instead of recomputing them from the blurred image |
//!
//! `C = w·h·candidates_per_mille/1000 + 64` and `V = max_link_pixels`, both
//! from [`Config`]. The anchor pass keeps at most `C - 64` candidates; the
//! extraction orders them in passes through the row scratch (free by then).
//! Running out drops the weakest candidates (or thins them, when one
//! strength is most of the list: see `stage::candidates`); running out of
//! `V` ends a linking early. Both are counted in [`Summary`](crate::Summary), never
//! errors. Each bit map pads its rows to a byte. Up to 3 bytes of slack let
//! the `u32` regions start aligned whatever the slab's address.

use crate::limits::{MAX_DIMENSION, MAX_PIXELS};
use crate::{Config, Error};

/// Byte offsets and capacities of the workspace regions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Pixel count `w·h`.
    pub pixels: usize,
    /// Bytes of the blurred image: `w·h`, or 0 when the caller's frame is
    /// smoothed in place.
    pub blur_bytes: usize,
    /// Candidate capacity C.
    pub candidates: usize,
    /// How many candidates the anchor pass may keep: `C - 64`, so that the
    /// extraction always has a little free room to order them in (it also
    /// uses the row scratch).
    pub push_cap: usize,
    /// Visited-list capacity V.
    pub visited: usize,
    /// `u32` words of the visited, undo and bridge lists.
    pub lists: usize,
    /// `u32` words of the row index.
    pub row_index: usize,
    /// `u32` words of row scratch (`9·w` `u16` values, rounded up).
    pub row_words: usize,
    /// Bytes of the class map.
    pub class_bytes: usize,
    /// Bytes of the visited map.
    pub visited_bytes: usize,
    /// Bytes of the class row.
    pub class_row: usize,
    /// `u32` words of the group index: `w·h / 2` rounded up in the indexed
    /// layout ([`Layout::indexed`]) of an image up to [`INDEX_MAX_WIDTH`]
    /// wide, else 0.
    pub index: usize,
    /// Bytes of the magnitude cache: `w·h` in the indexed layout when it
    /// holds the index, else 0.
    pub mags: usize,
    /// Total bytes, including alignment slack.
    pub total: usize,
}

/// The widest image whose indexed layout holds the group index: an entry
/// names its group's record by its rank in the centre's row, in 12 bits
/// (`stage::packed::index_entry`).
pub(crate) const INDEX_MAX_WIDTH: usize = crate::stage::packed::index_entry::MAX_WIDTH;

/// `u16` rows of scratch per image column.
pub(crate) const ROW_SCRATCH_PER_COLUMN: usize = 9;
/// Words of sort scratch: key counts, then bucket ends.
pub(crate) const SORT_WORDS: usize = 2 * crate::stage::order::BUCKETS;
/// Bytes of alignment slack.
const ALIGN_SLACK: usize = 3;
/// Candidate slots beyond `w·h·candidates_per_mille/1000`: the
/// extraction's free room to order the candidates in.
const CANDIDATE_RESERVE: usize = 64;

macro_rules! tri {
    ($e:expr) => {
        match $e {
            Some(v) => v,
            None => return None,
        }
    };
}

impl Layout {
    /// The layout for a `width` x `height` image, or `None` when a dimension
    /// is zero or over the limits, or a size overflows `usize`. `in_place`:
    /// the caller's frame holds the blurred image (no region for it).
    pub const fn compute(
        width: usize,
        height: usize,
        cfg: &Config,
        in_place: bool,
    ) -> Option<Self> {
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return None;
        }
        let pixels = width * height; // <= 32767², no overflow on 32-bit usize
        if pixels > MAX_PIXELS {
            return None;
        }
        let per_mille = cfg.candidates_per_mille as usize;
        let candidates = tri!(tri!(pixels.checked_mul(per_mille)).checked_div(1000));
        let candidates = tri!(candidates.checked_add(CANDIDATE_RESERVE));
        let visited = cfg.max_link_pixels as usize;
        let lists = tri!(visited.checked_add(visited / 3 + 1 + 2 * (visited / 6)));
        let row_index = tri!(height.checked_add(1));
        let row_words = tri!(width.checked_mul(ROW_SCRATCH_PER_COLUMN)).div_ceil(2);
        let class_bytes = tri!(crate::stage::state::row_bytes(width, 2).checked_mul(height));
        let push_cap = candidates - CANDIDATE_RESERVE;
        // The visited bit map, which the candidates' keys use until the
        // linking starts.
        let bitmap = tri!(crate::stage::state::row_bytes(width, 1).checked_mul(height));
        let visited_bytes = if bitmap > push_cap { bitmap } else { push_cap };
        // u32 regions first (aligned), then u16, then bytes.
        let words = tri!(tri!(candidates.checked_add(row_index)).checked_add(lists));
        let words = tri!(words.checked_add(SORT_WORDS));
        let mut total = ALIGN_SLACK;
        total = tri!(total.checked_add(tri!(words.checked_mul(4))));
        total = tri!(total.checked_add(tri!(row_words.checked_mul(4))));
        let blur_bytes = if in_place { 0 } else { pixels };
        total = tri!(total.checked_add(blur_bytes));
        total = tri!(total.checked_add(class_bytes));
        total = tri!(total.checked_add(visited_bytes));
        total = tri!(total.checked_add(width));
        Some(Self {
            pixels,
            blur_bytes,
            candidates,
            push_cap,
            visited,
            lists,
            row_index,
            row_words,
            class_bytes,
            visited_bytes,
            class_row: width,
            index: 0,
            mags: 0,
            total,
        })
    }

    /// This layout with the group index: one `u16` per pixel that names,
    /// at each group centre and member, its group's record, so that the
    /// linking finds a group in one load instead of searching the
    /// neighbours and the row's records; and with the magnitude cache, one
    /// byte per pixel, so that a walk step loads its candidates'
    /// magnitudes instead of computing each from four pixels. Images wider
    /// than [`INDEX_MAX_WIDTH`] get neither (the layout is unchanged).
    /// `None` when the size overflows.
    pub const fn indexed(self) -> Option<Self> {
        // The class row holds one byte per column: it is the width.
        if self.class_row > INDEX_MAX_WIDTH {
            return Some(self);
        }
        let words = self.pixels.div_ceil(2);
        let total = tri!(self.total.checked_add(tri!(words.checked_mul(4))));
        Some(Self {
            index: words,
            mags: self.pixels,
            total: tri!(total.checked_add(self.pixels)),
            ..self
        })
    }
}

/// `u32` scratch as `u16` values (always aligned).
pub(crate) fn as_u16(words: &mut [u32]) -> &mut [u16] {
    bytemuck::cast_slice_mut(words)
}

/// The regions of a carved workspace.
pub(crate) struct Regions<'a> {
    pub blur: &'a mut [u8],
    pub classes: &'a mut [u8],
    pub visited: &'a mut [u8],
    pub class_row: &'a mut [u8],
    pub cand: &'a mut [u32],
    pub row_index: &'a mut [u32],
    pub lists: &'a mut [u32],
    pub sort: &'a mut [u32],
    /// Row scratch, as `u32` words (see [`as_u16`]).
    pub rows: &'a mut [u32],
    /// The group index (empty unless the layout is [`Layout::indexed`]), as
    /// `u32` words (see [`as_u16`]): before the index is built, the
    /// extraction orders its candidates there.
    pub index: &'a mut [u32],
    /// The magnitude cache (empty unless the layout is [`Layout::indexed`]).
    pub mags: &'a mut [u8],
}

/// Scratch memory for [`detect`](crate::detect), borrowed from the caller.
///
/// ```
/// use aaglsd::{Config, Workspace};
/// let needed = Workspace::bytes_needed(320, 240, &Config::DEFAULT).unwrap();
/// let mut slab = vec![0u8; needed];
/// let ws = Workspace::new(&mut slab);
/// assert_eq!(ws.len(), needed);
/// ```
///
/// A workspace can be reused for any number of calls and image sizes (as
/// long as it is large enough); each call initialises what it reads.
#[derive(Debug)]
pub struct Workspace<'a> {
    buf: &'a mut [u8],
}

/// The constant terms of the size formula, for bindings that state it as a
/// compile-time expression in another language (the C header's
/// `AAGLSD_WORKSPACE_BYTES`, generated by `ffi/gen-header`, which checks
/// its formula against [`Workspace::bytes_needed`]). With
/// `C = w·h·candidates_per_mille/1000 + CANDIDATE_RESERVE` and
/// `V = max_link_pixels`, [`Workspace::bytes_needed`] is
///
/// ```text
/// ALIGN_SLACK + 4·(C + (h + 1) + (V + V/3 + 1 + 2·(V/6)) + SORT_WORDS)
///   + 4·ceil(ROW_SCRATCH_PER_COLUMN·w / 2) + w·h + ceil(2w/8)·h
///   + max(ceil(w/8)·h, C - CANDIDATE_RESERVE) + w
/// ```
///
/// (all divisions round down unless written `ceil`);
/// [`Workspace::bytes_needed_in_place`] drops the `w·h` term, and
/// [`Workspace::bytes_needed_fast`] adds `4·ceil(w·h/2) + w·h` when
/// `w <= INDEX_MAX_WIDTH`. The table in this module's source says what each
/// region is for.
impl Workspace<'_> {
    /// Bytes of alignment slack in every size.
    pub const ALIGN_SLACK: usize = ALIGN_SLACK;
    /// Candidate slots beyond `w·h·candidates_per_mille/1000`.
    pub const CANDIDATE_RESERVE: usize = CANDIDATE_RESERVE;
    /// `u32` words of sort scratch.
    pub const SORT_WORDS: usize = SORT_WORDS;
    /// `u16` values of row scratch per image column.
    pub const ROW_SCRATCH_PER_COLUMN: usize = ROW_SCRATCH_PER_COLUMN;
    /// The widest image whose [`Workspace::bytes_needed_fast`] layout holds
    /// the group index and the magnitude cache.
    pub const INDEX_MAX_WIDTH: usize = INDEX_MAX_WIDTH;
}

impl<'a> Workspace<'a> {
    /// Wraps a caller slab. Its size is checked by each
    /// [`detect`](crate::detect) call against [`Workspace::bytes_needed`].
    pub fn new(buf: &'a mut [u8]) -> Self {
        Self { buf }
    }

    /// Length of the slab in bytes.
    pub fn len(&self) -> usize {
        self.buf.len()
    }

    /// True for an empty slab.
    pub fn is_empty(&self) -> bool {
        self.buf.is_empty()
    }

    /// Bytes of workspace that [`detect`](crate::detect) needs for a
    /// `width` x `height` image with `cfg`'s capacities, including 3 bytes of
    /// alignment slack. `None` when the dimensions are zero or over
    /// [`MAX_DIMENSION`](crate::MAX_DIMENSION) /
    /// [`MAX_PIXELS`](crate::MAX_PIXELS), or the size overflows `usize`.
    ///
    /// 1.8 to 1.9 bytes per pixel at the default capacities for frames from
    /// 320x240 to 1064x708 (see the README's memory report).
    pub const fn bytes_needed(width: usize, height: usize, cfg: &Config) -> Option<usize> {
        match Layout::compute(width, height, cfg, false) {
            Some(l) => Some(l.total),
            None => None,
        }
    }

    /// Bytes of workspace that [`detect_in_place`](crate::detect_in_place)
    /// needs: [`Workspace::bytes_needed`] less the `width·height` bytes of
    /// the smoothed image, which stays in the caller's frame.
    ///
    /// ```
    /// use aaglsd::{Config, Workspace};
    /// let cfg = Config::DEFAULT;
    /// let (a, b) = (
    ///     Workspace::bytes_needed(320, 240, &cfg).unwrap(),
    ///     Workspace::bytes_needed_in_place(320, 240, &cfg).unwrap(),
    /// );
    /// assert_eq!(a - b, 320 * 240);
    /// ```
    pub const fn bytes_needed_in_place(width: usize, height: usize, cfg: &Config) -> Option<usize> {
        match Layout::compute(width, height, cfg, true) {
            Some(l) => Some(l.total),
            None => None,
        }
    }

    /// Bytes of workspace with which [`detect`](crate::detect) runs
    /// faster: [`Workspace::bytes_needed`] plus 3 bytes per pixel (2 of
    /// them rounded up to 4 bytes in all): a group index, which lets the
    /// linking find the group of a pixel in one load, and a cache of the
    /// gradient magnitudes, which the walk's steps read. For an image wider
    /// than 4096 pixels the two sizes are equal and there is no index. The
    /// result is the same with either size; this one is for hosts with
    /// memory to spare (the README gives the time of each).
    /// [`detect_in_place`](crate::detect_in_place) takes the index when
    /// its workspace holds [`Workspace::bytes_needed_in_place`] plus the
    /// same number of bytes. A build for size (opt-level `s` or `z`)
    /// leaves the index out and uses only the smaller size.
    ///
    /// ```
    /// use aaglsd::{Config, Workspace};
    /// let cfg = Config::DEFAULT;
    /// let (small, fast) = (
    ///     Workspace::bytes_needed(320, 240, &cfg).unwrap(),
    ///     Workspace::bytes_needed_fast(320, 240, &cfg).unwrap(),
    /// );
    /// assert_eq!(fast - small, 3 * 320 * 240);
    /// ```
    pub const fn bytes_needed_fast(width: usize, height: usize, cfg: &Config) -> Option<usize> {
        match Layout::compute(width, height, cfg, false) {
            Some(l) => match l.indexed() {
                Some(l) => Some(l.total),
                None => None,
            },
            None => None,
        }
    }

    /// [`Workspace::bytes_needed`] for [`Config::DEFAULT`], usable as an array
    /// length. Fails to compile (const panic) for invalid dimensions.
    ///
    /// ```
    /// const N: usize = aaglsd::Workspace::bytes_needed_default(320, 240);
    /// static mut SLAB: [u8; N] = [0; N];
    /// ```
    ///
    /// # Panics
    /// Only in const evaluation (a compile error) or when called at run time
    /// with dimensions for which [`Workspace::bytes_needed`] is `None`; use
    /// that function for run-time sizes.
    #[allow(clippy::panic)] // the point of this wrapper: a compile-time error
    pub const fn bytes_needed_default(width: usize, height: usize) -> usize {
        match Self::bytes_needed(width, height, &Config::DEFAULT) {
            Some(n) => n,
            None => panic!("image dimensions out of range"),
        }
    }

    /// The size of each workspace region, in bytes, for the memory report
    /// (`examples/memory.rs`). Unstable: behind the `_unstable-hooks`
    /// feature.
    #[cfg(feature = "_unstable-hooks")]
    pub fn region_bytes(
        width: usize,
        height: usize,
        cfg: &Config,
    ) -> Option<[(&'static str, usize); 10]> {
        let l = Layout::compute(width, height, cfg, false)?;
        Some([
            ("blurred image (u8 per pixel)", l.pixels),
            ("pixel classes (2 bits per pixel)", l.class_bytes),
            ("visited set (1 bit per pixel)", l.visited_bytes),
            (
                "candidates, then seeds and group records (u32)",
                l.candidates * 4,
            ),
            ("row index of the group records (u32)", l.row_index * 4),
            ("visited, undo and bridge lists (u32)", l.lists * 4),
            ("row scratch (u16, 9 rows)", l.row_words * 4),
            ("class row (u8)", l.class_row),
            ("sort scratch (512 u32)", SORT_WORDS * 4),
            ("alignment slack", ALIGN_SLACK),
        ])
    }

    /// Carves the slab for `layout`.
    pub(crate) fn carve(&mut self, layout: &Layout) -> Result<Regions<'_>, Error> {
        let got = self.buf.len();
        let too_small = Error::WorkspaceTooSmall {
            needed: layout.total,
            got,
        };
        if got < layout.total {
            return Err(too_small);
        }
        let pad = self.buf.as_ptr().align_offset(4).min(ALIGN_SLACK);
        let rest = self.buf.get_mut(pad..).ok_or(too_small)?;
        let words = layout.candidates + layout.row_index + layout.lists + SORT_WORDS + layout.index;
        // Each region is the front of what is left.
        fn take<'b, T>(rest: &mut &'b mut [T], n: usize, e: Error) -> Result<&'b mut [T], Error> {
            let (head, tail) = core::mem::take(rest).split_at_mut_checked(n).ok_or(e)?;
            *rest = tail;
            Ok(head)
        }
        let mut rest = rest;
        let w32 = take(&mut rest, words * 4, too_small)?;
        let mut w32: &mut [u32] = bytemuck::try_cast_slice_mut(w32).map_err(|_| too_small)?;
        let cand = take(&mut w32, layout.candidates, too_small)?;
        let row_index = take(&mut w32, layout.row_index, too_small)?;
        let lists = take(&mut w32, layout.lists, too_small)?;
        let index = take(&mut w32, layout.index, too_small)?;
        let sort = w32;
        let w32b = take(&mut rest, layout.row_words * 4, too_small)?;
        let rows: &mut [u32] = bytemuck::try_cast_slice_mut(w32b).map_err(|_| too_small)?;
        let blur = take(&mut rest, layout.blur_bytes, too_small)?;
        let classes = take(&mut rest, layout.class_bytes, too_small)?;
        let visited = take(&mut rest, layout.visited_bytes, too_small)?;
        let mags = take(&mut rest, layout.mags, too_small)?;
        let class_row = rest.get_mut(..layout.class_row).ok_or(too_small)?;
        Ok(Regions {
            blur,
            classes,
            visited,
            class_row,
            cand,
            row_index,
            lists,
            sort,
            rows,
            index,
            mags,
        })
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Workspace<'_> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "Workspace {{ bytes: {} }}", self.buf.len());
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    #[test]
    fn sizes() {
        let cfg = Config::DEFAULT;
        assert_eq!(Workspace::bytes_needed(0, 10, &cfg), None);
        assert_eq!(Workspace::bytes_needed(10, 0, &cfg), None);
        assert_eq!(Workspace::bytes_needed(MAX_DIMENSION + 1, 1, &cfg), None);
        assert_eq!(Workspace::bytes_needed(8192, 8193, &cfg), None);
        // The memory goal: at most 2 bytes per pixel at the default
        // capacities for the documented sizes.
        for (w, h) in [(320, 240), (640, 480), (1064, 708)] {
            let n = Workspace::bytes_needed(w, h, &cfg).unwrap();
            let per_px = n as f64 / (w * h) as f64;
            assert!(per_px > 1.0 && per_px <= 2.0, "{w}x{h}: {per_px}");
        }
    }

    #[test]
    fn carving_any_alignment() {
        let cfg = Config::DEFAULT;
        let layout = Layout::compute(33, 17, &cfg, false).unwrap();
        let mut slab = vec![0u8; layout.total + 8];
        for off in 0..4 {
            let mut ws = Workspace::new(&mut slab[off..off + layout.total]);
            let r = ws.carve(&layout).unwrap();
            assert_eq!(r.blur.len(), 33 * 17);
            assert_eq!(r.classes.len(), 9 * 17);
            assert_eq!(r.visited.len(), (5 * 17).max(layout.push_cap));
            assert_eq!(r.cand.len(), layout.candidates);
            assert_eq!(r.sort.len(), 512);
            assert_eq!(r.rows.len() * 2, 33 * 9 + 1);
        }
        // The indexed layout: one more u16 per pixel (561, rounded up to
        // 562) and one more byte, the rest unchanged.
        let fast = layout.indexed().unwrap();
        assert_eq!(fast.total, layout.total + 2 * 562 + 561);
        assert_eq!(Workspace::bytes_needed_fast(33, 17, &cfg), Some(fast.total));
        let mut big = vec![0u8; fast.total + 3];
        for off in 0..4 {
            let mut ws = Workspace::new(&mut big[off..off + fast.total]);
            let r = ws.carve(&fast).unwrap();
            assert_eq!(as_u16(r.index).len(), 562);
            assert_eq!(r.mags.len(), 561);
            assert_eq!(r.cand.len(), layout.candidates);
            assert_eq!(r.sort.len(), 512);
        }
        // No index beyond INDEX_MAX_WIDTH columns: the layouts are equal.
        for (w, indexed) in [(INDEX_MAX_WIDTH, true), (INDEX_MAX_WIDTH + 1, false)] {
            let plain = Layout::compute(w, 3, &cfg, false).unwrap();
            let fast = plain.indexed().unwrap();
            assert_eq!(fast.index > 0, indexed, "{w}");
            assert_eq!(fast.mags > 0, indexed, "{w}");
            assert_eq!(fast.total - plain.total, 4 * fast.index + fast.mags, "{w}");
            assert_eq!(Workspace::bytes_needed_fast(w, 3, &cfg), Some(fast.total));
        }
        let mut short = vec![0u8; layout.total - 1];
        let mut ws = Workspace::new(&mut short);
        assert!(matches!(
            ws.carve(&layout),
            Err(Error::WorkspaceTooSmall { .. })
        ));
    }
}
