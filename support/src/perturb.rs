//! Deterministic changes of a gray image, for measuring how stable the
//! detections are (the stability harness, `examples/stability.rs`): tone
//! curves, additive Gaussian noise, a JPEG round trip, an integer
//! translation and a 3x3 box blur.
//!
//! Every change is a pure function of its input (and, for the noise, of a
//! seed). The float math goes through the `libm` crate's portable
//! implementations, not the platform's maths library, and each float result
//! is rounded to nearest, ties away from zero, then clamped to 0..=255;
//! the translation and the blur are integer. Reruns, and other machines,
//! get the same pixels.

use crate::image::Gray;

/// To nearest, ties away from zero, then into 0..=255.
fn round_clamp(v: f64) -> u8 {
    libm::round(v).clamp(0.0, 255.0) as u8
}

/// `data` as an image of `g`'s size.
fn like(g: &Gray, data: Vec<u8>) -> Gray {
    debug_assert_eq!(data.len(), g.width * g.height);
    Gray {
        width: g.width,
        height: g.height,
        data,
    }
}

/// Each pixel through a 256-entry table built from `f`.
pub fn map_levels(g: &Gray, f: impl Fn(u8) -> u8) -> Gray {
    let table: [u8; 256] = std::array::from_fn(|v| f(v as u8));
    like(g, g.data.iter().map(|&v| table[usize::from(v)]).collect())
}

/// `255 * (v / 255)^gamma`: a gamma below 1 brightens the image (lifts the
/// shadows, flattens the highlights), above 1 darkens it. 0 and 255 stay.
pub fn gamma(g: &Gray, gamma: f64) -> Gray {
    map_levels(g, |v| {
        round_clamp(255.0 * libm::pow(f64::from(v) / 255.0, gamma))
    })
}

/// `128 + factor * (v - 128)`: contrast scaled about mid-grey (not the
/// image mean, so the change does not depend on the content).
pub fn contrast(g: &Gray, factor: f64) -> Gray {
    map_levels(g, |v| round_clamp(128.0 + factor * (f64::from(v) - 128.0)))
}

