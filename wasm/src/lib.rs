//! `aaglsd` for `wasm32-unknown-unknown`, with raw exports and no
//! wasm-bindgen: buffers of any size live in the module's linear memory,
//! sized for each call with the core's `Workspace::bytes_needed`, and the
//! configuration is passed as the C ABI's `#[repr(C)] AaglsdConfig` (the
//! same definition, included from `ffi/src/types.rs`).
//!
//! Exports (wasm32 only; `usize` and pointers are `u32` there, `i32` in JS):
//!
//! | export | returns |
//! |---|---|
//! | `memory` | the linear memory |
//! | `alloc(n)` | a 16-byte aligned block of `n` bytes (growing the memory), or 0 |
//! | `release(ptr)` | frees `ptr` and every block allocated after it; 0 or `-status` |
//! | `config_size()`, `config_field_offset(i)` | the `AaglsdConfig` layout: size, offset of field `i` (in [`FIELD_NAMES`] order) |
//! | `config_profile(profile, cfg)` | writes profile 0 (default), 1 (official) or 2 (paper) to `cfg`; 0 or `-status` |
//! | `config_validate(cfg)` | 0, the `ConfigField` code (1..=14) of the first bad field, or `-status` |
//! | `workspace_size(w, h, cfg)` | workspace bytes for a `w` x `h` image, or `-status` |
//! | `default_max_segments(w, h)` | the output capacity the JS wrapper and the CLI use: `max(w*h/16, 64)` |
//! | `segment_size()` | [`SEGMENT_BYTES`], the bytes of one output segment (20) |
//! | `simd128()` | 1 when the module was built with the `simd128` target feature, else 0 |
//! | `detect(img, img_len, w, h, stride, cfg, ws, ws_len, out, out_cap, summary)` | the segment count, or `-status`; `out` gets `x0 y0 x1 y1 score` as `f32` per segment |
//! | `status_name(code, buf, cap)`, `config_field_name(code, buf, cap)` | copies the name to `buf`; its length or `-status` |
//!
//! Every pointer is checked before use: NULL is [`Status::NullPointer`], a
//! block that is not wholly inside the caller's part of the memory (from
//! `__heap_base` to the memory's end: never the module's stack or data) is
//! [`Status::OutOfBounds`]. So no argument makes an export trap. The
//! statuses are those of `AaglsdStatus` in the C header, plus
//! [`Status::OutOfBounds`] and [`Status::OutOfMemory`].
//!
//! A segment in `out` is the core's `#[repr(C)] Segment`: five
//! little-endian `f32`, `x0 y0 x1 y1 score` ([`SEGMENT_BYTES`] = 20 bytes,
//! 4-byte aligned). The brighter side lies on the left of `(x0, y0) ->
//! (x1, y1)` as the image is displayed (x right, y down); the score is the
//! gradient contrast summed along the segment, an integer below 2^24
//! (higher: likelier a true line). A short output keeps the
//! highest-scoring segments, best first, and the summary's
//! `dropped_segments` counts the rest.
//!
//! The validating functions take the memory's bounds as a [`Memory`], so
//! the host tests run them on a buffer standing for the linear memory.
#![cfg_attr(target_arch = "wasm32", no_std)]
#![deny(missing_docs, unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

use core::mem::{offset_of, size_of};
use core::ptr;

use aaglsd::{Config, ConfigField, Error, GrayImage, Profile, Segment, Workspace};

/// The C ABI's `#[repr(C)]` types and conversions, shared with `ffi/`.
#[path = "../../ffi/src/types.rs"]
pub mod cabi;
pub use cabi::{AaglsdConfig, AaglsdStatus, AaglsdSummary};

/// Result codes of the exports, negated on return. 0 to 12 are
/// `AaglsdStatus` of the C header; the rest are this module's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// A status of the C ABI (core errors, NULL, misalignment, overlap, a
    /// bad enumerated argument).
    C(AaglsdStatus),
    /// A pointer + length lies outside the caller's part of the memory.
    OutOfBounds,
    /// `alloc` could not grow the memory.
    OutOfMemory,
}

