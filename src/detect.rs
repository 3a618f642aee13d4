//! The pipeline skeleton: validation at the entry, then each stage in the
//! paper's order on the caller's workspace.

use core::num::NonZeroUsize;

use crate::invariant::Invariant;
use crate::params::Params;
use crate::stage::anchors::{self, AnchorStats};
use crate::stage::best::{Best, by_score};
use crate::stage::groups::Groups;
use crate::stage::output::SegQ8;
use crate::stage::state::{BitMap, ClassMap};
use crate::stage::work::Work;
use crate::stage::{extract, link, merge, smooth};
use crate::target::{SIMD, SMALL};
use crate::workspace::{AnchorPass, Extraction, Layout, Linking, Merge, Workspace};
use crate::{Config, Error, GrayImage, Segment, Summary};

/// [`detect`] into a `heapless::Vec`: the vector is cleared, filled with at
/// most `N` segments, and the [`Summary`] counts any that did not fit.
///
/// ```
/// use aaglsd::{detect_into_vec, Config, GrayImage, Segment, Workspace};
/// let px = [0u8; 32 * 32];
/// let img = GrayImage::new(&px, 32, 32, 32)?;
/// let mut slab = [0u8; Workspace::bytes_needed_default(32, 32)];
/// let mut out: heapless::Vec<Segment, 8> = heapless::Vec::new();
/// let s = detect_into_vec(&img, &Config::DEFAULT, &mut Workspace::new(&mut slab), &mut out)?;
/// assert_eq!((s.segments, out.len()), (0, 0)); // a flat image has no lines
/// # Ok::<(), aaglsd::Error>(())
/// ```
///
/// # Errors
/// As [`detect`]; [`Error::OutputEmpty`] when `N == 0`. On error `out` is empty.
pub fn detect_into_vec<const N: usize>(
    img: &GrayImage<'_>,
    cfg: &Config,
    ws: &mut Workspace<'_>,
    out: &mut heapless::Vec<Segment, N>,
) -> Result<Summary, Error> {
    out.clear();
    // Cannot fail: the length equals the capacity.
    let _ = out.resize_default(N);
    let r = detect(img, cfg, ws, out.as_mut_slice());
    out.truncate(r.map_or(0, |s| s.segments));
    r
}

/// A part of [`detect`] that the benchmarks time alone ([`detect_part`]).
/// Unstable: behind the `_unstable-hooks` feature.
#[cfg(any(test, feature = "_unstable-hooks"))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The speed floor: the core's own first pass alone (smoothing into the
    /// workspace, then the gradient and thresholded magnitude of every row
    /// into the ring). Its value is the sum of the magnitudes.
    Floor,
    /// Everything before the linking (smoothing, gradients, anchors, their
    /// processing order, the groups and the group-direction cache). Its
    /// value is the number of groups; the walk, the validation and the
    /// merging do not run.
    FrontEnd,
}

/// Runs one [`Part`] of [`detect`] on `img` and returns its value.
/// Unstable: behind the `_unstable-hooks` feature, for the benchmarks.
///
/// # Errors
/// As [`detect`], without the output check.
#[cfg(any(test, feature = "_unstable-hooks"))]
pub fn detect_part(
    part: Part,
    img: &GrayImage<'_>,
    cfg: &Config,
    ws: &mut Workspace<'_>,
) -> Result<u64, Error> {
    if part == Part::FrontEnd {
        let mut out = [Segment::default()];
        let s = detect_with(Source::Image(img), cfg, ws, &mut out, Run::FrontEnd)?;
        return Ok(s.groups as u64);
    }
    // Without the group index, which the floor does not use.
    let (layout, p) = prepare(img.width(), img.height(), cfg, false, 0)?;
    let (blur, mut slab) = ws.carve(&layout)?;
    smooth::blur_into(img, blur, slab.smoothing());
    let ring = slab.anchor_pass().ring;
    let (w, h) = (img.width(), img.height());
    Ok(crate::stage::gradient::magnitude_sum(&p, blur, w, h, ring))
}

