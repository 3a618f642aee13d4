//! Unit tests that call the `extern "C"` functions directly, as C would.
//! Images are small so that the suite also runs under Miri.
#![allow(clippy::undocumented_unsafe_blocks)] // tests: every call passes valid Rust buffers

use core::ffi::CStr;
use core::mem::MaybeUninit;
use core::ptr;

use super::*;
#[allow(unused_imports)]
use aaglsd::{Config, ConfigField, Error, GrayImage, Profile, Reseed, Segment, Summary, Workspace};
use core::ffi::c_char;

const W: usize = 48;
const H: usize = 40;

/// A dark rectangle and a bright diagonal bar on a mid-gray background.
fn scene(w: usize, h: usize) -> Vec<u8> {
    let mut px = vec![150u8; w * h];
    for y in 0..h {
        for x in 0..w {
            if (8..30).contains(&y) && (10..34).contains(&x) {
                px[y * w + x] = 40;
            }
            if (x + 2 * y) / 3 == 24 || (x + 2 * y) / 3 == 25 {
                px[y * w + x] = 230;
            }
        }
    }
    px
}

fn profile(p: AaglsdProfile) -> AaglsdConfig {
    let mut c = MaybeUninit::<AaglsdConfig>::uninit();
    assert_eq!(
        unsafe { aaglsd_config_profile(p as u32, c.as_mut_ptr()) },
        AaglsdStatus::Ok
    );
    unsafe { c.assume_init() }
}

fn ws_size(w: usize, h: usize, cfg: &AaglsdConfig) -> usize {
    let mut n = usize::MAX;
    assert_eq!(
        unsafe { aaglsd_workspace_size(w, h, cfg, &mut n) },
        AaglsdStatus::Ok
    );
    n
}

struct Run {
    status: AaglsdStatus,
    summary: AaglsdSummary,
}

/// The signature of `aaglsd_detect` and `aaglsd_detect_in_place`, whose
/// pixel pointers (`P`) differ in mutability.
type DetectFn<P> = unsafe extern "C" fn(
    P,
    usize,
    usize,
    usize,
    usize,
    *const AaglsdConfig,
    *mut u8,
    usize,
    *mut AaglsdSegment,
    usize,
    *mut AaglsdSummary,
) -> AaglsdStatus;

/// The pixels of a [`run`] and the function it calls on them: an image to
/// read (`&`) goes to `aaglsd_detect`, a frame it may overwrite (`&mut`)
/// to `aaglsd_detect_in_place`.
trait Pixels {
    type Ptr;
    const DETECT: DetectFn<Self::Ptr>;
    fn raw(self) -> (Self::Ptr, usize);
}

impl<T: AsRef<[u8]> + ?Sized> Pixels for &T {
    type Ptr = *const u8;
    const DETECT: DetectFn<*const u8> = aaglsd_detect;
    fn raw(self) -> (*const u8, usize) {
        let px = self.as_ref();
        (px.as_ptr(), px.len())
    }
}

impl Pixels for &mut [u8] {
    type Ptr = *mut u8;
    const DETECT: DetectFn<*mut u8> = aaglsd_detect_in_place;
    fn raw(self) -> (*mut u8, usize) {
        (self.as_mut_ptr(), self.len())
    }
}

/// Detection on `px`, rows `stride` bytes apart, with the other buffers
/// as slices; the summary starts non-zero, so that a zeroed one shows the
/// function wrote it.
#[allow(clippy::too_many_arguments)]
fn run<P: Pixels>(
    px: P,
    w: usize,
    h: usize,
    stride: usize,
    cfg: &AaglsdConfig,
    ws: &mut [u8],
    out: &mut [AaglsdSegment],
) -> Run {
    let mut summary = AaglsdSummary {
        segments: 99,
        ..AaglsdSummary::default()
    };
    let (px, len) = px.raw();
    let status = unsafe {
        P::DETECT(
            px,
            len,
            w,
            h,
            stride,
            cfg,
            ws.as_mut_ptr(),
            ws.len(),
            out.as_mut_ptr(),
            out.len(),
            &mut summary,
        )
    };
    Run { status, summary }
}

