//! Paper §3.3, first half: a linking's endpoints and its validation
//! (design §8).
//!
//! The endpoints are the walk's two ends projected onto the fitted line
//! along the minor axis (as the authors' code does, not orthogonally), in
//! Q8. Then, with `T_len`, `N_aag`, ρ1 and ρ2 from [`Params`], one of three
//! verdicts:
//! * **discard** (too short, fewer than one link, or an anchor density below
//!   ρ1): the links the walk made stay;
//! * **weak** (too few groups, or an aligned density below ρ2): the caller
//!   releases the links made on the normal route, so those groups can seed
//!   again;
//! * **strong**: the segment is output.
//!
//! The densities count the Bresenham pixels of the segment inside the image:
//! anchors (regular or in a group) for ρ1, and pixels whose gradient is
//! within T_aligned of the segment normal for ρ2 (`|g × n|·cos T ≤
//! |g · n|·sin T`, with `n·cos T` and `n·sin T` pre-scaled below 2^40).

use core::num::NonZeroUsize;

use super::P;
use super::fit::Line;
use super::gradient::gradient_at;
use super::output::SegQ8;
use super::packed::point::unpack;
use super::raster::{self, Raster};
use super::state::ClassMap;
use super::trim::Longest;
use crate::num::q8::{div_round_u64, isqrt_u64};
use crate::params::Params;

/// The aligned-pixel test of a segment with direction `(dx, dy)`: a
/// gradient `g` is aligned with the normal `n = (-dy, dx)` when
/// `|g × n|·cos T ≤ |g · n|·sin T` (T = T_aligned), with `n·cos T` and
/// `n·sin T` pre-scaled below 2^40 (so every product fits `i64`). A zero
/// gradient counts as `(1, 0)`, as the reference's orientation 0° does.
pub(crate) struct NormalTest {
    nxc: i64,
    nyc: i64,
    nxs: i64,
    nys: i64,
}

impl NormalTest {
    pub(crate) fn new(p: &Params, dx: i64, dy: i64) -> Self {
        Self::within(p.align_cos, p.align_sin, dx, dy)
    }

    /// The test for the angle T of Q30 cosine `ct` and sine `st`.
    pub(crate) fn within(ct: i64, st: i64, dx: i64, dy: i64) -> Self {
        // `|cos T|, |sin T| <= 2^30`: with both deltas below 2^32 (every
        // segment in an image: its ends are Q8 values below 2^23) the
        // products fit `i64`, and shifting them below 2^40 gives the values
        // of the exact `i128` scaling (`normal_scaling_is_the_wide_one`).
        if (dx.unsigned_abs() | dy.unsigned_abs()) >> 32 == 0
            && (ct.unsigned_abs() | st.unsigned_abs()) >> 30 <= 1
        {
            Self::scaled(-dy, dx, ct, st)
        } else {
            Self::wide(ct, st, dx, dy)
        }
    }

    /// `n·cos T` and `n·sin T` for `|n| <= 2^32` and `|cos T|, |sin T| <
    /// 2^31`, shifted below 2^40.
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    fn scaled(nx: i64, ny: i64, ct: i64, st: i64) -> Self {
        let mut v = [nx * ct, ny * ct, nx * st, ny * st];
        let big = v.iter().map(|x| x.unsigned_abs()).max().unwrap_or(0);
        let shift = (64 - big.leading_zeros()).saturating_sub(40);
        for x in &mut v {
            *x >>= shift;
        }
        let [nxc, nyc, nxs, nys] = v;
        Self { nxc, nyc, nxs, nys }
    }

    /// [`NormalTest::new`] for deltas beyond 32 bits (no segment has them):
    /// shifted into 32 bits first, which keeps their direction to 2^-31,
    /// instead of 128-bit products (which a 32-bit core pays for in flash).
    #[cold]
    #[inline(never)]
    fn wide(ct: i64, st: i64, dx: i64, dy: i64) -> Self {
        let pre = 64 - ((dx.unsigned_abs() | dy.unsigned_abs()) >> 32).leading_zeros();
        let (dx, dy) = (dx >> pre, dy >> pre);
        let clamp = |v: i64| v.clamp(-(1 << 30), 1 << 30);
        Self::scaled(-dy, dx, clamp(ct), clamp(st))
    }

