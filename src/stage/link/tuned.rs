//! The tuned forms of the walk's step away from the border (design §7.2).
//! Each picks the pixel [`super::step::best_in_image`] picks, with fewer
//! instructions, because the step runs once per visited pixel and is the
//! walk's hottest code:
//!
//! - [`from_cache`]: with the magnitude cache (the host workspace), three
//!   byte loads, one copy per walk table so that the candidates' offsets
//!   are constants.
//! - [`from_block`]: without it, four word loads of the 4x4 block of the
//!   blurred image around the pixel, each candidate's magnitude from two
//!   of them, again one copy per walk table; a build for size keeps one
//!   copy that reads the table at run time (flash over speed).
//!
//! `each_tuned_form_matches_the_plain_step` compares both with the plain
//! form on random images.

use super::Frame;
use crate::invariant::Invariant;
use crate::limits::MAX_DIMENSION;
use crate::spec::WALK;
use crate::stage::P;
use crate::target::SMALL;

/// [`best_of`] from the magnitude cache around the raster index `i` of a
/// pixel whose 3x3 neighbourhood is in the image.
#[inline(always)]
pub(super) fn from_cache(frame: &Frame, t: usize, i: usize) -> Option<P> {
    let w = frame.w.get();
    // One bounds test for the 3x3 block, as in `from_block`.
    let win = match frame.mags.get(i - w - 1..) {
        Some(b) if w <= MAX_DIMENSION && b.len() >= 2 * w + 3 => b,
        _ => &[],
    };
    let floor = frame.p.mag_min.max(1);
    match t {
        0 => best_cached::<0>(win, w, floor),
        1 => best_cached::<1>(win, w, floor),
        2 => best_cached::<2>(win, w, floor),
        3 => best_cached::<3>(win, w, floor),
        4 => best_cached::<4>(win, w, floor),
        5 => best_cached::<5>(win, w, floor),
        6 => best_cached::<6>(win, w, floor),
        _ => best_cached::<7>(win, w, floor),
    }
}

/// [`best_of`] with walk table `t` (whose candidates are `offsets`) from
/// the blurred image around the raster index `i` of a pixel at least two
/// columns and rows from the image's top-left and one from its
/// bottom-right edge.
#[inline(always)]
pub(super) fn from_block(frame: &Frame, t: usize, offsets: &[P; 3], i: usize) -> Option<P> {
    let w = frame.w.get();
    // Every candidate has its whole gradient window in the 4x4 block of
    // rows y-2..=y+1, columns x-2..=x+1. One bounds test for the block
    // (its rows start at k·w, k = 0..=3), not one per row: with `w` within
    // MAX_DIMENSION (always: the image was validated) no `k·w + 4` can
    // wrap, so the compiler drops the rows' own tests.
    let block = match frame.blur.get(i - 2 * w - 2..) {
        Some(b) if w <= MAX_DIMENSION && b.len() >= 3 * w + 4 => b,
        _ => &[],
    };
    let row = |k: usize| match block.get(k * w..).and_then(|r| r.first_chunk::<4>()) {
        Some(&b) => u32::from_le_bytes(b),
        None => 0,
    };
    let rows = [row(0), row(1), row(2), row(3)];
    let floor = frame.p.mag_min.max(1);
    match t {
        _ if SMALL => best_of(*offsets, &rows, floor),
        0 => best_of_table::<0>(&rows, floor),
        1 => best_of_table::<1>(&rows, floor),
        2 => best_of_table::<2>(&rows, floor),
        3 => best_of_table::<3>(&rows, floor),
        4 => best_of_table::<4>(&rows, floor),
        5 => best_of_table::<5>(&rows, floor),
        6 => best_of_table::<6>(&rows, floor),
        _ => best_of_table::<7>(&rows, floor),
    }
}

