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
//! | pixel state | `u8` | `w·h` | anchor class, group link, linked and visited bits |
//! | magnitude | `u8` | `w·h` | `min(m, 255)`: the walk reads three per step (255 means "recompute exactly") |
//! | candidates in raster order, then the group centres in raster order | `u32` | `C` | groups ≤ candidates; the binary-search key of the direction cache |
//! | candidates sorted, then groups in id order + their directions | `u32` | `C` | groups ≤ candidates; directions are cached when `2·groups ≤ C` |
//! | visited + undo lists | `u32` | `V + V/3 + 1` | one linking: a group adds 3 visited pixels, so links ≤ V/3 |
//! | row scratch | `u16` | `9·w` | blur: 5 rows; gradient ring: 3 rows of m, gx, gy |
//! | histogram | `u32` | 256 | counting sort keys `min(m, 255)` |
//!
//! `C = w·h·candidates_per_mille/1000 + 64` and `V = max_link_pixels`, both
//! from [`Config`]. Running out of `C` drops the weakest candidates; running
//! out of `V` ends a linking early. Both are counted in
//! [`Summary`](crate::Summary), never errors. Up to 3 bytes of slack let the
//! `u32` regions start aligned whatever the slab's address.

use crate::image::{MAX_DIMENSION, MAX_PIXELS};
use crate::{Config, Error};

/// Byte offsets and capacities of the workspace regions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Pixel count `w·h`.
    pub pixels: usize,
    /// Candidate capacity C.
    pub candidates: usize,
    /// Visited-list capacity V.
    pub visited: usize,
    /// Undo-list capacity.
    pub undo: usize,
    /// `u32` words of the visited + undo lists.
    pub lists: usize,
    /// `u32` words of region A (raster candidates / visited + undo).
    pub words_a: usize,
    /// `u16` words of row scratch.
    pub row_words: usize,
    /// Total bytes, including alignment slack.
    pub total: usize,
}

/// `u16` rows of scratch per image column.
pub(crate) const ROW_SCRATCH_PER_COLUMN: usize = 9;
/// Histogram bins.
pub(crate) const HISTOGRAM_BINS: usize = 256;
/// Bytes of alignment slack.
const ALIGN_SLACK: usize = 3;

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
    /// is zero or over the limits, or a size overflows `usize`.
    pub const fn compute(width: usize, height: usize, cfg: &Config) -> Option<Self> {
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return None;
        }
        let pixels = width * height; // <= 32767², no overflow on 32-bit usize
        if pixels > MAX_PIXELS {
            return None;
        }
        let per_mille = cfg.candidates_per_mille as usize;
        let candidates = tri!(tri!(pixels.checked_mul(per_mille)).checked_div(1000));
        let candidates = tri!(candidates.checked_add(64));
        let visited = cfg.max_link_pixels as usize;
        let undo = visited / 3 + 1;
        let lists = tri!(visited.checked_add(undo));
        let words_a = candidates;
        let row_words = tri!(width.checked_mul(ROW_SCRATCH_PER_COLUMN));
        // u32 regions first (aligned), then u16, then bytes.
        let mut total = ALIGN_SLACK;
        total = tri!(total.checked_add(tri!(words_a.checked_mul(4))));
        total = tri!(total.checked_add(tri!(candidates.checked_mul(4))));
        total = tri!(total.checked_add(tri!(lists.checked_mul(4))));
        total = tri!(total.checked_add(HISTOGRAM_BINS * 4));
        total = tri!(total.checked_add(tri!(row_words.checked_mul(2))));
        total = tri!(total.checked_add(tri!(pixels.checked_mul(3))));
        Some(Self {
            pixels,
            candidates,
            visited,
            undo,
            lists,
            words_a,
            row_words,
            total,
        })
    }
}

