//! Paper §3.1, first step: 5x5 Gaussian smoothing (σ = 1), exact in integers.
//!
//! This is the fixed-point path that OpenCV's `GaussianBlur` takes for 8-bit
//! images, which the authors' code calls: the separable kernel
//! `[14, 62, 104, 62, 14] / 256` with *reflect-101* borders
//! (`… c b | a b c … x y | x w …`). The horizontal pass is exact in units of
//! 1/256 (at most 255·256 = 65 280, a `u16`), the vertical pass in units of
//! 1/65 536 (at most 16 711 680, a `u32`), and the output rounds half up:
//! `B = (s + 32 768) >> 16`, at most 255. No step can overflow.
//!
//! Both implementations (the fixed core and the float reference) use this
//! module: the stage is exact in integers, so it is written once.

use crate::GrayImage;

/// The 1-D kernel, in units of 1/256 (sums to 256).
#[cfg(test)]
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
    p.max(0).min(n - 1) as usize
}

/// `a·14 + b·62 + c·104 + d·62 + e·14`: one kernel application.
#[inline]
fn taps(a: u32, b: u32, c: u32, d: u32, e: u32) -> u32 {
    (a + e) * KERNEL_OUTER + (b + d) * KERNEL_INNER + c * KERNEL_CENTRE
}

const KERNEL_OUTER: u32 = 14;
const KERNEL_INNER: u32 = 62;
const KERNEL_CENTRE: u32 = 104;

/// Whether the vertical pass runs in 16-bit lanes ([`vertical_u16`]):
/// where the compiler vectorises the loops (SSE2, NEON, SIMD128: the
/// anchor pass's row strategy), twice the lanes of `u32` and a native
/// 16-bit multiply (SSE2 has none for 32-bit lanes). A core without SIMD
/// keeps the `u32` form, one multiply-accumulate per tap.
const VERTICAL_LANES: bool = crate::target::SIMD;

/// [`taps`] of five bytes (`a..e <= 255`) in 16-bit arithmetic: every
/// partial sum is at most 255·256 = 65 280 (no wrap).
#[inline(always)]
fn taps_u16(a: u16, b: u16, c: u16, d: u16, e: u16) -> u16 {
    (a + e) * KERNEL_OUTER as u16 + (b + d) * KERNEL_INNER as u16 + c * KERNEL_CENTRE as u16
}

/// One output byte of the vertical pass from the five horizontal sums
/// `a..e` (each at most 65 280), in 16-bit arithmetic: the same value as
/// `(taps(a..e) + 32 768) >> 16`.
///
/// Each sum splits into its high and low bytes, `v = 256·hi + lo`. The
/// kernel applied to the high bytes (`A`) and to the low bytes (`B`) is
/// each at most 255·256, a `u16`, and the full sum is `s = 256·A + B`.
/// Then `T = A + ⌊B / 256⌋ <= s / 256 <= 65 280`, and `⌊(s + 2^15) / 2^16⌋
/// = ⌊(T + 128) / 256⌋` (the floors nest, and `2^15 = 128·256`), with
/// `T + 128` still a `u16`. `vertical_lanes_equal_u32` checks it.
#[inline(always)]
fn vertical_u16(a: u16, b: u16, c: u16, d: u16, e: u16) -> u8 {
    let hi = taps_u16(a >> 8, b >> 8, c >> 8, d >> 8, e >> 8);
    let lo = taps_u16(a & 255, b & 255, c & 255, d & 255, e & 255);
    let t = hi + (lo >> 8);
    ((t + 128) >> 8) as u8
}

/// Horizontal pass of one row into `h` (units of 1/256). `LANES`: the
/// interior columns by [`horizontal_swar`] (the detector passes [`SWAR`];
/// the tests run both).
fn horizontal<const LANES: bool>(src: &[u8], h: &mut [u16]) {
    let w = src.len().min(h.len());
    let px = |x: isize| u32::from(src.get(reflect101(x, w)).copied().unwrap_or(0));
    // Border columns through reflect101 (all of them when w <= 4).
    let edge = 2.min(w);
    for x in (0..edge).chain(w.saturating_sub(2).max(edge)..w) {
        let xi = x as isize;
        let s = taps(px(xi - 2), px(xi - 1), px(xi), px(xi + 1), px(xi + 2));
        if let Some(o) = h.get_mut(x) {
            *o = s as u16; // <= 65 280
        }
    }
    // Interior columns 2..w-2: four at a time in 16-bit lanes where the
    // target has no SIMD for the compiler to use, then from the 5-wide
    // windows.
    let swar_done = if LANES { horizontal_swar(src, h, w) } else { 0 };
    let lo = 2 + swar_done;
    if let (Some(inner), Some(from)) = (h.get_mut(lo..w.saturating_sub(2)), src.get(lo - 2..)) {
        for (o, win) in inner.iter_mut().zip(from.windows(5)) {
            if let &[a, b, c, d, e] = win {
                let s = taps(a.into(), b.into(), c.into(), d.into(), e.into());
                *o = s as u16;
            }
        }
    }
}

