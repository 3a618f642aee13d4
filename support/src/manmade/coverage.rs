//! The coverage metric (see [`coverage_with`]).

/// The precision [`Coverage::handled`] asks for (the 0.9).
pub const HANDLED_PRECISION: f64 = 0.9;

/// Spacing of the sample points along each segment, in px.
const STEP: f64 = 0.1;

/// How close a segment must be to cover a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Largest point-to-segment distance, in px.
    pub dist_px: f64,
    /// Largest undirected angle between the two segments, in degrees.
    pub angle_deg: f64,
}

impl Tolerance {
    /// 1 px and 3 degrees (the accuracy protocol's D_c and D_a).
    pub const DEFAULT: Tolerance = Tolerance {
        dist_px: 1.0,
        angle_deg: 3.0,
    };
}

impl Default for Tolerance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One detector's coverage of one image's true lines (or, from
/// [`Coverage::pooled`], of several images').
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coverage {
    /// `covered_len / truth_len`; NaN when there are no true lines.
    pub recall: f64,
    /// `good_len / detected_len`; NaN when nothing of positive length was
    /// detected (undefined, so that a mean over images cannot count an
    /// empty output as perfectly precise).
    pub precision: f64,
    /// Total length of the true lines, in px.
    pub truth_len: f64,
    /// The part of it covered by detected segments.
    pub covered_len: f64,
    /// Total length of the detected segments, in px.
    pub detected_len: f64,
    /// The part of it on true lines.
    pub good_len: f64,
    /// Number of detected segments.
    pub segments: usize,
}

impl Coverage {
    /// Whether the image counts as handled: some segments, precision at
    /// least [`HANDLED_PRECISION`], and recall at least `target` when
    /// there is one (see [`super::Family::recall_target`]).
    pub fn handled(&self, target: Option<f64>) -> bool {
        self.segments > 0
            && self.precision >= HANDLED_PRECISION
            && target.is_none_or(|t| self.recall >= t)
    }

    /// The harmonic mean of recall and precision; 0 when either is 0 or
    /// undefined.
    pub fn f_score(&self) -> f64 {
        let (r, p) = (self.recall, self.precision);
        if r > 0.0 && p > 0.0 {
            2.0 * r * p / (r + p)
        } else {
            0.0
        }
    }

    /// The lengths and counts of `items` summed, recall and precision
    /// recomputed from the sums (pooled over images).
    pub fn pooled<'a>(items: impl IntoIterator<Item = &'a Coverage>) -> Coverage {
        let mut sum = Coverage::from_lengths(0.0, 0.0, 0.0, 0.0, 0);
        for c in items {
            sum = Coverage::from_lengths(
                sum.truth_len + c.truth_len,
                sum.covered_len + c.covered_len,
                sum.detected_len + c.detected_len,
                sum.good_len + c.good_len,
                sum.segments + c.segments,
            );
        }
        sum
    }

    fn from_lengths(truth: f64, covered: f64, detected: f64, good: f64, segments: usize) -> Self {
        let share = |part: f64, whole: f64| {
            if whole > 0.0 { part / whole } else { f64::NAN }
        };
        Coverage {
            recall: share(covered, truth),
            precision: share(good, detected),
            truth_len: truth,
            covered_len: covered,
            detected_len: detected,
            good_len: good,
            segments,
        }
    }
}

/// [`coverage_with`] at [`Tolerance::DEFAULT`] (1 px, 3 degrees).
pub fn coverage(truth: &[[f32; 4]], detected: &[[f32; 4]]) -> Coverage {
    coverage_with(truth, detected, Tolerance::DEFAULT)
}

/// The coverage of the true lines `truth` by the segments `detected`, both
/// `[x0, y0, x1, y1]` in the same frame: how much of the true lines'
/// length the segments cover, and how much of the segments' length lies
/// on true lines.
///
/// A point of a true line is covered when some detected segment makes an
/// undirected angle of at most `tol.angle_deg` with the line and the point
/// lies within `tol.dist_px` of that segment (the segment, ends included,
/// not its infinite line: a segment does not cover what lies beyond its
/// end). Recall is the covered share of the true length; precision is the
/// same rule the other way round: the share of the detected length within
/// the distance of a true line at a small angle. Each segment is measured
/// at sample points 0.1 px apart (the middles of equal pieces), so shares
/// are exact to about a sample.
///
/// Length, not count, is scored: a board edge found in one piece or in
/// eight counts the same, and a short stray segment costs only its length.
/// Zero-length segments have no direction: they count in `segments` but
/// cover nothing and weigh nothing.
pub fn coverage_with(truth: &[[f32; 4]], detected: &[[f32; 4]], tol: Tolerance) -> Coverage {
    let t: Vec<Seg> = truth.iter().map(Seg::new).collect();
    let d: Vec<Seg> = detected.iter().map(Seg::new).collect();
    let (truth_len, covered) = covered_length(&t, &d, tol);
    let (detected_len, good) = covered_length(&d, &t, tol);
    Coverage::from_lengths(truth_len, covered, detected_len, good, detected.len())
}