/// The regions of a carved workspace.
pub(crate) struct Regions<'a> {
    pub blur: &'a mut [u8],
    pub state: &'a mut [u8],
    pub mag: &'a mut [u8],
    pub region_a: &'a mut [u32],
    pub sorted: &'a mut [u32],
    pub lists: &'a mut [u32],
    pub histogram: &'a mut [u32],
    pub rows: &'a mut [u16],
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
    /// 3.8 to 4.0 bytes per pixel at the default capacities (see the README's
    /// memory report).
    pub const fn bytes_needed(width: usize, height: usize, cfg: &Config) -> Option<usize> {
        match Layout::compute(width, height, cfg) {
            Some(l) => Some(l.total),
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
    ) -> Option<[(&'static str, usize); 9]> {
        let l = Layout::compute(width, height, cfg)?;
        Some([
            ("blurred image (u8 per pixel)", l.pixels),
            ("pixel state (u8 per pixel)", l.pixels),
            ("magnitude cache (u8 per pixel)", l.pixels),
            (
                "candidates, raster order / group centres (u32)",
                l.words_a * 4,
            ),
            (
                "candidates, sorted / groups + directions (u32)",
                l.candidates * 4,
            ),
            ("visited + undo lists (u32)", l.lists * 4),
            ("row scratch (u16, 9 rows)", l.row_words * 2),
            ("histogram (256 u32)", HISTOGRAM_BINS * 4),
            ("alignment slack", ALIGN_SLACK),
        ])
    }

    /// Carves the slab for `layout`.
    pub(crate) fn carve(&mut self, layout: &Layout) -> Result<Regions<'_>, Error> {
        let got = self.buf.len();
        if got < layout.total {
            return Err(Error::WorkspaceTooSmall {
                needed: layout.total,
                got,
            });
        }
        let too_small = Error::WorkspaceTooSmall {
            needed: layout.total,
            got,
        };
        let pad = self.buf.as_ptr().align_offset(4).min(ALIGN_SLACK);
        let rest = self.buf.get_mut(pad..).ok_or(too_small)?;
        let words = layout.words_a + layout.candidates + layout.lists + HISTOGRAM_BINS;
        let (w32, rest) = rest.split_at_mut_checked(words * 4).ok_or(too_small)?;
        let w32: &mut [u32] = bytemuck::try_cast_slice_mut(w32).map_err(|_| too_small)?;
        let (region_a, w32) = w32.split_at_mut_checked(layout.words_a).ok_or(too_small)?;
        let (sorted, w32) = w32
            .split_at_mut_checked(layout.candidates)
            .ok_or(too_small)?;
        let (lists, histogram) = w32.split_at_mut_checked(layout.lists).ok_or(too_small)?;
        let (w16, rest) = rest
            .split_at_mut_checked(layout.row_words * 2)
            .ok_or(too_small)?;
        let rows: &mut [u16] = bytemuck::try_cast_slice_mut(w16).map_err(|_| too_small)?;
        let (blur, rest) = rest.split_at_mut_checked(layout.pixels).ok_or(too_small)?;
        let (state, rest) = rest.split_at_mut_checked(layout.pixels).ok_or(too_small)?;
        let mag = rest.get_mut(..layout.pixels).ok_or(too_small)?;
        Ok(Regions {
            blur,
            state,
            mag,
            region_a,
            sorted,
            lists,
            histogram,
            rows,
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
        // The memory goal: at most 4 bytes per pixel at the default
        // capacities for the documented sizes.
        for (w, h) in [(320, 240), (640, 480), (1064, 708)] {
            let n = Workspace::bytes_needed(w, h, &cfg).unwrap();
            let per_px = n as f64 / (w * h) as f64;
            assert!(per_px > 3.0 && per_px <= 4.0, "{w}x{h}: {per_px}");
        }
    }

    #[test]
    fn carving_any_alignment() {
        let cfg = Config::DEFAULT;
        let layout = Layout::compute(33, 17, &cfg).unwrap();
        let mut slab = vec![0u8; layout.total + 8];
        for off in 0..4 {
            let mut ws = Workspace::new(&mut slab[off..off + layout.total]);
            let r = ws.carve(&layout).unwrap();
            assert_eq!(r.blur.len(), 33 * 17);
            assert_eq!(r.state.len(), 33 * 17);
            assert_eq!(r.sorted.len(), layout.candidates);
            assert_eq!(r.histogram.len(), 256);
            assert_eq!(r.rows.len(), 33 * 9);
        }
        let mut short = vec![0u8; layout.total - 1];
        let mut ws = Workspace::new(&mut short);
        assert!(matches!(
            ws.carve(&layout),
            Err(Error::WorkspaceTooSmall { .. })
        ));
    }
}
