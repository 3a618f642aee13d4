//! `aaglsd` for `wasm32-unknown-unknown`, with raw exports and no
//! wasm-bindgen: the module owns static buffers (an image of up to
//! [`MAX_WIDTH`] x [`MAX_HEIGHT`], the workspace for it, [`MAX_SEGMENTS`]
//! output segments and a summary), JavaScript writes pixels into the image
//! buffer and reads the results from linear memory.
//!
//! Exports (wasm32 only; `usize` and pointers are `u32` there):
//!
//! | export | returns |
//! |---|---|
//! | `memory` | the linear memory |
//! | `image_ptr()` | address of the image buffer: `height` rows of `width` bytes, packed |
//! | `segments_ptr()` | address of the output: `x0 y0 x1 y1` as `f32`, 16 bytes per segment |
//! | `summary_ptr()` | address of 7 `u32`: segments, dropped_segments, dropped_candidates, truncated_linkings, candidates, groups, merged |
//! | `max_width()`, `max_height()`, `max_segments()` | the buffer capacities |
//! | `detect(width, height, profile)` | the segment count (>= 0), or a negative [`Status`] |
//!
//! `profile` is 0 (default), 1 (official) or 2 (paper), as `AaglsdProfile`
//! in the C header. The same functions exist on other targets (without
//! `no_mangle`) so that the host tests run them.
#![cfg_attr(target_arch = "wasm32", no_std)]
#![deny(missing_docs, unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicBool, Ordering};

use aaglsd::{Config, Error, GrayImage, Segment, Summary, Workspace};

/// Widest image the static buffers hold.
pub const MAX_WIDTH: usize = 640;
/// Tallest image the static buffers hold.
pub const MAX_HEIGHT: usize = 480;
/// Output capacity in segments. With merging on (the paper profile) it
/// also holds the fragments before they are merged; more than this many
/// are dropped and counted in the summary.
pub const MAX_SEGMENTS: usize = 2048;
/// Number of `u32` values at `summary_ptr()`.
pub const SUMMARY_LEN: usize = 7;

const IMAGE_BYTES: usize = MAX_WIDTH * MAX_HEIGHT;

/// The larger of two workspace sizes for the maximal image.
const fn max_workspace(a: &Config, b: &Config) -> usize {
    let (x, y) = (
        Workspace::bytes_needed(MAX_WIDTH, MAX_HEIGHT, a),
        Workspace::bytes_needed(MAX_WIDTH, MAX_HEIGHT, b),
    );
    match (x, y) {
        (Some(x), Some(y)) if x > y => x,
        (Some(_), Some(y)) => y,
        _ => panic!("MAX_WIDTH x MAX_HEIGHT is a valid image size"),
    }
}

/// Enough workspace for every profile at up to `MAX_WIDTH` x `MAX_HEIGHT`
/// (the size grows with both dimensions).
const WORKSPACE_BYTES: usize = max_workspace(&Config::OFFICIAL, &Config::PAPER);
const _: () = assert!(WORKSPACE_BYTES >= Workspace::bytes_needed_default(MAX_WIDTH, MAX_HEIGHT));

/// Result codes of `detect`, negated. The numbers are those of
/// `AaglsdStatus` in the C header (`ffi/include/aaglsd.h`).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Width or height is zero.
    ZeroDimension = 1,
    /// The image exceeds `MAX_WIDTH` x `MAX_HEIGHT` (or the core's limits).
    ImageTooLarge = 2,
    /// (Not returned: the image buffer is packed.)
    StrideTooSmall = 3,
    /// (Not returned: the image buffer always holds the image.)
    BufferTooShort = 4,
    /// (Not returned: the workspace is sized for the largest image.)
    WorkspaceTooSmall = 5,
    /// (Not returned: the output holds `MAX_SEGMENTS`.)
    OutputEmpty = 6,
    /// A configuration field is out of range.
    InvalidConfig = 7,
    /// `profile` is not 0, 1 or 2.
    InvalidArgument = 11,
    /// An error of the core that this crate does not know.
    Unknown = 12,
    /// `detect` was called while another call was running (only possible
    /// with threads; never from single-threaded JavaScript).
    Busy = 13,
}

impl From<Error> for Status {
    fn from(e: Error) -> Self {
        match e {
            Error::ZeroDimension { .. } => Self::ZeroDimension,
            Error::ImageTooLarge { .. } => Self::ImageTooLarge,
            Error::StrideTooSmall { .. } => Self::StrideTooSmall,
            Error::BufferTooShort { .. } => Self::BufferTooShort,
            Error::WorkspaceTooSmall { .. } => Self::WorkspaceTooSmall,
            Error::OutputEmpty => Self::OutputEmpty,
            Error::InvalidConfig(_) => Self::InvalidConfig,
            _ => Self::Unknown,
        }
    }
}

/// The configuration of a profile number (0 default, 1 official, 2 paper).
pub const fn profile_config(profile: u32) -> Option<Config> {
    match profile {
        0 => Some(Config::DEFAULT),
        1 => Some(Config::OFFICIAL),
        2 => Some(Config::PAPER),
        _ => None,
    }
}

