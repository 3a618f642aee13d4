//! The fixed-point core against the float reference on small structured
//! scenes (straight-edged polygons, low noise), default and paper profiles.
//!
//! Agreed tolerance (the same geometry as `tests/fixed_vs_reference.rs`,
//! loosened for single small images): a segment is matched when the other
//! implementation has one with both endpoints within 1.5 px; on each side
//! at most `2 + n/4` of `n` segments may be unmatched. The two differ only
//! where a decision sits on an exact tie (f32 NMS weights versus exact
//! rationals) or within about 1e-6 degrees of an angle threshold.
#![no_main]

#[path = "common.rs"]
mod common;

use aaglsd::{Config, GrayImage};
use aaglsd_support::matching::unmatched;
use aaglsd_support::run::detect_with_capacity;

common::fuzz_bytes!(|b| {
    let (w, h) = (b.size(8, 40), b.size(8, 40));
    let cfg = if b.u8() & 1 == 0 {
        Config::DEFAULT
    } else {
        Config::PAPER
    };
    // The reference has no work limit and no candidate capacity: lift the
    // core's. On a tiny image a pathological scene could reach 2 work units
    // per pixel, and candidates on more than 9.2% of the pixels (the default
    // capacity, sized for natural images), which the core would drop and
    // the reference keep.
    let cfg = Config {
        work_per_mille: 100_000,
        candidates_per_mille: 1000,
        ..cfg
    };
    let px = common::scene(&mut b, w, h);
    let img = GrayImage::new(&px, w, h, w).unwrap();
    let reference = aaglsd::reference::detect(&img, &cfg).unwrap();
    let fixed = detect_with_capacity(&img, &cfg, 4096).unwrap().segments;
    let (ur, uf) = (
        unmatched(&reference, &fixed, 1.5),
        unmatched(&fixed, &reference, 1.5),
    );
    assert!(
        ur <= 2 + reference.len() / 4 && uf <= 2 + fixed.len() / 4,
        "reference {} (unmatched {ur}) vs fixed {} (unmatched {uf})\nref {reference:?}\nfixed {fixed:?}",
        reference.len(),
        fixed.len()
    );
});
