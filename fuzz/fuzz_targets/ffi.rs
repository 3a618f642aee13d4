//! The C entry points with arbitrary arguments: any config bit pattern,
//! arbitrary (possibly lying) dimensions and stride, buffer lengths up to
//! the real buffer sizes (claiming more than that would be the caller's
//! undefined behaviour), NULL for any pointer. Asserts that the status
//! agrees with the Rust API on the same inputs, that the segments are the
//! same bits, and that nothing beyond `out_capacity` is written.
#![no_main]

#[path = "common.rs"]
mod common;
// The C API compiled into this binary (the ffi crate's library carries a
// no_std panic handler, so it is not linked as a crate).
#[allow(dead_code, unsafe_op_in_unsafe_fn)]
#[path = "../../ffi/src/capi.rs"]
mod capi;

use capi::{AaglsdConfig, AaglsdSegment, AaglsdStatus, AaglsdSummary};
use common::Bytes;

fn f32_bits(b: &mut Bytes<'_>) -> f32 {
    f32::from_bits(u32::from(b.u16()) | u32::from(b.u16()) << 16)
}

/// A config from raw bytes: either a valid profile with one field replaced
/// by arbitrary bits, or every field arbitrary.
fn config(b: &mut Bytes<'_>) -> AaglsdConfig {
    let mut c = AaglsdConfig::from(&aaglsd::Config::DEFAULT);
    if b.u8() & 1 == 1 {
        c = AaglsdConfig {
            magnitude_threshold: f32_bits(b),
            anchor_margin: b.u16(),
            align_tolerance_deg: f32_bits(b),
            dist_tolerance_px: f32_bits(b),
            skip_min: b.u8(),
            skip_regular: b.u8(),
            skip_group: b.u8(),
            min_length_px: f32_bits(b),
            min_groups: b.u8(),
            anchor_density: f32_bits(b),
            aligned_density: f32_bits(b),
            min_score: u32::from(b.u16()) | u32::from(b.u8()) << 16,
            extend_max_px: b.u16(),
            reseed: b.u8(),
            maxima: b.u8(),
            bridge_px: b.u8(),
            merge: b.u8(),
            trim: b.u8(),
            merge_center_px: f32_bits(b),
            merge_angle_deg: f32_bits(b),
            merge_gap_px: f32_bits(b),
            candidates_per_mille: b.u16(),
            max_link_pixels: u32::from(b.u16()) | u32::from(b.u16()) << 16,
            work_per_mille: u32::from(b.u16()) | u32::from(b.u16()) << 16,
            work_budget: u32::from(b.u16()),
        };
    } else {
        match b.u8() % 9 {
            0 => c.magnitude_threshold = f32_bits(b),
            1 => c.max_link_pixels = u32::from(b.u16()),
            2 => c.candidates_per_mille = b.u16(),
            3 => c.merge = b.u8(),
            4 => c.skip_min = b.u8(),
            5 => c.maxima = b.u8(),
            6 => c.bridge_px = b.u8(),
            7 => c.min_score = u32::from(b.u16()),
            8 => c.trim = b.u8(),
            _ => {}
        }
    }
    c
}

common::fuzz_bytes!(|b| {
    let nulls = b.u8();
    let w = usize::from(b.u8() % 48);
    let h = usize::from(b.u8() % 48);
    let stride = w.wrapping_add(usize::from(b.u8() % 10)).wrapping_sub(2);
    let cfg = config(&mut b);
    let px_len = usize::from(b.u16() % 3000);
    let ws_len = usize::from(b.u16()) * 4;
    let cap = usize::from(b.u8() % 40);
    let pixels: Vec<u8> =
        b.0.iter()
            .copied()
            .cycle()
            .take(px_len)
            .chain(core::iter::repeat(7))
            .take(px_len)
            .collect();
    let mut ws = vec![0x5Au8; ws_len];
    let mut out = vec![
        AaglsdSegment {
            x0: -9.0,
            y0: -9.0,
            x1: -9.0,
            y1: -9.0,
            score: -9.0,
        };
        cap + 2
    ];
    let mut summary = AaglsdSummary::default();
    let p = |bit: u8, ptr: *const u8| {
        if nulls & bit != 0 {
            core::ptr::null()
        } else {
            ptr
        }
    };
    let status = unsafe {
        capi::aaglsd_detect(
            p(1, pixels.as_ptr()),
            px_len,
            w,
            h,
            stride,
            if nulls & 2 != 0 {
                core::ptr::null()
            } else {
                &cfg
            },
            if nulls & 4 != 0 {
                core::ptr::null_mut()
            } else {
                ws.as_mut_ptr()
            },
            ws_len,
            if nulls & 8 != 0 {
                core::ptr::null_mut()
            } else {
                out.as_mut_ptr()
            },
            cap,
            if nulls & 16 != 0 {
                core::ptr::null_mut()
            } else {
                &mut summary
            },
        )
    };
    // Nothing beyond the capacity is written.
    for s in &out[cap..] {
        assert_eq!(s.x0, -9.0);
    }
    if nulls & 31 != 0 {
        assert_eq!(status, AaglsdStatus::NullPointer);
        return;
    }
    // The same inputs through the Rust API.
    let rcfg = aaglsd::Config::from(&cfg);
    let mut ws2 = vec![0u8; ws_len];
    let mut out2 = vec![aaglsd::Segment::default(); cap];
    let rust = aaglsd::GrayImage::new(&pixels, w, h, stride).and_then(|img| {
        aaglsd::detect(
            &img,
            &rcfg,
            &mut aaglsd::Workspace::new(&mut ws2),
            &mut out2,
        )
    });
    match rust {
        Ok(s) => {
            assert_eq!(status, AaglsdStatus::Ok);
            assert_eq!(summary.segments, s.segments);
            for (a, b) in out[..s.segments].iter().zip(&out2) {
                assert_eq!(
                    [a.x0, a.y0, a.x1, a.y1, a.score].map(f32::to_bits),
                    [b.x0, b.y0, b.x1, b.y1, b.score].map(f32::to_bits)
                );
            }
        }
        Err(e) => {
            assert_ne!(status, AaglsdStatus::Ok, "C said OK, Rust said {e:?}");
            assert_eq!(summary, AaglsdSummary::default());
        }
    }
});
