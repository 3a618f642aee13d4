//! The SVG overlay: the gray image with the segments drawn on it.
//!
//! The picture is embedded as a base64 PNG, so the file stands alone. Up to
//! [`EMBED_MAX_PIXELS`] it is embedded at full resolution; a larger image is
//! embedded downscaled by the smallest integer factor that brings it under
//! that bound (box filter), each embedded pixel covering exactly
//! `factor x factor` image pixels, so the overlay still lines up. Viewers
//! refuse very long attributes (libxml2, under librsvg, stops at 10 MB; a
//! 4000 x 3000 photo at full resolution needs about 12 MB of base64), and a
//! preview needs no more pixels than a screen has. The segments always keep
//! their full-resolution coordinates, and each is drawn with an opacity
//! that grows with its score ([`score_opacity`]): the strong lines stand
//! out of the weak ones.

use std::fmt::Write as _;

use aaglsd::Segment;

use crate::image::Gray;

/// Most pixels embedded at full resolution (2 megapixels).
pub const EMBED_MAX_PIXELS: usize = 2_000_000;

/// The integer factor by which a `width` x `height` image is downscaled
/// for embedding: 1 up to [`EMBED_MAX_PIXELS`].
pub fn embed_factor(width: usize, height: usize) -> usize {
    (1..)
        .find(|&k| width.div_ceil(k) * height.div_ceil(k) <= EMBED_MAX_PIXELS)
        .unwrap_or(1)
}

/// `img` reduced by `k` in each direction: every output pixel is the
/// rounded mean of its `k x k` block (clipped at the right and bottom edges).
pub fn downscale(img: &Gray, k: usize) -> Gray {
    let (w, h) = (img.width.div_ceil(k), img.height.div_ceil(k));
    let mut sum = vec![0u32; w * h];
    let mut count = vec![0u32; w * h];
    for (y, row) in img.data.chunks_exact(img.width.max(1)).enumerate() {
        let base = (y / k) * w;
        for (x, &v) in row.iter().enumerate() {
            sum[base + x / k] += u32::from(v);
            count[base + x / k] += 1;
        }
    }
    let data = sum
        .iter()
        .zip(&count)
        .map(|(&s, &n)| ((s + n / 2) / n.max(1)) as u8)
        .collect();
    Gray {
        width: w,
        height: h,
        data,
    }
}

/// The stroke opacity of a score of 0; the image's best is drawn opaque.
pub const MIN_OPACITY: f32 = 0.25;

/// The stroke opacity of each segment, linear in its score: 1 for the
/// highest score of `segs`, [`MIN_OPACITY`] for a score of 0 (all 1 when
/// no score is positive, e.g. segments read from a file without scores).
/// The browser demo (`wasm/demo/demo.js`) shades the same way.
pub fn score_opacity(segs: &[Segment]) -> Vec<f32> {
    let best = segs.iter().map(|g| g.score).fold(0.0, f32::max);
    segs.iter()
        .map(|g| {
            if best > 0.0 {
                MIN_OPACITY + (1.0 - MIN_OPACITY) * (g.score.max(0.0) / best)
            } else {
                1.0
            }
        })
        .collect()
}