    /// `n·cos T` and `n·sin T` scaled below 2^40 in `i128`, for any deltas:
    /// the test oracle of [`NormalTest::new`].
    #[cfg(test)]
    fn scaled_wide(p: &Params, dx: i64, dy: i64) -> [i64; 4] {
        let (nx, ny) = (-i128::from(dy), i128::from(dx));
        let (ct, st) = (i128::from(p.align_cos), i128::from(p.align_sin));
        let v = [nx * ct, ny * ct, nx * st, ny * st];
        let big = v.iter().map(|x| x.unsigned_abs()).max().unwrap_or(0);
        let shift = (128 - big.leading_zeros()).saturating_sub(40);
        v.map(|x| (x >> shift) as i64)
    }

    /// Whether the gradient `(gx, gy)` is aligned with the normal.
    #[inline]
    pub(crate) fn aligned(&self, g: (i32, i32)) -> bool {
        let (cross, dot) = self.parts(g);
        cross.unsigned_abs() <= dot.unsigned_abs()
    }

    /// `g × n·cos T` and `g · n·sin T` as scaled (each below 2^50): `g` is
    /// aligned when the first is at most the second in magnitude. The
    /// second is `-sin T·(gx·dy - gy·dx)`, scaled.
    #[inline]
    pub(crate) fn parts(&self, (gx, gy): (i32, i32)) -> (i64, i64) {
        let (gx, gy) = if gx == 0 && gy == 0 {
            (1, 0)
        } else {
            (i64::from(gx), i64::from(gy))
        };
        (gx * self.nyc - gy * self.nxc, gx * self.nxs + gy * self.nys)
    }

    /// `|n·sin T|` as scaled, the unit of the second of [`Self::parts`]
    /// (below 2^40), shifted right by [`Sums::SHIFT`].
    fn sin_len(&self) -> u64 {
        // Shifted below 2^31 first: the sum of squares fits `u64`, and
        // each square is one 32 x 32 -> 64-bit multiplication.
        let sq = |v: i64| {
            let v = (v.unsigned_abs() >> 9) as u32;
            u64::from(v) * u64::from(v)
        };
        isqrt_u64(sq(self.nxs) + sq(self.nys)) >> (Sums::SHIFT - 9)
    }
}

/// The outcome of [`validate`].
/// Whether the segment pixel `p` lies strictly between the two ends of a
/// bridge (design §7.5) along the major axis of the line (`steep`: y).
/// `bridges` holds pairs of ends, each a [`point`](super::packed::point).
fn bridged(bridges: &[u32], steep: bool, p: P) -> bool {
    let major = |q: P| if steep { q.1 } else { q.0 };
    let u = major(p);
    for b in bridges.chunks_exact(2) {
        if let [a, c] = *b {
            let (a, c) = (major(unpack(a)), major(unpack(c)));
            if u > a.min(c) && u < a.max(c) {
                return true;
            }
        }
    }
    false
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// Rejected; the walk's links stay.
    Discard,
    /// Rejected; the links made on the normal route are released.
    Weak,
    /// A segment of the output, and its score's sums so far.
    Strong(SegQ8, Sums),
}

