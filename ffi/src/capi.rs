//! The `aaglsd_*` entry points (see the crate docs in `lib.rs`); their
//! `#[repr(C)]` types are in `types.rs`. Kept free of crate-level
//! attributes so that the fuzz harness can include this file as a module.

use core::ffi::c_char;
use core::mem::size_of;
use core::ptr;

use aaglsd::{Config, Error, GrayImage, Profile, Segment, Summary, Workspace};

/// Largest accepted width or height, in pixels (`aaglsd::MAX_DIMENSION`).
pub const AAGLSD_MAX_DIMENSION: usize = 32_767;
/// Largest accepted pixel count `width * height` (`aaglsd::MAX_PIXELS`, 2^26).
pub const AAGLSD_MAX_PIXELS: usize = 67_108_864;

const _: () = assert!(AAGLSD_MAX_DIMENSION == aaglsd::MAX_DIMENSION);
const _: () = assert!(AAGLSD_MAX_PIXELS == aaglsd::MAX_PIXELS);

#[path = "types.rs"]
mod types;
pub use types::*;

/// `Result` with the C status as the error.
type Status<T> = Result<T, AaglsdStatus>;

/// Collapses a `Status<()>` into the returned code.
fn code(r: Status<()>) -> AaglsdStatus {
    match r {
        Ok(()) => AaglsdStatus::Ok,
        Err(s) => s,
    }
}

/// Reads a caller struct by copy (it may be unaligned).
///
/// # Safety
/// `p` is NULL or valid for reading one `T` (every bit pattern of `T` valid).
unsafe fn read_in<T: Copy>(p: *const T) -> Status<T> {
    if p.is_null() {
        return Err(AaglsdStatus::NullPointer);
    }
    // SAFETY: non-null and, by the caller's contract, readable; unaligned
    // reads are allowed by `read_unaligned`.
    Ok(unsafe { ptr::read_unaligned(p) })
}

/// Writes a caller struct (it may be unaligned). Does nothing for NULL.
///
/// # Safety
/// `p` is NULL or valid for writing one `T`.
unsafe fn write_out<T>(p: *mut T, v: T) {
    if !p.is_null() {
        // SAFETY: non-null and, by the caller's contract, writable.
        unsafe { ptr::write_unaligned(p, v) }
    }
}

/// Largest byte length a real buffer can have (`isize::MAX`): longer claims
/// are clamped so that building a slice from them is defined.
const MAX_BYTES: usize = isize::MAX as usize;

/// True when the byte ranges `[a, a + a_len)` and `[b, b + b_len)` share a
/// byte. Empty ranges overlap nothing.
fn overlaps(a: usize, a_len: usize, b: usize, b_len: usize) -> bool {
    a_len != 0 && b_len != 0 && a < b.saturating_add(b_len) && b < a.saturating_add(a_len)
}

/// The configuration of an `AaglsdProfile` value: the core's
/// [`Profile::code`] numbering (`status_values_are_the_core_codes`).
fn profile_config(profile: u32) -> Option<Config> {
    Profile::from_code(profile).map(Profile::config)
}

/// The library version, e.g. `"0.1.0"`: a static NUL-terminated string.
#[unsafe(no_mangle)]
pub extern "C" fn aaglsd_version() -> *const c_char {
    const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");
    VERSION.as_ptr().cast()
}

/// A static NUL-terminated English description of `status` (an
/// `AaglsdStatus` value); `"unknown status"` for any other value. Never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn aaglsd_status_str(status: i32) -> *const c_char {
    AaglsdStatus::by_value(status)
        .map_or(c"unknown status", |(_, text)| text)
        .as_ptr()
}

/// A static NUL-terminated name of `field` (an `AaglsdConfigField` value),
/// as written in `AaglsdConfig`; `"none"` for `AAGLSD_CONFIG_FIELD_NONE` and
/// `"unknown field"` for any other value. Never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn aaglsd_config_field_str(field: i32) -> *const c_char {
    // `Unknown` and the values no variant has read "unknown field".
    AaglsdConfigField::by_value(field)
        .map_or(c"unknown field", |(_, text)| text)
        .as_ptr()
}

