//! Images to 8-bit gray: PGM (P5, 8-bit), PNG (gray or RGB(A), 8 or 16
//! bit) and JPEG (its luma channel), the PGM writer and (feature
//! `jpeg-encode`) the gray JPEG encoder.
//!
//! JPEGs are decoded with zune-jpeg straight to their luma (Y) channel, as
//! libjpeg (and so OpenCV's `imread(path, IMREAD_GRAYSCALE)`) does; colour
//! PNGs are converted with the Rec. 601 weights 0.299, 0.587, 0.114;
//! 16-bit PNG samples keep their high byte. Every test, golden and score of
//! the repository is measured on exactly these pixels.

use std::path::{Path, PathBuf};

use aaglsd::{Error, GrayImage};

/// A decoded 8-bit gray image, rows packed (`stride == width`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Gray {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width * height` bytes, row by row.
    pub data: Vec<u8>,
}

impl Gray {
    /// The pixels as the detector's image type.
    ///
    /// # Errors
    /// The core's image checks, e.g. [`Error::ImageTooLarge`] for a side
    /// over [`aaglsd::MAX_DIMENSION`] or more than [`aaglsd::MAX_PIXELS`]
    /// pixels.
    pub fn image(&self) -> Result<GrayImage<'_>, Error> {
        GrayImage::new(&self.data, self.width, self.height, self.width)
    }

    /// The `width` x `height` window at column `x`, row `y`.
    ///
    /// # Errors
    /// When the window does not fit in the image.
    pub fn crop(&self, x: usize, y: usize, width: usize, height: usize) -> Result<Gray, String> {
        if x.checked_add(width).is_none_or(|r| r > self.width)
            || y.checked_add(height).is_none_or(|b| b > self.height)
        {
            return Err(format!(
                "a {width}x{height} crop at ({x}, {y}) does not fit in {}x{}",
                self.width, self.height
            ));
        }
        let mut data = Vec::with_capacity(width * height);
        for row in self.data.chunks_exact(self.width).skip(y).take(height) {
            data.extend_from_slice(&row[x..x + width]);
        }
        Ok(Gray {
            width,
            height,
            data,
        })
    }

    /// The image as a binary (P5) 8-bit PGM file.
    pub fn to_pgm(&self) -> Vec<u8> {
        let mut pgm = format!("P5\n{} {}\n255\n", self.width, self.height).into_bytes();
        pgm.extend_from_slice(&self.data);
        pgm
    }
}

/// Reads and decodes an image file (see [`decode`]).
///
/// # Errors
/// The I/O or decoding error, without the path (callers name the file).
pub fn load_gray(path: &Path) -> Result<Gray, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    decode(&bytes)
}

/// Decodes a PGM (P5), PNG or JPEG file, told apart by its first bytes.
///
/// # Errors
/// An unknown format, a malformed or truncated file, or dimensions the core
/// rejects (checked before the pixels are allocated).
pub fn decode(bytes: &[u8]) -> Result<Gray, String> {
    if bytes.starts_with(b"P5") {
        parse_pgm(bytes)
    } else if bytes.starts_with(b"\x89PNG") {
        decode_png(bytes)
    } else if bytes.starts_with(&[0xFF, 0xD8]) {
        decode_jpeg(bytes)
    } else {
        Err("not a PGM (P5), PNG or JPEG file".into())
    }
}

/// The core's dimension checks, before a decoder allocates the pixels: a
/// file that claims 100000 x 100000 pixels is an error, not 10 GB.
fn check_dimensions(width: usize, height: usize) -> Result<(), String> {
    match GrayImage::new(&[], width, height, width) {
        Err(e @ (Error::ZeroDimension { .. } | Error::ImageTooLarge { .. })) => Err(e.to_string()),
        _ => Ok(()),
    }
}

fn parse_pgm(bytes: &[u8]) -> Result<Gray, String> {
    // Header: magic, width, height, maxval, separated by white space and
    // `#` comments, then exactly one white-space byte before the pixels.
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
    if fields[0] != "P5" {
        return Err(format!("PGM magic {:?}, expected \"P5\"", fields[0]));
    }
    let num = |s: &str| {
        s.parse::<usize>()
            .map_err(|_| format!("bad PGM header field {s:?}"))
    };
    let (width, height, maxval) = (num(&fields[1])?, num(&fields[2])?, num(&fields[3])?);
    if maxval != 255 {
        return Err(format!("PGM maxval {maxval} unsupported (only 8-bit)"));
    }
    check_dimensions(width, height)?;
    let n = width * height; // at most MAX_PIXELS (checked)
    let data = bytes
        .get(pos + 1..)
        .and_then(|rest| rest.get(..n))
        .ok_or_else(|| format!("PGM pixel data truncated: {width}x{height} needs {n} bytes"))?
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
    let mut reader = dec.read_info().map_err(|e| format!("PNG: {e}"))?;
    let header = reader.info();
    check_dimensions(header.width as usize, header.height as usize)?;
    let mut buf = vec![0; reader.output_buffer_size().ok_or("PNG too large")?];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("PNG: {e}"))?;
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
    // zune-jpeg fills what is missing of a cut-short file with grey and
    // returns success; a half image would be detected as if it were whole.
    check_jpeg_complete(bytes)?;
    let opts = DecoderOptions::default()
        .jpeg_set_out_colorspace(ColorSpace::Luma)
        .set_max_width(aaglsd::MAX_DIMENSION)
        .set_max_height(aaglsd::MAX_DIMENSION);
    let mut dec = zune_jpeg::JpegDecoder::new_with_options(bytes, opts);
    dec.decode_headers().map_err(|e| format!("JPEG: {e:?}"))?;
    let (w, h) = dec.dimensions().ok_or("JPEG without dimensions")?;
    check_dimensions(w, h)?;
    let data = dec.decode().map_err(|e| format!("JPEG: {e:?}"))?;
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

