//! Inputs a fuzz campaign failed on, replayed through the target's own
//! decoding and check (`fuzz/fuzz_targets/common.rs`), from the files the
//! target's seed corpus keeps.
//!
//! Repository-only (uses `aaglsd-support`; not in the published package).
#![allow(clippy::unwrap_used)]

#[path = "../fuzz/fuzz_targets/common.rs"]
#[allow(unused)] // the other targets' helpers and the libFuzzer macro
mod common;

use aaglsd::{GrayImage, Maxima};
use common::{Bytes, Differential};

/// A 47x15 scene, paper profile: a dark line from (2, 0) to (35, 14). The
/// core and the reference each link three overlapping segments on it,
/// which merge into one in both; under `Maxima::Strict` (the paper
/// profile's when the input was found) the core's merged none. The angle
/// between the first two is 4.996° with the ends rounded to the nearest
/// Q8 values, 5.003° (over D_a) with the core's end one unit off, which
/// its minor-axis projection allowed (design §8).
const MERGE_AT_DA: &[u8] =
    include_bytes!("../fuzz/corpus/differential/49a7042d44a4e7a74de891bb155b06b2a2d8695a");

#[test]
fn differential_merge_at_the_angle_threshold() {
    let case = Differential::decode(&mut Bytes(MERGE_AT_DA));
    assert_eq!((case.width, case.height, case.cfg.merge), (47, 15, true));
    case.check().unwrap();
    let strict = Differential {
        cfg: aaglsd::Config {
            maxima: Maxima::Strict,
            ..case.cfg
        },
        ..case
    };
    strict.check().unwrap();
    let img = GrayImage::new(&strict.pixels, strict.width, strict.height, strict.width).unwrap();
    let reference = aaglsd::reference::detect(&img, &strict.cfg).unwrap();
    let fixed = aaglsd_support::detect_fixed(&img, &strict.cfg).unwrap();
    assert_eq!((reference.len(), fixed.segments.len()), (1, 1));
    assert_eq!(fixed.summary.merged, 2);
}