/// Writes the default profile (`Config::DEFAULT`) to `*out`.
///
/// Returns `AAGLSD_STATUS_NULL_POINTER` when `out` is NULL.
///
/// # Safety
/// `out` is NULL or valid for writing one `AaglsdConfig` (any alignment).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_config_default(out: *mut AaglsdConfig) -> AaglsdStatus {
    // SAFETY: forwarded contract.
    unsafe { aaglsd_config_profile(AaglsdProfile::Default as u32, out) }
}

/// Writes the named profile (an `AaglsdProfile` value) to `*out`.
///
/// Returns `AAGLSD_STATUS_NULL_POINTER` when `out` is NULL and
/// `AAGLSD_STATUS_INVALID_ARGUMENT` (leaving `*out` untouched) for an unknown
/// profile.
///
/// # Safety
/// `out` is NULL or valid for writing one `AaglsdConfig` (any alignment).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_config_profile(
    profile: u32,
    out: *mut AaglsdConfig,
) -> AaglsdStatus {
    if out.is_null() {
        return AaglsdStatus::NullPointer;
    }
    match profile_config(profile) {
        Some(cfg) => {
            // SAFETY: non-null; writable by the caller's contract.
            unsafe { write_out(out, AaglsdConfig::from(&cfg)) };
            AaglsdStatus::Ok
        }
        None => AaglsdStatus::InvalidArgument,
    }
}

/// Checks every field of `*cfg` against its documented range (NaN is out of
/// range). Returns `AAGLSD_STATUS_OK` or `AAGLSD_STATUS_INVALID_CONFIG`, and
/// writes the first offending field (or `AAGLSD_CONFIG_FIELD_NONE`) to
/// `*field` unless `field` is NULL (it is optional).
///
/// Returns `AAGLSD_STATUS_NULL_POINTER` when `cfg` is NULL.
///
/// # Safety
/// `cfg` is NULL or valid for reading one `AaglsdConfig`; `field` is NULL or
/// valid for writing one `AaglsdConfigField` (any alignment).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_config_validate(
    cfg: *const AaglsdConfig,
    field: *mut AaglsdConfigField,
) -> AaglsdStatus {
    // SAFETY: forwarded contract.
    let c = match unsafe { read_in(cfg) } {
        Ok(c) => Config::from(&c),
        Err(s) => return s,
    };
    let (status, f) = match c.validate() {
        Ok(()) => (AaglsdStatus::Ok, AaglsdConfigField::None),
        Err(Error::InvalidConfig(f)) => (AaglsdStatus::InvalidConfig, f.into()),
        Err(e) => (e.into(), AaglsdConfigField::Unknown),
    };
    // SAFETY: NULL or writable by the caller's contract.
    unsafe { write_out(field, f) };
    status
}

/// Writes to `*out_bytes` the workspace size in bytes that `aaglsd_detect`
/// needs for a `width` x `height` image with `*cfg`'s capacities (the same
/// for every stride). The slab needs no particular alignment and may be
/// uninitialised; reuse it for any number of calls.
///
/// Checked in this order: `AAGLSD_STATUS_NULL_POINTER` (`cfg`,
/// `out_bytes`), `AAGLSD_STATUS_ZERO_DIMENSION`,
/// `AAGLSD_STATUS_IMAGE_TOO_LARGE`, `AAGLSD_STATUS_INVALID_CONFIG`. On error
/// `*out_bytes` is set to 0 (when not NULL).
///
/// # Safety
/// `cfg` is NULL or valid for reading one `AaglsdConfig`; `out_bytes` is NULL
/// or valid for writing one `size_t` (any alignment).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_workspace_size(
    width: usize,
    height: usize,
    cfg: *const AaglsdConfig,
    out_bytes: *mut usize,
) -> AaglsdStatus {
    // SAFETY: forwarded contract.
    unsafe { workspace_size(width, height, cfg, out_bytes, Workspace::bytes_needed) }
}

/// Writes to `*out_bytes` the workspace size with which `aaglsd_detect`
/// runs faster: `aaglsd_workspace_size`'s plus `3·width·height` bytes
/// (rounded up to 4) for a group index (one load per group lookup in the
/// linking) and a cache of the gradient magnitudes (read by the walk's
/// steps); the same size for an image wider than 4096 pixels, which gets
/// neither. The segments are the same with either size; this one
/// is for hosts with memory to spare. Checks and errors as
/// `aaglsd_workspace_size`.
///
/// # Safety
/// As `aaglsd_workspace_size`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_workspace_size_fast(
    width: usize,
    height: usize,
    cfg: *const AaglsdConfig,
    out_bytes: *mut usize,
) -> AaglsdStatus {
    // SAFETY: forwarded contract.
    unsafe { workspace_size(width, height, cfg, out_bytes, Workspace::bytes_needed_fast) }
}