fn bits(s: &[AaglsdSegment]) -> Vec<[u32; 5]> {
    s.iter()
        .map(|s| [s.x0, s.y0, s.x1, s.y1, s.score].map(f32::to_bits))
        .collect()
}

fn core_bits(s: &[Segment]) -> Vec<[u32; 5]> {
    s.iter()
        .map(|s| [s.x0, s.y0, s.x1, s.y1, s.score].map(f32::to_bits))
        .collect()
}

/// The core's own result for `px` (tightly packed).
fn core_detect(px: &[u8], w: usize, h: usize, cfg: &Config) -> (Summary, Vec<[u32; 5]>) {
    let img = GrayImage::new(px, w, h, w).unwrap();
    let mut slab = vec![0u8; Workspace::bytes_needed(w, h, cfg).unwrap()];
    let mut out = vec![Segment::default(); 64];
    let s = aaglsd::detect(&img, cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
    (s, core_bits(&out[..s.segments]))
}

fn c_str(p: *const c_char) -> &'static str {
    assert!(!p.is_null());
    unsafe { CStr::from_ptr(p) }.to_str().unwrap()
}

/// `Summary` is `#[non_exhaustive]`, so `From<Summary>` cannot name every
/// field: a counter added to it makes it larger than the mirror, all of whose
/// fields are `usize` like its own.
#[test]
fn every_summary_field_is_mirrored() {
    assert_eq!(size_of::<Summary>(), size_of::<AaglsdSummary>());
    assert_eq!(
        size_of::<AaglsdSummary>(),
        AaglsdSummary::default().values().len() * size_of::<usize>()
    );
}

#[test]
fn status_and_field_values_are_stable() {
    use AaglsdStatus as S;
    let all = [
        S::Ok,
        S::ZeroDimension,
        S::ImageTooLarge,
        S::StrideTooSmall,
        S::BufferTooShort,
        S::WorkspaceTooSmall,
        S::OutputEmpty,
        S::InvalidConfig,
        S::NullPointer,
        S::Misaligned,
        S::BuffersOverlap,
        S::InvalidArgument,
        S::Unknown,
    ];
    for (i, s) in all.iter().enumerate() {
        assert_eq!(*s as i32, i as i32);
    }
    assert_eq!(AaglsdConfigField::LinkCapacity as i32, 14);
    assert_eq!(AaglsdProfile::Paper as u32, 2);
}

#[test]
fn reseed_bytes_map_to_the_rust_enum() {
    for (byte, want) in [
        (0, Reseed::Never),
        (1, Reseed::Always),
        (2, Reseed::Once),
        (3, Reseed::Misfit),
        (7, Reseed::Always),
    ] {
        let c = AaglsdConfig {
            reseed: byte,
            ..profile(AaglsdProfile::Default)
        };
        assert_eq!(Config::from(&c).reseed, want, "byte {byte}");
    }
    for r in [Reseed::Never, Reseed::Always, Reseed::Once, Reseed::Misfit] {
        let cfg = Config {
            reseed: r,
            ..Config::DEFAULT
        };
        assert_eq!(AaglsdConfig::from(&cfg).reseed, r.code());
        assert_eq!(Config::from(&AaglsdConfig::from(&cfg)), cfg);
    }
    assert_eq!(
        profile(AaglsdProfile::Default).reseed,
        Reseed::Misfit.code()
    );
    assert_eq!(
        profile(AaglsdProfile::Official).reseed,
        Reseed::Always.code()
    );
}

#[test]
fn status_strings_are_static_and_distinct() {
    let known: Vec<&str> = (0..=12).map(|s| c_str(aaglsd_status_str(s))).collect();
    for (i, a) in known.iter().enumerate() {
        assert!(!a.is_empty() && a != &"unknown status", "{i}: {a}");
        for b in &known[i + 1..] {
            assert_ne!(a, b);
        }
    }
    assert_eq!(known[0], "ok");
    for s in [-1, 13, i32::MIN, i32::MAX] {
        assert_eq!(c_str(aaglsd_status_str(s)), "unknown status");
    }
    assert_eq!(c_str(aaglsd_config_field_str(0)), "none");
    assert_eq!(c_str(aaglsd_config_field_str(14)), "max_link_pixels");
    assert_eq!(c_str(aaglsd_config_field_str(16)), "work_per_mille");
    assert_eq!(c_str(aaglsd_config_field_str(17)), "bridge_px");
    assert_eq!(c_str(aaglsd_config_field_str(18)), "min_score");
    assert_eq!(c_str(aaglsd_config_field_str(19)), "unknown field");
    assert_eq!(c_str(aaglsd_config_field_str(255)), "unknown field");
    assert_eq!(c_str(aaglsd_config_field_str(-1)), "unknown field");
    assert_eq!(c_str(aaglsd_version()), env!("CARGO_PKG_VERSION"));
}