/// The offset of the first strictly largest thresholded magnitude among
/// the three candidates of walk table `T`, or `None` when none is above
/// zero, from the 4x4 block `rows` of the blurred image around the current
/// pixel (rows y-2..=y+1, one little-endian word each, columns x-2..=x+1;
/// see [`from_block`]). `floor` is `max(mag_min, 1)`.
///
/// The threshold is applied to the winner only: a candidate below it is a
/// zero, which cannot beat a winner at or above it, and when every
/// candidate is below it the walk stops either way. So the raw maxima
/// (`|gx| + |gy|` halved: the larger of the two diagonal differences) are
/// compared, and the winner's magnitude against the threshold once.
///
/// Inlined once per walk table by [`best_of_table`], so that the
/// candidates' rows and byte positions are constants; a build for size
/// ([`SMALL`]) inlines it once, with the table read at run time.
#[cfg_attr(not(aaglsd_small), inline(always))]
#[cfg_attr(aaglsd_small, inline(never))]
fn best_of(offsets: [(i32, i32); 3], rows: &[u32; 4], floor: u16) -> Option<(i32, i32)> {
    let half = |(dx, dy): (i32, i32)| {
        // The candidate's row is block row dy + 2, the one above it
        // dy + 1; its column is byte dx + 2, the one left of it dx + 1.
        let r = (dy + 1) as usize & 3;
        let shift = (8 * (dx + 1)) as u32 & 31;
        let up = rows.get(r).copied().or_broken(0) >> shift;
        let lo = rows.get((r + 1) & 3).copied().or_broken(0) >> shift;
        let (d, u) = ((up & 255) as i32, ((up >> 8) & 255) as i32);
        let (l, a) = ((lo & 255) as i32, ((lo >> 8) & 255) as i32);
        (a - d).abs().max((u - l).abs()) as u16
    };
    first_largest(offsets, half, floor)
}

/// The offset of the first strictly largest of `half` over the three
/// `offsets`, when twice that value reaches `floor`.
#[inline(always)]
fn first_largest(
    offsets: [(i32, i32); 3],
    half: impl Fn((i32, i32)) -> u16,
    floor: u16,
) -> Option<(i32, i32)> {
    let [o0, o1, o2] = offsets;
    let (m0, m1, m2) = (half(o0), half(o1), half(o2));
    // As selects: which candidate wins is data-dependent and a branch
    // would mispredict.
    use core::hint::select_unpredictable as pick;
    let best = pick(m1 > m0, (m1, o1), (m0, o0));
    let (m, off) = pick(m2 > best.0, (m2, o2), best);
    (2 * m >= floor).then_some(off)
}

/// [`best_of`] from the magnitude cache: `win` starts at the current
/// pixel's upper-left neighbour, rows `w` apart, and holds half of each
/// thresholded magnitude. The same offset as [`best_of`]'s (a candidate
/// below the threshold reads 0, which cannot beat a winner at or above
/// it). One copy per walk table `T`, as [`best_of_table`].
#[inline(always)]
fn best_cached<const T: usize>(win: &[u8], w: usize, floor: u16) -> Option<(i32, i32)> {
    let half = |(dx, dy): (i32, i32)| {
        let k = (dy + 1) as usize * w + (dx + 1) as usize;
        u16::from(win.get(k).copied().or_broken(0))
    };
    first_largest(WALK.get(T).copied().or_broken([(0, 0); 3]), half, floor)
}