/// Name of each status code, `STATUS_NAMES[code]`: JavaScript reads them
/// through `status_name`.
pub const STATUS_NAMES: [&str; 15] = [
    "ok",
    "zero_dimension",
    "image_too_large",
    "stride_too_small",
    "buffer_too_short",
    "workspace_too_small",
    "output_empty",
    "invalid_config",
    "null_pointer",
    "misaligned",
    "buffers_overlap",
    "invalid_argument",
    "unknown",
    "out_of_bounds",
    "out_of_memory",
];

impl Status {
    /// The positive status number.
    pub const fn code(self) -> i32 {
        match self {
            Self::C(s) => s as i32,
            Self::OutOfBounds => 13,
            Self::OutOfMemory => 14,
        }
    }

    /// The value an export returns: the status, negated.
    pub const fn ret(self) -> i32 {
        -self.code()
    }
}

impl From<AaglsdStatus> for Status {
    fn from(s: AaglsdStatus) -> Self {
        Self::C(s)
    }
}

impl From<Error> for Status {
    fn from(e: Error) -> Self {
        Self::C(e.into())
    }
}

/// `Config` field names in the order of `config_field_offset` (the order of
/// `AaglsdConfig` and `aaglsd::Config`).
pub const FIELD_NAMES: [&str; 25] = [
    "magnitude_threshold",
    "anchor_margin",
    "align_tolerance_deg",
    "dist_tolerance_px",
    "skip_min",
    "skip_regular",
    "skip_group",
    "min_length_px",
    "min_groups",
    "anchor_density",
    "aligned_density",
    "min_score",
    "extend_max_px",
    "reseed",
    "maxima",
    "bridge_px",
    "merge",
    "trim",
    "merge_center_px",
    "merge_angle_deg",
    "merge_gap_px",
    "candidates_per_mille",
    "max_link_pixels",
    "work_per_mille",
    "work_budget",
];

/// Byte offsets of the fields of `AaglsdConfig`, in [`FIELD_NAMES`] order.
pub const FIELD_OFFSETS: [usize; 25] = [
    offset_of!(AaglsdConfig, magnitude_threshold),
    offset_of!(AaglsdConfig, anchor_margin),
    offset_of!(AaglsdConfig, align_tolerance_deg),
    offset_of!(AaglsdConfig, dist_tolerance_px),
    offset_of!(AaglsdConfig, skip_min),
    offset_of!(AaglsdConfig, skip_regular),
    offset_of!(AaglsdConfig, skip_group),
    offset_of!(AaglsdConfig, min_length_px),
    offset_of!(AaglsdConfig, min_groups),
    offset_of!(AaglsdConfig, anchor_density),
    offset_of!(AaglsdConfig, aligned_density),
    offset_of!(AaglsdConfig, min_score),
    offset_of!(AaglsdConfig, extend_max_px),
    offset_of!(AaglsdConfig, reseed),
    offset_of!(AaglsdConfig, maxima),
    offset_of!(AaglsdConfig, bridge_px),
    offset_of!(AaglsdConfig, merge),
    offset_of!(AaglsdConfig, trim),
    offset_of!(AaglsdConfig, merge_center_px),
    offset_of!(AaglsdConfig, merge_angle_deg),
    offset_of!(AaglsdConfig, merge_gap_px),
    offset_of!(AaglsdConfig, candidates_per_mille),
    offset_of!(AaglsdConfig, max_link_pixels),
    offset_of!(AaglsdConfig, work_per_mille),
    offset_of!(AaglsdConfig, work_budget),
];

/// Bytes of one output segment: `x0 y0 x1 y1 score`, five `f32` (the
/// core's `#[repr(C)] Segment`), the `segment_size` export.
pub const SEGMENT_BYTES: usize = size_of::<Segment>();

// The layout the module docs, the JS wrapper and the README give.
const _: () = {
    assert!(SEGMENT_BYTES == 20 && align_of::<Segment>() == 4);
    assert!(offset_of!(Segment, x0) == 0 && offset_of!(Segment, y0) == 4);
    assert!(offset_of!(Segment, x1) == 8 && offset_of!(Segment, y1) == 12);
    assert!(offset_of!(Segment, score) == 16);
};

/// The output capacity that the JS wrapper, the expected-output generator
/// and the Rust CLI use: one segment per 16 pixels, at least 64.
pub const fn default_capacity(width: usize, height: usize) -> usize {
    let n = width.saturating_mul(height) / 16;
    if n > 64 { n } else { 64 }
}

