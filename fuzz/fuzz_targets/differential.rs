//! The fixed-point core against the float reference on small structured
//! scenes (straight-edged polygons, low noise), default and paper profiles,
//! within the tolerance of `common::Differential::check`. The two differ
//! only where a decision sits on an exact tie (f32 NMS weights versus exact
//! rationals) or within about 1e-6 degrees of an angle threshold.
#![no_main]

#[path = "common.rs"]
mod common;

common::fuzz_bytes!(|b| {
    if let Err(e) = common::Differential::decode(&mut b).check() {
        panic!("{e}");
    }
});