#[test]
fn config_field_strings_match_the_core() {
    for f in ConfigField::ALL {
        let c = AaglsdConfigField::from(f);
        assert_eq!(c_str(aaglsd_config_field_str(c as i32)), f.name());
    }
}

/// The C enums carry the core's numbers: every core error kind, config
/// field and profile maps to the C value equal to its code.
#[test]
fn status_values_are_the_core_codes() {
    // Every kind of core error, as the core reports it.
    let px = [0u8; 8];
    let img = GrayImage::new(&px, 2, 2, 2).unwrap();
    let mut slab = vec![0u8; Workspace::bytes_needed(2, 2, &Config::DEFAULT).unwrap()];
    let run = |slab: &mut [u8], out: &mut [Segment]| {
        aaglsd::detect(&img, &Config::DEFAULT, &mut Workspace::new(slab), out).unwrap_err()
    };
    let no_groups = Config {
        min_groups: 0,
        ..Config::DEFAULT
    };
    let errors = [
        GrayImage::new(&px, 0, 1, 1).unwrap_err(),
        GrayImage::new(&px, 1 << 20, 1, 1 << 20).unwrap_err(),
        GrayImage::new(&px, 2, 1, 1).unwrap_err(),
        GrayImage::new(&px, 4, 4, 4).unwrap_err(),
        run(&mut [], &mut [Segment::ZERO]),
        run(&mut slab, &mut []),
        no_groups.validate().unwrap_err(),
    ];
    let mut codes: Vec<i32> = errors.iter().map(Error::code).collect();
    codes.sort_unstable();
    assert_eq!(codes, [1, 2, 3, 4, 5, 6, 7], "one error of each kind");
    for e in errors {
        assert_eq!(AaglsdStatus::from(e) as i32, e.code(), "{e:?}");
    }
    for f in ConfigField::ALL {
        assert_eq!(AaglsdConfigField::from(f) as i32, f.code(), "{f:?}");
    }
    for (c, p) in [
        (AaglsdProfile::Default, Profile::Default),
        (AaglsdProfile::Official, Profile::Official),
        (AaglsdProfile::Paper, Profile::Paper),
    ] {
        assert_eq!(c as u32, p.code());
    }
    assert_eq!(Profile::ALL.len(), 3, "a new core profile needs a C value");
}

#[test]
fn profiles_mirror_the_core() {
    for (p, core) in [
        (AaglsdProfile::Default, Config::DEFAULT),
        (AaglsdProfile::Official, Config::OFFICIAL),
        (AaglsdProfile::Paper, Config::PAPER),
    ] {
        let c = profile(p);
        assert_eq!(Config::from(&c), core);
        assert_eq!(c, AaglsdConfig::from(&core));
    }
    let mut d = MaybeUninit::<AaglsdConfig>::uninit();
    assert_eq!(
        unsafe { aaglsd_config_default(d.as_mut_ptr()) },
        AaglsdStatus::Ok
    );
    assert_eq!(unsafe { d.assume_init() }, profile(AaglsdProfile::Default));
    // Any non-zero byte turns merging on.
    let mut c = profile(AaglsdProfile::Official);
    c.merge = 0xA5;
    assert!(Config::from(&c).merge);
    // Unknown profile: error, output untouched.
    let mut c = profile(AaglsdProfile::Paper);
    let before = c;
    for p in [3, u32::MAX] {
        assert_eq!(
            unsafe { aaglsd_config_profile(p, &mut c) },
            AaglsdStatus::InvalidArgument
        );
        assert_eq!(c, before);
    }
}