/// Writes to `*out_bytes` the workspace size that `aaglsd_detect_in_place`
/// needs: `aaglsd_workspace_size`'s less the `width·height` bytes of the
/// smoothed image, which stays in the caller's frame. Adding the same
/// `3·width·height` bytes (rounded up to 4) as `aaglsd_workspace_size_fast`
/// adds gives `aaglsd_detect_in_place` the faster layout. Checks and errors
/// as `aaglsd_workspace_size`.
///
/// # Safety
/// As `aaglsd_workspace_size`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn aaglsd_workspace_size_in_place(
    width: usize,
    height: usize,
    cfg: *const AaglsdConfig,
    out_bytes: *mut usize,
) -> AaglsdStatus {
    // SAFETY: forwarded contract.
    unsafe {
        workspace_size(
            width,
            height,
            cfg,
            out_bytes,
            Workspace::bytes_needed_in_place,
        )
    }
}

/// The body of the three size functions, with the core's size function
/// `size`.
///
/// # Safety
/// As `aaglsd_workspace_size`.
unsafe fn workspace_size(
    width: usize,
    height: usize,
    cfg: *const AaglsdConfig,
    out_bytes: *mut usize,
    size: fn(usize, usize, &Config) -> Option<usize>,
) -> AaglsdStatus {
    let inner = || -> Status<usize> {
        if out_bytes.is_null() {
            return Err(AaglsdStatus::NullPointer);
        }
        // SAFETY: forwarded contract.
        let c = Config::from(&unsafe { read_in(cfg) }?);
        // The core's own dimension checks (an empty buffer passes them and
        // fails later, on its length).
        if let Err(e @ (Error::ZeroDimension { .. } | Error::ImageTooLarge { .. })) =
            GrayImage::new(&[], width, height, width)
        {
            return Err(e.into());
        }
        c.validate().map_err(AaglsdStatus::from)?;
        size(width, height, &c).ok_or(AaglsdStatus::ImageTooLarge)
    };
    let r = inner();
    // SAFETY: NULL or writable by the caller's contract.
    unsafe { write_out(out_bytes, r.unwrap_or(0)) };
    code(r.map(|_| ()))
}

/// Detects line segments in an 8-bit grayscale image.
///
/// `pixels` holds `height` rows of `width` bytes, each row starting `stride`
/// bytes after the previous one (`pixels_len >= stride * (height - 1) +
/// width`). `workspace` is a scratch slab of at least
/// `aaglsd_workspace_size` bytes, or of `aaglsd_workspace_size_fast` bytes
/// for the faster run with the same result (any alignment, may be
/// uninitialised: the first `aaglsd_workspace_size` or
/// `aaglsd_workspace_size_fast` bytes, whichever the slab holds, are zeroed
/// before use, and so are the `out_capacity` output slots, once every check
/// has passed).
/// Up to `out_capacity` segments are written to the front of `out`; the
/// summary gives their number and counts those that did not fit.
///
/// Checked in this order, before anything is written:
/// 1. `AAGLSD_STATUS_NULL_POINTER`: any pointer is NULL (all are required);
/// 2. `AAGLSD_STATUS_MISALIGNED`: `out` is not 4-byte aligned;
/// 3. `AAGLSD_STATUS_BUFFERS_OVERLAP`: two of `pixels[0..pixels_len]`,
///    `workspace[0..workspace_len]`, `out[0..out_capacity]` share a byte;
/// 4. the image: `ZERO_DIMENSION`, `IMAGE_TOO_LARGE`, `STRIDE_TOO_SMALL`,
///    `BUFFER_TOO_SHORT`;
/// 5. `AAGLSD_STATUS_INVALID_CONFIG` (see `aaglsd_config_validate`);
/// 6. `AAGLSD_STATUS_WORKSPACE_TOO_SMALL`;
/// 7. `AAGLSD_STATUS_OUTPUT_EMPTY`: `out_capacity` is 0.
///
/// On error, `out` is untouched, the workspace content is unspecified and
/// `*summary` is zeroed (when not NULL).
///
/// # Safety
/// Each pointer is NULL or valid for its length: `pixels` readable for
/// `pixels_len` bytes, `workspace` writable for `workspace_len` bytes, `out`
/// writable for `out_capacity` segments, `cfg` readable and `summary`
/// writable for one struct (any alignment). The buffers may not be written
/// by anyone else during the call.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)] // the C signature: one pointer and one length per buffer
pub unsafe extern "C" fn aaglsd_detect(
    pixels: *const u8,
    pixels_len: usize,
    width: usize,
    height: usize,
    stride: usize,
    cfg: *const AaglsdConfig,
    workspace: *mut u8,
    workspace_len: usize,
    out: *mut AaglsdSegment,
    out_capacity: usize,
    summary: *mut AaglsdSummary,
) -> AaglsdStatus {
    let buffers = Buffers {
        pixels: Pixels::Read(pixels),
        pixels_len,
        workspace,
        workspace_len,
        out,
        out_capacity,
    };
    // SAFETY: forwarded contract.
    unsafe { detect_c(buffers, width, height, stride, cfg, summary) }
}