/// Whether [`horizontal`] takes its interior columns four at a time in
/// two 16-bit lanes of a `u32` ([`horizontal_swar`]). Where the compiler
/// vectorises the plain loop (SSE2, NEON, SIMD128: the targets for which
/// the anchor pass also takes its row strategy) that loop is faster. A
/// build for size ([`SMALL`](crate::target::SMALL)) keeps the plain loop only.
const SWAR: bool = !crate::target::SIMD && !crate::target::SMALL;

/// The interior columns of [`horizontal`] from column 2, four per round, in
/// two 16-bit lanes of a `u32`: each lane's sum is at most 255·256 = 65 280,
/// and every partial sum is below it (all terms are nonnegative), so no lane
/// carries into the other and one multiplication weighs two pixels. Returns
/// how many columns it wrote (a multiple of 4; the caller takes the rest).
///
/// For output columns `x..x+4` it reads the bytes `b(x-2)..b(x+6)` as two
/// little-endian words and splits each into its even and odd bytes:
/// `A = (b-2, b0)`, `B = (b-1, b1)`, `C = (b2, b4)`, `D = (b3, b5)` (low
/// lane first, offsets from `x`). Columns `x` and `x+2` are then
/// `(A + C)·14 + (B + M1)·62 + M0·104` and columns `x+1` and `x+3`
/// `(B + D)·14 + (M0 + C)·62 + M1·104`, with `M0 = (b0, b2)` and
/// `M1 = (b1, b3)` taken from the halves of `A, C` and `B, D`.
fn horizontal_swar(src: &[u8], h: &mut [u16], w: usize) -> usize {
    const EVEN: u32 = 0x00FF_00FF;
    let Some(inner) = h.get_mut(2..w.saturating_sub(2)) else {
        return 0;
    };
    // Words of four bytes (`as_chunks`: the size is checked at compile
    // time, so no panic path at any opt-level); each round's high word is
    // the next round's low word, so one new word per four columns.
    let (words, _) = src.as_chunks::<4>();
    let Some((&first, rest)) = words.split_first() else {
        return 0;
    };
    let lo = u32::from_le_bytes(first);
    let (mut a, mut b) = (lo & EVEN, (lo >> 8) & EVEN);
    let mut done = 0;
    for (out, &next) in inner.as_chunks_mut::<4>().0.iter_mut().zip(rest) {
        let hi = u32::from_le_bytes(next);
        let (c, d) = (hi & EVEN, (hi >> 8) & EVEN);
        let m0 = (a >> 16) | (c << 16);
        let m1 = (b >> 16) | (d << 16);
        let even = (a + c) * KERNEL_OUTER + (b + m1) * KERNEL_INNER + m0 * KERNEL_CENTRE;
        let odd = (b + d) * KERNEL_OUTER + (m0 + c) * KERNEL_INNER + m1 * KERNEL_CENTRE;
        let [o0, o1, o2, o3] = out;
        *o0 = even as u16;
        *o1 = odd as u16;
        *o2 = (even >> 16) as u16;
        *o3 = (odd >> 16) as u16;
        (a, b) = (c, d);
        done += 4;
    }
    done
}

/// Where [`blur`] reads source rows and writes smoothed ones.
trait Frame {
    /// Source row `y` (`w` bytes; empty when absent).
    fn source(&self, y: usize) -> &[u8];
    /// Output row `y` (`w` bytes; empty when absent).
    fn target(&mut self, y: usize) -> &mut [u8];
}

/// A source image and a separate packed output.
struct Separate<'a, 'b> {
    img: &'a GrayImage<'b>,
    out: &'a mut [u8],
}

impl Frame for Separate<'_, '_> {
    fn source(&self, y: usize) -> &[u8] {
        self.img.row(y)
    }

