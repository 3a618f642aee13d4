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

    #[test]
    fn a_rectangle_and_the_errors() {
        let (w, h) = (64, 48);
        let mut px = vec![200u8; w * h];
        for y in 12..36 {
            px[y * w + 16..y * w + 48].fill(30);
        }
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
    }
}
