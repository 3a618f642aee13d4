//! Host side of the firmware check (`firmware/run.sh`).
//!
//! ```text
//! host-tools crop IN X Y OUT    320x240 crop at column X, row Y of a gray PNG or a
//!                               JPEG (decoded to its luma), written as raw 8-bit gray
//! host-tools detect IN          aaglsd::detect (Config::DEFAULT) on a 320x240 raw
//!                               gray file, printed exactly as the firmware prints it
//! ```

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use aaglsd::{Config, GrayImage, Segment, Summary, Workspace, detect};

/// Image width, as in the firmware.
const W: usize = 320;
/// Image height, as in the firmware.
const H: usize = 240;
/// Output capacity, as in the firmware (a full output must be reported the
/// same way on both sides).
const MAX_SEGMENTS: usize = 512;

const USAGE: &str = "usage: host-tools crop IN X Y OUT | host-tools detect IN";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = match argv.as_slice() {
        ["crop", input, x, y, output] => crop(Path::new(input), x, y, Path::new(output)),
        ["detect", input] => run_detect(Path::new(input)),
        _ => Err(USAGE.to_string()),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("host-tools: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A decoded 8-bit gray image.
struct Gray {
    width: usize,
    height: usize,
    data: Vec<u8>,
}

fn crop(input: &Path, x: &str, y: &str, output: &Path) -> Result<(), String> {
    let x0: usize = x.parse().map_err(|_| format!("bad X {x:?}"))?;
    let y0: usize = y.parse().map_err(|_| format!("bad Y {y:?}"))?;
    let bytes = std::fs::read(input).map_err(|e| format!("{}: {e}", input.display()))?;
    let img = if bytes.starts_with(b"\x89PNG") {
        decode_png(&bytes)
    } else if bytes.starts_with(&[0xFF, 0xD8]) {
        decode_jpeg(&bytes)
    } else {
        Err("not a PNG or JPEG file".to_string())
    }
    .map_err(|e| format!("{}: {e}", input.display()))?;
    if x0 + W > img.width || y0 + H > img.height {
        return Err(format!(
            "a {W}x{H} crop at ({x0}, {y0}) does not fit in {}x{}",
            img.width, img.height
        ));
    }
    let mut out = Vec::with_capacity(W * H);
    for row in img.data.chunks_exact(img.width).skip(y0).take(H) {
        out.extend_from_slice(&row[x0..x0 + W]);
    }
    std::fs::write(output, &out).map_err(|e| format!("{}: {e}", output.display()))
}

/// 8-bit gray (or gray + alpha) PNGs only: the test images are gray, and a
/// colour conversion here would be one more thing to keep identical.
fn decode_png(bytes: &[u8]) -> Result<Gray, String> {
    let dec = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = dec.read_info().map_err(|e| e.to_string())?;
    let mut buf = vec![0; reader.output_buffer_size().ok_or("PNG too large")?];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    let channels = match (info.color_type, info.bit_depth) {
        (png::ColorType::Grayscale, png::BitDepth::Eight) => 1,
        (png::ColorType::GrayscaleAlpha, png::BitDepth::Eight) => 2,
        (c, d) => return Err(format!("PNG is {c:?} {d:?}; only 8-bit gray is supported")),
    };
    let (width, height) = (info.width as usize, info.height as usize);
    let mut data = Vec::with_capacity(width * height);
    for row in buf.chunks_exact(info.line_size).take(height) {
        data.extend(row.iter().step_by(channels).take(width));
    }
    Ok(Gray {
        width,
        height,
        data,
    })
}

/// Decodes straight to the luma (Y) channel, as libjpeg and OpenCV's
/// `imread(path, IMREAD_GRAYSCALE)` do.
fn decode_jpeg(bytes: &[u8]) -> Result<Gray, String> {
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let opts = DecoderOptions::default().jpeg_set_out_colorspace(ColorSpace::Luma);
    let mut dec = zune_jpeg::JpegDecoder::new_with_options(bytes, opts);
    let data = dec.decode().map_err(|e| format!("{e:?}"))?;
    let (width, height) = dec.dimensions().ok_or("JPEG without dimensions")?;
    if data.len() != width * height {
        return Err(format!(
            "JPEG decoded to {} bytes, expected {}",
            data.len(),
            width * height
        ));
    }
    Ok(Gray {
        width,
        height,
        data,
    })
}

fn run_detect(input: &Path) -> Result<(), String> {
    let data = std::fs::read(input).map_err(|e| format!("{}: {e}", input.display()))?;
    if data.len() != W * H {
        return Err(format!(
            "{}: {} bytes; expected a {W}x{H} raw 8-bit gray image ({} bytes)",
            input.display(),
            data.len(),
            W * H
        ));
    }
    let img = GrayImage::new(&data, W, H, W).map_err(|e| e.to_string())?;
    // The same sizing as the firmware's `static` workspace.
    let mut slab = vec![0u8; Workspace::bytes_needed_default(W, H)];
    let mut out = [Segment::default(); MAX_SEGMENTS];
    let summary = detect(
        &img,
        &Config::DEFAULT,
        &mut Workspace::new(&mut slab),
        &mut out,
    )
    .map_err(|e| e.to_string())?;
    let mut text = String::new();
    for s in &out[..summary.segments] {
        write_segment(&mut text, s);
    }
    write_summary(&mut text, &summary);
    print!("{text}");
    Ok(())
}

/// The firmware's `print_segment`, character for character.
fn write_segment(text: &mut String, s: &Segment) {
    let _ = writeln!(
        text,
        "{} {} {} {} {:08x} {:08x} {:08x} {:08x}",
        s.x0,
        s.y0,
        s.x1,
        s.y1,
        s.x0.to_bits(),
        s.y0.to_bits(),
        s.x1.to_bits(),
        s.y1.to_bits()
    );
}

/// The firmware's `print_summary`, character for character.
fn write_summary(text: &mut String, s: &Summary) {
    let _ = writeln!(
        text,
        "summary segments={} dropped_segments={} dropped_candidates={} truncated_linkings={} candidates={} groups={} merged={}",
        s.segments,
        s.dropped_segments,
        s.dropped_candidates,
        s.truncated_linkings,
        s.candidates,
        s.groups,
        s.merged
    );
}
