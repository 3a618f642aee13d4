//! Every kind of bad input gets its named error, and caller buffers are left
//! in the documented state (`out` untouched on error). The README lists
//! this table.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use std::sync::LazyLock;

use aaglsd::{
    Config, ConfigField, Error, GrayImage, MAX_DIMENSION, MAX_PIXELS, Segment, Workspace, detect,
};

const SENTINEL: Segment = Segment {
    x0: -7.0,
    y0: -7.0,
    x1: -7.0,
    y1: -7.0,
    score: -7.0,
};

#[test]
fn image_errors() {
    let px = [0u8; 64];
    assert_eq!(
        GrayImage::new(&px, 0, 4, 4).unwrap_err(),
        Error::ZeroDimension {
            width: 0,
            height: 4
        }
    );
    assert_eq!(
        GrayImage::new(&px, 4, 0, 4).unwrap_err(),
        Error::ZeroDimension {
            width: 4,
            height: 0
        }
    );
    // Product overflows usize: still ImageTooLarge, no overflow panic.
    assert_eq!(
        GrayImage::new(&px, usize::MAX, usize::MAX, usize::MAX).unwrap_err(),
        Error::ImageTooLarge {
            width: usize::MAX,
            height: usize::MAX
        }
    );
    assert!(matches!(
        GrayImage::new(&px, MAX_DIMENSION + 1, 1, MAX_DIMENSION + 1),
        Err(Error::ImageTooLarge { .. })
    ));
    // Both sides legal, product over MAX_PIXELS.
    let side = 8193;
    assert!(side * side > MAX_PIXELS);
    assert!(matches!(
        GrayImage::new(&px, side, side, side),
        Err(Error::ImageTooLarge { .. })
    ));
    assert_eq!(
        GrayImage::new(&px, 8, 2, 7).unwrap_err(),
        Error::StrideTooSmall {
            stride: 7,
            width: 8
        }
    );
    // One byte short: stride*(h-1) + w = 10*5 + 8 = 58 needed.
    assert_eq!(
        GrayImage::new(&px[..57], 8, 6, 10).unwrap_err(),
        Error::BufferTooShort {
            needed: 58,
            got: 57
        }
    );
    assert!(GrayImage::new(&px[..58], 8, 6, 10).is_ok());
    // Stride * height overflowing usize is a short buffer, not a panic.
    assert!(matches!(
        GrayImage::new(&px, 4, 4, usize::MAX),
        Err(Error::BufferTooShort {
            needed: usize::MAX,
            ..
        })
    ));
}

/// A dark rectangle (columns 16..48, rows 12..36) on a light 64 x 48 image.
fn image() -> GrayImage<'static> {
    static PIXELS: LazyLock<Vec<u8>> = LazyLock::new(|| {
        let mut px = vec![200u8; 64 * 48];
        for row in px.chunks_exact_mut(64).skip(12).take(24) {
            row[16..48].fill(30);
        }
        px
    });
    GrayImage::new(&PIXELS, 64, 48, 64).unwrap()
}

/// A workspace of exactly the size [`image`] needs with `cfg`.
fn slab_for(img: &GrayImage<'_>, cfg: &Config) -> Vec<u8> {
    vec![0u8; Workspace::bytes_needed(img.width(), img.height(), cfg).unwrap()]
}

#[test]
fn workspace_one_byte_short() {
    let img = image();
    let cfg = Config::DEFAULT;
    let needed = Workspace::bytes_needed(img.width(), img.height(), &cfg).unwrap();
    let mut slab = vec![0u8; needed - 1];
    let mut out = [SENTINEL; 8];
    let r = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out);
    assert_eq!(
        r,
        Err(Error::WorkspaceTooSmall {
            needed,
            got: needed - 1
        })
    );
    assert!(out.iter().all(|s| *s == SENTINEL), "out must be untouched");
    let mut slab = vec![0u8; needed];
    assert!(detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).is_ok());
    assert!(matches!(
        detect(&img, &cfg, &mut Workspace::new(&mut []), &mut out),
        Err(Error::WorkspaceTooSmall { got: 0, .. })
    ));
}

#[test]
fn empty_output() {
    let (img, cfg) = (image(), Config::DEFAULT);
    let mut slab = slab_for(&img, &cfg);
    let r = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut []);
    assert_eq!(r, Err(Error::OutputEmpty));
    let mut v: heapless::Vec<Segment, 0> = heapless::Vec::new();
    let r = aaglsd::detect_into_vec(&img, &cfg, &mut Workspace::new(&mut slab), &mut v);
    assert_eq!(r, Err(Error::OutputEmpty));
}