/// The caller-owned part of the linear memory, `[start, end)`: from
/// `__heap_base` (below it are the module's stack and data) to the current
/// end of the memory.
#[derive(Clone, Copy, Debug)]
pub struct Memory {
    start: usize,
    end: usize,
}

impl Memory {
    /// The module's own linear memory, now.
    #[cfg(target_arch = "wasm32")]
    pub fn linear() -> Self {
        unsafe extern "C" {
            /// Set by the linker at the end of the stack and data.
            static __heap_base: u8;
        }
        Self {
            start: (&raw const __heap_base).addr(),
            end: core::arch::wasm32::memory_size(0) * PAGE,
        }
    }

    /// The `len` bytes at `start` standing for the memory (the host tests).
    /// Exposes the pointer's provenance: the functions taking a `Memory`
    /// turn addresses inside it back into pointers.
    pub fn new(start: *mut u8, len: usize) -> Self {
        let start = start.expose_provenance();
        Self {
            start,
            end: start.saturating_add(len),
        }
    }

    /// Checks that the `len` bytes at `addr` are non-NULL and inside.
    fn check(&self, addr: usize, len: usize) -> Result<(), Status> {
        if addr == 0 {
            return Err(AaglsdStatus::NullPointer.into());
        }
        match addr.checked_add(len) {
            Some(end) if addr >= self.start && end <= self.end => Ok(()),
            _ => Err(Status::OutOfBounds),
        }
    }

    /// Reads a struct from a checked address (by copy; any alignment).
    ///
    /// # Safety
    /// `self` describes memory that is readable (a [`Memory::linear`], or a
    /// live buffer given to [`Memory::new`]); every bit pattern of `T` is valid.
    unsafe fn read<T: Copy>(&self, addr: usize) -> Result<T, Status> {
        self.check(addr, size_of::<T>())?;
        // SAFETY: inside the memory (checked), readable by the contract;
        // unaligned reads are allowed by `read_unaligned`.
        Ok(unsafe { ptr::read_unaligned(ptr::with_exposed_provenance::<T>(addr)) })
    }

    /// Writes a struct to a checked address (any alignment).
    ///
    /// # Safety
    /// `self` describes memory that is writable and that no Rust reference
    /// covers at `addr` during the call.
    unsafe fn write<T>(&self, addr: usize, v: T) -> Result<(), Status> {
        self.check(addr, size_of::<T>())?;
        // SAFETY: inside the memory (checked), writable by the contract.
        unsafe { ptr::write_unaligned(ptr::with_exposed_provenance_mut::<T>(addr), v) };
        Ok(())
    }
}

/// The WebAssembly page size.
pub const PAGE: usize = 65_536;

/// `0` for success, else the negated status.
fn ret(r: Result<(), Status>) -> i32 {
    r.map_or_else(Status::ret, |()| 0)
}

/// True when `[a, a + a_len)` and `[b, b + b_len)` share a byte.
fn overlaps(a: usize, a_len: usize, b: usize, b_len: usize) -> bool {
    a_len != 0 && b_len != 0 && a < b.saturating_add(b_len) && b < a.saturating_add(a_len)
}

/// `config_profile`: writes the profile's `AaglsdConfig` to `cfg`.
///
/// # Safety
/// As [`Memory::write`].
pub unsafe fn config_profile_in(mem: Memory, profile: u32, cfg: usize) -> i32 {
    let r = match Profile::from_code(profile) {
        // SAFETY: forwarded contract.
        Some(p) => unsafe { mem.write(cfg, AaglsdConfig::from(&p.config())) },
        None => mem
            .check(cfg, size_of::<AaglsdConfig>())
            .and(Err(AaglsdStatus::InvalidArgument.into())),
    };
    ret(r)
}

/// `config_validate`: 0 when `cfg` is valid, else the code of the first bad
/// field; `-status` for a bad pointer.
///
/// # Safety
/// As [`Memory::read`].
pub unsafe fn config_validate_in(mem: Memory, cfg: usize) -> i32 {
    // SAFETY: forwarded contract.
    match unsafe { mem.read::<AaglsdConfig>(cfg) } {
        Ok(c) => match Config::from(&c).validate() {
            Ok(()) => 0,
            Err(Error::InvalidConfig(f)) => f.code(),
            Err(e) => Status::from(e).ret(),
        },
        Err(s) => s.ret(),
    }
}

