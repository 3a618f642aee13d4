//! `size_probe` without the `detect` call: the runtime's own flash (reset
//! handler, exception handlers, memset/memcpy) and the same `.bss` buffers.
//! `size_probe` minus this is the library's cost. Never run; only built.

#![no_std]
#![no_main]

#[path = "../probe.rs"]
mod probe;

use core::hint::black_box;

probe::probe_main!(touch);

/// Reads the buffers (so that they stay), and nothing else.
#[inline(always)]
fn touch(image: &probe::Image, slab: &mut probe::Slab, out: &mut probe::Out) {
    black_box(&image[..]);
    black_box(&mut slab[..]);
    black_box(&mut out[..]);
}
