//! `detect` on arbitrary bytes: dimensions, stride, config and pixels come
//! from the input. Asserts the API contract: no panic, an error only for an
//! invalid config or short buffers, `segments <= capacity`, every endpoint
//! finite and inside the image, and identical results on a reused (dirty)
//! workspace and on one with the group index and magnitude cache
//! (`bytes_needed_fast`).
#![no_main]

#[path = "common.rs"]
mod common;

use aaglsd::{Error, GrayImage, Segment, Workspace, detect};

common::fuzz_bytes!(|b| {
    let (w, h) = (b.size(1, 48), b.size(1, 48));
    let stride = w + usize::from(b.u8() % 8);
    let short = b.u8() % 16 == 0; // sometimes a pixel buffer one byte short
    let cap = 1 + usize::from(b.u8() % 32);
    let cfg = common::config(&mut b);
    let raw = b.u8() & 1 == 1;
    let mut pixels = if raw {
        let mut v: Vec<u8> = b.0.iter().copied().cycle().take(stride * h).collect();
        v.resize(stride * h, 0);
        v
    } else {
        let s = common::scene(&mut b, w, h);
        let mut v = vec![0u8; stride * h];
        for y in 0..h {
            v[y * stride..y * stride + w].copy_from_slice(&s[y * w..(y + 1) * w]);
        }
        v
    };
    let needed = stride * (h - 1) + w;
    pixels.truncate(if short { needed - 1 } else { needed });
    let img = match GrayImage::new(&pixels, w, h, stride) {
        Ok(img) => img,
        Err(e) => {
            assert!(short, "unexpected image error {e:?}");
            assert!(matches!(e, Error::BufferTooShort { .. }));
            return;
        }
    };
    let size = Workspace::bytes_needed(w, h, &aaglsd::Config::DEFAULT).unwrap_or(0);
    let mut slab = vec![0xA5u8; size.max(Workspace::bytes_needed(w, h, &cfg).unwrap_or(0))];
    let mut out = vec![Segment::default(); cap];
    match detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out) {
        Ok(s) => {
            assert!(cfg.validate().is_ok());
            assert!(s.segments <= cap);
            for g in &out[..s.segments] {
                for (x, y) in [(g.x0, g.y0), (g.x1, g.y1)] {
                    assert!(x.is_finite() && y.is_finite());
                    assert!((-0.5..=w as f32 - 0.5).contains(&x), "{g:?} {w}x{h}");
                    assert!((-0.5..=h as f32 - 0.5).contains(&y), "{g:?} {w}x{h}");
                }
            }
            // Reusing the now dirty workspace gives the same answer.
            let mut again = vec![Segment::default(); cap];
            let s2 = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut again).unwrap();
            assert_eq!(s, s2);
            assert_eq!(&out[..s.segments], &again[..s2.segments]);
            // A workspace with the group index and magnitude cache (dirty
            // too) gives the same.
            if let Some(n) = Workspace::bytes_needed_fast(w, h, &cfg) {
                let mut fast = vec![0x5Au8; n];
                let s3 = detect(&img, &cfg, &mut Workspace::new(&mut fast), &mut again).unwrap();
                assert_eq!(s, s3);
                assert_eq!(&out[..s.segments], &again[..s3.segments]);
            }
        }
        Err(Error::InvalidConfig(_)) => assert!(cfg.validate().is_err()),
        Err(e) => panic!("unexpected error {e:?}"),
    }
});