/// The summary as the 7 `u32` values published at `summary_ptr()`.
pub fn summary_words(s: &Summary) -> [u32; SUMMARY_LEN] {
    let Summary {
        segments,
        dropped_segments,
        dropped_candidates,
        truncated_linkings,
        candidates,
        groups,
        merged,
    } = *s;
    [
        segments,
        dropped_segments,
        dropped_candidates,
        truncated_linkings,
        candidates,
        groups,
        merged,
    ]
    .map(|v| u32::try_from(v).unwrap_or(u32::MAX))
}

/// What `detect` does, on caller buffers of any size: runs the detector on
/// the `width` x `height` image in `image` (rows packed) with a profile, and
/// returns the segment count. `summary` is zeroed on error.
///
/// # Errors
/// [`Status::InvalidArgument`] for an unknown profile, then whatever the
/// core reports for the buffers given.
pub fn detect_into(
    image: &[u8],
    width: usize,
    height: usize,
    profile: u32,
    workspace: &mut [u8],
    out: &mut [Segment],
    summary: &mut [u32; SUMMARY_LEN],
) -> Result<usize, Status> {
    *summary = [0; SUMMARY_LEN];
    let cfg = profile_config(profile).ok_or(Status::InvalidArgument)?;
    let img = GrayImage::new(image, width, height, width)?;
    let s = aaglsd::detect(&img, &cfg, &mut Workspace::new(workspace), out)?;
    *summary = summary_words(&s);
    Ok(s.segments)
}

/// A static buffer shared with JavaScript through its address.
#[repr(transparent)]
struct Shared<T>(UnsafeCell<T>);

// SAFETY: the contents are only accessed inside `detect`, which the `BUSY`
// flag makes exclusive, and by the host (JavaScript) between calls.
unsafe impl<T> Sync for Shared<T> {}

impl<T> Shared<T> {
    const fn get(&self) -> *mut T {
        self.0.get()
    }
}

const ZERO_SEGMENT: Segment = Segment {
    x0: 0.0,
    y0: 0.0,
    x1: 0.0,
    y1: 0.0,
};

static IMAGE: Shared<[u8; IMAGE_BYTES]> = Shared(UnsafeCell::new([0; IMAGE_BYTES]));
static WORKSPACE: Shared<[u8; WORKSPACE_BYTES]> = Shared(UnsafeCell::new([0; WORKSPACE_BYTES]));
static SEGMENTS: Shared<[Segment; MAX_SEGMENTS]> =
    Shared(UnsafeCell::new([ZERO_SEGMENT; MAX_SEGMENTS]));
static SUMMARY: Shared<[u32; SUMMARY_LEN]> = Shared(UnsafeCell::new([0; SUMMARY_LEN]));
static BUSY: AtomicBool = AtomicBool::new(false);

/// Address of the image buffer (`max_width() * max_height()` bytes).
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn image_ptr() -> *mut u8 {
    IMAGE.get().cast()
}

/// Address of the output segments (`max_segments()` of them).
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn segments_ptr() -> *const Segment {
    SEGMENTS.get().cast()
}

/// Address of the summary (7 `u32`, see the crate docs).
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn summary_ptr() -> *const u32 {
    SUMMARY.get().cast()
}

/// [`MAX_WIDTH`].
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn max_width() -> usize {
    MAX_WIDTH
}

/// [`MAX_HEIGHT`].
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn max_height() -> usize {
    MAX_HEIGHT
}

/// [`MAX_SEGMENTS`].
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn max_segments() -> usize {
    MAX_SEGMENTS
}

/// Detects the segments of the `width` x `height` image in the image buffer
/// with profile `profile`; returns their number, written from
/// `segments_ptr()`, or a negative [`Status`]. The summary is rewritten on
/// every call (zeroed on error).
#[cfg_attr(target_arch = "wasm32", unsafe(no_mangle))]
pub extern "C" fn detect(width: u32, height: u32, profile: u32) -> i32 {
    if BUSY
        .compare_exchange(false, true, Ordering::Acquire, Ordering::Relaxed)
        .is_err()
    {
        return -(Status::Busy as i32);
    }
    // SAFETY: `BUSY` is held, so no other `detect` touches the buffers, and
    // nothing else in Rust creates references to them; the host only
    // accesses them between calls. The four statics are distinct.
    let (image, workspace, out, summary) = unsafe {
        (
            &*IMAGE.get(),
            &mut *WORKSPACE.get(),
            &mut *SEGMENTS.get(),
            &mut *SUMMARY.get(),
        )
    };
    let (w, h) = (width as usize, height as usize); // u32 fits usize on wasm32 and hosts
    let r = if w == 0 || h == 0 {
        Err(Status::ZeroDimension)
    } else if w > MAX_WIDTH || h > MAX_HEIGHT {
        Err(Status::ImageTooLarge)
    } else {
        detect_into(image, w, h, profile, workspace, out, summary)
    };
    if r.is_err() {
        *summary = [0; SUMMARY_LEN];
    }
    BUSY.store(false, Ordering::Release);
    match r {
        // At most MAX_SEGMENTS.
        Ok(n) => i32::try_from(n).unwrap_or(i32::MAX),
        Err(s) => -(s as i32),
    }
}

