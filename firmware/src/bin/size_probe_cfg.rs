//! As `size_probe`, with the `Config` itself `black_box`ed, so nothing in it
//! is constant-folded (as for a firmware that picks its profile at run
//! time). `detect` on a `black_box`ed 320x240 image (data and dimensions),
//! nothing printed, a panic handler that only loops, so no `core::fmt` is
//! linked. Measure with `arm-none-eabi-size -A` and subtract `size_baseline`.
//! Never run; only built.

#![no_std]
#![no_main]

#[path = "../probe.rs"]
mod probe;

probe::probe_main!(probe::detect_black_boxed::<true>);
