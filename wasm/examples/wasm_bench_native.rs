//! The native side of the wasm timing bench (`wasm/bench/run.sh`, which
//! runs `wasm/bench/bench.mjs`).
//!
//! `cargo run -p aaglsd-wasm --release --example wasm_bench_native -- [--reps N] OUT_DIR IMAGE...`
//!
//! For each image: decodes it to gray, writes the pixels to
//! `OUT_DIR/<stem>.pgm` for node to read, then times `aaglsd::detect` with
//! `Config::DEFAULT` as the wasm module runs it: a workspace of
//! `Workspace::bytes_needed` bytes (what the `workspace_size` export
//! returns) and an output of `default_capacity` segments. One warm-up run,
//! then `N` timed runs (default 7) of the call alone. The same is done on a
//! workspace of `Workspace::bytes_needed_fast` bytes (the host layout, which
//! the module does not use), for reference. Prints one JSON line per image:
//! `{"image", "pgm", "width", "height", "count", "hash", "ms", "ms_fast"}`,
//! the times being the medians in milliseconds and `hash` the FNV-1a (32-bit)
//! of the segments' `f32` bit patterns, which the node side checks the
//! modules' output against.

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Instant;

use aaglsd::{Config, Segment, Workspace};
use aaglsd_support::image::load_gray;
use aaglsd_wasm::default_capacity;

/// FNV-1a over the little-endian bytes of each `u32`, as `bench.mjs` has it.
fn fnv1a(words: impl Iterator<Item = u32>) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for w in words {
        for b in w.to_le_bytes() {
            h = (h ^ u32::from(b)).wrapping_mul(0x0100_0193);
        }
    }
    h
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// The median of `reps` timed runs (after one warm-up) and the last output.
fn time(
    img: &aaglsd::GrayImage<'_>,
    slab: &mut [u8],
    out: &mut [Segment],
    reps: usize,
) -> Result<(f64, usize), String> {
    let cfg = Config::DEFAULT;
    let mut n = 0;
    let mut ms = Vec::with_capacity(reps);
    for i in 0..=reps {
        let t0 = Instant::now();
        let s = aaglsd::detect(
            black_box(img),
            &cfg,
            &mut Workspace::new(slab),
            black_box(&mut *out),
        )
        .map_err(|e| e.to_string())?;
        let dt = t0.elapsed().as_secs_f64() * 1e3;
        n = black_box(s.segments);
        if i > 0 {
            ms.push(dt);
        }
    }
    Ok((median(&mut ms), n))
}

fn main() -> Result<(), String> {
    const USAGE: &str = "usage: wasm_bench_native [--reps N] OUT_DIR IMAGE...";
    let mut args = std::env::args().skip(1).peekable();
    let mut reps = 7;
    if args.peek().is_some_and(|a| a == "--reps") {
        args.next();
        reps = args
            .next()
            .and_then(|n| n.parse().ok())
            .filter(|&n| n > 0)
            .ok_or(USAGE)?;
    }
    let out_dir = PathBuf::from(args.next().ok_or(USAGE)?);
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    for image in args {
        let path = PathBuf::from(&image);
        let gray = load_gray(&path).map_err(|e| format!("{image}: {e}"))?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("image");
        let pgm = out_dir.join(format!("{stem}.pgm"));
        std::fs::write(&pgm, gray.to_pgm()).map_err(|e| format!("{}: {e}", pgm.display()))?;

        let (w, h) = (gray.width, gray.height);
        let img = gray.image().map_err(|e| format!("{image}: {e}"))?;
        let cfg = Config::DEFAULT;
        let mut out = vec![Segment::ZERO; default_capacity(w, h)];
        let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).ok_or("too large")?];
        let (ms, count) = time(&img, &mut slab, &mut out, reps)?;
        let hash = fnv1a(
            out[..count]
                .iter()
                .flat_map(|s| [s.x0, s.y0, s.x1, s.y1, s.score].map(f32::to_bits)),
        );
        let mut fast = vec![0u8; Workspace::bytes_needed_fast(w, h, &cfg).ok_or("too large")?];
        let (ms_fast, count_fast) = time(&img, &mut fast, &mut out, reps)?;
        if count_fast != count {
            return Err(format!(
                "{image}: {count} segments, {count_fast} with the fast layout"
            ));
        }
        println!(
            "{{\"image\":{image:?},\"pgm\":{:?},\"width\":{w},\"height\":{h},\"count\":{count},\
             \"hash\":{hash},\"ms\":{ms:.4},\"ms_fast\":{ms_fast:.4}}}",
            pgm.display().to_string()
        );
    }
    Ok(())
}
