//! Host-side helpers shared by the examples: image decoding (PGM, PNG, JPEG)
//! and output writers (text, JSON, SVG). Not part of the library: the core
//! never decodes images.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path;

use aaglsd::Segment;

/// A decoded 8-bit gray image.
pub struct Gray {
    pub width: usize,
    pub height: usize,
    pub data: Vec<u8>,
}

impl Gray {
    pub fn image(&self) -> aaglsd::GrayImage<'_> {
        // Decoders produce width*height bytes; this cannot fail for them.
        aaglsd::GrayImage::new(&self.data, self.width, self.height, self.width)
            .expect("decoder produced a consistent buffer")
    }
}

/// Decodes a PGM (P5, 8-bit), PNG (gray or RGB(A), 8 or 16 bit) or JPEG file
/// to 8-bit gray. JPEGs are decoded straight to their luma (Y) channel, as
/// libjpeg (and so OpenCV's `imread(path, 0)`) does; colour PNGs are
/// converted with the Rec. 601 weights 0.299, 0.587, 0.114.
pub fn load_gray(path: &Path) -> Result<Gray, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let r = if bytes.starts_with(b"P5") {
        parse_pgm(&bytes)
    } else if bytes.starts_with(b"\x89PNG") {
        decode_png(&bytes)
    } else if bytes.starts_with(&[0xFF, 0xD8]) {
        decode_jpeg(&bytes)
    } else {
        Err("not a PGM (P5), PNG or JPEG file".to_string())
    };
    r.map_err(|e| format!("{}: {e}", path.display()))
}

fn parse_pgm(bytes: &[u8]) -> Result<Gray, String> {
    let mut pos = 0;
    let mut fields = Vec::new();
    while fields.len() < 4 {
        while bytes.get(pos).is_some_and(u8::is_ascii_whitespace) {
            pos += 1;
        }
        if bytes.get(pos) == Some(&b'#') {
            while bytes.get(pos).is_some_and(|&b| b != b'\n') {
                pos += 1;
            }
            continue;
        }
        let start = pos;
        while bytes.get(pos).is_some_and(|b| !b.is_ascii_whitespace()) {
            pos += 1;
        }
        if start == pos {
            return Err("truncated PGM header".into());
        }
        fields.push(String::from_utf8_lossy(&bytes[start..pos]).into_owned());
    }
    let num = |s: &str| {
        s.parse::<usize>()
            .map_err(|_| format!("bad PGM header field {s:?}"))
    };
    let (width, height, maxval) = (num(&fields[1])?, num(&fields[2])?, num(&fields[3])?);
    if maxval != 255 {
        return Err(format!("PGM maxval {maxval} unsupported (only 8-bit)"));
    }
    let n = width.checked_mul(height).ok_or("PGM dimensions overflow")?;
    let data = bytes
        .get(pos + 1..pos + 1 + n)
        .ok_or("PGM pixel data truncated")?
        .to_vec();
    Ok(Gray {
        width,
        height,
        data,
    })
}

fn decode_png(bytes: &[u8]) -> Result<Gray, String> {
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::EXPAND);
    let mut reader = dec.read_info().map_err(|e| e.to_string())?;
    let mut buf = vec![0; reader.output_buffer_size().ok_or("PNG too large")?];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    let (w, h) = (info.width as usize, info.height as usize);
    let step = if info.bit_depth == png::BitDepth::Sixteen {
        2
    } else {
        1
    };
    let ch = info.color_type.samples();
    let line = info.line_size;
    let mut data = Vec::with_capacity(w * h);
    for y in 0..h {
        let row = &buf[y * line..];
        for x in 0..w {
            let s = |c: usize| u32::from(row[(x * ch + c) * step]);
            let v = match ch {
                1 | 2 => s(0),
                _ => (299 * s(0) + 587 * s(1) + 114 * s(2) + 500) / 1000,
            };
            data.push(v as u8);
        }
    }
    Ok(Gray {
        width: w,
        height: h,
        data,
    })
}

fn decode_jpeg(bytes: &[u8]) -> Result<Gray, String> {
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let opts = DecoderOptions::default().jpeg_set_out_colorspace(ColorSpace::Luma);
    let mut dec = zune_jpeg::JpegDecoder::new_with_options(bytes, opts);
    let data = dec.decode().map_err(|e| format!("{e:?}"))?;
    let (w, h) = dec.dimensions().ok_or("JPEG without dimensions")?;
    if data.len() != w * h {
        return Err(format!(
            "JPEG decoded to {} bytes, expected {}",
            data.len(),
            w * h
        ));
    }
    Ok(Gray {
        width: w,
        height: h,
        data,
    })
}

/// Runs the fixed-point core with a heap workspace sized by
/// `Workspace::bytes_needed` and an output queue large enough that nothing
/// is dropped (reported as an error if something is).
pub fn detect_fixed(
    img: &aaglsd::GrayImage<'_>,
    cfg: &aaglsd::Config,
) -> Result<Vec<Segment>, String> {
    let needed =
        aaglsd::Workspace::bytes_needed(img.width(), img.height(), cfg).ok_or("image too large")?;
    let mut slab = vec![0u8; needed];
    let mut out = vec![Segment::default(); (img.width() * img.height() / 16).max(64)];
    let s = aaglsd::detect(img, cfg, &mut aaglsd::Workspace::new(&mut slab), &mut out)
        .map_err(|e| e.to_string())?;
    if !s.is_complete() {
        eprintln!("warning: detection incomplete: {s:?}");
    }
    out.truncate(s.segments);
    Ok(out)
}

/// One `x0 y0 x1 y1` line per segment.
pub fn to_text(segs: &[Segment]) -> String {
    let mut s = String::new();
    for g in segs {
        let _ = writeln!(s, "{} {} {} {}", g.x0, g.y0, g.x1, g.y1);
    }
    s
}

/// `{"width":…,"height":…,"segments":[[x0,y0,x1,y1],…]}`.
pub fn to_json(width: usize, height: usize, segs: &[Segment]) -> String {
    let mut s = format!("{{\"width\":{width},\"height\":{height},\"segments\":[");
    for (i, g) in segs.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(s, "[{},{},{},{}]", g.x0, g.y0, g.x1, g.y1);
    }
    s.push_str("]}\n");
    s
}

/// An SVG with the gray image embedded (PNG, base64) and the segments drawn
/// on it. Pixel `(c, r)` covers `[c, c+1) x [r, r+1)` in SVG units, so a
/// pixel-centre coordinate `x` is drawn at `x + 0.5`.
pub fn to_svg(img: &Gray, segs: &[Segment]) -> String {
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_bytes, img.width as u32, img.height as u32);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        if let Ok(mut w) = enc.write_header() {
            let _ = w.write_image_data(&img.data);
        }
    }
    let (w, h) = (img.width, img.height);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<image width=\"{w}\" height=\"{h}\" href=\"data:image/png;base64,{}\"/>\n<g stroke=\"#ff2020\" stroke-width=\"1.2\" stroke-linecap=\"round\" fill=\"none\">\n",
        base64(&png_bytes)
    );
    for g in segs {
        let _ = writeln!(
            s,
            "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\"/>",
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

/// Image files of a folder, sorted by name.
pub fn images_in(dir: &Path) -> Result<Vec<std::path::PathBuf>, String> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                matches!(
                    e.to_ascii_lowercase().as_str(),
                    "jpg" | "jpeg" | "png" | "pgm"
                )
            })
        })
        .collect();
    v.sort();
    Ok(v)
}
