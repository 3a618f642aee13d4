//! `aaglsd::detect` on an emulated Cortex-M: QEMU `mps2-an386` (Cortex-M4,
//! the default target), `mps2-an505` (Cortex-M33) or `microbit` (Cortex-M0),
//! picked by the build target (see `build.rs` and `board.rs`).
//!
//! Reads a 320x240 raw 8-bit gray image from the host at run time
//! (semihosting file I/O, path relative to QEMU's working directory, given
//! as the first semihosting argument), runs the detector with
//! [`Config::DEFAULT`] on a `static` workspace, and prints:
//!
//! - one line per segment, `x0 y0 x1 y1` then the four `f32` bit patterns in
//!   hex, and a `summary ...` line: the same format as `host-tools detect`,
//!   so `run.sh` diffs the two for bit-exactness;
//! - `# ...` metric lines: instructions for the `detect` call (the board's
//!   timer under `-icount shift=0`, see [`board`]) and its stack high-water
//!   mark (painted stack).
//!
//! Exit status (semihosting): 0 on success, 1 on an I/O or detector error,
//! 101 on a panic.

#![no_std]
#![no_main]

mod board;
mod report;

use core::ffi::CStr;
use core::panic::PanicInfo;

use aaglsd::{Config, Error, GrayImage, Segment, Summary, Workspace, detect};
use cortex_m_rt::entry;
use semihosting::io::Read;
use semihosting::{eprintln, println};

use report::{SegmentLine, SummaryLine};

/// Image width in pixels.
const W: usize = 320;
/// Image height in pixels.
const H: usize = 240;
/// Pixels (and bytes) of the image.
const PIXELS: usize = W * H;
/// Workspace bytes, from the library's `const fn`.
const SLAB_BYTES: usize = Workspace::bytes_needed_default(W, H);
/// Output capacity. `host-tools detect` uses the same, so a full output
/// would be reported identically on both sides.
const MAX_SEGMENTS: usize = 512;
/// Image read when QEMU passes no semihosting argument (`cargo run` from
/// `firmware/`).
const DEFAULT_IMAGE: &CStr = c"../testdata/castle1_320x240.gray";

