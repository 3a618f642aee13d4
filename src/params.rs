//! [`Config`] turned into the integer thresholds the fixed-point core uses.
//! Computed once per call; no float arithmetic: `f32` fields are converted
//! exactly through the `fixed` crate (bit manipulation) and scaled in
//! integers.

use crate::Config;
use crate::num::q8::q32_of;
use crate::num::trig::{Bam, bam_from_degrees, sin_cos};

/// Validated, pre-scaled parameters.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Params {
    /// Smallest magnitude kept (`m < T_mag` is zeroed; m is an integer, so
    /// this is `ceil(T_mag)`).
    pub mag_min: u16,
    /// T_anchor in L1 levels.
    pub margin: i32,
    /// T_aligned as a binary angle.
    pub align: Bam,
    /// `cos` and `sin` of T_aligned in Q30, for cross/dot alignment tests.
    pub align_cos: i64,
    /// See [`Params::align_cos`].
    pub align_sin: i64,
    /// `2·cos²(T/2)/cos T` in Q8 (T = T_aligned; saturated): the score's
    /// test of an alignment within T/2 from the T test's products
    /// (design §8.1).
    pub sharp_k_q8: u64,
    /// T_dist in Q30 pixels.
    pub dist_q30: i64,
    /// S_min, S_ra, S_aag.
    pub skip_min: u8,
    /// See [`Params::skip_min`].
    pub skip_regular: u8,
    /// See [`Params::skip_min`].
    pub skip_group: u8,
    /// `(T_len in Q8)²`.
    pub min_len_sq_q16: i64,
    /// N_aag.
    pub min_groups: u8,
    /// ρ1 and ρ2 in Q32, rounded up.
    pub rho1_q32: u64,
    /// See [`Params::rho1_q32`].
    pub rho2_q32: u64,
    /// See [`Config::reseed`].
    pub reseed: crate::Reseed,
    /// 1 under [`crate::Maxima::Symmetric`], else 0: added to the centre's
    /// side of the maximum tests that allow equality, it turns `>` into
    /// `>=` on integers.
    pub tie: u16,
    /// See [`Config::bridge_px`].
    pub bridge: u8,
    /// Whether a linking that fails ρ2 may keep its longest passing part (design §8.2).
    pub trim: bool,
    /// See [`Config::min_score`].
    pub min_score: u32,
    /// The endpoint extension's limit, in pixels (0: off).
    pub extend_max: u16,
    /// Merging switch and its thresholds: D_c and D_e in Q8, `cos D_a` in Q30.
    pub merge: bool,
    /// See [`Params::merge`].
    pub merge_dc_q8: i64,
    /// See [`Params::merge`].
    pub merge_cos_q30: i64,
    /// See [`Params::merge`].
    pub merge_de_q8: i64,
    /// The merging's direction window, D_a + 1° (at most 89°), in binary
    /// angle units of 2^32 per 180°.
    pub merge_window: u32,
    /// How many direction bins of `merge_window` cover 180° (the last one
    /// may be narrower).
    pub merge_bins: u32,
    /// `sin(W / 2)` in Q30: how far from its bin's centre direction a
    /// segment can point.
    pub merge_sin_half_q30: i64,
}

/// The merging's direction window, D_a + 1° and at most 89°, in binary
/// angle units of 2^32 per 180°: the degree covers the drift of a segment
/// that grows during a sweep, and below 90° no two segments are in each
/// other's window. The reference uses the same window.
fn merge_window(merge_angle_deg: f32) -> u32 {
    let w = bam_from_degrees(merge_angle_deg).saturating_add(bam_from_degrees(1.0));
    w.min(bam_from_degrees(89.0)).wrapping_shl(1)
}

/// Q32 bits of a non-negative `f32` (exact; saturating).
fn q32(v: f32) -> i64 {
    // `checked_`: NaN (rejected by `Config::validate`) must not panic here.
    q32_of(v).unwrap_or(if v > 0.0 { i64::MAX } else { 0 })
}

/// `v` in Q`bits` (0 <= bits <= 32), rounded to nearest.
fn q(v: f32, bits: u32) -> i64 {
    let shift = 32 - bits;
    if shift == 0 {
        return q32(v);
    }
    (q32(v) + (1 << (shift - 1))) >> shift
}