/// Endpoints and verdict of a linking whose fitted line is `l`, walk ends
/// `ends` (forward, backward) and group links `links`, on the `w` x `h`
/// blurred image `blur` with pixel classes `classes`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn validate(
    p: &Params,
    blur: &[u8],
    classes: &ClassMap<'_>,
    w: NonZeroUsize,
    h: usize,
    l: &Line,
    ends: [P; 2],
    links: u32,
    bridges: &[u32],
    mut track: Option<&mut Longest<'_>>,
) -> Verdict {
    let Some((seg, dx, dy)) = (links >= 1).then(|| endpoints(p, l, ends)).flatten() else {
        return Verdict::Discard;
    };
    let steep = l.steep();
    let few_groups = p.few_groups(links);
    if few_groups && p.reseed.skips_trace_of_few() {
        return Verdict::Weak;
    }
    let normal = NormalTest::new(p, dx, dy);
    let mut t = Tally::default();
    let (from, to) = seg.pixel_ends();
    let w = w.get();
    // `rho <= 2^32` and `inside` at most the raster's length, below 2^17
    // (both ends lie within an image side of the in-image pixels they
    // project, |slope| <= 1 along the major axis): no overflow.
    let dense = |k: u64, rho: u64, inside: u64| (k << 32) >= rho * inside;
    let (rho1, rho2) = (p.rho1_q32, p.rho2_q32);
    // Each density settled as early as it can be ([`Tally`]).
    let mut judge_aligned = !few_groups;
    let mut rem = raster::pixel_count(from, to);
    for (x, y) in Raster::new(from, to) {
        rem = rem.saturating_sub(1);
        let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) else {
            continue;
        };
        if x >= w || y >= h {
            continue;
        }
        // Within a bridge (design §7.5) the pixels of the crossing edge
        // (a nonzero gradient not aligned with the normal) do not count.
        if !bridges.is_empty() && bridged(bridges, steep, (x as i32, y as i32)) {
            let g = gradient_at(blur, w, x, y);
            if over(p, g) && !normal.aligned(g) {
                continue;
            }
        }
        t.inside += 1;
        if classes.get(x, y).is_anchor() {
            t.anchors += 1;
        }
        if judge_aligned {
            let (g, at) = (gradient_at(blur, w, x, y), (x as i32, y as i32));
            t.judge_at(p, &normal, g, at, track.as_deref_mut());
            // A tracked trace judges every pixel (its parts need them).
            judge_aligned = track.is_some() || dense(t.aligned + rem, rho2, t.judged + rem);
        } else if dense(t.anchors, rho1, t.inside + rem) {
            break; // weak: the anchor density passes whatever follows
        }
        if !dense(t.anchors + rem, rho1, t.inside + rem) {
            return Verdict::Discard; // links are kept
        }
    }
    if t.inside == 0 || !dense(t.anchors, rho1, t.inside) {
        return Verdict::Discard; // links are kept
    }
    // A run of pixels not aligned at the end is no junction.
    if !judge_aligned || !dense(t.aligned, rho2, t.judged + t.run) {
        return Verdict::Weak;
    }
    // Design §8.1: the brighter side on the left (every pixel was traced:
    // a strong verdict judges the alignment to the end). Balanced sides
    // keep the walk's order.
    // The densities' counts, below 2^17 (above): exact in `u32`.
    let mut sums = t.sums;
    (sums.anchors, sums.inside, sums.unit) = (t.anchors as u32, t.inside as u32, normal.sin_len());
    Verdict::Strong(if t.polarity < 0 { seg.reversed() } else { seg }, sums)
}

/// The segment of a linking whose fitted line is `l` and walk ends `ends`
/// (forward, backward): the ends projected onto `l` along its minor axis,
/// and its deltas; `None` when it is shorter than the minimum length.
fn endpoints(p: &Params, l: &Line, ends: [P; 2]) -> Option<(SegQ8, i64, i64)> {
    // Both ends on one line: its centroid and slope computed once.
    let steep = l.steep();
    let minor = if steep { l.x_by_row() } else { l.y_by_column() };
    let end = |(x, y): P| -> Option<(i64, i64)> {
        let (x, y) = (i64::from(x), i64::from(y));
        if steep {
            Some((minor.at(y)?, y << 8))
        } else {
            Some((x << 8, minor.at(x)?))
        }
    };
    let [fwd, bwd] = ends;
    let (b, e) = (end(fwd)?, end(bwd)?);
    let seg = SegQ8::new(b.0, b.1, e.0, e.1);
    let (dx, dy) = (
        i64::from(seg.x1) - i64::from(seg.x0),
        i64::from(seg.y1) - i64::from(seg.y0),
    );
    // Shorter than the minimum length (its square is at most 2^48): a side
    // of 2^30 or more is longer, and below that the squares fit 64 bits.
    let short =
        dx.unsigned_abs().max(dy.unsigned_abs()) < 1 << 30 && dx * dx + dy * dy < p.min_len_sq_q16;
    (!short).then_some((seg, dx, dy))
}

