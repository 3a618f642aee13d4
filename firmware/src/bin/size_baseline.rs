//! `size_probe` without the `detect` call: the runtime's own flash (reset
//! handler, exception handlers, memset/memcpy) and the same `.bss` buffers.
//! `size_probe` minus this is the library's cost. Never run; only built.

#![no_std]
#![no_main]

#[macro_use]
#[path = "../probe.rs"]
mod probe;

use core::hint::black_box;

probe_main!(|image, slab, out| {
    black_box(&image[..]);
    black_box(&mut slab[..]);
    black_box(&mut out[..]);
});
