//! Writes the input and the expected output of the C smoke test
//! (`ffi/tests/smoke.c`, run by `ffi/tests/run.sh`).
//!
//! `cargo run -p aaglsd-ffi --release --example smoke_expected -- OUT_DIR [IMAGE.png]`
//!
//! Decodes an 8-bit gray PNG (default `testdata/castle1.png`), writes it to
//! `OUT_DIR/input.pgm`, runs the Rust core (`aaglsd::detect`, not the C ABI)
//! with the official and the paper profiles, and writes every summary and
//! segment to `OUT_DIR/expected.txt`, coordinates as `f32` bit patterns so
//! that the C side can compare them exactly.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use aaglsd::{Config, GrayImage, Segment, Workspace};

/// Profile numbers as in `AaglsdProfile` (ffi/include/aaglsd.h).
const RUNS: [(u32, Config); 2] = [(1, Config::OFFICIAL), (2, Config::PAPER)];

fn decode_gray_png(path: &Path) -> Result<(usize, usize, Vec<u8>), String> {
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut buf = vec![0; reader.output_buffer_size().ok_or("PNG too large")?];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    if info.color_type != png::ColorType::Grayscale || info.bit_depth != png::BitDepth::Eight {
        return Err(format!("{}: not an 8-bit gray PNG", path.display()));
    }
    let (w, h) = (info.width as usize, info.height as usize);
    let mut data = Vec::with_capacity(w * h);
    for row in buf.chunks(info.line_size).take(h) {
        data.extend_from_slice(&row[..w]);
    }
    Ok((w, h, data))
}

fn main() -> Result<(), String> {
    let mut args = std::env::args_os().skip(1);
    let out_dir = PathBuf::from(
        args.next()
            .ok_or("usage: smoke_expected OUT_DIR [IMAGE.png]")?,
    );
    let image = args.next().map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/castle1.png"),
        PathBuf::from,
    );
    let (w, h, pixels) = decode_gray_png(&image)?;
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;

    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&pixels);
    let pgm_path = out_dir.join("input.pgm");
    std::fs::write(&pgm_path, pgm).map_err(|e| format!("{}: {e}", pgm_path.display()))?;

    let img = GrayImage::new(&pixels, w, h, w).map_err(|e| e.to_string())?;
    let mut text = String::new();
    writeln!(
        text,
        "# Expected output of aaglsd::detect (Rust) on input.pgm ({}), for ffi/tests/smoke.c.\n\
         # run PROFILE SEGMENTS DROPPED_SEGMENTS DROPPED_CANDIDATES TRUNCATED_LINKINGS CANDIDATES GROUPS MERGED\n\
         # then SEGMENTS lines: x0 y0 x1 y1 as f32 bit patterns (hex), then as decimals",
        image.display()
    )
    .map_err(|e| e.to_string())?;
    for (profile, cfg) in RUNS {
        let needed = Workspace::bytes_needed(w, h, &cfg).ok_or("image too large")?;
        let mut slab = vec![0u8; needed];
        let mut out = vec![Segment::default(); 4096];
        let s = aaglsd::detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out)
            .map_err(|e| e.to_string())?;
        if s.dropped_segments != 0 {
            return Err("output array too small for the expected file".into());
        }
        let _ = writeln!(
            text,
            "run {profile} {} {} {} {} {} {} {}",
            s.segments,
            s.dropped_segments,
            s.dropped_candidates,
            s.truncated_linkings,
            s.candidates,
            s.groups,
            s.merged
        );
        for seg in &out[..s.segments] {
            let v = [seg.x0, seg.y0, seg.x1, seg.y1];
            let _ = writeln!(
                text,
                "{:08x} {:08x} {:08x} {:08x}  {} {} {} {}",
                v[0].to_bits(),
                v[1].to_bits(),
                v[2].to_bits(),
                v[3].to_bits(),
                v[0],
                v[1],
                v[2],
                v[3]
            );
        }
        eprintln!("profile {profile}: {} segments", s.segments);
    }
    let path = out_dir.join("expected.txt");
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {} and {}", pgm_path.display(), path.display());
    Ok(())
}