/// Whether the gradient `g` has a magnitude over the threshold (a nonzero
/// one in the thresholded map).
#[inline(always)]
fn over(p: &Params, g: (i32, i32)) -> bool {
    g.0.unsigned_abs() + g.1.unsigned_abs() >= u32::from(p.mag_min.max(1))
}

/// What [`validate`] counts along a segment (design §8).
///
/// The densities decide from the final counts, but each can be settled
/// early (exactly): with `rem` pixels left, of which any number may be in
/// the image, the final density of `k` lies between `k / (inside + rem)`
/// and `(k + rem) / (inside + rem)` (`Params` clamps each `rho` to at most
/// 1; for ρ2 the pixels not yet judged, a junction's, count as left). A
/// segment with too few groups, or whose aligned density can no longer
/// pass, is weak unless its anchor density fails: from then on only the
/// anchors are counted (no gradient), until their density is settled too.
#[derive(Default)]
struct Tally {
    /// In-image pixels, and the anchors among them (for ρ1).
    inside: u64,
    anchors: u64,
    /// Pixels within T_aligned of the normal, and the pixels they are
    /// judged against for ρ2: `inside` less the junctions' pixels and the
    /// current run.
    aligned: u64,
    judged: u64,
    /// Pixels not aligned since the last aligned one, and the side that
    /// one's gradient crosses the line towards (the sign of the gradient
    /// across, towards the left; 0 below the magnitude threshold).
    run: u64,
    side: i64,
    /// The gradient across, towards the left of the segment as displayed,
    /// scaled (below 2^34 a pixel shifted, 2^51 in all).
    polarity: i64,
    /// Design §8.1, the score's sums: the contrast across the segment,
    /// and the pixels aligned within half of T_aligned.
    sums: Sums,
}

impl Tally {
    /// Judges a pixel of gradient `g` against the normal; whether it is
    /// aligned. A junction (design §8: at most `bridge` pixels in a row
    /// not aligned, between two aligned pixels whose gradients cross the
    /// line towards opposite sides, where the line's contrast changes
    /// sign) is left out of ρ2.
    #[inline(always)]
    fn judge(&mut self, p: &Params, normal: &NormalTest, g: (i32, i32)) -> bool {
        let (c, d) = normal.parts(g);
        let (c_abs, d_abs) = (c.unsigned_abs(), d.unsigned_abs());
        let over = over(p, g);
        if over {
            // `-d` is the gradient across, towards the left.
            self.polarity -= d >> Sums::SHIFT;
            self.sums.add(c_abs, d_abs, p.sharp_k_q8);
        }
        if c_abs <= d_abs {
            let side = if over { -d.signum() } else { 0 };
            if self.run > u64::from(p.bridge) || self.side * side >= 0 {
                self.judged += self.run;
            }
            self.aligned += 1;
            self.judged += 1;
            (self.run, self.side) = (0, side);
            true
        } else {
            self.run += 1;
            false
        }
    }

    /// [`Tally::judge`] of the pixel `at`, which `track` (design §8.2)
    /// hears of when it is aligned.
    #[inline(always)]
    fn judge_at(
        &mut self,
        p: &Params,
        normal: &NormalTest,
        g: (i32, i32),
        at: P,
        track: Option<&mut Longest<'_>>,
    ) {
        if self.judge(p, normal, g)
            && let Some(track) = track
        {
            track.aligned(at, self.aligned - 1, self.judged - 1);
        }
    }
}

/// Design §8.1: what a strong segment's score sums over the pixels
/// validation traces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Sums {
    /// `|g · n|` over the pixels of nonzero magnitude, in the unit
    /// `unit` ([`NormalTest::parts`], shifted right by [`Sums::SHIFT`]).
    pub contrast: u64,
    /// The length of the scaled normal in the unit of `contrast`.
    pub unit: u64,
    /// Anchors among the pixels (the counts below 2^17: a raster's
    /// length; 32 bits, one register each on a 32-bit core).
    pub anchors: u32,
    /// Pixels of nonzero magnitude aligned within T_aligned/2 of the normal.
    pub sharp: u32,
    /// In-image pixels.
    pub inside: u32,
}

impl Sums {
    /// The scaled products lose this many bits before they are summed
    /// (below 2^34 each, 2^49 over a side of 2^15 pixels).
    pub const SHIFT: u32 = 16;

