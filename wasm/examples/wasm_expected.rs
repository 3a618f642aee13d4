//! Writes the input and the expected output of the node test
//! (`wasm/tests/detect.test.mjs`, run by `wasm/tests/run.sh`).
//!
//! `cargo run -p aaglsd-wasm --release --example wasm_expected -- OUT_DIR [IMAGE.png]`
//!
//! Decodes an 8-bit gray PNG (default `testdata/castle1.png`, at most
//! 640 x 480), writes it to `OUT_DIR/input.pgm`, runs the Rust core on the
//! host (`aaglsd::detect` with an output of `MAX_SEGMENTS`, as the module
//! has) for profiles 0, 1 and 2, and writes `OUT_DIR/expected.json`:
//! `{"width", "height", "runs": [{"profile", "count", "summary": [7 u32],
//! "bits": [[x0, y0, x1, y1] as f32 bit patterns, ...]}]}`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use aaglsd::{GrayImage, Segment, Workspace};
use aaglsd_wasm::{MAX_HEIGHT, MAX_SEGMENTS, MAX_WIDTH, profile_config, summary_words};

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
            .ok_or("usage: wasm_expected OUT_DIR [IMAGE.png]")?,
    );
    let image = args.next().map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/castle1.png"),
        PathBuf::from,
    );
    let (w, h, pixels) = decode_gray_png(&image)?;
    if w > MAX_WIDTH || h > MAX_HEIGHT {
        return Err(format!(
            "{w}x{h} exceeds the module's {MAX_WIDTH}x{MAX_HEIGHT}"
        ));
    }
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&pixels);
    let pgm_path = out_dir.join("input.pgm");
    std::fs::write(&pgm_path, pgm).map_err(|e| format!("{}: {e}", pgm_path.display()))?;

    let img = GrayImage::new(&pixels, w, h, w).map_err(|e| e.to_string())?;
    let mut runs = Vec::new();
    for profile in 0..3 {
        let cfg = profile_config(profile).ok_or("unknown profile")?;
        let mut slab = vec![0u8; Workspace::bytes_needed(w, h, &cfg).ok_or("image too large")?];
        let mut out = vec![Segment::default(); MAX_SEGMENTS];
        let s = aaglsd::detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out)
            .map_err(|e| e.to_string())?;
        let summary = summary_words(&s).map(|v| v.to_string()).join(",");
        let mut bits = String::new();
        for (i, seg) in out[..s.segments].iter().enumerate() {
            let v = [seg.x0, seg.y0, seg.x1, seg.y1].map(f32::to_bits);
            let sep = if i == 0 { "" } else { "," };
            let _ = write!(bits, "{sep}\n    [{},{},{},{}]", v[0], v[1], v[2], v[3]);
        }
        runs.push(format!(
            "{{\"profile\":{profile},\"count\":{},\"summary\":[{summary}],\"bits\":[{bits}]}}",
            s.segments
        ));
        eprintln!("profile {profile}: {} segments", s.segments);
    }
    let json = format!(
        "{{\"width\":{w},\"height\":{h},\"runs\":[\n  {}\n]}}\n",
        runs.join(",\n  ")
    );
    let path = out_dir.join("expected.json");
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {} and {}", pgm_path.display(), path.display());
    Ok(())
}