    fn target(&mut self, y: usize) -> &mut [u8] {
        let w = self.img.width();
        self.out.get_mut(y * w..(y + 1) * w).unwrap_or(&mut [])
    }
}

/// One buffer: source rows `stride` apart, output rows packed from the
/// start. Output row `y` ends at `(y + 1)·w <= (y + 1)·stride`, before
/// source row `y + 1`; by then [`blur`] has taken the horizontal pass of
/// every source row up to `y + 2`, so no row is overwritten before it is
/// read.
struct InPlace<'a> {
    buf: &'a mut [u8],
    w: usize,
    stride: usize,
}

impl Frame for InPlace<'_> {
    fn source(&self, y: usize) -> &[u8] {
        let start = y.saturating_mul(self.stride);
        self.buf
            .get(start..start.saturating_add(self.w))
            .unwrap_or(&[])
    }

    fn target(&mut self, y: usize) -> &mut [u8] {
        self.buf
            .get_mut(y * self.w..(y + 1) * self.w)
            .unwrap_or(&mut [])
    }
}

/// The smoothing loop: the horizontal pass of each source row into a ring of
/// [`SCRATCH_ROWS`] rows as soon as an output row needs it, then the
/// vertical pass of each output row from the ring.
/// A build for size ([`SMALL`](crate::target::SMALL)) takes every frame as a
/// `dyn Frame` (one copy of the loop for both; a call per row).
fn blur<F: Frame>(f: &mut F, w: usize, h: usize, scratch: &mut [u16]) {
    if crate::target::SMALL {
        blur_rows(f as &mut dyn Frame, w, h, scratch);
    } else {
        blur_rows(f, w, h, scratch);
    }
}

/// [`blur`]'s loop.
fn blur_rows<F: Frame + ?Sized>(f: &mut F, w: usize, h: usize, scratch: &mut [u16]) {
    let mut next_src = 0usize; // next source row whose horizontal pass is due
    for y in 0..h {
        let last_needed = (y + 2).min(h - 1);
        while next_src <= last_needed {
            let slot = next_src % SCRATCH_ROWS;
            if let Some(dst) = scratch.get_mut(slot * w..(slot + 1) * w) {
                horizontal::<SWAR>(f.source(next_src), dst);
            }
            next_src += 1;
        }
        let row = |j: isize| -> &[u16] {
            let s = reflect101(y as isize + j, h) % SCRATCH_ROWS;
            scratch.get(s * w..(s + 1) * w).unwrap_or(&[])
        };
        let (r0, r1, r2, r3, r4) = (row(-2), row(-1), row(0), row(1), row(2));
        for (((((o, &a), &b), &c), &d), &e) in f
            .target(y)
            .iter_mut()
            .zip(r0)
            .zip(r1)
            .zip(r2)
            .zip(r3)
            .zip(r4)
        {
            *o = if VERTICAL_LANES {
                vertical_u16(a, b, c, d, e)
            } else {
                vertical_u32(a, b, c, d, e)
            };
        }
    }
}

/// One output byte of the vertical pass in `u32` arithmetic.
#[inline(always)]
fn vertical_u32(a: u16, b: u16, c: u16, d: u16, e: u16) -> u8 {
    let s = taps(a.into(), b.into(), c.into(), d.into(), e.into());
    // s <= 255·65 536 (each pass's weights sum to 256), so the rounded
    // value is at most 255: no clamp (the module docs).
    ((s + 32_768) >> 16) as u8
}

/// Smooths `img` into `out` (`width * height` bytes, row-major, no padding).
///
/// `scratch` must hold `SCRATCH_ROWS * width` values; with less, or with a
/// short `out`, the call writes nothing (callers size both from the image,
/// so this cannot happen through the public API).
pub fn blur_into(img: &GrayImage<'_>, out: &mut [u8], scratch: &mut [u16]) {
    let (w, h) = (img.width(), img.height());
    if w == 0 || h == 0 || scratch.len() < SCRATCH_ROWS * w || out.len() < w * h {
        return;
    }
    blur(&mut Separate { img, out }, w, h, scratch);
}

