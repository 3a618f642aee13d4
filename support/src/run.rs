//! The fixed-point core on the host, with heap buffers sized for the image.

use aaglsd::{Config, Error, GrayImage, Segment, Summary, Workspace};

/// What one [`detect_fixed`] call found.
#[derive(Clone, Debug, PartialEq)]
pub struct Detection {
    /// The segments, in the core's output order.
    pub segments: Vec<Segment>,
    /// The core's summary (its `segments` is `segments.len()`).
    pub summary: Summary,
}

/// The output capacity [`detect_fixed`] gives a `width` x `height` image:
/// one segment per 16 pixels, at least 64; far more than any test image
/// needs, and a full output is still reported in the summary.
pub fn default_capacity(width: usize, height: usize) -> usize {
    (width.saturating_mul(height) / 16).max(64)
}

/// Runs [`aaglsd::detect`] with a workspace of exactly
/// [`Workspace::bytes_needed_fast`] bytes (the host's choice: the same
/// result as [`Workspace::bytes_needed`], sooner) and [`default_capacity`]
/// output slots.
///
/// # Errors
/// The core's: an invalid `cfg` (checked first, so the error names the
/// field rather than a size).
pub fn detect_fixed(img: &GrayImage<'_>, cfg: &Config) -> Result<Detection, Error> {
    detect_with_capacity(img, cfg, default_capacity(img.width(), img.height()))
}

/// As [`detect_fixed`], with `capacity` output slots.
///
/// # Errors
/// As [`detect_fixed`]; [`Error::OutputEmpty`] for a zero capacity.
pub fn detect_with_capacity(
    img: &GrayImage<'_>,
    cfg: &Config,
    capacity: usize,
) -> Result<Detection, Error> {
    cfg.validate()?;
    let (width, height) = (img.width(), img.height());
    // A valid image and config always have a size; `ImageTooLarge` is what
    // the core would report for the only other cause.
    let needed = Workspace::bytes_needed_fast(width, height, cfg)
        .ok_or(Error::ImageTooLarge { width, height })?;
    let mut slab = vec![0u8; needed];
    let mut out = vec![Segment::ZERO; capacity];
    let summary = aaglsd::detect(img, cfg, &mut Workspace::new(&mut slab), &mut out)?;
    out.truncate(summary.segments);
    Ok(Detection {
        segments: out,
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::rectangle;

    #[test]
    fn a_rectangle_and_the_errors() {
        let (w, h, px) = rectangle(30);
        let img = GrayImage::new(&px, w, h, w).unwrap();
        let d = detect_fixed(&img, &Config::DEFAULT).unwrap();
        assert_eq!(d.segments.len(), 4);
        assert_eq!(d.summary.segments, 4);
        assert!(d.summary.is_complete());
        let bad = Config {
            min_groups: 0,
            ..Config::DEFAULT
        };
        assert!(matches!(
            detect_fixed(&img, &bad),
            Err(Error::InvalidConfig(_))
        ));
        assert_eq!(
            detect_with_capacity(&img, &Config::DEFAULT, 0),
            Err(Error::OutputEmpty)
        );
        let one = detect_with_capacity(&img, &Config::DEFAULT, 1).unwrap();
        assert_eq!((one.segments.len(), one.summary.dropped_segments), (1, 3));
        // The one kept is the best: the rectangle's sides are 32 and 24
        // px of the same contrast, so a long side.
        let best = d.segments.iter().map(|g| g.score).fold(0.0, f32::max);
        assert_eq!(one.segments[0].score, best);
        assert!(one.segments[0].length() > 28.0);
    }

    /// The rectangle's segments as the `detect` CLI writes them: 4 columns
    /// by default, the score as a 5th with `--scores`, 5 numbers a segment
    /// in JSON; and each side with the light background on its left.
    #[test]
    fn the_rectangle_as_files_with_and_without_scores() {
        use crate::segments::{Format, parse_segments};
        let (w, h, px) = rectangle(30);
        let img = GrayImage::new(&px, w, h, w).unwrap();
        let segs = detect_fixed(&img, &Config::DEFAULT).unwrap().segments;
        assert_eq!(segs.len(), 4);
        let columns =
            |text: &str| -> Vec<usize> { text.lines().map(|l| l.split(' ').count()).collect() };

        let (text, ext) = Format::default().write(w, h, &segs);
        assert_eq!((columns(&text), ext), (vec![4; 4], "txt"));
        let plain = parse_segments(&text).unwrap();
        assert!(plain.iter().all(|g| g.score == 0.0), "no score column");

        let scores = Format {
            scores: true,
            ..Format::default()
        };
        let (text, ext) = scores.write(w, h, &segs);
        assert_eq!((columns(&text), ext), (vec![5; 4], "txt"));
        assert_eq!(
            parse_segments(&text).unwrap(),
            segs,
            "exact, scores included"
        );
        for g in &segs {
            // A 170-level step along 24 or 32 px: a large integer score.
            assert!(
                g.score > 100.0 * g.length() && g.score.fract() == 0.0,
                "{g:?}"
            );
            // Three pixels to the left of the direction (x right, y down)
            // is the light background, three to the right the rectangle.
            let (dx, dy) = ((g.x1 - g.x0) / g.length(), (g.y1 - g.y0) / g.length());
            let (mx, my) = ((g.x0 + g.x1) / 2.0, (g.y0 + g.y1) / 2.0);
            let at = |x: f32, y: f32| px[y.round() as usize * w + x.round() as usize];
            assert_eq!(at(mx + 3.0 * dy, my - 3.0 * dx), 200, "left of {g:?}");
            assert_eq!(at(mx - 3.0 * dy, my + 3.0 * dx), 30, "right of {g:?}");
        }

        for scores in [false, true] {
            let (json, ext) = Format { json: true, scores }.write(w, h, &segs);
            assert_eq!(ext, "json");
            let first = format!(
                "[[{},{},{},{},{}],",
                segs[0].x0, segs[0].y0, segs[0].x1, segs[0].y1, segs[0].score
            );
            assert!(json.contains(&first), "{json}");
            assert_eq!(json.matches('[').count(), 1 + 4);
            assert_eq!(json.matches(',').count(), 2 + 4 * 4 + 3);
        }
    }
}