/// How far [`detect_with`] runs.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Run {
    /// Everything; the linker gets the group cache when `cache` (the tests
    /// also run without it: the linker's fallback when it does not fit).
    Full { cache: bool },
    /// Up to the linking (`Part::FrontEnd`).
    #[cfg_attr(not(any(test, feature = "_unstable-hooks")), allow(dead_code))]
    FrontEnd,
}

/// The entry checks shared by [`detect`] and `detect_part`: the
/// config, then the layout of the workspace for this image, with the group
/// index when the workspace's `ws_len` bytes hold it (see
/// `Workspace::bytes_needed_fast`; never in a build for size).
fn prepare(
    width: usize,
    height: usize,
    cfg: &Config,
    in_place: bool,
    ws_len: usize,
) -> Result<(Layout, Params), Error> {
    cfg.validate()?;
    // Cannot fail: `GrayImage::new` checked the dimensions.
    let layout = Layout::compute(width, height, cfg, in_place)
        .ok_or(Error::ImageTooLarge { width, height })?;
    let layout = match layout.indexed() {
        Some(l) if !SMALL && ws_len >= l.total => l,
        _ => layout,
    };
    Ok((layout, Params::new(cfg)))
}

/// Where [`detect_with`] takes its pixels from.
enum Source<'a, 'b> {
    /// A borrowed image, smoothed into the workspace.
    Image(&'a GrayImage<'b>),
    /// A frame smoothed in place (already checked by `GrayImage::new`).
    Frame {
        buf: &'a mut [u8],
        width: usize,
        height: usize,
        stride: usize,
    },
}

impl Source<'_, '_> {
    fn size(&self) -> (usize, usize) {
        match self {
            Self::Image(img) => (img.width(), img.height()),
            Self::Frame { width, height, .. } => (*width, *height),
        }
    }
}

/// Detects line segments in `img`, writing them to the front of `out`.
///
/// Runs entirely on `ws` (no allocation) and returns what it did: the number
/// of segments written and everything it had to drop. Segments are in 0-based
/// pixel-centre coordinates, in the order their seeds were processed
/// (strongest aligned anchor group first); with merging on, a merged segment
/// takes the place of its first fragment.
///
/// ```
/// use aaglsd::{Config, GrayImage, Segment, Workspace, detect};
/// // A dark square on a light background.
/// let (w, h) = (64, 48);
/// let mut px = vec![200u8; w * h];
/// for y in 12..36 {
///     for x in 16..48 {
///         px[y * w + x] = 40;
///     }
/// }
/// let img = GrayImage::new(&px, w, h, w)?;
/// let cfg = Config::DEFAULT;
/// let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
/// let mut out = [Segment::default(); 32];
/// let summary = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out)?;
/// assert_eq!(summary.segments, 4); // the four sides
/// # Ok::<(), aaglsd::Error>(())
/// ```
///
/// # Errors
/// Checked in this order, before anything is written: [`Error::InvalidConfig`]
/// ([`Config::validate`]), [`Error::WorkspaceTooSmall`] (see
/// [`Workspace::bytes_needed`]), [`Error::OutputEmpty`]. Image errors are
/// caught earlier, by [`GrayImage::new`]. On error, `out` is untouched and
/// the workspace content is unspecified.
pub fn detect(
    img: &GrayImage<'_>,
    cfg: &Config,
    ws: &mut Workspace<'_>,
    out: &mut [Segment],
) -> Result<Summary, Error> {
    detect_with(Source::Image(img), cfg, ws, out, Run::Full { cache: true })
}

