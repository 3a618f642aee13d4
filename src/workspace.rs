//! The caller-provided scratch memory, sized by a `const fn`.
//!
//! One `&mut [u8]` slab holds every per-call region. [`Layout::compute`]
//! decides the regions with checked arithmetic; [`Workspace::bytes_needed`]
//! returns its total and [`detect`](crate::detect()) carves the slab with the
//! same function, so sizing and carving cannot disagree.
//!
//! The regions and their roles are documented in one place, [`Region`]:
//! each variant says what the region holds in each phase of a call, how
//! many elements it has and why. [`Layout::bytes`] sizes each one from
//! the layout, [`Layout::compute`]'s total is their sum
//! (`regions_add_up_to_the_total`), and `Workspace::region_bytes` (the
//! memory report) lists them. A call borrows the regions through one
//! phase view at a time ([`Slab::anchor_pass`], [`Slab::extraction`],
//! [`Slab::linking`], [`Slab::merge`]), each naming its regions by their
//! role in that phase: a region used in the wrong phase is not in scope.
//!
//! `C = w·h·candidates_per_mille/1000 + 64` and `V = max_link_pixels`, both
//! from [`Config`]. The anchor pass keeps at most `C - 64` candidates; the
//! extraction orders them in passes through the row scratch (free by then).
//! Running out drops the weakest candidates (or thins them, when one
//! strength is most of the list: see `stage::candidates`); running out of
//! `V` ends a linking early. Both are counted in [`Summary`](crate::Summary), never
//! errors. Each bit map pads its rows to a byte. Up to 3 bytes of slack let
//! the `u32` regions start aligned whatever the slab's address.

mod views;

pub(crate) use views::{AnchorPass, Extraction, Linking, Merge, Slab};

use crate::limits::{MAX_DIMENSION, MAX_PIXELS};
use crate::stage::order::BUCKETS;
use crate::{Config, Error};

/// The workspace's regions, in the slab's order: what each holds in each
/// phase of a call, its size and why. This is the one description of the
/// regions; the phase views below name them by these roles.
///
/// `C = w·h·candidates_per_mille/1000 + CANDIDATE_RESERVE` and
/// `V = max_link_pixels`. The smoothing and the anchor pass are the front
/// end ([`Slab::smoothing`], [`Slab::anchor_pass`]); then come the
/// extraction ([`Slab::extraction`]), the linking with its group tables
/// ([`Slab::linking`]) and the merge ([`Slab::merge`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Region {
    /// `u32` x C. Anchor pass: the group candidates (at most `C - 64`,
    /// [`Layout::push_cap`]). Extraction: the candidates, replaced in place
    /// by the group records; the free tail takes the order's chunks.
    /// Linking: the records, then each group's direction when they fit
    /// ([`Layout::caches_directions`]: always on natural images). Merge:
    /// the sort pairs, two words per segment ([`Layout::merge_room`]).
    /// Every candidate may become a group, so the records always fit.
    Candidates,
    /// `u32` x `h + 1`. Extraction writes, linking reads: the row index of
    /// the records (`rows[y]`: the records above row `y`), so that a lookup
    /// searches one row.
    RowIndex,
    /// `u32` x `V + V/3 + 1 + 2·(V/6)`. Anchor pass: the thinning's claim
    /// ring. Linking: the visited, undo and bridge lists of one linking (a
    /// group adds 3 visited pixels, so links <= V/3; bridges, 2 words each,
    /// are half as many).
    Lists,
    /// `u32` x [`SORT_WORDS`]: two halves of [`BUCKETS`] words. Anchor
    /// pass: the key counts (first half). Extraction and seeds: counts or
    /// cursors, and bucket starts.
    Sort,
    /// `u16` x `9·w` (in `u32` words). Smoothing: 5 rows of horizontal
    /// sums. Anchor pass: the gradient ring (3 rows of m, gx, gy).
    /// Extraction: the order's chunks, when longer than the other choices.
    /// Linking: the seed chunks.
    Rows,
    /// `u8` x `w·h`, or none when the caller's frame is smoothed in place:
    /// the blurred image, written by the smoothing and read by every later
    /// phase (they recompute gradients from it).
    Blur,
    /// 2 bits x `w·h` (rows padded to a byte): the pixel classes (none,
    /// regular anchor, group centre, member). Anchor pass writes them,
    /// extraction marks the groups, linking reads them.
    Classes,
    /// 1 bit x `w·h` (rows padded to a byte), and at least `C - 64` bytes.
    /// Anchor pass and extraction: the candidates' keys, one byte each.
    /// Linking: the visited set of the current linking.
    Visited,
    /// `u8` x `w`. Anchor pass: the current row of classes and gates.
    ClassRow,
    /// `u16` x `w·h` rounded up to even, only in the indexed layout
    /// ([`Layout::indexed`], up to [`INDEX_MAX_WIDTH`] columns).
    /// Extraction: the order's chunks (the longest free region: one pass).
    /// Linking: the group index, a group centre or member naming its
    /// group's record within its row (one load per lookup).
    Index,
    /// `u8` x `w·h`, only in the indexed layout. Anchor pass writes, linking
    /// reads: half of each pixel's thresholded gradient magnitude (at most
    /// 255), so that a walk step loads its candidates' magnitudes.
    Mags,
    /// Up to [`ALIGN_SLACK`] bytes, so that the `u32` regions start
    /// aligned whatever the slab's address.
    Slack,
}