/// A segment with its unit direction and length.
struct Seg {
    a: (f64, f64),
    b: (f64, f64),
    dir: (f64, f64),
    len: f64,
}

impl Seg {
    fn new(s: &[f32; 4]) -> Self {
        let [x0, y0, x1, y1] = s.map(f64::from);
        let len = (x1 - x0).hypot(y1 - y0);
        let dir = if len > 0.0 {
            ((x1 - x0) / len, (y1 - y0) / len)
        } else {
            (0.0, 0.0)
        };
        Seg {
            a: (x0, y0),
            b: (x1, y1),
            dir,
            len,
        }
    }

    /// Distance along the segment from `a` of `p`'s projection.
    fn along(&self, p: (f64, f64)) -> f64 {
        (p.0 - self.a.0) * self.dir.0 + (p.1 - self.a.1) * self.dir.1
    }

    /// Distance from `p` to the nearest point of the segment.
    fn distance(&self, p: (f64, f64)) -> f64 {
        let t = self.along(p).clamp(0.0, self.len);
        (p.0 - self.a.0 - t * self.dir.0).hypot(p.1 - self.a.1 - t * self.dir.1)
    }

    /// Whether the bounding boxes, `r` apart at most, meet.
    fn near(&self, o: &Seg, r: f64) -> bool {
        let span = |s: &Seg, i: usize| {
            let (p, q) = if i == 0 {
                (s.a.0, s.b.0)
            } else {
                (s.a.1, s.b.1)
            };
            (p.min(q), p.max(q))
        };
        (0..2).all(|i| {
            let ((a0, a1), (b0, b1)) = (span(self, i), span(o, i));
            a0 <= b1 + r && b0 <= a1 + r
        })
    }
}