#[test]
fn full_output_is_reported_not_hidden() {
    let (img, cfg) = (image(), Config::DEFAULT);
    let mut slab = slab_for(&img, &cfg);
    let mut big = [Segment::default(); 16];
    let all = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut big).unwrap();
    assert_eq!(all.segments, 4);
    let mut small = [Segment::default(); 1];
    let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut small).unwrap();
    assert_eq!((s.segments, s.dropped_segments), (1, 3));
    assert!(!s.is_complete());
    // The one kept is the highest-scoring.
    let best = big[..4]
        .iter()
        .max_by(|a, b| a.score.total_cmp(&b.score))
        .unwrap();
    assert_eq!(small[0], *best);
}

/// `FIELD.member = [v, ...]`: one case per value, the field set to it
/// alone, which must fail with `InvalidConfig(ConfigField::FIELD)`.
macro_rules! out_of_range {
    ($($field:ident . $member:ident = [$($v:expr),+];)*) => {{
        type Edit = Box<dyn Fn(&mut Config)>;
        let cases: Vec<(ConfigField, Edit)> = vec![$($(
            (ConfigField::$field, Box::new(|c: &mut Config| c.$member = $v)),
        )+)*];
        cases
    }};
}

/// Every config field, set out of range (and to NaN for floats), is named.
#[test]
fn every_config_field() {
    let cases = out_of_range! {
        MagnitudeThreshold.magnitude_threshold = [-1.0, 1021.0, f32::NAN];
        AnchorMargin.anchor_margin = [1021];
        AlignTolerance.align_tolerance_deg = [0.0, 90.0, f32::NAN];
        DistTolerance.dist_tolerance_px = [0.0, 64.5, f32::INFINITY];
        SkipSteps.skip_min = [0];
        SkipSteps.skip_regular = [0];
        SkipSteps.skip_group = [0];
        MinLength.min_length_px = [-0.5, 70_000.0, f32::NAN];
        MinGroups.min_groups = [0];
        AnchorDensity.anchor_density = [1.5, f32::NAN];
        AlignedDensity.aligned_density = [-0.1];
        MergeCenter.merge_center_px = [0.0];
        MergeAngle.merge_angle_deg = [95.0];
        MergeGap.merge_gap_px = [-1.0, f32::NAN];
        CandidateCapacity.candidates_per_mille = [0, 1001];
        LinkCapacity.max_link_pixels = [15, 65_536];
        ExtendMax.extend_max_px = [1025];
        WorkLimit.work_per_mille = [0, 100_001];
    };
    assert_eq!(cases.len(), 31);
    let img = image();
    let mut slab = vec![0u8; 1 << 20];
    for (field, edit) in &cases {
        let mut cfg = Config::DEFAULT;
        edit(&mut cfg);
        assert_eq!(
            cfg.validate(),
            Err(Error::InvalidConfig(*field)),
            "{field:?}"
        );
        let mut out = [SENTINEL; 4];
        let r = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out);
        assert_eq!(r, Err(Error::InvalidConfig(*field)));
        assert!(out.iter().all(|s| *s == SENTINEL));
        // The error names the field in its message.
        assert!(r.unwrap_err().to_string().contains(field.name()));
    }
    // The documented extremes are accepted.
    let mut cfg = Config::DEFAULT;
    cfg.magnitude_threshold = 1020.0;
    cfg.align_tolerance_deg = 89.9;
    cfg.min_length_px = 0.0;
    cfg.anchor_density = 1.0;
    cfg.aligned_density = 0.0;
    cfg.candidates_per_mille = 1000;
    cfg.max_link_pixels = 65_535;
    cfg.extend_max_px = 1024;
    cfg.work_per_mille = 100_000;
    cfg.work_budget = u32::MAX;
    assert_eq!(cfg.validate(), Ok(()));
}

#[test]
fn bytes_needed_rejects_bad_dimensions() {
    let cfg = Config::DEFAULT;
    assert_eq!(Workspace::bytes_needed(0, 1, &cfg), None);
    assert_eq!(Workspace::bytes_needed(1, 0, &cfg), None);
    assert_eq!(Workspace::bytes_needed(usize::MAX, usize::MAX, &cfg), None);
    assert_eq!(Workspace::bytes_needed(MAX_DIMENSION + 1, 1, &cfg), None);
    assert!(Workspace::bytes_needed(1, 1, &cfg).is_some());
    assert!(Workspace::bytes_needed(8192, 8192, &cfg).is_some());
}

/// Tiny images (1x1 up to 3x3) run and find nothing.
#[test]
fn tiny_images() {
    let cfg = Config::DEFAULT;
    for w in 1..=3 {
        for h in 1..=3 {
            let px: Vec<u8> = (0..w * h).map(|i| (i * 97 % 256) as u8).collect();
            let img = GrayImage::new(&px, w, h, w).unwrap();
            let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
            let mut out = [Segment::default(); 4];
            let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
            assert_eq!(s.segments, 0, "{w}x{h}");
        }
    }
}