/// `workspace_size`: the workspace bytes for a `width` x `height` image
/// with `cfg`'s capacities. Checked in this order: the pointer, the
/// dimensions, the config.
///
/// # Safety
/// As [`Memory::read`].
pub unsafe fn workspace_size_in(mem: Memory, width: usize, height: usize, cfg: usize) -> i32 {
    let inner = || -> Result<usize, Status> {
        // SAFETY: forwarded contract.
        let c = Config::from(&unsafe { mem.read::<AaglsdConfig>(cfg) }?);
        if let Err(e @ (Error::ZeroDimension { .. } | Error::ImageTooLarge { .. })) =
            GrayImage::new(&[], width, height, width)
        {
            return Err(e.into());
        }
        c.validate()?;
        Workspace::bytes_needed(width, height, &c).ok_or(Status::from(AaglsdStatus::ImageTooLarge))
    };
    match inner() {
        Ok(n) => i32::try_from(n).unwrap_or(Status::from(AaglsdStatus::ImageTooLarge).ret()),
        Err(s) => s.ret(),
    }
}

/// The buffers of a `detect` call: linear-memory addresses and lengths.
#[derive(Clone, Copy, Debug)]
pub struct DetectArgs {
    /// Pixels: `height` rows of `width` bytes, `stride` apart.
    pub image: usize,
    /// Bytes at `image`.
    pub image_len: usize,
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row stride in bytes.
    pub stride: usize,
    /// An `AaglsdConfig` (any alignment).
    pub cfg: usize,
    /// The workspace (any alignment).
    pub workspace: usize,
    /// Bytes at `workspace`.
    pub workspace_len: usize,
    /// Output segments, `x0 y0 x1 y1 score` as `f32`, [`SEGMENT_BYTES`]
    /// each (4-byte aligned).
    pub out: usize,
    /// Segments that fit at `out`.
    pub out_capacity: usize,
    /// An `AaglsdSummary` (9 `usize`; any alignment), zeroed on error.
    pub summary: usize,
}

/// `detect`: runs the core on the caller's buffers. Checked in this order,
/// before anything is written: NULL and out-of-bounds pointers, the
/// output's alignment, overlapping image/workspace/output, then the core's
/// checks (image, config, workspace size, output capacity).
///
/// # Safety
/// As [`Memory::write`], for every buffer.
pub unsafe fn detect_in(mem: Memory, a: DetectArgs) -> i32 {
    let out_bytes = a.out_capacity.saturating_mul(size_of::<Segment>());
    let inner = || -> Result<usize, Status> {
        mem.check(a.image, a.image_len)?;
        mem.check(a.workspace, a.workspace_len)?;
        mem.check(a.out, out_bytes)?;
        mem.check(a.summary, size_of::<AaglsdSummary>())?;
        if !a.out.is_multiple_of(align_of::<Segment>()) {
            return Err(AaglsdStatus::Misaligned.into());
        }
        if overlaps(a.image, a.image_len, a.workspace, a.workspace_len)
            || overlaps(a.image, a.image_len, a.out, out_bytes)
            || overlaps(a.workspace, a.workspace_len, a.out, out_bytes)
        {
            return Err(AaglsdStatus::BuffersOverlap.into());
        }
        // SAFETY: forwarded contract.
        let cfg = Config::from(&unsafe { mem.read::<AaglsdConfig>(a.cfg) }?);
        // SAFETY: the three blocks are inside the memory (checked above),
        // pairwise disjoint (checked), initialised (linear memory always
        // is) and, by the contract, not referenced elsewhere during the
        // call; `out` is aligned (checked) and every bit pattern is a valid
        // `Segment` (five `f32`).
        let (image, workspace, out) = unsafe {
            (
                core::slice::from_raw_parts(
                    ptr::with_exposed_provenance::<u8>(a.image),
                    a.image_len,
                ),
                core::slice::from_raw_parts_mut(
                    ptr::with_exposed_provenance_mut::<u8>(a.workspace),
                    a.workspace_len,
                ),
                core::slice::from_raw_parts_mut(
                    ptr::with_exposed_provenance_mut::<Segment>(a.out),
                    a.out_capacity,
                ),
            )
        };
        let img = GrayImage::new(image, a.width, a.height, a.stride)?;
        let s = aaglsd::detect(&img, &cfg, &mut Workspace::new(workspace), out)?;
        // SAFETY: forwarded contract; the slices above are no longer used.
        unsafe { mem.write(a.summary, AaglsdSummary::from(s)) }?;
        Ok(s.segments)
    };
    match inner() {
        // At most `out_capacity`, which fits the memory, so below 2^31 segments.
        Ok(n) => i32::try_from(n).unwrap_or(i32::MAX),
        Err(s) => {
            if mem.check(a.summary, size_of::<AaglsdSummary>()).is_ok() {
                // SAFETY: forwarded contract; checked just now.
                let _ = unsafe { mem.write(a.summary, AaglsdSummary::default()) };
            }
            s.ret()
        }
    }
}