/// The panic handler of the no_std wasm module: nothing here or in the core
/// panics (the core denies every panicking construct), so this is a
/// backstop that traps.
#[cfg(all(target_arch = "wasm32", not(test)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    core::arch::wasm32::unreachable()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The README's dark rectangle, 64 x 48.
    fn rectangle() -> (usize, usize, Vec<u8>) {
        let (w, h) = (64, 48);
        let mut px = vec![200u8; w * h];
        for y in 12..36 {
            for x in 16..48 {
                px[y * w + x] = 40;
            }
        }
        (w, h, px)
    }

    fn core_detect(px: &[u8], w: usize, h: usize, cfg: &Config) -> (Summary, Vec<Segment>) {
        let img = GrayImage::new(px, w, h, w).unwrap();
        let mut slab = vec![0u8; Workspace::bytes_needed(w, h, cfg).unwrap()];
        let mut out = vec![Segment::default(); MAX_SEGMENTS];
        let s = aaglsd::detect(&img, cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
        out.truncate(s.segments);
        (s, out)
    }

    fn bits(s: &[Segment]) -> Vec<[u32; 4]> {
        s.iter()
            .map(|s| [s.x0, s.y0, s.x1, s.y1].map(f32::to_bits))
            .collect()
    }

    /// The only test that touches the static buffers (tests run in threads).
    #[test]
    fn exported_functions_on_the_static_buffers() {
        let (w, h, px) = rectangle();
        // SAFETY: no `detect` runs now; the buffer holds MAX_WIDTH*MAX_HEIGHT bytes.
        unsafe { core::ptr::copy_nonoverlapping(px.as_ptr(), image_ptr(), px.len()) };
        for profile in 0..3 {
            let cfg = profile_config(profile).unwrap();
            let (want_summary, want) = core_detect(&px, w, h, &cfg);
            let n = detect(w as u32, h as u32, profile);
            assert_eq!(n, want.len() as i32);
            // SAFETY: detect returned; n <= MAX_SEGMENTS segments were written.
            let got = unsafe { core::slice::from_raw_parts(segments_ptr(), n as usize) };
            assert_eq!(bits(got), bits(&want));
            // SAFETY: as above; SUMMARY_LEN words.
            let summary = unsafe { *summary_ptr().cast::<[u32; SUMMARY_LEN]>() };
            assert_eq!(summary, summary_words(&want_summary));
        }
        assert_eq!(detect(0, 10, 0), -(Status::ZeroDimension as i32));
        assert_eq!(detect(10, 0, 0), -(Status::ZeroDimension as i32));
        assert_eq!(detect(641, 1, 0), -(Status::ImageTooLarge as i32));
        assert_eq!(detect(1, 481, 0), -(Status::ImageTooLarge as i32));
        assert_eq!(detect(1000, 300, 0), -(Status::ImageTooLarge as i32));
        assert_eq!(detect(0, u32::MAX, 0), -(Status::ZeroDimension as i32));
        assert_eq!(
            detect(u32::MAX, u32::MAX, 0),
            -(Status::ImageTooLarge as i32)
        );
        assert_eq!(
            detect(w as u32, h as u32, 3),
            -(Status::InvalidArgument as i32)
        );
        // SAFETY: as above.
        assert_eq!(unsafe { *summary_ptr() }, 0, "zeroed on error");
        assert_eq!(
            (max_width(), max_height(), max_segments()),
            (640, 480, 2048)
        );
    }

    #[test]
    fn rectangle_has_four_sides() {
        let (w, h, px) = rectangle();
        let mut ws = vec![0u8; WORKSPACE_BYTES];
        let mut out = vec![Segment::default(); 16];
        let mut summary = [0; SUMMARY_LEN];
        let n = detect_into(&px, w, h, 0, &mut ws, &mut out, &mut summary).unwrap();
        assert_eq!(n, 4);
        assert_eq!(summary[0], 4);
        assert!(out[..n].iter().all(|s| s.length() > 15.0));
    }

    #[test]
    #[cfg_attr(miri, ignore = "a 640 x 480 image takes minutes under Miri")]
    fn largest_image_fits_the_static_workspace() {
        let px = vec![0u8; IMAGE_BYTES];
        let mut ws = vec![0u8; WORKSPACE_BYTES];
        let mut out = vec![Segment::default(); 4];
        let mut summary = [0; SUMMARY_LEN];
        for profile in 0..3 {
            let r = detect_into(
                &px,
                MAX_WIDTH,
                MAX_HEIGHT,
                profile,
                &mut ws,
                &mut out,
                &mut summary,
            );
            assert_eq!(r, Ok(0));
        }
    }
}
