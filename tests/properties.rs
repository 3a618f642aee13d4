//! Property tests (proptest) of the fixed-point core.
//!
//! Scenes are random images from 1x1 up to 200x160 with a random stride:
//! either raw random bytes, or a background with random rectangles and
//! bounded noise (so that segments actually occur). `PROPTEST_CASES` sets
//! the number of cases (default 64 here; the long run in the README used
//! 10,000). Failures are persisted in `proptest-regressions/`.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use aaglsd::{Config, Error, GrayImage, Segment, Summary, Workspace, detect, detect_in_place};
use proptest::prelude::*;
use proptest::strategy::ValueTree;

/// A test image with row padding.
#[derive(Clone, Debug)]
struct Scene {
    w: usize,
    h: usize,
    stride: usize,
    data: Vec<u8>,
}

impl Scene {
    fn image(&self) -> GrayImage<'_> {
        GrayImage::new(&self.data, self.w, self.h, self.stride).unwrap()
    }

    fn px(&self, x: usize, y: usize) -> u8 {
        self.data[y * self.stride + x]
    }

    fn map(&self, w: usize, h: usize, f: impl Fn(usize, usize) -> u8) -> Scene {
        let mut data = vec![0u8; w * h];
        for y in 0..h {
            for x in 0..w {
                data[y * w + x] = f(x, y);
            }
        }
        Scene {
            w,
            h,
            stride: w,
            data,
        }
    }
}

/// A xorshift64 generator (`seed | 1`, so never stuck at zero).
fn xorshift(seed: u64) -> impl FnMut() -> u64 {
    let mut rng = seed | 1;
    move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    }
}

/// Paints `n` rectangles into the `w` x `h` image `img`, each drawn from
/// `next` as corner x, y, extent x, y (clipped at the image), then value.
fn paint_rectangles<T: Copy>(
    img: &mut [T],
    w: usize,
    h: usize,
    n: u64,
    next: &mut impl FnMut() -> u64,
    value: impl Fn(u64) -> T,
) {
    for _ in 0..n {
        let (x0, y0) = ((next() as usize) % w, (next() as usize) % h);
        let (x1, y1) = (x0 + (next() as usize) % w, y0 + (next() as usize) % h);
        let v = value(next());
        for y in y0..y1.min(h) {
            img[y * w + x0..y * w + x1.min(w)].fill(v);
        }
    }
}

fn scene() -> impl Strategy<Value = Scene> {
    (
        1usize..=200,
        1usize..=160,
        0usize..8,
        any::<bool>(),
        any::<u64>(),
    )
        .prop_map(|(w, h, pad, raw, seed)| {
            let stride = w + pad;
            let mut next = xorshift(seed);
            let mut data = vec![0u8; stride * h];
            if raw {
                data.iter_mut().for_each(|v| *v = next() as u8);
            } else {
                let bg = (next() % 256) as u8;
                let noise = (next() % 12) as i32;
                let mut img = vec![i32::from(bg); w * h];
                let n = next() % 6;
                paint_rectangles(&mut img, w, h, n, &mut next, |r| (r % 256) as i32);
                for y in 0..h {
                    for x in 0..w {
                        let n = if noise > 0 {
                            (next() % (2 * noise as u64 + 1)) as i32 - noise
                        } else {
                            0
                        };
                        data[y * stride + x] = (img[y * w + x] + n).clamp(0, 255) as u8;
                    }
                }
            }
            Scene { w, h, stride, data }
        })
}

/// Configs with every field inside its documented range.
fn config() -> impl Strategy<Value = Config> {
    (
        (0.0f32..40.0, 0u16..20, 5.0f32..60.0, 0.5f32..4.0),
        (1u8..12, 1u8..12, 1u8..12, 0.0f32..30.0, 1u8..6),
        (
            0.0f32..=1.0,
            0.0f32..=1.0,
            any::<bool>(),
            0.5f32..3.0,
            1.0f32..20.0,
            0.0f32..20.0,
        ),
        (1u16..=1000, 16u32..5000, 0u16..=64),
    )
        .prop_map(|(a, b, c, d)| Config {
            magnitude_threshold: a.0,
            anchor_margin: a.1,
            align_tolerance_deg: a.2,
            dist_tolerance_px: a.3,
            skip_min: b.0,
            skip_regular: b.1,
            skip_group: b.2,
            min_length_px: b.3,
            min_groups: b.4,
            anchor_density: c.0,
            aligned_density: c.1,
            merge: c.2,
            merge_center_px: c.3,
            merge_angle_deg: c.4,
            merge_gap_px: c.5,
            candidates_per_mille: d.0,
            max_link_pixels: d.1,
            extend_max_px: d.2,
            ..Config::OFFICIAL
        })
}

