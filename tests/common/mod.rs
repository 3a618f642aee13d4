//! Helpers shared by the integration tests: PGM I/O, segment files, matching.
#![allow(
    dead_code,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing
)]

use std::path::{Path, PathBuf};

use aaglsd::Segment;

/// A decoded 8-bit gray image.
pub struct Pgm {
    pub width: usize,
    pub height: usize,
    pub data: Vec<u8>,
}

impl Pgm {
    pub fn image(&self) -> aaglsd::GrayImage<'_> {
        aaglsd::GrayImage::new(&self.data, self.width, self.height, self.width).unwrap()
    }
}

/// Reads a binary (P5) 8-bit PGM.
pub fn read_pgm(path: &Path) -> Pgm {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_pgm(&bytes).unwrap_or_else(|| panic!("{}: not an 8-bit P5 PGM", path.display()))
}

pub fn parse_pgm(bytes: &[u8]) -> Option<Pgm> {
    let mut pos = 0;
    let mut fields = Vec::new();
    while fields.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if pos < bytes.len() && bytes[pos] == b'#' {
            while pos < bytes.len() && bytes[pos] != b'\n' {
                pos += 1;
            }
            continue;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return None;
        }
        fields.push(std::str::from_utf8(&bytes[start..pos]).ok()?.to_string());
    }
    if fields[0] != "P5" {
        return None;
    }
    let width: usize = fields[1].parse().ok()?;
    let height: usize = fields[2].parse().ok()?;
    if fields[3] != "255" {
        return None;
    }
    pos += 1;
    let data = bytes.get(pos..pos + width * height)?.to_vec();
    Some(Pgm {
        width,
        height,
        data,
    })
}

/// Reads `x0 y0 x1 y1` lines.
pub fn read_segments(path: &Path) -> Vec<Segment> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let v: Vec<f32> = l
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|s| !s.is_empty())
                .map(|s| s.parse().unwrap())
                .collect();
            Segment {
                x0: v[0],
                y0: v[1],
                x1: v[2],
                y1: v[3],
            }
        })
        .collect()
}

/// `../shared` beside the project root, when present.
pub fn shared_dir() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared");
    p.join("data").is_dir().then_some(p)
}

pub fn testdata() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("testdata")
}

/// The 12 readme image stems.
pub const README_STEMS: [&str; 12] = [
    "book1", "book2", "book3", "book4", "book5", "book6", "castle1", "castle2", "castle3",
    "castle4", "castle5", "castle6",
];

/// Largest endpoint distance between `a` and `b`, with `b` taken in whichever
/// orientation fits better.
pub fn endpoint_distance(a: &Segment, b: &Segment) -> f32 {
    let d = |x0: f32, y0: f32, x1: f32, y1: f32| ((x0 - x1).powi(2) + (y0 - y1).powi(2)).sqrt();
    let same = d(a.x0, a.y0, b.x0, b.y0).max(d(a.x1, a.y1, b.x1, b.y1));
    let swapped = d(a.x0, a.y0, b.x1, b.y1).max(d(a.x1, a.y1, b.x0, b.y0));
    same.min(swapped)
}

/// How many of `wanted` have a partner in `have` within `tol` px (both
/// endpoints), and how many match exactly (within 1e-3 px).
pub fn matched(wanted: &[Segment], have: &[Segment], tol: f32) -> (usize, usize) {
    let mut within = 0;
    let mut exact = 0;
    for w in wanted {
        let best = have
            .iter()
            .map(|h| endpoint_distance(w, h))
            .fold(f32::INFINITY, f32::min);
        if best <= tol {
            within += 1;
        }
        if best <= 1e-3 {
            exact += 1;
        }
    }
    (within, exact)
}

pub fn shifted(s: &[Segment], dx: f32, dy: f32) -> Vec<Segment> {
    s.iter()
        .map(|s| Segment {
            x0: s.x0 + dx,
            y0: s.y0 + dy,
            x1: s.x1 + dx,
            y1: s.y1 + dy,
        })
        .collect()
}