impl Region {
    /// Every region, in the slab's order.
    #[cfg_attr(not(test), allow(dead_code))]
    pub const ALL: [Region; 12] = [
        Region::Slack,
        Region::Candidates,
        Region::RowIndex,
        Region::Lists,
        Region::Index,
        Region::Sort,
        Region::Rows,
        Region::Blur,
        Region::Classes,
        Region::Visited,
        Region::Mags,
        Region::ClassRow,
    ];

    /// The regions of the smaller layout ([`Workspace::bytes_needed`]), as
    /// the memory report lists them.
    #[cfg_attr(not(any(test, feature = "_unstable-hooks")), allow(dead_code))]
    pub const PLAIN: [Region; 10] = [
        Region::Blur,
        Region::Classes,
        Region::Visited,
        Region::Candidates,
        Region::RowIndex,
        Region::Lists,
        Region::Rows,
        Region::ClassRow,
        Region::Sort,
        Region::Slack,
    ];

    /// The memory report's label.
    #[cfg_attr(not(any(test, feature = "_unstable-hooks")), allow(dead_code))]
    pub const fn label(self) -> &'static str {
        match self {
            Region::Candidates => {
                "candidates, then group records and directions, then merge pairs (u32)"
            }
            Region::RowIndex => "row index of the group records (u32)",
            Region::Lists => "claim ring, then visited, undo and bridge lists (u32)",
            Region::Sort => "sort scratch (512 u32)",
            Region::Rows => "row scratch (u16, 9 rows): blur, gradient ring, order chunks",
            Region::Blur => "blurred image (u8 per pixel)",
            Region::Classes => "pixel classes (2 bits per pixel)",
            Region::Visited => "candidate keys, then visited set (1 bit per pixel)",
            Region::ClassRow => "class row (u8)",
            Region::Index => "group index (u16 per pixel)",
            Region::Mags => "magnitude cache (u8 per pixel)",
            Region::Slack => "alignment slack",
        }
    }
}

/// The sizes of the workspace regions (each [`Region`] says what it is
/// for) and the capacities they give.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Pixel count `w·h`.
    pub pixels: usize,
    /// Bytes of [`Region::Blur`].
    pub blur_bytes: usize,
    /// Candidate capacity C: `u32` words of [`Region::Candidates`].
    pub candidates: usize,
    /// How many candidates the anchor pass may keep: `C - 64`, so that the
    /// extraction always has a little free room to order them in.
    pub push_cap: usize,
    /// Visited-list capacity V.
    pub visited: usize,
    /// `u32` words of [`Region::Lists`].
    pub lists: usize,
    /// `u32` words of [`Region::RowIndex`].
    pub row_index: usize,
    /// `u32` words of [`Region::Rows`].
    pub row_words: usize,
    /// Bytes of [`Region::Classes`].
    pub class_bytes: usize,
    /// Bytes of [`Region::Visited`].
    pub visited_bytes: usize,
    /// Bytes of [`Region::ClassRow`].
    pub class_row: usize,
    /// `u32` words of [`Region::Index`] (0 unless [`Layout::indexed`]).
    pub index: usize,
    /// Bytes of [`Region::Mags`] (0 unless [`Layout::indexed`]).
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
pub(crate) const SORT_WORDS: usize = 2 * BUCKETS;
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

