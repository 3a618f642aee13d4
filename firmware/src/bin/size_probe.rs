//! Flash and RAM of the library alone, as a firmware using
//! [`Config::DEFAULT`] gets it: `detect` on a `black_box`ed 320x240 image
//! (data and dimensions), nothing printed, a panic handler that only loops,
//! so no `core::fmt` is linked. Measure with `arm-none-eabi-size -A` and
//! subtract `size_baseline` (the same program without the `detect` call).
//! Never run; only built.

#![no_std]
#![no_main]

#[path = "../probe.rs"]
mod probe;

probe::probe_main!(probe::detect_black_boxed::<false>);