#[test]
fn config_pointers_may_be_unaligned() {
    let cfg = profile(AaglsdProfile::Paper);
    let mut buf = vec![0u8; size_of::<AaglsdConfig>() + 1];
    let p = unsafe { buf.as_mut_ptr().add(1) }.cast::<AaglsdConfig>();
    assert_eq!(
        unsafe { aaglsd_config_profile(AaglsdProfile::Paper as u32, p) },
        AaglsdStatus::Ok
    );
    assert_eq!(unsafe { ptr::read_unaligned(p) }, cfg);
    let mut field = [0u8; 5];
    let f = unsafe { field.as_mut_ptr().add(1) }.cast::<AaglsdConfigField>();
    assert_eq!(unsafe { aaglsd_config_validate(p, f) }, AaglsdStatus::Ok);
    assert_eq!(unsafe { ptr::read_unaligned(f) }, AaglsdConfigField::None);
    let mut n = [0u8; size_of::<usize>() + 1];
    let np = unsafe { n.as_mut_ptr().add(1) }.cast::<usize>();
    assert_eq!(
        unsafe { aaglsd_workspace_size(W, H, p, np) },
        AaglsdStatus::Ok
    );
    assert_eq!(
        unsafe { ptr::read_unaligned(np) },
        Workspace::bytes_needed(W, H, &Config::PAPER).unwrap()
    );
}

#[test]
fn workspace_size_matches_the_core() {
    let cfg = profile(AaglsdProfile::Default);
    for (w, h) in [(1, 1), (W, H), (640, 480), (8192, 8192), (32_767, 2048)] {
        assert_eq!(
            ws_size(w, h, &cfg),
            Workspace::bytes_needed(w, h, &Config::DEFAULT).unwrap()
        );
    }
}

#[test]
fn fast_workspace_size_and_result() {
    let px = scene(W, H);
    for p in [AaglsdProfile::Default, AaglsdProfile::Paper] {
        let cfg = profile(p);
        let mut fast = usize::MAX;
        assert_eq!(
            unsafe { aaglsd_workspace_size_fast(W, H, &cfg, &mut fast) },
            AaglsdStatus::Ok
        );
        let c = Config::from(&cfg);
        assert_eq!(Some(fast), Workspace::bytes_needed_fast(W, H, &c));
        assert_eq!(fast, ws_size(W, H, &cfg) + 4 * (W * H).div_ceil(2) + W * H);
        let (want_summary, want) = core_detect(&px, W, H, &c);
        // Dirty slabs: the fast size, one byte short of it (the smaller
        // layout), and more than it.
        for len in [fast, fast - 1, fast + 100] {
            let mut ws = vec![0xA5u8; len];
            let mut out = [AaglsdSegment::default(); 64];
            let r = run(&px, W, H, W, &cfg, &mut ws, &mut out);
            assert_eq!(r.status, AaglsdStatus::Ok);
            assert_eq!(r.summary, AaglsdSummary::from(want_summary));
            assert_eq!(bits(&out[..r.summary.segments]), want);
        }
    }
    let mut n = 7usize;
    assert_eq!(
        unsafe { aaglsd_workspace_size_fast(W, H, ptr::null(), &mut n) },
        AaglsdStatus::NullPointer
    );
    assert_eq!(n, 0);
    assert_eq!(
        unsafe { aaglsd_workspace_size_fast(0, H, &profile(AaglsdProfile::Default), &mut n) },
        AaglsdStatus::ZeroDimension
    );
}

#[test]
fn workspace_size_errors() {
    let cfg = profile(AaglsdProfile::Default);
    let mut n = 7usize;
    let ws =
        |w, h, c: *const AaglsdConfig, n: *mut usize| unsafe { aaglsd_workspace_size(w, h, c, n) };
    assert_eq!(ws(W, H, ptr::null(), &mut n), AaglsdStatus::NullPointer);
    assert_eq!(n, 0);
    assert_eq!(ws(W, H, &cfg, ptr::null_mut()), AaglsdStatus::NullPointer);
    assert_eq!(ws(0, H, &cfg, &mut n), AaglsdStatus::ZeroDimension);
    assert_eq!(ws(W, 0, &cfg, &mut n), AaglsdStatus::ZeroDimension);
    assert_eq!(ws(32_768, 1, &cfg, &mut n), AaglsdStatus::ImageTooLarge);
    assert_eq!(ws(8193, 8193, &cfg, &mut n), AaglsdStatus::ImageTooLarge);
    assert_eq!(
        ws(usize::MAX, usize::MAX, &cfg, &mut n),
        AaglsdStatus::ImageTooLarge
    );
    let mut bad = cfg;
    bad.candidates_per_mille = 0;
    n = 7;
    assert_eq!(ws(W, H, &bad, &mut n), AaglsdStatus::InvalidConfig);
    assert_eq!(n, 0);
}