impl Params {
    /// Converts a config that passed [`Config::validate`].
    pub fn new(cfg: &Config) -> Self {
        let (align_cos, align_sin) = sin_cos(bam_from_degrees(cfg.align_tolerance_deg));
        let (half_cos, _) = sin_cos(bam_from_degrees(cfg.align_tolerance_deg) / 2);
        // Q60 over Q30 gives Q30; shifted to Q8, rounded (Q30 cosines at
        // most 2^30: `2·cos²` at most 2^61).
        let (hc, ac) = (
            u64::from(half_cos.unsigned_abs()),
            u64::from(align_cos.unsigned_abs()),
        );
        let sharp_k_q8 = match ac << 22 {
            0 => u64::MAX,
            den => crate::num::q8::div_round_u64(2 * hc * hc, den),
        };
        let (merge_cos, _) = sin_cos(bam_from_degrees(cfg.merge_angle_deg));
        let window = merge_window(cfg.merge_angle_deg);
        let t = q32(cfg.magnitude_threshold);
        let mag_min = ((t + (1 << 32) - 1) >> 32).clamp(0, 1021) as u16; // ceil
        let rho = |v: f32| {
            let b = q32(v).max(0) as u64; // already Q32 and exact
            b.min(1 << 32)
        };
        let len_q8 = q(cfg.min_length_px, 8);
        Self {
            mag_min,
            margin: i32::from(cfg.anchor_margin),
            align: bam_from_degrees(cfg.align_tolerance_deg),
            align_cos: i64::from(align_cos),
            align_sin: i64::from(align_sin),
            sharp_k_q8,
            dist_q30: q(cfg.dist_tolerance_px, 30),
            skip_min: cfg.skip_min,
            skip_regular: cfg.skip_regular,
            skip_group: cfg.skip_group,
            min_len_sq_q16: len_q8.saturating_mul(len_q8),
            min_groups: cfg.min_groups,
            rho1_q32: rho(cfg.anchor_density),
            rho2_q32: rho(cfg.aligned_density),
            reseed: cfg.reseed,
            tie: u16::from(cfg.maxima == crate::Maxima::Symmetric),
            bridge: cfg.bridge_px,
            trim: cfg.trim,
            min_score: cfg.min_score,
            extend_max: cfg.extend_max_px,
            merge: cfg.merge,
            merge_dc_q8: q(cfg.merge_center_px, 8),
            merge_cos_q30: i64::from(merge_cos),
            merge_de_q8: q(cfg.merge_gap_px, 8),
            merge_window: window,
            // ceil(2^32 / W) = floor((2^32 - 1) / W) + 1, saturated (W = 1),
            // in 32-bit division.
            merge_bins: (u32::MAX / window.max(1)).saturating_add(1),
            merge_sin_half_q30: i64::from(sin_cos(window >> 2).1),
        }
    }

    /// Whether a linking of `links` group links has fewer groups, its seed
    /// counted, than N_aag (design §8: never strong).
    #[inline]
    pub fn few_groups(&self, links: u32) -> bool {
        links + 1 < u32::from(self.min_groups)
    }

    /// `(tie, margin)` for the NMS's gate of the group test (`margin` is
    /// at most 1020 by [`Config::validate`](crate::Config::validate)).
    pub fn gate(&self) -> (u16, u16) {
        (self.tie, self.margin.clamp(0, 1020) as u16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn official_values() {
        let p = Params::new(&Config::OFFICIAL);
        assert_eq!(p.mag_min, 6); // m < 5.22 zeroed: integers 0..=5
        assert_eq!(p.dist_q30, 3 << 29);
        assert_eq!(p.min_len_sq_q16, (5 * 256) * (5 * 256));
        assert_eq!(p.rho1_q32, 1 << 31);
        // 0.9f32 is 0.89999997615814208984375, exactly 3865470464 / 2^32.
        assert_eq!(p.rho2_q32, 3_865_470_464);
        assert_eq!(p.merge_dc_q8, 384);
        let p = Params::new(&Config {
            magnitude_threshold: 6.0,
            ..Config::OFFICIAL
        });
        assert_eq!(p.mag_min, 6);
        let p = Params::new(&Config {
            magnitude_threshold: 0.0,
            ..Config::OFFICIAL
        });
        assert_eq!(p.mag_min, 0);
    }
}