fn run(s: &Scene, cfg: &Config, cap: usize, slab: &mut [u8]) -> (Summary, Vec<Segment>) {
    let mut out = vec![Segment::default(); cap];
    let sum = detect(&s.image(), cfg, &mut Workspace::new(slab), &mut out).unwrap();
    out.truncate(sum.segments);
    (sum, out)
}

fn slab(s: &Scene, cfg: &Config) -> Vec<u8> {
    vec![0u8; Workspace::bytes_needed(s.w, s.h, cfg).unwrap()]
}

fn cases() -> ProptestConfig {
    let n = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64);
    ProptestConfig {
        cases: n,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(cases())]

    /// Valid configs never fail or panic; counts respect the capacity and
    /// every endpoint lies inside the image, [-0.5, w-0.5] x [-0.5, h-0.5].
    #[test]
    fn invariants(s in scene(), cfg in config(), cap in 1usize..64) {
        let mut ws = slab(&s, &cfg);
        let (sum, segs) = run(&s, &cfg, cap, &mut ws);
        prop_assert!(sum.segments <= cap);
        prop_assert_eq!(segs.len(), sum.segments);
        for g in &segs {
            for (x, y) in [(g.x0, g.y0), (g.x1, g.y1)] {
                prop_assert!(x.is_finite() && y.is_finite());
                prop_assert!(x >= -0.5 && x <= s.w as f32 - 0.5, "{:?} in {}x{}", g, s.w, s.h);
                prop_assert!(y >= -0.5 && y <= s.h as f32 - 0.5, "{:?} in {}x{}", g, s.w, s.h);
            }
        }
    }

    /// Arbitrary (also invalid, NaN) float fields: an error or a result,
    /// never a panic.
    #[test]
    fn arbitrary_floats_never_panic(s in scene(), v in any::<f32>(), which in 0usize..9) {
        let mut cfg = Config::DEFAULT;
        match which {
            0 => cfg.magnitude_threshold = v,
            1 => cfg.align_tolerance_deg = v,
            2 => cfg.dist_tolerance_px = v,
            3 => cfg.min_length_px = v,
            4 => cfg.anchor_density = v,
            5 => cfg.aligned_density = v,
            6 => cfg.merge_center_px = v,
            7 => cfg.merge_angle_deg = v,
            _ => cfg.merge_gap_px = v,
        }
        cfg.merge = true;
        let mut ws = vec![0u8; Workspace::bytes_needed(s.w, s.h, &Config::DEFAULT).unwrap()];
        let mut out = [Segment::default(); 8];
        match detect(&s.image(), &cfg, &mut Workspace::new(&mut ws), &mut out) {
            Ok(sum) => prop_assert!(cfg.validate().is_ok() && sum.segments <= 8),
            Err(Error::InvalidConfig(_)) => prop_assert!(cfg.validate().is_err()),
            Err(e) => prop_assert!(false, "unexpected {e:?}"),
        }
    }

    /// With merging off, a short output queue keeps the first segments and
    /// counts every other one in `dropped_segments`.
    #[test]
    fn dropped_segments_are_accounted(s in scene(), cap in 1usize..6) {
        let cfg = Config::OFFICIAL;
        let mut ws = slab(&s, &cfg);
        let (all, full) = run(&s, &cfg, 10_000, &mut ws);
        let (part, kept) = run(&s, &cfg, cap, &mut ws);
        prop_assert_eq!(part.segments + part.dropped_segments, all.segments);
        // The output keeps the highest scores, best first when it is short
        // (no merging here: the segments are the same ones).
        let mut best = full.clone();
        if part.dropped_segments > 0 {
            best.sort_by(|a, b| {
                b.score.total_cmp(&a.score)
                    .then(a.x0.total_cmp(&b.x0))
                    .then(a.y0.total_cmp(&b.y0))
                    .then(a.x1.total_cmp(&b.x1))
                    .then(a.y1.total_cmp(&b.y1))
            });
        }
        prop_assert_eq!(&kept[..], &best[..part.segments]);
        prop_assert_eq!(part.dropped_segments > 0, all.segments > cap);
        prop_assert_eq!(all.dropped_segments, 0);
    }

    /// Results are deterministic and do not depend on what the workspace
    /// held before (a dirty, reused workspace).
    #[test]
    fn dirty_workspace_same_result(s in scene(), other in scene(), junk in any::<u8>(), cfg in config()) {
        let mut clean = slab(&s, &cfg);
        let (a_sum, a) = run(&s, &cfg, 256, &mut clean);
        // Dirty it with another image, then with junk bytes in the tail.
        let n = clean.len().max(Workspace::bytes_needed(other.w, other.h, &cfg).unwrap());
        let mut dirty = vec![junk; n];
        let _ = run(&other, &cfg, 256, &mut dirty);
        let (b_sum, b) = run(&s, &cfg, 256, &mut dirty);
        prop_assert_eq!(a_sum, b_sum);
        prop_assert_eq!(a, b);
    }

    /// The group index and magnitude cache of the larger workspace
    /// (`bytes_needed_fast`), even dirty, give the same summary and
    /// segments as the smaller one, for any valid config (also the
    /// in-place entry point).
    #[test]
    fn fast_workspace_same_result(s in scene(), junk in any::<u8>(), cfg in config()) {
        let mut small = slab(&s, &cfg);
        let (a_sum, a) = run(&s, &cfg, 256, &mut small);
        let mut fast = vec![junk; Workspace::bytes_needed_fast(s.w, s.h, &cfg).unwrap()];
        let (b_sum, b) = run(&s, &cfg, 256, &mut fast);
        prop_assert_eq!(a_sum, b_sum);
        prop_assert_eq!(&a, &b);
        // In place, with the index and cache: the in-place size plus their bytes.
        let index = fast.len() - small.len();
        let in_place = Workspace::bytes_needed_in_place(s.w, s.h, &cfg).unwrap();
        let mut ws = vec![junk; in_place + index];
        let mut frame = s.data.clone();
        let mut out = vec![Segment::default(); 256];
        let c_sum = detect_in_place(&mut frame, s.w, s.h, s.stride, &cfg, &mut Workspace::new(&mut ws), &mut out).unwrap();
        out.truncate(c_sum.segments);
        prop_assert_eq!(a_sum, c_sum);
        prop_assert_eq!(a, out);
    }

    /// Adding a constant to every pixel (without saturating) changes
    /// nothing: the blur is exact and the gradient sees differences only.
    /// (The scene is first halved so any offset up to 128 stays in range.)
    #[test]
    fn brightness_offset_invariance(s in scene(), c in 1u8..=128) {
        let dark = s.map(s.w, s.h, |x, y| s.px(x, y) / 2);
        let brighter = s.map(s.w, s.h, |x, y| s.px(x, y) / 2 + c);
        let cfg = Config::DEFAULT;
        let mut ws = slab(&s, &cfg);
        let (_, a) = run(&dark, &cfg, 512, &mut ws);
        let (_, b) = run(&brighter, &cfg, 512, &mut ws);
        prop_assert_eq!(a, b);
    }
}

