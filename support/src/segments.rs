//! Segment files: `x0 y0 x1 y1` text (one segment a line; with the score
//! as a fifth column on request) and JSON (always with the score).

use std::fmt::Write as _;
use std::path::Path;

use aaglsd::Segment;

/// One `x0 y0 x1 y1` line per segment, each number in Rust's shortest
/// round-trip `f32` text (so reading it back is exact).
pub fn to_text(segs: &[Segment]) -> String {
    let mut s = String::new();
    for g in segs {
        let _ = writeln!(s, "{} {} {} {}", g.x0, g.y0, g.x1, g.y1);
    }
    s
}

/// [`to_text`] with the score as a fifth column (`x0 y0 x1 y1 score`).
pub fn to_text_scored(segs: &[Segment]) -> String {
    let mut s = String::new();
    for g in segs {
        let _ = writeln!(s, "{} {} {} {} {}", g.x0, g.y0, g.x1, g.y1, g.score);
    }
    s
}

/// `{"width":…,"height":…,"segments":[[x0,y0,x1,y1,score],…]}` and a
/// newline: each segment an array of its five fields.
pub fn to_json(width: usize, height: usize, segs: &[Segment]) -> String {
    let mut s = format!("{{\"width\":{width},\"height\":{height},\"segments\":[");
    for (i, g) in segs.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(s, "[{},{},{},{},{}]", g.x0, g.y0, g.x1, g.y1, g.score);
    }
    s.push_str("]}\n");
    s
}

/// How the `detect` CLI writes the segments of an image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Format {
    /// JSON ([`to_json`], with the scores) instead of text.
    pub json: bool,
    /// Text with the score as a fifth column ([`to_text_scored`]); JSON
    /// always has it.
    pub scores: bool,
}

impl Format {
    /// The file of a `width` x `height` image's segments, and its extension
    /// (`json` or `txt`).
    pub fn write(self, width: usize, height: usize, segs: &[Segment]) -> (String, &'static str) {
        if self.json {
            (to_json(width, height, segs), "json")
        } else if self.scores {
            (to_text_scored(segs), "txt")
        } else {
            (to_text(segs), "txt")
        }
    }
}

/// Parses segment text: one segment a line, four numbers separated by
/// white space or commas, and optionally a fifth, the score (further
/// numbers on a line are ignored); blank lines and lines starting with `#`
/// are skipped.
///
/// # Errors
/// The line number and what is wrong with it.
pub fn parse_segments(text: &str) -> Result<Vec<Segment>, String> {
    let mut segs = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let mut v = [0f32; 4];
        let mut fields = line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty());
        for slot in &mut v {
            let f = fields
                .next()
                .ok_or_else(|| format!("line {}: fewer than 4 numbers", i + 1))?;
            *slot = f
                .parse()
                .map_err(|_| format!("line {}: {f:?} is not a number", i + 1))?;
        }
        let score = match fields.next() {
            Some(f) => f
                .parse()
                .map_err(|_| format!("line {}: {f:?} is not a number", i + 1))?,
            None => 0.0,
        };
        segs.push(Segment {
            x0: v[0],
            y0: v[1],
            x1: v[2],
            y1: v[3],
            score,
        });
    }
    Ok(segs)
}

/// Reads a segment text file (see [`parse_segments`]).
///
/// # Errors
/// The path, with the I/O or parse error.
pub fn read_segments(path: &Path) -> Result<Vec<Segment>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse_segments(&text).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_exactly() {
        let segs = [
            Segment {
                x0: 0.1,
                y0: -0.5,
                x1: 1e-7,
                y1: 12345.678,
                score: 0.0,
            },
            Segment::ZERO,
        ];
        let text = to_text(&segs);
        assert_eq!(parse_segments(&text).unwrap(), segs);
        assert_eq!(
            parse_segments("# header\n\n1,2, 3 4 5 6\n").unwrap(),
            [Segment {
                x0: 1.0,
                y0: 2.0,
                x1: 3.0,
                y1: 4.0,
                score: 5.0,
            }]
        );
        let scored = [Segment {
            score: 1234.0,
            ..segs[0]
        }];
        assert_eq!(parse_segments(&to_text_scored(&scored)).unwrap(), scored);
        assert!(parse_segments("1 2 3\n").unwrap_err().contains("line 1"));
        assert!(parse_segments("1 2 3 x\n").unwrap_err().contains("\"x\""));
        assert_eq!(
            to_json(3, 2, &segs[1..]),
            "{\"width\":3,\"height\":2,\"segments\":[[0,0,0,0,0]]}\n"
        );
        assert_eq!(
            to_json(3, 2, &scored),
            "{\"width\":3,\"height\":2,\"segments\":[[0.1,-0.5,0.0000001,12345.678,1234]]}\n"
        );
    }
}