impl Layout {
    /// The bytes of region `r` (the slack at its largest).
    #[cfg_attr(not(any(test, feature = "_unstable-hooks")), allow(dead_code))]
    pub const fn bytes(&self, r: Region) -> usize {
        // Each product is a term of `total`, which did not overflow.
        match r {
            Region::Candidates => 4 * self.candidates,
            Region::RowIndex => 4 * self.row_index,
            Region::Lists => 4 * self.lists,
            Region::Sort => 4 * SORT_WORDS,
            Region::Rows => 4 * self.row_words,
            Region::Blur => self.blur_bytes,
            Region::Classes => self.class_bytes,
            Region::Visited => self.visited_bytes,
            Region::ClassRow => self.class_row,
            Region::Index => 4 * self.index,
            Region::Mags => self.mags,
            Region::Slack => ALIGN_SLACK,
        }
    }

    /// Whether the linking caches the directions of `groups` groups behind
    /// their records in [`Region::Candidates`]: two words per group. More
    /// than half the region in groups happens only on synthetic content;
    /// the walk then computes each direction as it looks a group up, a
    /// bounded cost per visit, with the same result.
    pub const fn caches_directions(&self, groups: usize) -> bool {
        groups <= self.candidates / 2
    }

    /// How many segments the merge can sort in [`Region::Candidates`]: two
    /// words each. Each strong segment links at least `min_groups` groups
    /// of at most C, so with `min_groups >= 2` every segment fits; beyond
    /// the room, segments are not merged (`stage::merge::merge_all`).
    pub const fn merge_room(&self) -> usize {
        self.candidates / 2
    }
}

/// `u32` scratch as `u16` values (always aligned).
pub(crate) fn as_u16(words: &mut [u32]) -> &mut [u16] {
    bytemuck::cast_slice_mut(words)
}

/// A region of `u32` words as such (`None` if misaligned: never, after
/// the slack).
#[inline(always)]
fn as_words(bytes: &mut [u8]) -> Option<&mut [u32]> {
    bytemuck::try_cast_slice_mut(bytes).ok()
}