/// [`best_of`] with walk table `T`: one function per table (a `match`
/// over plain calls with constant tables can be folded back into one body
/// that reads the table).
#[inline(always)]
fn best_of_table<const T: usize>(rows: &[u32; 4], floor: u16) -> Option<(i32, i32)> {
    best_of(WALK.get(T).copied().or_broken([(0, 0); 3]), rows, floor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::params::Params;
    use crate::stage::gradient::magnitude_at;
    use crate::stage::link::step::best_in_image;
    use core::num::NonZeroUsize;

    /// Each walk table's copy of the step picks what the plain rule picks
    /// (the first strictly largest [`magnitude_at`] of the table's three
    /// candidates, `None` when all are zero) on random 4x4 blocks, with the
    /// threshold at 0, at a typical value and above every magnitude.
    #[test]
    fn best_of_each_table_matches_the_plain_rule() {
        let mut next = crate::xorshift64(0x9e37_79b9);
        let (w, c) = (4usize, (2i32, 2i32));
        // Fewer under Miri, which interprets every instruction.
        let rounds = if cfg!(miri) { 100 } else { 20_000 };
        for round in 0..rounds {
            // Low-contrast blocks make ties and zero magnitudes common.
            let spread = if round % 2 == 0 { 4 } else { 256 };
            let blur: Vec<u8> = (0..16).map(|_| (next() % spread) as u8).collect();
            let rows: [u32; 4] = core::array::from_fn(|k| {
                u32::from_le_bytes([
                    blur[4 * k],
                    blur[4 * k + 1],
                    blur[4 * k + 2],
                    blur[4 * k + 3],
                ])
            });
            for t_min in [0u16, 1, 2, 5, 6, 7, 1020, 1021] {
                let floor = t_min.max(1);
                let got = WALK.map(|offsets| best_of(offsets, &rows, floor));
                for (t, (&got, table)) in got.iter().zip(&WALK).enumerate() {
                    let mut want = (0u16, None);
                    for &(dx, dy) in table {
                        let (x, y) = ((c.0 + dx) as usize, (c.1 + dy) as usize);
                        let m = magnitude_at(&blur, w, x, y, t_min);
                        if m > want.0 {
                            want = (m, Some((dx, dy)));
                        }
                    }
                    assert_eq!(got, want.1, "table {t}, t_min {t_min}, block {blur:?}");
                }
            }
        }
    }

    /// Both tuned forms pick the plain step's pixel at every position away
    /// from the border of random images, for every walk table, with the
    /// threshold at 0, at a typical value and above every magnitude.
    #[test]
    fn each_tuned_form_matches_the_plain_step() {
        let mut next = crate::xorshift64(0x6a09_e667_f3bc_c908);
        let (w, h) = (11usize, 9usize);
        // One low-contrast image at one threshold under Miri, which
        // interprets every instruction.
        let (rounds, t_mins): (usize, &[u16]) = if cfg!(miri) {
            (1, &[3])
        } else {
            (300, &[0, 3, 6, 1021])
        };
        for round in 0..rounds {
            let spread = if round % 2 == 0 { 5 } else { 256 };
            let blur: Vec<u8> = (0..w * h).map(|_| (next() % spread) as u8).collect();
            for &t_min in t_mins {
                let p = Params::new(&Config::DEFAULT);
                let p = Params {
                    mag_min: t_min,
                    ..p
                };
                let mags: Vec<u8> = (0..w * h)
                    .map(|i| (magnitude_at(&blur, w, i % w, i / w, t_min) / 2) as u8)
                    .collect();
                let frame = |mags| Frame {
                    p: &p,
                    blur: &blur,
                    mags,
                    w: NonZeroUsize::new(w).unwrap(),
                    h,
                };
                let (cached, plain) = (frame(&mags), frame(&[]));
                for (y, x) in (2..h - 1).flat_map(|y| (2..w - 1).map(move |x| (y, x))) {
                    let (c, i) = ((x as i32, y as i32), y * w + x);
                    for (t, offsets) in WALK.iter().enumerate() {
                        let want = best_in_image(&plain, offsets, c);
                        let at = |o: Option<P>| o.map(|(dx, dy)| (c.0 + dx, c.1 + dy));
                        let why = format!("table {t}, t_min {t_min}, at {c:?}, round {round}");
                        assert_eq!(at(from_cache(&cached, t, i)), want, "cache: {why}");
                        assert_eq!(at(from_block(&plain, t, offsets, i)), want, "block: {why}");
                    }
                }
            }
        }
    }
}