/// `g` as a baseline one-component (gray) JPEG at `quality`, 1 to 100 on
/// the IJG scale (jpeg-encoder's standard tables).
///
/// # Errors
/// A side over 65535 (JPEG's limit), a quality outside 1..=100, or the
/// encoder's error.
#[cfg(feature = "jpeg-encode")]
pub fn encode_jpeg(g: &Gray, quality: u8) -> Result<Vec<u8>, String> {
    if !(1..=100).contains(&quality) {
        return Err(format!("JPEG quality {quality} is not in 1..=100"));
    }
    let side = |n: usize| u16::try_from(n).map_err(|_| format!("{n} px is too large for JPEG"));
    let (w, h) = (side(g.width)?, side(g.height)?);
    let mut out = Vec::new();
    jpeg_encoder::Encoder::new(&mut out, quality)
        .encode(&g.data, w, h, jpeg_encoder::ColorType::Luma)
        .map_err(|e| format!("JPEG encoder: {e}"))?;
    Ok(out)
}

/// Checks that a JPEG stream reaches its end-of-image marker (EOI).
///
/// Walks the marker segments from SOI, skipping each by its length (so the
/// EOI of an EXIF thumbnail inside APP1 is not taken for the end), and the
/// entropy-coded data after each SOS up to the next marker (a 0xFF there is
/// followed by 0x00, a restart marker or the next marker). A file that
/// ends before EOI was cut short. Bytes after EOI are allowed.
///
/// # Errors
/// `truncated JPEG: ...` when the data ends before EOI.
pub fn check_jpeg_complete(b: &[u8]) -> Result<(), String> {
    let truncated = |at: &str| {
        Err(format!(
            "truncated JPEG: the file ends {at}, before the end-of-image marker ({} bytes)",
            b.len()
        ))
    };
    let mut i = 2; // after SOI
    loop {
        // The next marker: 0xFF (and any fill 0xFFs), then its code.
        while b.get(i).is_some_and(|&x| x != 0xFF) {
            i += 1;
        }
        while b.get(i + 1) == Some(&0xFF) {
            i += 1;
        }
        let Some(&code) = b.get(i + 1) else {
            return truncated("between two segments");
        };
        match code {
            0xD9 => return Ok(()),
            // Stand-alone markers: no length.
            0x01 | 0xD0..=0xD8 => i += 2,
            _ => {
                let (Some(&hi), Some(&lo)) = (b.get(i + 2), b.get(i + 3)) else {
                    return truncated("in a segment header");
                };
                i += 2 + usize::from(u16::from_be_bytes([hi, lo]));
                if i > b.len() {
                    return truncated("inside a segment");
                }
                if code == 0xDA {
                    // Entropy-coded data up to the next real marker.
                    loop {
                        match (b.get(i), b.get(i + 1)) {
                            (Some(0xFF), Some(0x00 | 0xD0..=0xD7)) => i += 2,
                            (Some(0xFF), Some(_)) => break,
                            (Some(_), _) => i += 1,
                            (None, _) => return truncated("inside the scan data"),
                        }
                    }
                }
            }
        }
    }
}

/// What the expected-output generators of the C and WASM tests start
/// from: `OUT_DIR [IMAGE]` on their command line.
pub struct TestInput {
    /// Where the expected output goes.
    pub out_dir: PathBuf,
    /// The image (`testdata/castle1.png` when not given).
    pub image: PathBuf,
    /// Its pixels.
    pub gray: Gray,
    /// `OUT_DIR/input.pgm`: the pixels, for the C or JS side to read.
    pub pgm: PathBuf,
}

