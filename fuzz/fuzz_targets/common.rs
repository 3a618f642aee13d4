//! Mapping fuzz bytes to images and configurations (shared by the targets).
#![allow(dead_code)]

use aaglsd::{Config, GrayImage};
use aaglsd_support::fields::{self, Value};
use aaglsd_support::matching::unmatched;
use aaglsd_support::run::detect_with_capacity;

/// A little-endian byte reader that yields zeros when exhausted.
pub struct Bytes<'a>(pub &'a [u8]);

impl Bytes<'_> {
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    pub fn u16(&mut self) -> u16 {
        u16::from(self.u8()) | u16::from(self.u8()) << 8
    }

    /// A size in `lo..lo + span`, from one byte.
    pub fn size(&mut self, lo: usize, span: u8) -> usize {
        lo + usize::from(self.u8() % span)
    }

    /// A value in `lo..=hi` (both within f32 range), `bits` of resolution.
    pub fn f32_in(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * f32::from(self.u16()) / 65535.0
    }
}

/// `fuzz_target!` with the input read through [`Bytes`], bound to the
/// caller's name: `fuzz_bytes!(|b| { ... })`.
macro_rules! fuzz_bytes {
    (|$b:ident| $body:block) => {
        libfuzzer_sys::fuzz_target!(|data: &[u8]| {
            let mut $b = crate::common::Bytes(data);
            $body
        });
    };
}
pub(crate) use fuzz_bytes;

/// A configuration: one selector byte picks "default", "a random valid
/// config" or "one field set to an arbitrary (possibly invalid) f32".
pub fn config(b: &mut Bytes<'_>) -> Config {
    let mut c = Config::DEFAULT;
    match b.u8() % 4 {
        0 => {}
        1 => c = Config::PAPER,
        2 => {
            c.magnitude_threshold = b.f32_in(0.0, 60.0);
            c.anchor_margin = u16::from(b.u8() % 32);
            c.align_tolerance_deg = b.f32_in(1.0, 80.0);
            c.dist_tolerance_px = b.f32_in(0.3, 6.0);
            c.skip_min = 1 + b.u8() % 16;
            c.skip_regular = 1 + b.u8() % 16;
            c.skip_group = 1 + b.u8() % 16;
            c.min_length_px = b.f32_in(0.0, 40.0);
            c.min_groups = 1 + b.u8() % 8;
            c.anchor_density = b.f32_in(0.0, 1.0);
            c.aligned_density = b.f32_in(0.0, 1.0);
            c.min_score = u32::from(b.u8()) * 4;
            c.merge = b.u8() & 1 == 1;
            c.trim = b.u8() & 1 == 1;
            c.merge_center_px = b.f32_in(0.1, 5.0);
            c.merge_angle_deg = b.f32_in(0.5, 45.0);
            c.merge_gap_px = b.f32_in(0.0, 40.0);
            c.candidates_per_mille = 1 + b.u16() % 1000;
            c.max_link_pixels = 16 + u32::from(b.u16() % 5000);
            c.extend_max_px = b.u16() % 200;
            c.reseed = aaglsd::Reseed::from_code(b.u8() % 3).unwrap_or(aaglsd::Reseed::Always);
            // Sometimes a limit or a budget that bites.
            c.work_per_mille = 1 + u32::from(b.u16()) * 2;
            c.work_budget = if b.u8() & 1 == 1 {
                u32::from(b.u16())
            } else {
                0
            };
        }
        _ => {
            let v = f32::from_bits(u32::from(b.u16()) | u32::from(b.u16()) << 16);
            let floats: Vec<&str> = fields::float_fields().collect();
            let name = floats[usize::from(b.u8()) % floats.len()];
            fields::set(&mut c, name, Value::F32(v)).unwrap();
            c.merge = true;
        }
    }
    c
}

/// A structured scene: a background and up to 8 polygons bounded by
/// straight edges (half-plane intersections), plus bounded noise.
pub fn scene(b: &mut Bytes<'_>, w: usize, h: usize) -> Vec<u8> {
    let bg = b.u8();
    let mut img = vec![i32::from(bg); w * h];
    for _ in 0..(b.u8() % 9) {
        let v = i32::from(b.u8());
        // Up to 4 half-planes a*x + b*y <= c with a, b in [-1, 1].
        let planes: Vec<(f32, f32, f32)> = (0..1 + b.u8() % 4)
            .map(|_| {
                let (a, bb) = (b.f32_in(-1.0, 1.0), b.f32_in(-1.0, 1.0));
                let c = b.f32_in(-((w + h) as f32), (w + h) as f32);
                (a, bb, c)
            })
            .collect();
        for y in 0..h {
            for x in 0..w {
                if planes
                    .iter()
                    .all(|&(a, bb, c)| a * x as f32 + bb * y as f32 <= c)
                {
                    img[y * w + x] = v;
                }
            }
        }
    }
    let noise = i32::from(b.u8() % 8);
    let mut seed = u32::from(b.u16()) | 1;
    img.iter()
        .map(|&v| {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            let n = if noise > 0 {
                (seed % (2 * noise as u32 + 1)) as i32 - noise
            } else {
                0
            };
            (v + n).clamp(0, 255) as u8
        })
        .collect()
}

/// The `differential` target's case: a structured scene of 8 to 47 pixels a
/// side and the default or the paper profile, with the core's work limit
/// and candidate capacity lifted. The reference has neither: on a tiny
/// image a pathological scene could reach 2 work units per pixel, and
/// candidates on more than 9.2% of the pixels (the default capacity, sized
/// for natural images), which the core would drop and the reference keep.
pub struct Differential {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<u8>,
    pub cfg: Config,
}

impl Differential {
    pub fn decode(b: &mut Bytes<'_>) -> Self {
        let (width, height) = (b.size(8, 40), b.size(8, 40));
        let cfg = if b.u8() & 1 == 0 {
            Config::DEFAULT
        } else {
            Config::PAPER
        };
        let cfg = Config {
            work_per_mille: 100_000,
            candidates_per_mille: 1000,
            ..cfg
        };
        let pixels = scene(b, width, height);
        Self {
            width,
            height,
            pixels,
            cfg,
        }
    }

    /// The agreed tolerance (the geometry of `tests/fixed_vs_reference.rs`,
    /// loosened for single small images): a segment is matched when the
    /// other implementation has one with both endpoints within 1.5 px; on
    /// each side at most `2 + n/4` of `n` segments may be unmatched. `Err`
    /// describes a disagreement beyond it.
    pub fn check(&self) -> Result<(), String> {
        let img = GrayImage::new(&self.pixels, self.width, self.height, self.width)
            .map_err(|e| format!("{e:?}"))?;
        let reference = aaglsd::reference::detect(&img, &self.cfg).map_err(|e| format!("{e:?}"))?;
        let fixed = detect_with_capacity(&img, &self.cfg, 4096)
            .map_err(|e| format!("{e:?}"))?
            .segments;
        let (ur, uf) = (
            unmatched(&reference, &fixed, 1.5),
            unmatched(&fixed, &reference, 1.5),
        );
        if ur <= 2 + reference.len() / 4 && uf <= 2 + fixed.len() / 4 {
            return Ok(());
        }
        Err(format!(
            "reference {} (unmatched {ur}) vs fixed {} (unmatched {uf})\nref {reference:?}\nfixed {fixed:?}",
            reference.len(),
            fixed.len()
        ))
    }
}