/// Bytes of stack painted below the caller of `detect`.
const STACK_PAINT: usize = 32 * 1024;
/// Bytes just below the stack pointer left unpainted (the painter's own frame).
const STACK_GUARD: usize = 256;
/// Paint pattern.
const PAINT: u32 = 0xDEAD_BEEF;

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` references, safely; the
    // workspace is a `static` sized at compile time by the library.
    static mut IMAGE: [u8; PIXELS] = [0; PIXELS];
    static mut SLAB: [u8; SLAB_BYTES] = [0; SLAB_BYTES];
    static mut OUT: [Segment; MAX_SEGMENTS] = [Segment::ZERO; MAX_SEGMENTS];

    let mut path_buf = [0u8; 256];
    let path = image_path(&mut path_buf);
    if let Err(msg) = read_image(path, IMAGE) {
        eprintln!("error: {}: {}", path.to_str().unwrap_or("?"), msg);
        semihosting::process::exit(1);
    }
    let img = match GrayImage::new(IMAGE, W, H, W) {
        Ok(img) => img,
        Err(e) => fail(e),
    };

    let m = measure(&img, SLAB, OUT);
    let summary = match m.result {
        Ok(s) => s,
        Err(e) => fail(e),
    };
    for s in OUT.iter().take(summary.segments) {
        println!("{}", SegmentLine(s));
    }
    println!("{}", SummaryLine(&summary));

    let insns = board::insns(m.ticks);
    let per_px_x100 = insns * 100 / PIXELS as u64;
    println!("# image {} {}x{}", path.to_str().unwrap_or("?"), W, H);
    println!(
        "# detect: {} timer ticks = {} instructions = {}.{:02} per pixel",
        m.ticks,
        insns,
        per_px_x100 / 100,
        per_px_x100 % 100
    );
    match m.stack {
        Some(bytes) => println!("# detect stack high-water: {} bytes", bytes),
        None => {
            eprintln!("error: detect used all {} painted stack bytes", STACK_PAINT);
            semihosting::process::exit(1);
        }
    }
    // With a second argument `stages`, the stages too, for the report: the
    // blur + gradient floor, then everything before the linking (the rest
    // of `detect` is the linking, validation and merging).
    if stages_requested() {
        let per_px = |ticks: u32| board::insns(ticks) * 100 / PIXELS as u64;
        for (name, part) in [
            ("floor (blur + gradient)", aaglsd::Part::Floor),
            ("front end (before linking)", aaglsd::Part::FrontEnd),
        ] {
            let ws = &mut Workspace::new(SLAB);
            let t = timed(|| aaglsd::detect_part(part, &img, &Config::DEFAULT, ws).is_ok());
            let v = per_px(t);
            println!("# stage {}: {}.{:02} per pixel", name, v / 100, v % 100);
        }
    }
    println!(
        "# static: workspace {} B, image {} B, output {} B ({} segments)",
        SLAB_BYTES,
        PIXELS,
        core::mem::size_of_val(OUT),
        MAX_SEGMENTS
    );
    semihosting::process::exit(0)
}

/// The first semihosting argument after the program name, or
/// [`DEFAULT_IMAGE`].
fn image_path(buf: &mut [u8; 256]) -> &CStr {
    let Ok(args) = semihosting::experimental::env::args::<256>() else {
        return DEFAULT_IMAGE;
    };
    let Some(Ok(arg)) = (&args).nth(1) else {
        return DEFAULT_IMAGE;
    };
    let bytes = arg.as_bytes();
    match buf.get_mut(..bytes.len()) {
        // The rest of `buf` is zero: the copy is NUL-terminated.
        Some(dst) if bytes.len() < 256 => dst.copy_from_slice(bytes),
        _ => return DEFAULT_IMAGE,
    }
    CStr::from_bytes_until_nul(buf).unwrap_or(DEFAULT_IMAGE)
}

/// Whether the second semihosting argument after the program name is
/// `stages`.
fn stages_requested() -> bool {
    let Ok(args) = semihosting::experimental::env::args::<256>() else {
        return false;
    };
    matches!((&args).nth(2), Some(Ok(a)) if a.as_bytes() == b"stages")
}

/// Reads exactly `dst.len()` bytes from the host file `path`, which must have
/// exactly that length.
fn read_image(path: &CStr, dst: &mut [u8]) -> Result<(), &'static str> {
    let mut f = semihosting::fs::File::open(path).map_err(|_| "cannot open")?;
    let len = f.metadata().map_err(|_| "cannot stat")?.len();
    if len != dst.len() as u64 {
        return Err("not a 320x240 raw 8-bit gray image (76800 bytes)");
    }
    f.read_exact(dst).map_err(|_| "short read")
}

/// What one measured `detect` call returned and cost.
struct Measured {
    result: Result<Summary, Error>,
    /// Timer ticks over the call (see [`board`]).
    ticks: u32,
    /// Deepest stack use below the caller's stack pointer, in bytes; `None`
    /// when the whole painted area was used.
    stack: Option<usize>,
}

/// Paints the stack below this frame, runs [`run_detect`] between two timer
/// reads, then scans for the deepest overwritten word.
#[inline(never)]
fn measure(img: &GrayImage<'_>, slab: &mut [u8], out: &mut [Segment]) -> Measured {
    let sp = stack_pointer();
    let top = sp - STACK_GUARD;
    let bottom = sp - STACK_PAINT;
    paint(bottom, top);
    board::timer_start();
    let t0 = board::timer_now();
    let result = run_detect(img, slab, out);
    let t1 = board::timer_now();
    let lowest = lowest_used(bottom, top);
    Measured {
        result,
        ticks: t1.wrapping_sub(t0),
        stack: (lowest > bottom).then(|| sp - lowest),
    }
}

/// Timer ticks over `f` (which must succeed).
fn timed(f: impl FnOnce() -> bool) -> u32 {
    board::timer_start();
    let t0 = board::timer_now();
    let ok = f();
    let t1 = board::timer_now();
    if !ok {
        eprintln!("error: a stage hook failed");
        semihosting::process::exit(1);
    }
    t1.wrapping_sub(t0)
}

/// The call under measurement, kept out of line so its frame is on the
/// painted stack.
#[inline(never)]
fn run_detect(img: &GrayImage<'_>, slab: &mut [u8], out: &mut [Segment]) -> Result<Summary, Error> {
    detect(img, &Config::DEFAULT, &mut Workspace::new(slab), out)
}

fn stack_pointer() -> usize {
    let sp: usize;
    // SAFETY: reads the stack pointer register; no memory access.
    unsafe { core::arch::asm!("mov {}, sp", out(reg) sp, options(nomem, nostack)) };
    sp
}

/// Fills the words in `[bottom, top)` with [`PAINT`].
#[inline(never)]
fn paint(bottom: usize, top: usize) {
    let mut a = bottom;
    while a < top {
        // SAFETY: `[bottom, top)` is free stack below the live frames (the
        // stack has at least 100 KiB of RAM below it on every board, and
        // this frame fits in STACK_GUARD); word-aligned because `sp` is
        // 8-byte aligned.
        unsafe { core::ptr::write_volatile(a as *mut u32, PAINT) };
        a += 4;
    }
}

/// The lowest address in `[bottom, top)` whose word is no longer [`PAINT`],
/// or `top` when none was touched.
#[inline(never)]
fn lowest_used(bottom: usize, top: usize) -> usize {
    let mut a = bottom;
    while a < top {
        // SAFETY: as in `paint`; the area is only read.
        if unsafe { core::ptr::read_volatile(a as *const u32) } != PAINT {
            return a;
        }
        a += 4;
    }
    top
}

fn fail(e: Error) -> ! {
    eprintln!("error: {:?}", e);
    semihosting::process::exit(1)
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    eprintln!("panic: {}", info);
    semihosting::process::exit(101)
}