/// Copies `name` to the `cap` bytes at `buf` (truncated to fit); returns its
/// full length, or `-status`.
///
/// # Safety
/// As [`Memory::write`].
pub unsafe fn copy_name(mem: Memory, name: Option<&str>, buf: usize, cap: usize) -> i32 {
    let Some(name) = name else {
        return Status::from(AaglsdStatus::InvalidArgument).ret();
    };
    if let Err(s) = mem.check(buf, cap) {
        return s.ret();
    }
    let n = name.len().min(cap);
    // SAFETY: `n <= cap` bytes inside the memory (checked), writable by the
    // contract; `name` is in the module's data, below `__heap_base`, so the
    // two do not overlap.
    unsafe {
        ptr::copy_nonoverlapping(name.as_ptr(), ptr::with_exposed_provenance_mut(buf), n);
    }
    i32::try_from(name.len()).unwrap_or(i32::MAX)
}

/// The name of a `ConfigField` code (1..=16), as `aaglsd::ConfigField::name`.
pub fn config_field_str(code: i32) -> Option<&'static str> {
    ConfigField::ALL
        .into_iter()
        .find(|f| f.code() == code)
        .map(ConfigField::name)
}

/// The bump allocator of `alloc` / `release`: every block lies between
/// `__heap_base` and the memory's end, in allocation order.
#[cfg(target_arch = "wasm32")]
mod heap {
    use core::sync::atomic::{AtomicUsize, Ordering};

    use super::{Memory, PAGE, Status};

    /// The first free address (0 before the first call).
    static TOP: AtomicUsize = AtomicUsize::new(0);
    const ALIGN: usize = 16;

    fn top(mem: &Memory) -> usize {
        match TOP.load(Ordering::Relaxed) {
            0 => mem.start.next_multiple_of(ALIGN),
            t => t,
        }
    }

    pub fn alloc(n: usize) -> usize {
        let mem = Memory::linear();
        let start = top(&mem);
        let Some(end) = n
            .checked_next_multiple_of(ALIGN)
            .and_then(|n| start.checked_add(n))
        else {
            return 0;
        };
        if end > mem.end {
            let pages = (end - mem.end).div_ceil(PAGE);
            if core::arch::wasm32::memory_grow(0, pages) == usize::MAX {
                return 0;
            }
        }
        TOP.store(end, Ordering::Relaxed);
        start
    }

    pub fn release(ptr: usize) -> Result<(), Status> {
        let mem = Memory::linear();
        if !ptr.is_multiple_of(ALIGN) || ptr < mem.start.next_multiple_of(ALIGN) || ptr > top(&mem)
        {
            return Err(Status::OutOfBounds);
        }
        TOP.store(ptr, Ordering::Relaxed);
        Ok(())
    }
}

/// The exports: each checks its pointers against [`Memory::linear`].
#[cfg(target_arch = "wasm32")]
mod exports {
    use super::*;

    /// A 16-byte aligned block of `n` bytes, after every block allocated
    /// before it, growing the memory as needed; 0 when it cannot.
    /// `alloc(0)` is the current top: a mark for `release`.
    #[unsafe(no_mangle)]
    pub extern "C" fn alloc(n: usize) -> usize {
        heap::alloc(n)
    }

