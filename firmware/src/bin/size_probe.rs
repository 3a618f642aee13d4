//! Flash and RAM of the library alone, as a firmware using
//! [`Config::DEFAULT`] gets it: `detect` on a `black_box`ed 320x240 image
//! (data and dimensions), nothing printed, a panic handler that only loops,
//! so no `core::fmt` is linked. Measure with `arm-none-eabi-size -A` and
//! subtract `size_baseline` (the same program without the `detect` call).
//! Never run; only built.

#![no_std]
#![no_main]

use core::hint::black_box;
use core::panic::PanicInfo;

use aaglsd::{Config, GrayImage, Segment, Workspace, detect};
use cortex_m_rt::entry;

const W: usize = 320;
const H: usize = 240;
const SLAB_BYTES: usize = Workspace::bytes_needed_default(W, H);
const MAX_SEGMENTS: usize = 512;
#[entry]
fn main() -> ! {
    // In .bss (read through `black_box`, so LTO keeps them): the image is
    // not in flash, so .text + .rodata is the code and its tables only.
    static mut IMAGE: [u8; W * H] = [0; W * H];
    static mut SLAB: [u8; SLAB_BYTES] = [0; SLAB_BYTES];
    static mut OUT: [Segment; MAX_SEGMENTS] = [Segment::ZERO; MAX_SEGMENTS];

    let pixels: &[u8] = black_box(&IMAGE[..]);
    let (w, h) = (black_box(W), black_box(H));
    if let Ok(img) = GrayImage::new(pixels, w, h, w) {
        let r = detect(&img, &Config::DEFAULT, &mut Workspace::new(SLAB), OUT);
        black_box(r.map(|s| s.segments).unwrap_or(0));
    }
    black_box(&OUT[..]);
    loop {
        core::hint::spin_loop();
    }
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