impl TestInput {
    /// Reads `OUT_DIR [IMAGE]` from `args`, decodes the image, creates
    /// `OUT_DIR` and writes the pixels to `OUT_DIR/input.pgm`.
    ///
    /// # Errors
    /// `usage` when `OUT_DIR` is missing; a file that cannot be read,
    /// decoded or written, named.
    pub fn from_args(
        mut args: impl Iterator<Item = std::ffi::OsString>,
        usage: &str,
    ) -> Result<Self, String> {
        let out_dir = PathBuf::from(args.next().ok_or(usage)?);
        let image = args.next().map_or_else(
            || crate::data::testdata().join("castle1.png"),
            PathBuf::from,
        );
        let gray = load_gray(&image).map_err(|e| format!("{}: {e}", image.display()))?;
        std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
        let pgm = out_dir.join("input.pgm");
        std::fs::write(&pgm, gray.to_pgm()).map_err(|e| format!("{}: {e}", pgm.display()))?;
        Ok(Self {
            out_dir,
            image,
            gray,
            pgm,
        })
    }
}

/// Image files of a folder (`.jpg`, `.jpeg`, `.png`, `.pgm`, any case),
/// sorted by name.
///
/// # Errors
/// The folder cannot be read.
pub fn images_in(dir: &Path) -> Result<Vec<PathBuf>, String> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::testdata;

    #[test]
    fn pgm_round_trip_and_errors() {
        let g = Gray {
            width: 3,
            height: 2,
            data: vec![1, 2, 3, 4, 5, 6],
        };
        let pgm = g.to_pgm();
        assert_eq!(decode(&pgm).unwrap(), g);
        let commented = b"P5 # a comment\n3\n2 255\n\x01\x02\x03\x04\x05\x06";
        assert_eq!(decode(commented).unwrap(), g);
        assert!(
            decode(&pgm[..pgm.len() - 1])
                .unwrap_err()
                .contains("truncated")
        );
        assert!(decode(b"P5\n3 2\n65535\n").unwrap_err().contains("maxval"));
        assert!(decode(b"P5\n3").unwrap_err().contains("header"));
        assert!(decode(b"GIF89a").unwrap_err().contains("not a PGM"));
        assert_eq!(g.crop(1, 1, 2, 1).unwrap().data, [5, 6]);
        assert!(g.crop(2, 0, 2, 1).is_err());
        assert!(g.crop(usize::MAX, 0, 2, 1).is_err());
    }

    #[test]
    fn oversized_images_are_errors_before_allocation() {
        // A header claiming 40000 x 2 with the pixels present decodes, and
        // the core's image check rejects it; a larger claim without pixels
        // is rejected from the header alone.
        let mut wide = b"P5\n40000 2\n255\n".to_vec();
        wide.resize(wide.len() + 80_000, 7);
        let e = decode(&wide).unwrap_err();
        assert!(e.contains("40000x2 exceeds the limits"), "{e}");
        let e = decode(b"P5\n100000 100000\n255\n").unwrap_err();
        assert!(e.contains("exceeds the limits"), "{e}");
        let g = Gray {
            width: 40_000,
            height: 2,
            data: vec![0; 80_000],
        };
        assert!(matches!(g.image(), Err(Error::ImageTooLarge { .. })));
    }

    #[test]
    fn png_fixture_decodes() {
        let g = load_gray(&testdata().join("castle1.png")).unwrap();
        assert_eq!((g.width, g.height, g.data.len()), (633, 470, 633 * 470));
        // The committed 320x240 crop (firmware/run.sh makes the same check).
        let crop = g.crop(120, 150, 320, 240).unwrap();
        let raw = std::fs::read(testdata().join("castle1_320x240.gray")).unwrap();
        assert_eq!(crop.data, raw);
    }

    #[test]
    fn jpeg_fixture_decodes_and_truncation_is_an_error() {
        let bytes = std::fs::read(testdata().join("castle1_crop.jpg")).unwrap();
        let g = decode(&bytes).unwrap();
        assert_eq!((g.width, g.height), (160, 120));
        // Decoded luma stays close to the PNG pixels it was encoded from.
        let png = load_gray(&testdata().join("castle1.png")).unwrap();
        let src = png.crop(200, 200, 160, 120).unwrap();
        let mean_err = g
            .data
            .iter()
            .zip(&src.data)
            .map(|(&a, &b)| f64::from(a.abs_diff(b)))
            .sum::<f64>()
            / g.data.len() as f64;
        assert!(mean_err < 4.0, "mean error {mean_err}");
        assert_eq!(check_jpeg_complete(&bytes), Ok(()));
        for cut in [bytes.len() - 2, bytes.len() / 2, 400, 3] {
            let e = decode(&bytes[..cut]).unwrap_err();
            assert!(e.starts_with("truncated JPEG"), "cut at {cut}: {e}");
        }
        // Bytes after EOI are allowed.
        let mut trailing = bytes.clone();
        trailing.extend_from_slice(b"trailer");
        assert_eq!(decode(&trailing).unwrap(), g);
    }
}