/// [`detect`] on a frame that it may overwrite: the frame is smoothed in
/// place, so the workspace needs no copy of the image
/// ([`Workspace::bytes_needed_in_place`], `w·h` bytes less than
/// [`Workspace::bytes_needed`]). The `width` x `height` pixels are rows
/// `stride` bytes apart in `frame`. The output is the same as [`detect`]'s
/// on the same pixels. Afterwards the first `width·height` bytes of `frame`
/// hold the smoothed image, rows packed; the rest of it is unchanged.
///
/// ```
/// use aaglsd::{Config, Segment, Workspace, detect_in_place};
/// let (w, h) = (64, 48);
/// let mut frame = vec![200u8; w * h];
/// for y in 12..36 {
///     for x in 16..48 {
///         frame[y * w + x] = 40;
///     }
/// }
/// let cfg = Config::DEFAULT;
/// let mut slab = vec![0u8; Workspace::bytes_needed_in_place(w, h, &cfg).unwrap()];
/// let mut out = [Segment::ZERO; 32];
/// let s = detect_in_place(&mut frame, w, h, w, &cfg, &mut Workspace::new(&mut slab), &mut out)?;
/// assert_eq!(s.segments, 4);
/// # Ok::<(), aaglsd::Error>(())
/// ```
///
/// # Errors
/// Those of [`GrayImage::new`] for the frame, then those of [`detect`]
/// (checked against [`Workspace::bytes_needed_in_place`]). On error,
/// `frame` and `out` are untouched.
pub fn detect_in_place(
    frame: &mut [u8],
    width: usize,
    height: usize,
    stride: usize,
    cfg: &Config,
    ws: &mut Workspace<'_>,
    out: &mut [Segment],
) -> Result<Summary, Error> {
    GrayImage::new(frame, width, height, stride)?;
    let src = Source::Frame {
        buf: frame,
        width,
        height,
        stride,
    };
    detect_with(src, cfg, ws, out, Run::Full { cache: true })
}

/// [`detect`], run as far as `run` says: the paper's stages in order,
/// each on its phase's view of the workspace.
fn detect_with(
    src: Source<'_, '_>,
    cfg: &Config,
    ws: &mut Workspace<'_>,
    out: &mut [Segment],
    run: Run,
) -> Result<Summary, Error> {
    let (w, h) = src.size();
    let ws_len = ws.len();
    let (layout, p) = prepare(w, h, cfg, matches!(src, Source::Frame { .. }), ws_len)?;
    let (blur_region, mut slab) = ws.carve(&layout)?;
    if out.is_empty() {
        return Err(Error::OutputEmpty);
    }
    let Some(wnz) = NonZeroUsize::new(w) else {
        return Err(Error::ZeroDimension {
            width: w,
            height: h,
        });
    };

    // Paper §3.1: smoothing, gradient and anchors; the greedy extraction.
    let blur = smoothed(src, blur_region, slab.smoothing());
    let stats = anchor_pass(&p, blur, w, h, slab.anchor_pass());
    let (groups, refused) = extraction(slab.extraction(), stats.candidates, wnz, h);
    let mut summary = Summary {
        groups,
        candidates: stats.candidates,
        dropped_candidates: stats.dropped + refused,
        ..Summary::default()
    };

    // Paper §3.2-3.3: the group tables, then linking and validation.
    let cache = run != (Run::Full { cache: false }) && layout.caches_directions(groups);
    let (t, ln) = slab.linking();
    let Some(records) = Groups::build(t.records, groups, blur, wnz, t.row_index, cache, t.index)
    else {
        // Unreachable: the records fit where their candidates were.
        return Err(Error::WorkspaceTooSmall {
            needed: layout.total,
            got: ws_len,
        });
    };
    if run == Run::FrontEnd {
        return Ok(summary);
    }
    let frame = link::Frame {
        p: &p,
        blur,
        mags: ln.mags,
        w: wnz,
        h,
    };
    let (count, work) = link_all(frame, ln, records, cfg, out, &mut summary);

    // Paper §3.3: merging, on the Q8 values; then the output frame.
    merge_and_output(&p, out, count, slab.merge(), work, &mut summary, (w, h));
    Ok(summary)
}