#[test]
fn detect_matches_the_core_bit_for_bit() {
    let px = scene(W, H);
    for p in [AaglsdProfile::Official, AaglsdProfile::Paper] {
        let cfg = profile(p);
        let (want_summary, want) = core_detect(&px, W, H, &Config::from(&cfg));
        assert!(
            want.len() >= 4,
            "{p:?}: the scene has lines ({})",
            want.len()
        );
        let mut ws = vec![0u8; ws_size(W, H, &cfg)];
        let mut out = [AaglsdSegment::default(); 64];
        let r = run(&px, W, H, W, &cfg, &mut ws, &mut out);
        assert_eq!(r.status, AaglsdStatus::Ok);
        assert_eq!(r.summary, AaglsdSummary::from(want_summary));
        assert_eq!(bits(&out[..r.summary.segments]), want);
    }
}

#[test]
fn padded_stride_unaligned_and_uninitialised_buffers_give_the_same_result() {
    let px = scene(W, H);
    let cfg = profile(AaglsdProfile::Default);
    let (want_summary, want) = core_detect(&px, W, H, &Config::DEFAULT);
    // Rows 5 bytes apart more than the width; no padding after the last row.
    let stride = W + 5;
    let mut padded = vec![0xEEu8; stride * (H - 1) + W];
    for y in 0..H {
        padded[y * stride..y * stride + W].copy_from_slice(&px[y * W..(y + 1) * W]);
    }
    let n = ws_size(W, H, &cfg);
    // Uninitialised memory, as from C's malloc: the core may only write it
    // before reading (Miri checks this).
    let mut ws = vec![MaybeUninit::<u8>::uninit(); n + 3];
    let mut out = vec![MaybeUninit::<AaglsdSegment>::uninit(); 64];
    // Every slab alignment (two under Miri, for time).
    let offsets: &[usize] = if cfg!(miri) { &[0, 3] } else { &[0, 1, 2, 3] };
    for &off in offsets {
        let mut summary = AaglsdSummary::default();
        let status = unsafe {
            aaglsd_detect(
                padded.as_ptr(),
                padded.len(),
                W,
                H,
                stride,
                &cfg,
                ws.as_mut_ptr().cast::<u8>().add(off),
                n,
                out.as_mut_ptr().cast(),
                out.len(),
                &mut summary,
            )
        };
        assert_eq!(status, AaglsdStatus::Ok);
        assert_eq!(summary, AaglsdSummary::from(want_summary));
        let got: Vec<AaglsdSegment> = out[..summary.segments]
            .iter()
            .map(|s| unsafe { s.assume_init() })
            .collect();
        assert_eq!(bits(&got), want);
    }
}

#[test]
fn a_full_output_counts_the_dropped_segments() {
    let px = scene(W, H);
    let cfg = profile(AaglsdProfile::Official);
    let (want_summary, mut want) = core_detect(&px, W, H, &Config::OFFICIAL);
    let mut ws = vec![0u8; ws_size(W, H, &cfg)];
    let mut out = [AaglsdSegment::default(); 2];
    let r = run(&px, W, H, W, &cfg, &mut ws, &mut out);
    assert_eq!(r.status, AaglsdStatus::Ok);
    assert_eq!(r.summary.segments, 2);
    assert_eq!(r.summary.dropped_segments, want_summary.segments - 2);
    // The two best by score, best first (no merging in OFFICIAL): the
    // scores are non-negative, so their bits order as they do.
    want.sort_by_key(|b| core::cmp::Reverse(b[4]));
    assert!(
        want[1][4] > want[2][4],
        "a tie at the cut: pick another scene"
    );
    assert_eq!(bits(&out), want[..2]);
}