/// Maps a segment through `f` applied to both endpoints.
fn mapped(segs: &[Segment], f: impl Fn(f32, f32) -> (f32, f32)) -> Vec<Segment> {
    segs.iter()
        .map(|s| {
            let (x0, y0) = f(s.x0, s.y0);
            let (x1, y1) = f(s.x1, s.y1);
            Segment {
                x0,
                y0,
                x1,
                y1,
                score: s.score,
            }
        })
        .collect()
}

/// Whether `t` lies on the line of `s` (both its endpoints within `tol` px
/// of that line) and the two overlap along it by at least half the shorter.
fn same_line(s: &Segment, t: &Segment, tol: f32) -> bool {
    let (dx, dy) = (s.x1 - s.x0, s.y1 - s.y0);
    let len = (dx * dx + dy * dy).sqrt();
    if len == 0.0 {
        return false;
    }
    let (ux, uy) = (dx / len, dy / len);
    let off = |x: f32, y: f32| ((x - s.x0) * uy - (y - s.y0) * ux).abs();
    let along = |x: f32, y: f32| (x - s.x0) * ux + (y - s.y0) * uy;
    let (a, b) = (along(t.x0, t.y0), along(t.x1, t.y1));
    let overlap = a.max(b).min(len) - a.min(b).max(0.0);
    off(t.x0, t.y0) <= tol && off(t.x1, t.y1) <= tol && overlap >= 0.5 * len.min((a - b).abs())
}

