//! Writes the inputs of the C firmware example's check (`ffi/firmware/run.sh
//! --check`): each image as an 8-bit PGM and as a YUYV camera frame.
//!
//! ```text
//! cargo run -p aaglsd-ffi --release --example fw_inputs -- OUT_DIR INPUT...
//! ```
//!
//! An INPUT is an image file (PGM, PNG, JPEG, or a raw `.gray` of 320x240
//! bytes), `crop:FILE:X:Y` (its 320x240 crop at column X, row Y), or
//! `corpus:NAME` (the adversarial pattern `aaglsd_support::corpus` NAME at
//! 320x240). For each, `OUT_DIR/NAME.pgm` and `OUT_DIR/NAME.yuyv` (Y0 U Y1 V
//! with Y the gray value and U = V = 128, 2 bytes a pixel), and one line
//! `NAME WIDTH HEIGHT` on stdout.

use std::path::{Path, PathBuf};

use aaglsd_support::Gray;
use aaglsd_support::image::load_gray;

/// The size of the committed raw crops and of the rendered patterns.
const W: usize = 320;
const H: usize = 240;

fn input(spec: &str) -> Result<(String, Gray), String> {
    let stem = |p: &str| {
        Path::new(p)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("image")
            .to_string()
    };
    if let Some(name) = spec.strip_prefix("corpus:") {
        let pixels = aaglsd_support::corpus::render(name, W, H)
            .ok_or_else(|| format!("unknown corpus pattern {name:?}"))?;
        return Ok((
            format!("corpus-{name}"),
            Gray {
                width: W,
                height: H,
                data: pixels,
            },
        ));
    }
    if let Some(rest) = spec.strip_prefix("crop:") {
        let mut parts = rest.rsplitn(3, ':');
        let (y, x, file) = (parts.next(), parts.next(), parts.next());
        let (Some(y), Some(x), Some(file)) = (y, x, file) else {
            return Err(format!("{spec}: want crop:FILE:X:Y"));
        };
        let num = |s: &str| s.parse::<usize>().map_err(|e| format!("{spec}: {e}"));
        let g = load_gray(Path::new(file))
            .map_err(|e| format!("{file}: {e}"))?
            .crop(num(x)?, num(y)?, W, H)?;
        return Ok((format!("{}_crop", stem(file)), g));
    }
    if spec.ends_with(".gray") {
        let pixels = std::fs::read(spec).map_err(|e| format!("{spec}: {e}"))?;
        if pixels.len() != W * H {
            return Err(format!("{spec}: {} bytes, not {W}x{H}", pixels.len()));
        }
        return Ok((
            stem(spec),
            Gray {
                width: W,
                height: H,
                data: pixels,
            },
        ));
    }
    let g = load_gray(Path::new(spec)).map_err(|e| format!("{spec}: {e}"))?;
    Ok((stem(spec), g))
}

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(
        args.next()
            .ok_or("usage: fw_inputs OUT_DIR INPUT... (see the source)")?,
    );
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    for spec in args {
        let (name, g) = input(&spec)?;
        let write = |ext: &str, bytes: &[u8]| {
            let p = out.join(format!("{name}.{ext}"));
            std::fs::write(&p, bytes).map_err(|e| format!("{}: {e}", p.display()))
        };
        write("pgm", &g.to_pgm())?;
        let yuyv: Vec<u8> = g.data.iter().flat_map(|&y| [y, 128]).collect();
        write("yuyv", &yuyv)?;
        println!("{name} {} {}", g.width, g.height);
    }
    Ok(())
}