/// Every failing call must zero the summary and leave `out` untouched.
fn expect_error(r: &Run, out: &[AaglsdSegment], status: AaglsdStatus) {
    assert_eq!(r.status, status);
    assert_eq!(r.summary, AaglsdSummary::default(), "{status:?}");
    assert!(out.iter().all(|s| *s == SENTINEL), "{status:?}");
}

/// What the error tests fill the output with: a failing call leaves it.
const SENTINEL: AaglsdSegment = AaglsdSegment {
    x0: -1.0,
    y0: -2.0,
    x1: -3.0,
    y1: -4.0,
    score: -5.0,
};

fn sentinel_out<const N: usize>() -> [AaglsdSegment; N] {
    [SENTINEL; N]
}

/// The error tests' buffers: the scene, the default profile, a workspace
/// of its size and an output of `N` sentinels.
fn error_setup<const N: usize>() -> (Vec<u8>, AaglsdConfig, Vec<u8>, [AaglsdSegment; N]) {
    let px = scene(W, H);
    let cfg = profile(AaglsdProfile::Default);
    let ws = vec![0u8; ws_size(W, H, &cfg)];
    (px, cfg, ws, sentinel_out())
}

#[test]
fn null_pointers() {
    let (px, cfg, mut ws, mut out) = error_setup::<8>();
    let mut summary = AaglsdSummary {
        groups: 5,
        ..AaglsdSummary::default()
    };
    for which in 0..5 {
        let status = unsafe {
            aaglsd_detect(
                if which == 0 { ptr::null() } else { px.as_ptr() },
                px.len(),
                W,
                H,
                W,
                if which == 1 { ptr::null() } else { &cfg },
                if which == 2 {
                    ptr::null_mut()
                } else {
                    ws.as_mut_ptr()
                },
                ws.len(),
                if which == 3 {
                    ptr::null_mut()
                } else {
                    out.as_mut_ptr()
                },
                out.len(),
                if which == 4 {
                    ptr::null_mut()
                } else {
                    &mut summary
                },
            )
        };
        if which == 4 {
            // No summary to zero; the local one is untouched.
            assert_eq!(status, AaglsdStatus::NullPointer);
            assert_eq!(summary.groups, 5);
        } else {
            expect_error(&Run { status, summary }, &out, AaglsdStatus::NullPointer);
        }
        summary.groups = 5;
    }
    assert_eq!(
        unsafe { aaglsd_config_default(ptr::null_mut()) },
        AaglsdStatus::NullPointer
    );
    assert_eq!(
        unsafe { aaglsd_config_profile(1, ptr::null_mut()) },
        AaglsdStatus::NullPointer
    );
    assert_eq!(
        unsafe { aaglsd_config_validate(ptr::null(), ptr::null_mut()) },
        AaglsdStatus::NullPointer
    );
    // The field out-parameter is optional.
    assert_eq!(
        unsafe { aaglsd_config_validate(&cfg, ptr::null_mut()) },
        AaglsdStatus::Ok
    );
}

#[test]
fn image_errors() {
    let (px, cfg, mut ws, mut out) = error_setup::<8>();
    let cases: [(usize, usize, usize, usize, AaglsdStatus); 8] = [
        (0, H, W, px.len(), AaglsdStatus::ZeroDimension),
        (W, 0, W, px.len(), AaglsdStatus::ZeroDimension),
        (32_768, 1, 32_768, px.len(), AaglsdStatus::ImageTooLarge),
        (1, 32_768, 1, px.len(), AaglsdStatus::ImageTooLarge),
        (8193, 8193, 8193, px.len(), AaglsdStatus::ImageTooLarge),
        (W, H, W - 1, px.len(), AaglsdStatus::StrideTooSmall),
        (W, H, W, px.len() - 1, AaglsdStatus::BufferTooShort),
        (W, H, usize::MAX, px.len(), AaglsdStatus::BufferTooShort),
    ];
    for (w, h, stride, len, status) in cases {
        let r = run(&px[..len], w, h, stride, &cfg, &mut ws, &mut out);
        expect_error(&r, &out, status);
    }
}