/// Scratch memory for [`detect`](crate::detect()), borrowed from the caller.
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
    /// [`detect`](crate::detect()) call against [`Workspace::bytes_needed`].
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

    /// Bytes of workspace that [`detect`](crate::detect()) needs for a
    /// `width` x `height` image with `cfg`'s capacities, including 3 bytes of
    /// alignment slack. `None` when the dimensions are zero or over
    /// [`MAX_DIMENSION`] /
    /// [`MAX_PIXELS`], or the size overflows `usize`.
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

    /// Bytes of workspace with which [`detect`](crate::detect()) runs
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
        Some(Region::PLAIN.map(|r| (r.label(), l.bytes(r))))
    }

    /// Carves the slab for `layout`: the blurred image's region, and the
    /// others.
    pub(crate) fn carve(&mut self, layout: &Layout) -> Result<(&mut [u8], Slab<'_>), Error> {
        let got = self.buf.len();
        let too_small = Error::WorkspaceTooSmall {
            needed: layout.total,
            got,
        };
        if got < layout.total {
            return Err(too_small);
        }
        // The slack before the regions aligns them (they follow in
        // `Region::ALL`'s order: the `u32` ones first, as one block of
        // words); each region is the front of what is left.
        let pad = self.buf.as_ptr().align_offset(4).min(ALIGN_SLACK);
        let rest = self.buf.get_mut(pad..).ok_or(too_small)?;
        let words = layout.candidates + layout.row_index + layout.lists + layout.index + SORT_WORDS;
        fn take<'b, T>(rest: &mut &'b mut [T], n: usize, e: Error) -> Result<&'b mut [T], Error> {
            let (head, tail) = core::mem::take(rest).split_at_mut_checked(n).ok_or(e)?;
            *rest = tail;
            Ok(head)
        }
        let mut rest = rest;
        let mut w32 = as_words(take(&mut rest, words * 4, too_small)?).ok_or(too_small)?;
        let cand = take(&mut w32, layout.candidates, too_small)?;
        let row_index = take(&mut w32, layout.row_index, too_small)?;
        let lists = take(&mut w32, layout.lists, too_small)?;
        let index = take(&mut w32, layout.index, too_small)?;
        let sort = w32;
        let rows = as_words(take(&mut rest, layout.row_words * 4, too_small)?).ok_or(too_small)?;
        let blur = take(&mut rest, layout.blur_bytes, too_small)?;
        let classes = take(&mut rest, layout.class_bytes, too_small)?;
        let visited = take(&mut rest, layout.visited_bytes, too_small)?;
        let mags = take(&mut rest, layout.mags, too_small)?;
        let class_row = rest.get_mut(..layout.class_row).ok_or(too_small)?;
        let slab = Slab {
            layout: *layout,
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
        };
        Ok((blur, slab))
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
            let (blur, mut slab) = ws.carve(&layout).unwrap();
            assert_eq!(blur.len(), 33 * 17);
            assert_eq!(slab.smoothing().len(), 33 * 9 + 1);
            let a = slab.anchor_pass();
            assert_eq!(a.classes.len(), 9 * 17);
            assert_eq!(a.keys.len(), (5 * 17).max(layout.push_cap));
            assert_eq!(a.candidates.len(), layout.push_cap);
            assert_eq!(a.counts.len(), BUCKETS);
            let e = slab.extraction();
            assert_eq!(e.region.len(), layout.candidates);
            assert_eq!((e.counts.len(), e.starts.len()), (BUCKETS, BUCKETS));
            assert_eq!(e.spare.len() * 2, 33 * 9 + 1);
            let (t, l) = slab.linking();
            assert_eq!(t.records.len(), layout.candidates);
            assert_eq!((l.starts.len(), l.cursor.len()), (BUCKETS, BUCKETS));
            assert!(t.index.is_empty() && l.mags.is_empty());
            assert_eq!(slab.merge().pairs.len(), layout.candidates);
        }
        // The indexed layout: one more u16 per pixel (561, rounded up to
        // 562) and one more byte, the rest unchanged.
        let fast = layout.indexed().unwrap();
        assert_eq!(fast.total, layout.total + 2 * 562 + 561);
        assert_eq!(Workspace::bytes_needed_fast(33, 17, &cfg), Some(fast.total));
        let mut big = vec![0u8; fast.total + 3];
        for off in 0..4 {
            let mut ws = Workspace::new(&mut big[off..off + fast.total]);
            let (_, mut slab) = ws.carve(&fast).unwrap();
            // The index is longer than the row scratch: the extraction
            // orders its candidates there.
            assert_eq!(slab.extraction().spare.len(), 281);
            let (t, l) = slab.linking();
            assert_eq!((t.index.len(), l.mags.len()), (562, 561));
            assert_eq!(t.records.len(), layout.candidates);
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

    /// The regions' sizes add up to the total of each layout: sizing,
    /// carving and the memory report read the same sizes.
    #[test]
    fn regions_add_up_to_the_total() {
        let cfg = Config::DEFAULT;
        for (w, h) in [(1, 1), (33, 17), (320, 240), (INDEX_MAX_WIDTH + 1, 2)] {
            for in_place in [false, true] {
                let plain = Layout::compute(w, h, &cfg, in_place).unwrap();
                for l in [plain, plain.indexed().unwrap()] {
                    let sum: usize = Region::ALL.iter().map(|&r| l.bytes(r)).sum();
                    assert_eq!(sum, l.total, "{w}x{h}");
                }
                let listed: usize = Region::PLAIN.iter().map(|&r| plain.bytes(r)).sum();
                assert_eq!(listed, plain.total, "{w}x{h}");
            }
        }
    }

    /// The direction cache takes two words per group, the merge two per
    /// segment, both in the candidate region.
    #[test]
    fn candidate_region_roles_fit() {
        for per_mille in [0, 1, 7, 100] {
            let cfg = Config {
                candidates_per_mille: per_mille,
                ..Config::DEFAULT
            };
            let l = Layout::compute(37, 23, &cfg, false).unwrap();
            let c = l.candidates;
            for g in [0, 1, c / 2, c / 2 + 1, c] {
                assert_eq!(l.caches_directions(g), 2 * g <= c, "{c} {g}");
            }
            assert!(2 * l.merge_room() <= c && 2 * l.merge_room() + 2 > c);
        }
    }
}