/// `aaglsd_detect` on a frame that it may overwrite: the frame is smoothed
/// in place, so the workspace needs no copy of the image
/// (`aaglsd_workspace_size_in_place`, `width·height` bytes less than
/// `aaglsd_workspace_size`). The segments and the summary are the same as
/// `aaglsd_detect`'s on the same pixels. Afterwards the first
/// `width·height` bytes of `frame` hold the smoothed image, rows packed;
/// the rest of it is unchanged.
///
/// A camera frame in another format (YUYV, RGB565) can be reduced to its
/// luma in the same buffer first, rows packed, so that one `w·h` buffer
/// serves both (`ffi/firmware/`).
///
/// Checks and errors as `aaglsd_detect`, with the workspace checked against
/// `aaglsd_workspace_size_in_place`. On error, `frame` and `out` are
/// untouched, and `*summary` is zeroed (when not NULL).
///
/// # Safety
/// As `aaglsd_detect`, with `frame` readable and writable for `frame_len`
/// bytes.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)] // the C signature: one pointer and one length per buffer
pub unsafe extern "C" fn aaglsd_detect_in_place(
    frame: *mut u8,
    frame_len: usize,
    width: usize,
    height: usize,
    stride: usize,
    cfg: *const AaglsdConfig,
    workspace: *mut u8,
    workspace_len: usize,
    out: *mut AaglsdSegment,
    out_capacity: usize,
    summary: *mut AaglsdSummary,
) -> AaglsdStatus {
    let buffers = Buffers {
        pixels: Pixels::Frame(frame),
        pixels_len: frame_len,
        workspace,
        workspace_len,
        out,
        out_capacity,
    };
    // SAFETY: forwarded contract.
    unsafe { detect_c(buffers, width, height, stride, cfg, summary) }
}

/// The caller's pixels: read only (`aaglsd_detect`), or a frame to smooth
/// in place (`aaglsd_detect_in_place`).
#[derive(Clone, Copy)]
enum Pixels {
    Read(*const u8),
    Frame(*mut u8),
}

impl Pixels {
    fn addr(self) -> *const u8 {
        match self {
            Pixels::Read(p) => p,
            Pixels::Frame(p) => p.cast_const(),
        }
    }
}

/// The three caller buffers of a detection and their lengths.
struct Buffers {
    pixels: Pixels,
    pixels_len: usize,
    workspace: *mut u8,
    workspace_len: usize,
    out: *mut AaglsdSegment,
    out_capacity: usize,
}