    /// Adds a pixel of nonzero magnitude, of [`NormalTest::parts`] `(c, d)`
    /// (their magnitudes `c_abs`, `d_abs`):
    /// within T/2 of the normal when `|c|·K ≤ |d|`, `K = 2cos²(T/2)/cos T`
    /// (`k_q8`, Q8) (the counts of anchors and pixels are the caller's).
    pub(crate) fn add(&mut self, c_abs: u64, d_abs: u64, k_q8: u64) {
        self.contrast += d_abs >> Self::SHIFT;
        self.sharp += u32::from(c_abs.saturating_mul(k_q8) <= d_abs << 8);
    }

    /// The score: `C·A²·S²`, `C` the contrast in gradient levels × pixels
    /// (rounded), `A` and `S` the shares of anchors and of sharp pixels in
    /// Q16 (rounded), the products rounded to integers after `A²` and after
    /// `S²`; at most [`SegQ8::MAX_SCORE`]. 64-bit products only: a
    /// 128-bit division would cost a 32-bit core its routine in flash.
    #[cfg_attr(aaglsd_small, inline(never))]
    pub(crate) fn score(&self) -> u32 {
        let div = div_round_u64;
        let c = div(self.contrast, self.unit).min(u64::from(SegQ8::MAX_SCORE));
        // Counts below 2^17: shares at most 2^16, squares at most 2^32.
        let share = |k: u32| div(u64::from(k) << 16, self.inside.into()).min(1 << 16);
        let (a, s) = (share(self.anchors), share(self.sharp));
        let half = 1 << 31;
        // Each product below 2^24 · 2^32.
        let ca = (c * (a * a) + half) >> 32;
        let score = (ca * (s * s) + half) >> 32;
        score.min(u64::from(SegQ8::MAX_SCORE)) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    #[test]
    fn wide_deltas_keep_their_direction() {
        // Deltas beyond 32 bits (no segment has them): no overflow, and the
        // scaled normal within 2^-20 of the exact one (relative to its
        // largest component).
        let p = Params::new(&Config::DEFAULT);
        let mut seed = 0x9E37_79B9u64;
        for k in 0..if cfg!(miri) { 200 } else { 20_000 } {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let (dx, dy) = match k {
                0 => (i64::MIN, i64::MAX),
                1 => (i64::MAX, i64::MIN),
                2 => (i64::MIN, 0),
                _ => (
                    seed as i64 >> (k % 31),
                    (seed.rotate_left(17) as i64) >> (k % 29),
                ),
            };
            let t = NormalTest::new(&p, dx, dy);
            let got = [t.nxc, t.nyc, t.nxs, t.nys];
            let want = NormalTest::scaled_wide(&p, dx, dy);
            let big = want.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
            for (g, w) in got.into_iter().zip(want) {
                assert!(
                    g.abs_diff(w) <= (big >> 20) + 2,
                    "{dx}, {dy}: {got:?} vs {want:?}"
                );
            }
        }
    }

    /// The 64-bit path gives the `i128` path's values for every segment
    /// delta below 2^32, at several tolerances.
    #[test]
    fn normal_scaling_is_the_wide_one() {
        let mut seed = 0x1234_5678u64;
        for deg in [0.5f32, 3.0, 22.5, 45.0, 89.0] {
            let p = Params::new(&Config {
                align_tolerance_deg: deg,
                ..Config::DEFAULT
            });
            for _ in 0..if cfg!(miri) { 200 } else { 100_000 } {
                seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                // Deltas of every magnitude up to 2^32 - 1, either sign.
                let bits = (seed >> 58) as u32 % 33;
                let mask = (1u64 << bits) - 1;
                let dx = ((seed >> 8) & mask) as i64 * if seed & 1 == 0 { 1 } else { -1 };
                let dy = ((seed >> 20) & mask) as i64 * if seed & 2 == 0 { 1 } else { -1 };
                let t = NormalTest::new(&p, dx, dy);
                assert_eq!(
                    [t.nxc, t.nyc, t.nxs, t.nys],
                    NormalTest::scaled_wide(&p, dx, dy),
                    "{deg}: {dx}, {dy}"
                );
            }
        }
    }
}