/// The total length of `segs` and the part within `tol` of some segment
/// of `by`.
fn covered_length(segs: &[Seg], by: &[Seg], tol: Tolerance) -> (f64, f64) {
    let cos_max = tol.angle_deg.to_radians().cos();
    let r = tol.dist_px;
    let (mut total, mut covered) = (0.0, 0.0);
    let mut hit = Vec::new();
    for s in segs.iter().filter(|s| s.len > 0.0) {
        total += s.len;
        let n = (s.len / STEP).ceil() as usize;
        let piece = s.len / n as f64;
        hit.clear();
        hit.resize(n, false);
        for o in by.iter().filter(|o| o.len > 0.0) {
            let cos = (s.dir.0 * o.dir.0 + s.dir.1 * o.dir.1).abs();
            if cos < cos_max || !s.near(o, r) {
                continue;
            }
            // Only the samples whose projection is within r of the other
            // segment's span can be within r of it.
            let (t0, t1) = (s.along(o.a), s.along(o.b));
            let first = ((t0.min(t1) - r) / piece - 0.5).floor().max(0.0) as usize;
            let last = ((t0.max(t1) + r) / piece - 0.5).ceil().min(n as f64 - 1.0);
            if last < first as f64 {
                continue;
            }
            for (k, h) in hit
                .iter_mut()
                .enumerate()
                .take(last as usize + 1)
                .skip(first)
            {
                let at = (k as f64 + 0.5) * piece;
                let p = (s.a.0 + at * s.dir.0, s.a.1 + at * s.dir.1);
                if !*h && o.distance(p) <= r {
                    *h = true;
                }
            }
        }
        // As a share first, so that all covered gives exactly the length.
        covered += s.len * (hit.iter().filter(|&&h| h).count() as f64 / n as f64);
    }
    (total, covered)
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: [f32; 4] = [10.0, 20.0, 210.0, 20.0];

    fn moved(s: [f32; 4], dx: f32, dy: f32) -> [f32; 4] {
        [s[0] + dx, s[1] + dy, s[2] + dx, s[3] + dy]
    }

    /// `s` turned by `deg` about its middle.
    fn turned(s: [f32; 4], deg: f64) -> [f32; 4] {
        let [x0, y0, x1, y1] = s.map(f64::from);
        let (mx, my) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        let (sn, c) = deg.to_radians().sin_cos();
        let t = |x: f64, y: f64| {
            let (dx, dy) = (x - mx, y - my);
            (
                (mx + dx * c - dy * sn) as f32,
                (my + dx * sn + dy * c) as f32,
            )
        };
        let (a, b) = (t(x0, y0), t(x1, y1));
        [a.0, a.1, b.0, b.1]
    }

    #[test]
    fn identity_and_shifts() {
        let diag = [5.0, 5.0, 105.0, 80.0];
        let c = coverage(&[H, diag], &[H, diag]);
        assert_eq!((c.recall, c.precision, c.segments), (1.0, 1.0, 2));
        assert!((c.truth_len - 325.0).abs() < 1e-9 && c.detected_len == c.truth_len);
        // Reversed direction is the same line.
        let rev = [H[2], H[3], H[0], H[1]];
        assert_eq!(coverage(&[H], &[rev]).recall, 1.0);
        let c = coverage(&[H], &[moved(H, 0.0, 2.0)]);
        assert_eq!((c.recall, c.precision), (0.0, 0.0));
        let c = coverage(&[H], &[moved(H, 0.0, -0.8)]);
        assert_eq!((c.recall, c.precision), (1.0, 1.0));
        // 0.8 px across a diagonal, too.
        let c = coverage(&[diag], &[moved(diag, 0.48, -0.64)]);
        assert_eq!((c.recall, c.precision), (1.0, 1.0));
        // Along the line, 3 px: all but the 2 px at one end (the last px
        // is within 1 px of the other's end), each way.
        let c = coverage(&[H], &[moved(H, 3.0, 0.0)]);
        assert!((c.recall - 198.0 / 200.0).abs() < 1e-9, "{c:?}");
        assert!((c.precision - 198.0 / 200.0).abs() < 1e-9, "{c:?}");
    }

    #[test]
    fn half_length_and_segment_not_line() {
        // The detection covers its own 100 px and the 1 px beyond its end.
        let c = coverage(&[H], &[[10.0, 20.0, 110.0, 20.0]]);
        assert!((c.recall - 0.505).abs() < 1e-3, "{c:?}");
        assert_eq!(c.precision, 1.0);
        // Collinear, but 2 px beyond the true line's end: nothing.
        let c = coverage(&[H], &[[212.0, 20.0, 400.0, 20.0]]);
        assert_eq!((c.recall, c.precision), (0.0, 0.0));
        // Beyond by 0.5 px: only the 0.5 px next to the gap.
        let c = coverage(&[H], &[[210.5, 20.0, 400.0, 20.0]]);
        assert!((c.recall - 0.5 / 200.0).abs() < 1e-3, "{c:?}");
    }

    #[test]
    fn angle_tolerance() {
        // Turned about the middle, the two ends are 7 px (4 degrees) and
        // 3.5 px (2 degrees) off the line; near the middle it is close.
        let c = coverage(&[H], &[turned(H, 4.0)]);
        assert_eq!((c.recall, c.precision), (0.0, 0.0));
        let c = coverage(&[H], &[turned(H, 2.0)]);
        // Within 1 px where |t| sin 2 deg <= 1: 2 / sin 2 deg ~ 57 px.
        assert!((c.recall - 57.3 / 200.0).abs() < 0.01, "{c:?}");
        assert!(c.precision > 0.25 && c.precision < 0.3, "{c:?}");
        let loose = Tolerance {
            angle_deg: 5.0,
            ..Tolerance::DEFAULT
        };
        assert!(coverage_with(&[H], &[turned(H, 4.0)], loose).recall > 0.1);
    }

    #[test]
    fn empty_cases_and_handled() {
        let c = coverage(&[H], &[]);
        assert_eq!((c.recall, c.segments), (0.0, 0));
        assert!(c.precision.is_nan());
        assert!(!c.handled(None) && !c.handled(Some(0.0)));
        assert_eq!(c.f_score(), 0.0);
        let c = coverage(&[], &[H]);
        assert!(c.recall.is_nan());
        assert_eq!(c.precision, 0.0);
        let c = coverage(&[], &[]);
        assert!(c.recall.is_nan() && c.precision.is_nan());
        // A zero-length segment counts but covers and weighs nothing.
        let c = coverage(&[H], &[[5.0, 20.0, 5.0, 20.0]]);
        assert_eq!((c.recall, c.segments, c.detected_len), (0.0, 1, 0.0));
        assert!(c.precision.is_nan());
        // Handled: recall to the target, precision 0.9, some segments.
        let half = coverage(&[H], &[[10.0, 20.0, 110.0, 20.0]]);
        assert!(half.handled(Some(0.5)) && !half.handled(Some(0.6)));
        assert!(half.handled(None));
        let stray = [[10.0, 20.0, 210.0, 20.0], [10.0, 60.0, 40.0, 60.0]];
        let c = coverage(&[H], &stray);
        assert_eq!(c.recall, 1.0);
        assert!((c.precision - 200.0 / 230.0).abs() < 1e-9);
        assert!(!c.handled(Some(0.9)));
        let both = Coverage::pooled(&[half, c]);
        assert_eq!(both.segments, 3);
        assert!(
            (both.recall - (101.0 + 200.0) / 400.0).abs() < 1e-3,
            "{both:?}"
        );
    }
}