/// The body of `aaglsd_detect` and `aaglsd_detect_in_place`.
///
/// # Safety
/// As `aaglsd_detect` (for a `Pixels::Frame`, as `aaglsd_detect_in_place`).
unsafe fn detect_c(
    b: Buffers,
    width: usize,
    height: usize,
    stride: usize,
    cfg: *const AaglsdConfig,
    summary: *mut AaglsdSummary,
) -> AaglsdStatus {
    let Buffers {
        pixels,
        pixels_len,
        workspace,
        workspace_len,
        out,
        out_capacity,
    } = b;
    let in_place = matches!(pixels, Pixels::Frame(_));
    let inner = || -> Status<Summary> {
        if pixels.addr().is_null()
            || cfg.is_null()
            || workspace.is_null()
            || out.is_null()
            || summary.is_null()
        {
            return Err(AaglsdStatus::NullPointer);
        }
        if !out.is_aligned() {
            return Err(AaglsdStatus::Misaligned);
        }
        let pixels_len = pixels_len.min(MAX_BYTES);
        let workspace_len = workspace_len.min(MAX_BYTES);
        let out_capacity = out_capacity.min(MAX_BYTES / size_of::<AaglsdSegment>());
        let out_bytes = out_capacity * size_of::<AaglsdSegment>(); // <= MAX_BYTES
        let (p, w, o) = (pixels.addr().addr(), workspace.addr(), out.addr());
        if overlaps(p, pixels_len, w, workspace_len)
            || overlaps(p, pixels_len, o, out_bytes)
            || overlaps(w, workspace_len, o, out_bytes)
        {
            return Err(AaglsdStatus::BuffersOverlap);
        }
        // SAFETY: non-null, readable by the caller's contract.
        let c = Config::from(&unsafe { read_in(cfg) }?);
        // SAFETY: non-null; readable for `pixels_len` bytes (clamped to
        // isize::MAX); not accessed by anyone else during the call and
        // disjoint from the two other buffers (checked above). This shared
        // slice is dead before the frame's mutable one is made.
        let data = unsafe { core::slice::from_raw_parts(pixels.addr(), pixels_len) };
        GrayImage::new(data, width, height, stride)?;
        // The core's remaining checks, in its order, before anything is
        // written (so `out` and the frame stay untouched on any error):
        // config, workspace size, output capacity.
        c.validate()?;
        let size = if in_place {
            Workspace::bytes_needed_in_place
        } else {
            Workspace::bytes_needed
        };
        let needed = size(width, height, &c).ok_or(AaglsdStatus::ImageTooLarge)?;
        if workspace_len < needed {
            return Err(Error::WorkspaceTooSmall {
                needed,
                got: workspace_len,
            }
            .into());
        }
        // The group index and magnitude cache when the workspace holds
        // them: the same bytes on top of either size.
        let extra = match (
            Workspace::bytes_needed_fast(width, height, &c),
            Workspace::bytes_needed(width, height, &c),
        ) {
            (Some(fast), Some(plain)) => fast - plain,
            _ => 0,
        };
        let needed = match needed.checked_add(extra) {
            Some(fast) if workspace_len >= fast => fast,
            _ => needed,
        };
        if out_capacity == 0 {
            return Err(AaglsdStatus::OutputEmpty);
        }
        // C callers pass `malloc` memory: initialise the part of each buffer
        // that becomes a Rust slice, through raw pointers, so that no
        // reference ever covers uninitialised bytes (about 1% of a frame).
        // SAFETY: non-null; writable for `workspace_len >= needed` bytes and
        // for `out_capacity` segments (caller contract); `out` is aligned
        // (checked); nothing else refers to these bytes now.
        unsafe {
            ptr::write_bytes(workspace, 0, needed);
            ptr::write_bytes(out, 0, out_capacity);
        }
        // SAFETY: non-null; `needed` initialised bytes (above), writable;
        // disjoint from the other buffers (checked).
        let slab = unsafe { core::slice::from_raw_parts_mut(workspace, needed) };
        // SAFETY: non-null and aligned (checked); `out_capacity` initialised
        // segments (above); `AaglsdSegment` and `Segment` have the same
        // layout (asserted at compile time); disjoint from the other buffers.
        let segs = unsafe { core::slice::from_raw_parts_mut(out.cast::<Segment>(), out_capacity) };
        let ws = &mut Workspace::new(slab);
        match pixels {
            Pixels::Read(_) => {
                let img = GrayImage::new(data, width, height, stride)?;
                Ok(aaglsd::detect(&img, &c, ws, segs)?)
            }
            Pixels::Frame(frame) => {
                // SAFETY: non-null; readable and writable for `pixels_len`
                // bytes by the caller's contract; disjoint from the other
                // buffers (checked); the shared `data` is not used again.
                let frame = unsafe { core::slice::from_raw_parts_mut(frame, pixels_len) };
                Ok(aaglsd::detect_in_place(
                    frame, width, height, stride, &c, ws, segs,
                )?)
            }
        }
    };
    let r = inner();
    let s = r.map(AaglsdSummary::from).unwrap_or_default();
    // SAFETY: NULL or writable by the caller's contract; the slices above are
    // dead.
    unsafe { write_out(summary, s) };
    code(r.map(|_| ()))
}