/// Paper §3.2-3.3: links every seed of `groups` in group-id order and
/// validates each linking. The strong segments go to `out` as Q8
/// gradient-grid values in the slots (exact in f32), a full output keeping
/// the best scores (design §8.1). Counts the dropped segments and the
/// truncated linkings in `summary`; returns the number of segments and the
/// work spent.
fn link_all(
    frame: link::Frame<'_>,
    ln: Linking<'_>,
    groups: Groups<'_>,
    cfg: &Config,
    out: &mut [Segment],
    summary: &mut Summary,
) -> (usize, Work) {
    let w = frame.w.get();
    let classes = ClassMap::new(ln.classes, w);
    let visited = BitMap::new_cleared(ln.visited, w);
    let work = Work::new(w * frame.h, cfg.work_per_mille, cfg.work_budget);
    let (lists, max_visits) = (ln.lists, ln.max_visits);
    let mut linker = link::Linker::new(frame, classes, visited, lists, max_visits, groups, work);
    let mut best = Best::new(out);
    linker.link_all(ln.seeds, ln.starts, ln.cursor, |seg| {
        best.push(seg.to_slot())
    });
    let (count, dropped) = best.finish();
    summary.dropped_segments = dropped;
    summary.truncated_linkings = linker.stats.truncated;
    (count, linker.work)
}

/// Smooths the source (paper §3.1): an image into `region`, a frame in
/// place; returns the blurred image. `scratch`: the smoothing's rows.
fn smoothed<'x>(src: Source<'x, '_>, region: &'x mut [u8], scratch: &mut [u16]) -> &'x [u8] {
    match src {
        Source::Image(img) => {
            smooth::blur_into(img, region, scratch);
            region
        }
        Source::Frame {
            buf,
            width,
            height,
            stride,
        } => {
            smooth::blur_in_place(buf, width, height, stride, scratch);
            // `GrayImage::new` checked that the frame holds `w·h` bytes.
            buf.get(..width * height).or_broken(&[])
        }
    }
}

/// The anchor pass (paper §3.1) on its regions.
fn anchor_pass(p: &Params, blur: &[u8], w: usize, h: usize, a: AnchorPass<'_>) -> AnchorStats {
    anchors::classify::<{ SIMD }>(
        p,
        blur,
        w,
        h,
        &mut ClassMap::new(a.classes, w),
        a.class_row,
        a.ring,
        a.candidates,
        a.keys,
        a.counts,
        a.claims,
        a.mags,
    )
}

/// The greedy extraction (paper §3.1, design §4) of the `n` candidates
/// the anchor pass left; every candidate may become a group (the records
/// replace the candidates in their region). Returns the number of groups
/// and of candidates refused for the cap.
fn extraction(e: Extraction<'_>, n: usize, w: NonZeroUsize, h: usize) -> (usize, usize) {
    let max_groups = e.region.len();
    extract::extract_groups(e, n, w, h, max_groups)
}