/// `v + delta`, clamped.
pub fn brightness(g: &Gray, delta: i32) -> Gray {
    map_levels(g, |v| (i32::from(v) + delta).clamp(0, 255) as u8)
}

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny generator whose whole
/// state is the seed, so a seed names one noise image.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1]: the top 53 bits, plus one, so `ln` is finite.
    fn next_open01(&mut self) -> f64 {
        ((self.next_u64() >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Adds `sigma` times a standard normal sample to each pixel (Box–Muller:
/// each pair of uniforms gives two samples, used for two consecutive
/// pixels in row order), rounded and clamped. The same `seed` gives the same
/// image.
pub fn gaussian_noise(g: &Gray, sigma: f64, seed: u64) -> Gray {
    let mut rng = SplitMix64(seed);
    let mut data = Vec::with_capacity(g.data.len());
    for pair in g.data.chunks(2) {
        let r = libm::sqrt(-2.0 * libm::log(rng.next_open01()));
        let (s, c) = libm::sincos(std::f64::consts::TAU * rng.next_open01());
        for (&v, n) in pair.iter().zip([r * c, r * s]) {
            data.push(round_clamp(f64::from(v) + sigma * n));
        }
    }
    like(g, data)
}

/// The image translated by (`dx`, `dy`) pixels: output pixel (x, y) is
/// input pixel (x - dx, y - dy), the coordinates clamped into the image, so
/// the columns and rows uncovered repeat the border. A point at (x, y) of
/// the input is at (x + dx, y + dy) of the output: the homography from the
/// input to the output is the translation [[1, 0, dx], [0, 1, dy], [0, 0, 1]].
pub fn translate(g: &Gray, dx: isize, dy: isize) -> Gray {
    let src = |p: usize, d: isize, n: usize| p.saturating_add_signed(-d).min(n - 1);
    let mut data = Vec::with_capacity(g.data.len());
    for y in 0..g.height {
        let row = &g.data[src(y, dy, g.height) * g.width..][..g.width];
        data.extend((0..g.width).map(|x| row[src(x, dx, g.width)]));
    }
    like(g, data)
}

/// The mean of each pixel's 3x3 neighbourhood, rounded to nearest (never a
/// tie: the sum is an integer and 9 is odd), the border replicated outside
/// the image.
pub fn box_blur3(g: &Gray) -> Gray {
    let (w, h) = (g.width, g.height);
    let at = |x: usize, y: usize| u32::from(g.data[y * w + x]);
    let mut data = Vec::with_capacity(g.data.len());
    for y in 0..h {
        let rows = [y.saturating_sub(1), y, (y + 1).min(h - 1)];
        for x in 0..w {
            let cols = [x.saturating_sub(1), x, (x + 1).min(w - 1)];
            let sum: u32 = rows
                .iter()
                .flat_map(|&r| cols.iter().map(move |&c| at(c, r)))
                .sum();
            data.push(((sum + 4) / 9) as u8);
        }
    }
    like(g, data)
}

/// The image encoded as a baseline gray JPEG at `quality` (1 to 100, the
/// IJG scale) and decoded back to luma by [`crate::image::decode`], the
/// decoder every image of the repository goes through.
///
/// # Errors
/// The encoder's (e.g. a side over 65535) or the decoder's.
#[cfg(feature = "jpeg-encode")]
pub fn jpeg_round_trip(g: &Gray, quality: u8) -> Result<Gray, String> {
    crate::image::decode(&crate::image::encode_jpeg(g, quality)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gray(width: usize, height: usize, data: Vec<u8>) -> Gray {
        assert_eq!(data.len(), width * height);
        Gray {
            width,
            height,
            data,
        }
    }

    fn ramp(width: usize, height: usize) -> Gray {
        gray(
            width,
            height,
            (0..width * height).map(|i| (i * 7 % 256) as u8).collect(),
        )
    }

    #[test]
    fn tone_curves() {
        let g = gray(6, 1, vec![0, 64, 127, 129, 200, 255]);
        // 255 * (64/255)^0.5 = 127.75; (64/255)^2 * 255 = 16.06.
        assert_eq!(gamma(&g, 0.5).data, [0, 128, 180, 181, 226, 255]);
        assert_eq!(gamma(&g, 2.0).data, [0, 16, 63, 65, 157, 255]);
        // 127.5 and 128.5 round away from zero.
        assert_eq!(contrast(&g, 0.5).data, [64, 96, 128, 129, 164, 192]);
        assert_eq!(brightness(&g, 40).data, [40, 104, 167, 169, 240, 255]);
        assert_eq!(brightness(&g, -40).data, [0, 24, 87, 89, 160, 215]);
    }

    #[test]
    fn noise_is_seeded_and_has_the_asked_spread() {
        let flat = gray(200, 100, vec![128; 20_000]);
        let a = gaussian_noise(&flat, 8.0, 42);
        assert_eq!(a, gaussian_noise(&flat, 8.0, 42));
        assert_ne!(a, gaussian_noise(&flat, 8.0, 43));
        let n = a.data.len() as f64;
        let mean = a.data.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
        let var = a
            .data
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / n;
        // Rounding adds 1/12 to the variance.
        assert!((mean - 128.0).abs() < 0.2, "mean {mean}");
        assert!((var.sqrt() - 8.0).abs() < 0.15, "sigma {}", var.sqrt());
        // An odd pixel count uses half of the last pair.
        let odd = ramp(3, 3);
        assert_eq!(gaussian_noise(&odd, 3.0, 1).data.len(), 9);
    }

    #[test]
    fn translation_replicates_the_border() {
        let g = gray(3, 2, vec![1, 2, 3, 4, 5, 6]);
        assert_eq!(translate(&g, 1, 0).data, [1, 1, 2, 4, 4, 5]);
        assert_eq!(translate(&g, -1, 0).data, [2, 3, 3, 5, 6, 6]);
        assert_eq!(translate(&g, 0, 1).data, [1, 2, 3, 1, 2, 3]);
        assert_eq!(translate(&g, 0, 0), g);
    }

    #[test]
    fn box_blur_means_and_borders() {
        let mut g = gray(4, 3, vec![0; 12]);
        g.data[5] = 90; // (1, 1)
        let b = box_blur3(&g);
        // Each pixel within one of (1, 1) sees it once (the replicated
        // border adds copies of row 0 and column 0, not of (1, 1)).
        assert_eq!(b.data, [10, 10, 10, 0, 10, 10, 10, 0, 10, 10, 10, 0]);
        let flat = gray(5, 4, vec![77; 20]);
        assert_eq!(box_blur3(&flat), flat);
        // Sums 13 and 14: 1.44 rounds down, 1.56 up.
        for (centre, want) in [(5, 1), (6, 2)] {
            let mut g = gray(3, 3, vec![1; 9]);
            g.data[4] = centre;
            assert_eq!(box_blur3(&g).data[4], want);
        }
    }

    #[cfg(feature = "jpeg-encode")]
    #[test]
    fn jpeg_round_trip_is_close_and_repeatable() {
        let g = box_blur3(&ramp(64, 48));
        let q30 = jpeg_round_trip(&g, 30).unwrap();
        assert_eq!((q30.width, q30.height), (64, 48));
        assert_eq!(q30, jpeg_round_trip(&g, 30).unwrap());
        let err = |q: &Gray| {
            q.data
                .iter()
                .zip(&g.data)
                .map(|(&a, &b)| f64::from(a.abs_diff(b)))
                .sum::<f64>()
                / g.data.len() as f64
        };
        let q95 = jpeg_round_trip(&g, 95).unwrap();
        assert!(err(&q95) < err(&q30), "{} vs {}", err(&q95), err(&q30));
        assert!(err(&q30) > 0.0);
    }
}
