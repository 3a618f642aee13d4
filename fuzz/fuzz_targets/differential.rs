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

use aaglsd::{Config, GrayImage, Segment, Workspace, detect};
use common::Bytes;
use libfuzzer_sys::fuzz_target;

fn near(a: &Segment, b: &Segment, tol: f32) -> bool {
    let d = |x0: f32, y0: f32, x1: f32, y1: f32| ((x0 - x1).powi(2) + (y0 - y1).powi(2)).sqrt();
    let same = d(a.x0, a.y0, b.x0, b.y0).max(d(a.x1, a.y1, b.x1, b.y1));
    let swap = d(a.x0, a.y0, b.x1, b.y1).max(d(a.x1, a.y1, b.x0, b.y0));
    same.min(swap) <= tol
}

fn unmatched(a: &[Segment], b: &[Segment]) -> usize {
    a.iter()
        .filter(|s| !b.iter().any(|t| near(s, t, 1.5)))
        .count()
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let w = 8 + usize::from(b.u8() % 40);
    let h = 8 + usize::from(b.u8() % 40);
    let cfg = if b.u8() & 1 == 0 {
        Config::DEFAULT
    } else {
        Config::PAPER
    };
    let px = common::scene(&mut b, w, h);
    let img = GrayImage::new(&px, w, h, w).unwrap();
    let reference = aaglsd::reference::detect(&img, &cfg).unwrap();
    let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
    let mut out = vec![Segment::default(); 4096];
    let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
    let fixed = &out[..s.segments];
    let (ur, uf) = (unmatched(&reference, fixed), unmatched(fixed, &reference));
    assert!(
        ur <= 2 + reference.len() / 4 && uf <= 2 + fixed.len() / 4,
        "reference {} (unmatched {ur}) vs fixed {} (unmatched {uf})\nref {reference:?}\nfixed {fixed:?}",
        reference.len(),
        fixed.len()
    );
});