    /// Frees the block at `ptr` (from `alloc`) and every block allocated
    /// after it. The memory does not shrink (WebAssembly cannot).
    #[unsafe(no_mangle)]
    pub extern "C" fn release(ptr: usize) -> i32 {
        ret(heap::release(ptr))
    }

    /// `size_of::<AaglsdConfig>()`.
    #[unsafe(no_mangle)]
    pub extern "C" fn config_size() -> usize {
        size_of::<AaglsdConfig>()
    }

    /// Byte offset of field `i` ([`FIELD_NAMES`] order) in `AaglsdConfig`.
    #[unsafe(no_mangle)]
    pub extern "C" fn config_field_offset(i: usize) -> i32 {
        FIELD_OFFSETS.get(i).map_or(
            Status::from(AaglsdStatus::InvalidArgument).ret(),
            |&o| o as i32, // below size_of::<AaglsdConfig>()
        )
    }

    /// [`config_profile_in`] on the linear memory.
    #[unsafe(no_mangle)]
    pub extern "C" fn config_profile(profile: u32, cfg: usize) -> i32 {
        // SAFETY: the linear memory above `__heap_base` is the caller's.
        unsafe { config_profile_in(Memory::linear(), profile, cfg) }
    }

    /// [`config_validate_in`] on the linear memory.
    #[unsafe(no_mangle)]
    pub extern "C" fn config_validate(cfg: usize) -> i32 {
        // SAFETY: as above.
        unsafe { config_validate_in(Memory::linear(), cfg) }
    }

    /// [`workspace_size_in`] on the linear memory.
    #[unsafe(no_mangle)]
    pub extern "C" fn workspace_size(width: usize, height: usize, cfg: usize) -> i32 {
        // SAFETY: as above.
        unsafe { workspace_size_in(Memory::linear(), width, height, cfg) }
    }

    /// [`default_capacity`].
    #[unsafe(no_mangle)]
    pub extern "C" fn default_max_segments(width: usize, height: usize) -> usize {
        default_capacity(width, height)
    }

    /// [`SEGMENT_BYTES`]: the JS wrapper checks it against the layout it reads.
    #[unsafe(no_mangle)]
    pub extern "C" fn segment_size() -> usize {
        SEGMENT_BYTES
    }

    /// 1 when this module was built with the `simd128` target feature
    /// (`wasm/build.sh`'s second module), else 0: the JS wrapper reports it
    /// as `lsd.simd`.
    #[unsafe(no_mangle)]
    pub extern "C" fn simd128() -> u32 {
        u32::from(cfg!(target_feature = "simd128"))
    }

    /// [`detect_in`] on the linear memory.
    #[unsafe(no_mangle)]
    #[allow(clippy::too_many_arguments)] // one address and one length per buffer
    pub extern "C" fn detect(
        image: usize,
        image_len: usize,
        width: usize,
        height: usize,
        stride: usize,
        cfg: usize,
        workspace: usize,
        workspace_len: usize,
        out: usize,
        out_capacity: usize,
        summary: usize,
    ) -> i32 {
        let a = DetectArgs {
            image,
            image_len,
            width,
            height,
            stride,
            cfg,
            workspace,
            workspace_len,
            out,
            out_capacity,
            summary,
        };
        // SAFETY: as above; JavaScript does not run during the call.
        unsafe { detect_in(Memory::linear(), a) }
    }

    /// Copies the name of status `code` ([`STATUS_NAMES`]) to `buf`.
    #[unsafe(no_mangle)]
    pub extern "C" fn status_name(code: i32, buf: usize, cap: usize) -> i32 {
        let name = usize::try_from(code)
            .ok()
            .and_then(|i| STATUS_NAMES.get(i).copied());
        // SAFETY: as above.
        unsafe { copy_name(Memory::linear(), name, buf, cap) }
    }

    /// Copies the name of `ConfigField` code `code` to `buf`.
    #[unsafe(no_mangle)]
    pub extern "C" fn config_field_name(code: i32, buf: usize, cap: usize) -> i32 {
        // SAFETY: as above.
        unsafe { copy_name(Memory::linear(), config_field_str(code), buf, cap) }
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
mod tests;