#[test]
fn workspace_and_output_errors() {
    let (px, cfg, mut ws, mut out) = error_setup::<8>();
    let n = ws.len();
    let r = run(&px, W, H, W, &cfg, &mut ws[..n - 1], &mut out);
    expect_error(&r, &out, AaglsdStatus::WorkspaceTooSmall);
    let r = run(&px, W, H, W, &cfg, &mut ws, &mut out[..0]);
    expect_error(&r, &out, AaglsdStatus::OutputEmpty);
}

/// One bad value per configuration field category, and NaN for every
/// float field.
fn bad_configs() -> Vec<(AaglsdConfig, AaglsdConfigField)> {
    use AaglsdConfigField as F;
    let base = profile(AaglsdProfile::Default);
    type Float = fn(&mut AaglsdConfig) -> &mut f32;
    type Edit = fn(&mut AaglsdConfig);
    // Each float field with a bad value, to be tested with NaN too.
    let floats: [(Float, f32, F); 9] = [
        (|c| &mut c.magnitude_threshold, -0.5, F::MagnitudeThreshold),
        (|c| &mut c.align_tolerance_deg, 0.0, F::AlignTolerance),
        (|c| &mut c.dist_tolerance_px, 64.5, F::DistTolerance),
        (|c| &mut c.min_length_px, f32::INFINITY, F::MinLength),
        (|c| &mut c.anchor_density, 1.5, F::AnchorDensity),
        (|c| &mut c.aligned_density, -0.1, F::AlignedDensity),
        (|c| &mut c.merge_center_px, 0.0, F::MergeCenter),
        (|c| &mut c.merge_angle_deg, 90.0, F::MergeAngle),
        (|c| &mut c.merge_gap_px, 4097.0, F::MergeGap),
    ];
    let others: [(Edit, F); 13] = [
        (|c| c.anchor_margin = 1021, F::AnchorMargin),
        (|c| c.skip_min = 0, F::SkipSteps),
        (|c| c.skip_regular = 0, F::SkipSteps),
        (|c| c.skip_group = 0, F::SkipSteps),
        (|c| c.min_groups = 0, F::MinGroups),
        (|c| c.candidates_per_mille = 0, F::CandidateCapacity),
        (|c| c.candidates_per_mille = 1001, F::CandidateCapacity),
        (|c| c.max_link_pixels = 15, F::LinkCapacity),
        (|c| c.max_link_pixels = 65_536, F::LinkCapacity),
        (|c| c.max_link_pixels = u32::MAX, F::LinkCapacity),
        (|c| c.extend_max_px = 1025, F::ExtendMax),
        (|c| c.work_per_mille = 0, F::WorkLimit),
        (|c| c.work_per_mille = 100_001, F::WorkLimit),
    ];
    let floats = floats.into_iter().flat_map(|(field, bad, f)| {
        [bad, f32::NAN].map(|v| {
            let mut c = base;
            *field(&mut c) = v;
            (c, f)
        })
    });
    let others = others.into_iter().map(|(edit, f)| {
        let mut c = base;
        edit(&mut c);
        (c, f)
    });
    floats.chain(others).collect()
}

#[test]
fn each_bad_config_field_is_reported() {
    let (px, _, mut ws, mut out) = error_setup::<8>();
    let cases = bad_configs();
    for (cfg, field) in &cases {
        let mut got = AaglsdConfigField::None;
        assert_eq!(
            unsafe { aaglsd_config_validate(cfg, &mut got) },
            AaglsdStatus::InvalidConfig
        );
        assert_eq!(got, *field);
        let r = run(&px, W, H, W, cfg, &mut ws, &mut out);
        expect_error(&r, &out, AaglsdStatus::InvalidConfig);
    }
    // Every category is covered.
    for f in 1..=14 {
        assert!(cases.iter().any(|(_, c)| *c as i32 == f), "field {f}");
    }
}

#[test]
fn misaligned_output_is_refused() {
    let (px, cfg, mut ws, mut out) = error_setup::<9>();
    let mut summary = AaglsdSummary::default();
    let status = unsafe {
        aaglsd_detect(
            px.as_ptr(),
            px.len(),
            W,
            H,
            W,
            &cfg,
            ws.as_mut_ptr(),
            ws.len(),
            out.as_mut_ptr().cast::<u8>().add(2).cast(),
            8,
            &mut summary,
        )
    };
    expect_error(&Run { status, summary }, &out, AaglsdStatus::Misaligned);
}