/// Flipping or transposing the image transforms the segments accordingly.
///
/// Line positions transform exactly (the 2x2 gradient's half-pixel
/// placement is undone by the pixel-centre output), but endpoints can move by
/// a few pixels at corners and junctions: which side of a corner claims the
/// corner pixels depends on the processing order (raster ties, walk
/// direction), which a flip changes. The tolerance is therefore geometric:
/// a segment is matched when the transformed output has a segment on the
/// same line (both endpoints within 1 px of it) overlapping it by at least
/// half the shorter one. Pooled over 300 random scenes (noise-free
/// rectangles and noisy ones) at least 90% of the segments, both ways, must
/// be matched for each transform (measured: 96-98%).
#[test]
fn flips_and_transpose_transform_segments() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let mut hit = [0usize; 3];
    let mut total = [0usize; 3];
    for k in 0..300 {
        let s = scene().new_tree(&mut runner).unwrap().current();
        let s = if k % 2 == 1 {
            s
        } else {
            // Noise-free rectangles on a flat background.
            let mut next = xorshift((s.w * 7919 + s.h * 104_729 + s.data.len()) as u64);
            let (w, h) = (s.w.max(20), s.h.max(20));
            let mut img = vec![(next() % 256) as u8; w * h];
            let n = 1 + next() % 5;
            paint_rectangles(&mut img, w, h, n, &mut next, |r| (r % 256) as u8);
            Scene {
                w,
                h,
                stride: w,
                data: img,
            }
        };
        let cfg = Config::DEFAULT;
        let mut ws = slab(&s, &cfg);
        let mut ws_t = vec![0u8; Workspace::bytes_needed(s.h, s.w, &cfg).unwrap()];
        let (_, a) = run(&s, &cfg, 4096, &mut ws);
        let (w, h) = (s.w as f32, s.h as f32);
        let flip_x = s.map(s.w, s.h, |x, y| s.px(s.w - 1 - x, y));
        let flip_y = s.map(s.w, s.h, |x, y| s.px(x, s.h - 1 - y));
        let transposed = s.map(s.h, s.w, |x, y| s.px(y, x));
        let (_, fx) = run(&flip_x, &cfg, 4096, &mut ws);
        let (_, fy) = run(&flip_y, &cfg, 4096, &mut ws);
        let (_, t) = run(&transposed, &cfg, 4096, &mut ws_t);
        let back = [
            mapped(&fx, |x, y| (w - 1.0 - x, y)),
            mapped(&fy, |x, y| (x, h - 1.0 - y)),
            mapped(&t, |x, y| (y, x)),
        ];
        for (i, b) in back.iter().enumerate() {
            for (from, to) in [(&a, b), (b, &a)] {
                hit[i] += from
                    .iter()
                    .filter(|s| to.iter().any(|t| same_line(s, t, 1.0)))
                    .count();
                total[i] += from.len();
            }
        }
    }
    for (name, (h, t)) in ["flip x", "flip y", "transpose"]
        .iter()
        .zip(hit.iter().zip(total))
    {
        let rate = *h as f64 / t.max(1) as f64;
        eprintln!("{name}: {h}/{t} = {rate:.4} matched");
        assert!(t > 500, "{name}: too few segments ({t}) to judge");
        assert!(rate >= 0.90, "{name}: only {rate:.4} of segments transform");
    }
}