/// An SVG of `img` with `segs` drawn on it (see the module docs). Pixel
/// `(c, r)` covers `[c, c+1) x [r, r+1)` in SVG units, so a pixel-centre
/// coordinate `x` is drawn at `x + 0.5`.
pub fn to_svg(img: &Gray, segs: &[Segment]) -> String {
    let (w, h) = (img.width, img.height);
    let k = embed_factor(w, h);
    let small;
    let embedded = if k == 1 {
        img
    } else {
        small = downscale(img, k);
        &small
    };
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(
            &mut png_bytes,
            embedded.width as u32,
            embedded.height as u32,
        );
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        if let Ok(mut w) = enc.write_header() {
            let _ = w.write_image_data(&embedded.data);
        }
    }
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n"
    );
    if k > 1 {
        let _ = writeln!(
            s,
            "<!-- the {w}x{h} image embedded downscaled {k}x ({}x{}); segments in full-resolution pixels -->",
            embedded.width, embedded.height
        );
    }
    let _ = writeln!(
        s,
        "<image width=\"{}\" height=\"{}\" href=\"data:image/png;base64,{}\"/>\n<g stroke=\"#ff2020\" stroke-width=\"1.2\" stroke-linecap=\"round\" fill=\"none\">",
        embedded.width * k,
        embedded.height * k,
        base64(&png_bytes)
    );
    for (g, opacity) in segs.iter().zip(score_opacity(segs)) {
        let _ = writeln!(
            s,
            "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke-opacity=\"{opacity:.2}\"/>",
            g.x0 + 0.5,
            g.y0 + 0.5,
            g.x1 + 0.5,
            g.y1 + 0.5
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}

fn base64(data: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= c.len() {
                out.push(T[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_rfc_vectors() {
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc);
        }
    }

    #[test]
    fn factor_and_downscale() {
        assert_eq!(embed_factor(1000, 1000), 1);
        assert_eq!(embed_factor(2000, 1000), 1);
        assert_eq!(embed_factor(2001, 1000), 2);
        assert_eq!(embed_factor(4000, 3000), 3);
        assert_eq!(embed_factor(32_767, 2048), 6);
        let g = Gray {
            width: 3,
            height: 2,
            data: vec![0, 10, 200, 20, 31, 100],
        };
        // Blocks: [0 10 20 31] -> 15.25 -> 15; [200 100] -> 150.
        assert_eq!(downscale(&g, 2).data, [15, 150]);
        assert_eq!(downscale(&g, 1), g);
    }

    #[test]
    fn large_images_are_embedded_small_and_aligned() {
        let (w, h) = (4000, 3000);
        let img = Gray {
            width: w,
            height: h,
            data: (0..w * h).map(|i| (i * 7919 % 251) as u8).collect(),
        };
        let seg = Segment {
            x0: 0.0,
            y0: 0.0,
            x1: 3999.0,
            y1: 2999.0,
            score: 0.0,
        };
        let svg = to_svg(&img, &[seg]);
        assert!(svg.len() < 4_000_000, "{} bytes", svg.len());
        assert!(svg.contains("viewBox=\"0 0 4000 3000\""));
        assert!(svg.contains("downscaled 3x (1334x1000)"));
        // 1334 embedded columns of 3 units each (the last one clipped).
        assert!(svg.contains("<image width=\"4002\" height=\"3000\""));
        assert!(svg.contains("x2=\"3999.50\" y2=\"2999.50\" stroke-opacity=\"1.00\""));
        let small = Gray {
            width: 4,
            height: 2,
            data: vec![9; 8],
        };
        let svg = to_svg(&small, &[]);
        assert!(!svg.contains("downscaled"));
        assert!(svg.contains("<image width=\"4\" height=\"2\""));
    }

    #[test]
    fn segments_are_shaded_by_score() {
        let seg = |score| Segment {
            x0: 1.0,
            y0: 0.0,
            x1: 3.0,
            y1: 1.0,
            score,
        };
        let segs = [seg(400.0), seg(100.0), seg(300.0), seg(0.0)];
        assert_eq!(score_opacity(&segs), [1.0, 0.4375, 0.8125, 0.25]);
        assert_eq!(score_opacity(&[seg(7.0), seg(7.0)]), [1.0, 1.0]);
        assert_eq!(score_opacity(&[seg(0.0), seg(0.0)]), [1.0, 1.0]);
        assert!(score_opacity(&[]).is_empty());
        let img = Gray {
            width: 4,
            height: 2,
            data: vec![9; 8],
        };
        let svg = to_svg(&img, &segs);
        let opacities: Vec<&str> = svg
            .split("stroke-opacity=\"")
            .skip(1)
            .map(|t| &t[..4])
            .collect();
        assert_eq!(opacities, ["1.00", "0.44", "0.81", "0.25"]);
    }
}
