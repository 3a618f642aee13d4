//! Paper §3.1, first step: 5x5 Gaussian smoothing (σ = 1), exact in integers.
//!
//! This is the fixed-point path that OpenCV's `GaussianBlur` takes for 8-bit
//! images, which the authors' code calls: the separable kernel
//! `[14, 62, 104, 62, 14] / 256` with *reflect-101* borders
//! (`… c b | a b c … x y | x w …`). The horizontal pass is exact in units of
//! 1/256 (at most 255·256 = 65 280, a `u16`), the vertical pass in units of
//! 1/65 536 (at most 16 711 680, a `u32`), and the output rounds half up:
//! `B = (s + 32 768) >> 16`. No step can overflow.
//!
//! Both implementations (the fixed core and the float reference) use this
//! module: the stage is exact in integers, so it is written once.

use crate::GrayImage;

/// The 1-D kernel, in units of 1/256 (sums to 256).
pub const KERNEL: [u32; 5] = [14, 62, 104, 62, 14];

/// Rows of `u16` scratch that [`blur_into`] needs, each `width` long.
pub const SCRATCH_ROWS: usize = 5;

/// Reflect-101 index mapping for a coordinate `i` in `-2..len+2`.
///
/// For `len == 1` every index maps to 0. Matches OpenCV's
/// `borderInterpolate(…, BORDER_REFLECT_101)` for the offsets the kernel uses.
#[inline]
pub fn reflect101(i: isize, len: usize) -> usize {
    if len <= 1 {
        return 0;
    }
    let n = len as isize; // len <= MAX_DIMENSION: no wrap
    let mut p = i;
    // Each round moves p strictly closer to the range; two rounds suffice
    // for the offsets used here, four bound it for any |i| <= 2n.
    for _ in 0..4 {
        if p < 0 {
            p = -p;
        } else if p >= n {
            p = 2 * n - 2 - p;
        } else {
            break;
        }
    }
    p.clamp(0, n - 1) as usize
}

/// Horizontal pass of one row into `h` (units of 1/256).
fn horizontal(src: &[u8], h: &mut [u16]) {
    let w = src.len().min(h.len());
    let tap = |x: usize, j: usize| -> u32 {
        let i = reflect101(x as isize + j as isize - 2, w);
        u32::from(src.get(i).copied().unwrap_or(0)) * KERNEL[j]
    };
    // Border columns through reflect101, interior without it.
    let edge = 2.min(w);
    for x in (0..edge).chain(w.saturating_sub(2).max(edge)..w) {
        let s: u32 = (0..5).map(|j| tap(x, j)).sum();
        if let Some(o) = h.get_mut(x) {
            *o = s as u16; // <= 65 280
        }
    }
    if w > 4 {
        for ((o, win), _) in h[2..w - 2].iter_mut().zip(src.windows(5)).zip(0..) {
            let s = u32::from(win[0]) * KERNEL[0]
                + u32::from(win[1]) * KERNEL[1]
                + u32::from(win[2]) * KERNEL[2]
                + u32::from(win[3]) * KERNEL[3]
                + u32::from(win[4]) * KERNEL[4];
            *o = s as u16;
        }
    }
}

/// Smooths `img` into `out` (`width * height` bytes, row-major, no padding).
///
/// `scratch` must hold `SCRATCH_ROWS * width` values; with less, or with a
/// short `out`, the call writes nothing (callers size both from the image,
/// so this cannot happen through the public API).
pub fn blur_into(img: &GrayImage<'_>, out: &mut [u8], scratch: &mut [u16]) {
    let (w, h) = (img.width(), img.height());
    if scratch.len() < SCRATCH_ROWS * w || out.len() < w * h {
        return;
    }
    let mut next_src = 0usize; // next source row whose horizontal pass is due
    for (y, out_row) in out.chunks_exact_mut(w).take(h).enumerate() {
        let last_needed = (y + 2).min(h - 1);
        while next_src <= last_needed {
            let slot = next_src % SCRATCH_ROWS;
            horizontal(img.row(next_src), &mut scratch[slot * w..(slot + 1) * w]);
            next_src += 1;
        }
        let slot_of = |j: usize| reflect101(y as isize + j as isize - 2, h) % SCRATCH_ROWS;
        let rows: [&[u16]; 5] = core::array::from_fn(|j| {
            let s = slot_of(j);
            &scratch[s * w..(s + 1) * w]
        });
        for (x, o) in out_row.iter_mut().enumerate() {
            let s = u32::from(rows[0][x]) * KERNEL[0]
                + u32::from(rows[1][x]) * KERNEL[1]
                + u32::from(rows[2][x]) * KERNEL[2]
                + u32::from(rows[3][x]) * KERNEL[3]
                + u32::from(rows[4][x]) * KERNEL[4];
            *o = ((s + 32_768) >> 16).min(255) as u8;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflect_matches_opencv_rule() {
        // … c b | a b c …  with a at index 0.
        assert_eq!(reflect101(-1, 5), 1);
        assert_eq!(reflect101(-2, 5), 2);
        assert_eq!(reflect101(5, 5), 3);
        assert_eq!(reflect101(6, 5), 2);
        assert_eq!(reflect101(-2, 2), 0);
        assert_eq!(reflect101(3, 2), 1);
        assert_eq!(reflect101(-1, 1), 0);
    }

    #[test]
    fn constant_image_is_unchanged() {
        for &(w, h) in &[(1, 1), (2, 3), (7, 5), (13, 1)] {
            let data = [77u8; 13 * 5];
            let img = GrayImage::new(&data, w, h, w).unwrap();
            let mut out = [0u8; 13 * 5];
            let mut scratch = [0u16; 5 * 13];
            blur_into(&img, &mut out, &mut scratch);
            assert!(out[..w * h].iter().all(|&v| v == 77), "{w}x{h}");
        }
    }

    #[test]
    fn impulse_gives_the_kernel_outer_product() {
        let mut data = [0u8; 9 * 9];
        data[4 * 9 + 4] = 255;
        let img = GrayImage::new(&data, 9, 9, 9).unwrap();
        let mut out = [0u8; 81];
        let mut scratch = [0u16; 45];
        blur_into(&img, &mut out, &mut scratch);
        for y in 0..9 {
            for x in 0..9 {
                let k = |i: usize| {
                    if (2..7).contains(&i) {
                        KERNEL[i - 2]
                    } else {
                        0
                    }
                };
                let expect = ((255 * k(x) * k(y) + 32_768) >> 16) as u8;
                assert_eq!(out[y * 9 + x], expect, "({x},{y})");
            }
        }
    }
}
