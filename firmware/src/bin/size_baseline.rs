//! `size_probe` without the `detect` call: the runtime's own flash (reset
//! handler, exception handlers, memset/memcpy) and the same `.bss` buffers.
//! `size_probe` minus this is the library's cost. Never run; only built.

#![no_std]
#![no_main]

use core::hint::black_box;
use core::panic::PanicInfo;

use aaglsd::{Segment, Workspace};
use cortex_m_rt::entry;

const W: usize = 320;
const H: usize = 240;
const SLAB_BYTES: usize = Workspace::bytes_needed_default(W, H);
const MAX_SEGMENTS: usize = 512;
#[entry]
fn main() -> ! {
    static mut IMAGE: [u8; W * H] = [0; W * H];
    static mut SLAB: [u8; SLAB_BYTES] = [0; SLAB_BYTES];
    static mut OUT: [Segment; MAX_SEGMENTS] = [Segment::ZERO; MAX_SEGMENTS];

    black_box(&IMAGE[..]);
    black_box(&mut SLAB[..]);
    black_box(&mut OUT[..]);
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