#[test]
fn overlapping_buffers_are_refused() {
    let cfg = profile(AaglsdProfile::Default);
    let n = ws_size(W, H, &cfg);
    let px_len = W * H;
    let out_bytes = 8 * size_of::<AaglsdSegment>();
    // One allocation holding [pixels | workspace | output], 4-aligned.
    let mut words = vec![0u32; (px_len + n + out_bytes).div_ceil(4) + 4];
    let base = words.as_mut_ptr().cast::<u8>();
    let call = |p_off: usize, w_off: usize, o_off: usize| {
        let mut summary = AaglsdSummary::default();
        unsafe {
            aaglsd_detect(
                base.add(p_off),
                px_len,
                W,
                H,
                W,
                &cfg,
                base.add(w_off),
                n,
                base.add(o_off).cast(),
                8,
                &mut summary,
            )
        }
    };
    let o_end = (px_len + n).next_multiple_of(4);
    // Disjoint: accepted (a flat image, no segments).
    assert_eq!(call(0, px_len, o_end), AaglsdStatus::Ok);
    // Pixels and workspace share their boundary byte.
    assert_eq!(call(0, px_len - 1, o_end), AaglsdStatus::BuffersOverlap);
    // Workspace and output share a byte.
    assert_eq!(call(0, px_len, o_end - 4), AaglsdStatus::BuffersOverlap);
    // Output inside the pixels.
    assert_eq!(call(0, px_len, 4), AaglsdStatus::BuffersOverlap);
    // Same buffer for all three.
    assert_eq!(call(0, 0, 0), AaglsdStatus::BuffersOverlap);
}

#[test]
fn in_place_matches_the_core_and_needs_a_frame_less() {
    let px = scene(W, H);
    for p in [AaglsdProfile::Default, AaglsdProfile::Paper] {
        let cfg = profile(p);
        let c = Config::from(&cfg);
        let mut small = usize::MAX;
        assert_eq!(
            unsafe { aaglsd_workspace_size_in_place(W, H, &cfg, &mut small) },
            AaglsdStatus::Ok
        );
        assert_eq!(Some(small), Workspace::bytes_needed_in_place(W, H, &c));
        assert_eq!(small + W * H, ws_size(W, H, &cfg));
        let (want_summary, want) = core_detect(&px, W, H, &c);
        // The core's smoothed frame, to compare the frame with afterwards.
        let mut smoothed = px.clone();
        let mut slab = vec![0u8; small];
        let mut out = [Segment::default(); 64];
        aaglsd::detect_in_place(
            &mut smoothed,
            W,
            H,
            W,
            &c,
            &mut Workspace::new(&mut slab),
            &mut out,
        )
        .unwrap();
        let fast = small + 4 * (W * H).div_ceil(2) + W * H;
        // Dirty slabs: the in-place size, one byte short of the faster
        // layout, and that layout's size.
        for len in [small, fast - 1, fast] {
            let mut frame = px.clone();
            let mut ws = vec![0xA5u8; len];
            let mut out = [AaglsdSegment::default(); 64];
            let r = run(frame.as_mut_slice(), W, H, W, &cfg, &mut ws, &mut out);
            assert_eq!(r.status, AaglsdStatus::Ok, "{p:?} {len}");
            let summary = r.summary;
            assert_eq!(summary, AaglsdSummary::from(want_summary));
            assert_eq!(bits(&out[..summary.segments]), want);
            assert_eq!(frame, smoothed);
        }
        // One byte short: refused, frame and output untouched.
        let mut frame = px.clone();
        let mut ws = vec![0u8; small - 1];
        let mut out = sentinel_out::<8>();
        let r = run(frame.as_mut_slice(), W, H, W, &cfg, &mut ws, &mut out);
        assert_eq!(r.status, AaglsdStatus::WorkspaceTooSmall);
        assert_eq!(frame, px);
        assert_eq!(bits(&out), bits(&sentinel_out::<8>()));
        assert_eq!(r.summary, AaglsdSummary::default());
    }
    let mut n = 7usize;
    assert_eq!(
        unsafe { aaglsd_workspace_size_in_place(W, H, ptr::null(), &mut n) },
        AaglsdStatus::NullPointer
    );
    assert_eq!(n, 0);
}