/// Smooths the `w` x `h` image whose rows start `stride` bytes apart in
/// `buf` in place: afterwards the first `w·h` bytes of `buf` hold the
/// smoothed image, rows packed. The caller has checked the dimensions and
/// the buffer length (as [`GrayImage::new`] does); otherwise nothing is
/// written.
pub fn blur_in_place(buf: &mut [u8], w: usize, h: usize, stride: usize, scratch: &mut [u16]) {
    if w == 0 || h == 0 || stride < w || scratch.len() < SCRATCH_ROWS * w {
        return;
    }
    let needed = stride.checked_mul(h - 1).and_then(|n| n.checked_add(w));
    if needed.is_none_or(|n| buf.len() < n) {
        return;
    }
    blur(&mut InPlace { buf, w, stride }, w, h, scratch);
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
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
        // 255 is the largest sum: the unclamped output must still be 255.
        for v in [0u8, 77, 255] {
            for &(w, h) in &[(1, 1), (2, 3), (7, 5), (13, 1)] {
                let data = [v; 13 * 5];
                let img = GrayImage::new(&data, w, h, w).unwrap();
                let mut out = [1u8; 13 * 5];
                let mut scratch = [0u16; 5 * 13];
                blur_into(&img, &mut out, &mut scratch);
                assert!(out[..w * h].iter().all(|&o| o == v), "{v}: {w}x{h}");
            }
        }
    }

    /// Smoothing in place, with any stride, equals smoothing into a
    /// separate buffer.
    #[test]
    fn in_place_equals_separate() {
        let mut next = crate::xorshift64(0x9E37_79B9);
        for &(w, h, pad) in &[(1, 1, 0), (5, 3, 2), (13, 9, 0), (13, 9, 7), (4, 17, 1)] {
            let stride = w + pad;
            let data: Vec<u8> = (0..stride * h).map(|_| next() as u8).collect();
            let img = GrayImage::new(&data, w, h, stride).unwrap();
            let mut want = vec![0u8; w * h];
            let mut scratch = vec![0u16; SCRATCH_ROWS * w];
            blur_into(&img, &mut want, &mut scratch);
            let mut buf = data.clone();
            blur_in_place(&mut buf, w, h, stride, &mut scratch);
            assert_eq!(&buf[..w * h], &want[..], "{w}x{h} stride {stride}");
        }
    }

    /// The horizontal pass gives the same sums with the four-column lanes
    /// as without, on random rows of every width up to 40 (borders
    /// included), with the extremes 0 and 255 common (the largest lane
    /// sums).
    #[test]
    fn lane_and_plain_horizontal_passes_agree() {
        let mut next = crate::xorshift64(0x51ED_2701);
        // Fewer under Miri, which interprets every instruction.
        let rounds = if cfg!(miri) { 80 } else { 4_000 };
        for round in 0..rounds {
            let w = 1 + round % 40;
            let src: Vec<u8> = (0..w)
                .map(|_| match next() % 4 {
                    0 => 0,
                    1 => 255,
                    _ => next() as u8,
                })
                .collect();
            let (mut lanes, mut plain) = (vec![1u16; w], vec![2u16; w]);
            horizontal::<true>(&src, &mut lanes);
            horizontal::<false>(&src, &mut plain);
            assert_eq!(lanes, plain, "{src:?}");
        }
    }

    /// The vertical pass gives the same byte in 16-bit lanes as in
    /// `u32`: on random horizontal sums (every sum a horizontal pass can
    /// produce is a kernel application to five bytes), with the extremes
    /// common, and on sums at and near the rounding boundaries.
    #[test]
    fn vertical_lanes_equal_u32() {
        let mut next = crate::xorshift64(0x0BAD_5EED);
        let byte = |next: &mut dyn FnMut() -> u64| match next() % 4 {
            0 => 0u32,
            1 => 255,
            _ => (next() & 255) as u32,
        };
        let rounds = if cfg!(miri) { 2_000 } else { 2_000_000 };
        for _ in 0..rounds {
            let sums: [u16; 5] = core::array::from_fn(|_| {
                let v: [u32; 5] = core::array::from_fn(|_| byte(&mut next));
                taps(v[0], v[1], v[2], v[3], v[4]) as u16
            });
            let [a, b, c, d, e] = sums;
            assert_eq!(
                vertical_u16(a, b, c, d, e),
                vertical_u32(a, b, c, d, e),
                "{sums:?}"
            );
        }
        // Constant columns: every output value, and each side of every
        // rounding boundary (s = 65 536·k ± 32 768 lies between them).
        for v in 0..=65_280u16 {
            assert_eq!(
                vertical_u16(v, v, v, v, v),
                vertical_u32(v, v, v, v, v),
                "{v}"
            );
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