/// Paper §3.3: merges the first `count` segments of `out` (Q8 slot
/// values) when the config says so, spending `work`; then the output
/// frame: a short output best first, as it kept them (on the slot values),
/// and each segment clipped to the `(w, h)` image and shifted to pixel
/// centres. Fills the summary's segment, merge and work counts.
fn merge_and_output(
    p: &Params,
    out: &mut [Segment],
    count: usize,
    m: Merge<'_>,
    mut work: Work,
    summary: &mut Summary,
    (w, h): (usize, usize),
) {
    let count = if p.merge && count > 1 {
        let merged = merge::merge_all(p, out, count, m.pairs, &mut work);
        summary.merged = count - merged;
        merged
    } else {
        count
    };
    summary.segments = count;
    // Saturates: a count of work units beyond `usize` on a 16-bit target.
    summary.work = usize::try_from(work.spent).unwrap_or(usize::MAX);
    summary.work_cut = work.cut;
    let out = out.get_mut(..count).or_broken(&mut []);
    if summary.dropped_segments > 0 {
        by_score(out);
    }
    for s in out.iter_mut() {
        *s = SegQ8::from_slot(s).clipped(w, h).to_output();
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing, clippy::unwrap_used)]
    //! Small end-to-end runs (also the Miri suite: they exercise the
    //! workspace carving at every alignment and every stage).
    use super::*;

    fn rectangle(w: usize, h: usize) -> Vec<u8> {
        let mut px = vec![190u8; w * h];
        for y in h / 4..3 * h / 4 {
            for x in w / 5..4 * w / 5 {
                px[y * w + x] = 35;
            }
        }
        px
    }

    #[test]
    fn small_scene_any_alignment_and_dirty_workspace() {
        // Miri: a smaller scene, and the aligned and the most misaligned
        // offsets only (it interprets every instruction).
        let (w, h) = if cfg!(miri) { (32, 24) } else { (40, 32) };
        let offsets: &[usize] = if cfg!(miri) { &[0, 3] } else { &[0, 1, 2, 3] };
        let px = rectangle(w, h);
        let img = GrayImage::new(&px, w, h, w).unwrap();
        for cfg in [Config::OFFICIAL, Config::PAPER] {
            let n = Workspace::bytes_needed(w, h, &cfg).unwrap();
            let mut slab = vec![0u8; n + 3];
            let mut first = None;
            for &off in offsets {
                slab.iter_mut().for_each(|b| *b = 0xA5 ^ off as u8);
                let mut out = [Segment::default(); 8];
                let s = detect(
                    &img,
                    &cfg,
                    &mut Workspace::new(&mut slab[off..off + n]),
                    &mut out,
                )
                .unwrap();
                assert!(s.segments >= 2, "{s:?}");
                let got = (s, out);
                match &first {
                    None => first = Some(got),
                    Some(f) => assert_eq!(f, &got),
                }
            }
        }
    }

    /// Without the group cache (the fallback when it does not fit: members
    /// by a neighbour search, directions computed on each lookup) the output
    /// is the same.
    /// `n` random boxes of random shades on a random background, in a
    /// `w` x `h` image with row stride `stride`.
    fn boxes(
        next: &mut impl FnMut() -> u64,
        w: usize,
        h: usize,
        stride: usize,
        n: usize,
    ) -> Vec<u8> {
        let mut px = vec![(next() % 256) as u8; stride * h];
        for _ in 0..n {
            let (x0, y0) = ((next() % w as u64) as usize, (next() % h as u64) as usize);
            let (x1, y1) = ((next() % w as u64) as usize, (next() % h as u64) as usize);
            let v = (next() % 256) as u8;
            for y in y0.min(y1)..y0.max(y1) {
                px[y * stride + x0.min(x1)..y * stride + x0.max(x1)].fill(v);
            }
        }
        px
    }

    #[test]
    fn group_cache_and_fallback_agree() {
        let mut next = crate::xorshift64(0x5EED);
        // Miri: one small scene (it interprets every instruction).
        let (w, h, scenes) = if cfg!(miri) {
            (28, 22, 1)
        } else {
            (96, 72, 40)
        };
        let mut total = 0;
        for _ in 0..scenes {
            // A few random boxes of random shades on a random background,
            // plus a little noise.
            let mut px = boxes(&mut next, w, h, w, 6);
            for p in px.iter_mut() {
                *p = p.saturating_add((next() % 7) as u8);
            }
            let img = GrayImage::new(&px, w, h, w).unwrap();
            for cfg in [Config::DEFAULT, Config::PAPER] {
                let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
                let mut run = |cache| {
                    let mut out = [Segment::default(); 64];
                    let ws = &mut Workspace::new(&mut slab);
                    let s =
                        detect_with(Source::Image(&img), &cfg, ws, &mut out, Run::Full { cache })
                            .unwrap();
                    (s, out)
                };
                let (with, without) = (run(true), run(false));
                assert_eq!(with, without);
                total += with.0.segments;
            }
        }
        // The scenes have lines to agree on.
        assert!(total >= if cfg!(miri) { 2 } else { 200 }, "{total}");
    }

    /// Smoothing the frame in place gives `detect`'s output on the same
    /// pixels, with a padded stride and for every profile; every error is
    /// reported before the frame is touched.
    #[test]
    fn in_place_equals_detect() {
        let mut next = crate::xorshift64(0x1234_5678);
        let (w, h, pad) = if cfg!(miri) { (24, 20, 3) } else { (96, 72, 5) };
        let stride = w + pad;
        let mut total = 0;
        for _ in 0..if cfg!(miri) { 1 } else { 6 } {
            let frame = boxes(&mut next, w, h, stride, 5);
            for cfg in [Config::DEFAULT, Config::PAPER] {
                let img = GrayImage::new(&frame, w, h, stride).unwrap();
                let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
                let mut want = [Segment::ZERO; 64];
                let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut want).unwrap();
                let n = Workspace::bytes_needed_in_place(w, h, &cfg).unwrap();
                assert_eq!(n + w * h, slab.len());
                let mut copy = frame.clone();
                let mut got = [Segment::ZERO; 64];
                let ws = &mut Workspace::new(&mut slab[..n]);
                let t = detect_in_place(&mut copy, w, h, stride, &cfg, ws, &mut got).unwrap();
                assert_eq!((s, want), (t, got));
                total += s.segments;
                // Errors leave the frame alone.
                let mut copy = frame.clone();
                let short = &mut Workspace::new(&mut slab[..n - 1]);
                let e = detect_in_place(&mut copy, w, h, stride, &cfg, short, &mut got);
                assert!(matches!(e, Err(Error::WorkspaceTooSmall { .. })), "{e:?}");
                let ws = &mut Workspace::new(&mut slab[..n]);
                let e = detect_in_place(&mut copy, w, h, w - 1, &cfg, ws, &mut got);
                assert!(matches!(e, Err(Error::StrideTooSmall { .. })), "{e:?}");
                let e = detect_in_place(&mut copy, w, h, stride, &cfg, ws, &mut []);
                assert_eq!(e, Err(Error::OutputEmpty));
                assert_eq!(copy, frame);
            }
        }
        assert!(total > 0, "the scenes have lines");
    }

    #[test]
    fn noise_and_tiny_images() {
        let mut next = crate::xorshift64(12345);
        for (w, h) in [(1, 1), (2, 7), (7, 2), (16, 16), (23, 9)] {
            let px: Vec<u8> = (0..w * h).map(|_| next() as u8).collect();
            let img = GrayImage::new(&px, w, h, w).unwrap();
            let cfg = Config::PAPER;
            let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
            let mut out = [Segment::default(); 4];
            let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
            assert!(s.segments <= 4);
            let floor =
                detect_part(Part::Floor, &img, &cfg, &mut Workspace::new(&mut slab)).unwrap();
            assert!(floor > 0 || w * h == 1);
        }
    }

    /// The front end finds the groups that `detect` links, and checks the
    /// workspace as `detect` does. (That it stops before the linking shows
    /// in the bench: it takes under half of `detect`'s time.)
    #[test]
    fn front_end_counts_the_groups_detect_links() {
        let (w, h) = if cfg!(miri) { (32, 24) } else { (64, 48) };
        let px = rectangle(w, h);
        let img = GrayImage::new(&px, w, h, w).unwrap();
        let cfg = Config::DEFAULT;
        let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).unwrap()];
        let mut out = [Segment::default(); 8];
        let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
        assert!(s.groups > 0 && s.segments > 0);
        let groups =
            detect_part(Part::FrontEnd, &img, &cfg, &mut Workspace::new(&mut slab)).unwrap();
        assert_eq!(groups, s.groups as u64);
        let short = Workspace::bytes_needed(w, h, &cfg).unwrap() - 1;
        assert!(matches!(
            detect_part(
                Part::FrontEnd,
                &img,
                &cfg,
                &mut Workspace::new(&mut slab[..short])
            ),
            Err(Error::WorkspaceTooSmall { .. })
        ));
    }
}
