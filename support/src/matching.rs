//! Segment matching: how the agreement tests, the goldens and the
//! differential fuzz target decide that two segment lists agree.

use aaglsd::Segment;

/// Largest endpoint distance between `a` and `b`, with `b` taken in whichever
/// orientation fits better.
pub fn endpoint_distance(a: &Segment, b: &Segment) -> f32 {
    let d = |x0: f32, y0: f32, x1: f32, y1: f32| ((x0 - x1).powi(2) + (y0 - y1).powi(2)).sqrt();
    let same = d(a.x0, a.y0, b.x0, b.y0).max(d(a.x1, a.y1, b.x1, b.y1));
    let swapped = d(a.x0, a.y0, b.x1, b.y1).max(d(a.x1, a.y1, b.x0, b.y0));
    same.min(swapped)
}

/// The segment of `have` nearest to `s` by [`endpoint_distance`], with
/// that distance.
pub fn nearest<'a>(s: &Segment, have: &'a [Segment]) -> Option<(&'a Segment, f32)> {
    have.iter()
        .map(|h| (h, endpoint_distance(s, h)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Of the segments of `wanted` with a partner in `have` within `tol` px
/// (both endpoints, [`nearest`]): how many ([`Attributes::pairs`]), how
/// many of those run the same way as their partner (the same polarity:
/// `(x0, y0)` nearer the partner's `(x0, y0)`), how many of them are exact
/// (both endpoints within 0.01 px), and how many of the exact ones have a
/// score within 1% (or 2) of the partner's: a score is a property of the
/// segment's pixels, so two segments that differ are not expected to
/// share it.
pub fn attributes_agree(wanted: &[Segment], have: &[Segment], tol: f32) -> Attributes {
    let mut a = Attributes::default();
    for w in wanted {
        let Some((h, d)) = nearest(w, have) else {
            continue;
        };
        if d > tol {
            continue;
        }
        a.pairs += 1;
        let dist = |x0: f32, y0: f32, x1: f32, y1: f32| (x0 - x1).hypot(y0 - y1);
        if dist(w.x0, w.y0, h.x0, h.y0) <= dist(w.x0, w.y0, h.x1, h.y1) {
            a.same_way += 1;
        }
        if d <= 0.01 {
            a.exact += 1;
            if (w.score - h.score).abs() <= (0.01 * w.score.abs().max(h.score.abs())).max(2.0) {
                a.same_score += 1;
            }
        }
    }
    a
}

/// What [`attributes_agree`] counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Attributes {
    /// Segments with a partner within the tolerance.
    pub pairs: usize,
    /// Of those, running the same way as their partner.
    pub same_way: usize,
    /// Of the pairs, those with both endpoints within 0.01 px.
    pub exact: usize,
    /// Of the exact pairs, those with a score within 1% (or 2).
    pub same_score: usize,
}

impl core::ops::AddAssign for Attributes {
    fn add_assign(&mut self, o: Self) {
        self.pairs += o.pairs;
        self.same_way += o.same_way;
        self.exact += o.exact;
        self.same_score += o.same_score;
    }
}

/// How many of `wanted` have a partner in `have` within `tol` px (both
/// endpoints), and how many match exactly (within 1e-3 px).
pub fn matched(wanted: &[Segment], have: &[Segment], tol: f32) -> (usize, usize) {
    let mut within = 0;
    let mut exact = 0;
    for w in wanted {
        let best = nearest(w, have).map_or(f32::INFINITY, |(_, d)| d);
        if best <= tol {
            within += 1;
        }
        if best <= 1e-3 {
            exact += 1;
        }
    }
    (within, exact)
}

/// How many of `wanted` have no partner in `have` within `tol` px.
pub fn unmatched(wanted: &[Segment], have: &[Segment], tol: f32) -> usize {
    wanted.len() - matched(wanted, have, tol).0
}

/// `segs` moved by `(dx, dy)`.
pub fn shifted(segs: &[Segment], dx: f32, dy: f32) -> Vec<Segment> {
    segs.iter()
        .map(|s| Segment {
            x0: s.x0 + dx,
            y0: s.y0 + dy,
            x1: s.x1 + dx,
            y1: s.y1 + dy,
            score: s.score,
        })
        .collect()
}

/// Two segment lists compared both ways, pooled over any number of images:
/// how many of each side have a partner on the other side within `tol`
/// px, and how many of side `a` within `exact_tol`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Agreement {
    /// Both endpoints within this many pixels: matched.
    pub tol: f32,
    /// Both endpoints within this many pixels: exact.
    pub exact_tol: f32,
    /// Segments on side `a`.
    pub a: usize,
    /// Segments on side `b`.
    pub b: usize,
    /// Segments of `a` matched by one of `b`.
    pub a_matched: usize,
    /// Segments of `b` matched by one of `a`.
    pub b_matched: usize,
    /// Segments of `a` matched exactly by one of `b`.
    pub a_exact: usize,
}

impl Agreement {
    /// Nothing compared yet.
    pub const fn new(tol: f32, exact_tol: f32) -> Self {
        Self {
            tol,
            exact_tol,
            a: 0,
            b: 0,
            a_matched: 0,
            b_matched: 0,
            a_exact: 0,
        }
    }

    /// Adds one image's lists; returns its own counts.
    pub fn add(&mut self, a: &[Segment], b: &[Segment]) -> Self {
        let one = Self {
            a: a.len(),
            b: b.len(),
            a_matched: matched(a, b, self.tol).0,
            b_matched: matched(b, a, self.tol).0,
            a_exact: matched(a, b, self.exact_tol).0,
            ..*self
        };
        self.a += one.a;
        self.b += one.b;
        self.a_matched += one.a_matched;
        self.b_matched += one.b_matched;
        self.a_exact += one.a_exact;
        one
    }

    /// Whether every segment of both sides is matched.
    pub const fn all_matched(&self) -> bool {
        self.a_matched == self.a && self.b_matched == self.b
    }

    /// Percent of `a` matched.
    pub fn a_percent(&self) -> f64 {
        percent(self.a_matched, self.a)
    }

    /// Percent of `b` matched.
    pub fn b_percent(&self) -> f64 {
        percent(self.b_matched, self.b)
    }

    /// Percent of `a` matched exactly.
    pub fn exact_percent(&self) -> f64 {
        percent(self.a_exact, self.a)
    }

    /// One line: the counts and rates, with the sides named.
    pub fn describe(&self, a: &str, b: &str) -> String {
        format!(
            "{a} {} {b} {}; {a} matched {}/{} = {:.2}%, {b} matched {}/{} = {:.2}% ({} px); exact ({} px) {:.2}%",
            self.a,
            self.b,
            self.a_matched,
            self.a,
            self.a_percent(),
            self.b_matched,
            self.b,
            self.b_percent(),
            self.tol,
            self.exact_tol,
            self.exact_percent()
        )
    }
}

/// `100 * part / whole`, and 0 for an empty whole.
pub fn percent(part: usize, whole: usize) -> f64 {
    100.0 * part as f64 / whole.max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    const fn seg(x0: f32, y0: f32, x1: f32, y1: f32) -> Segment {
        Segment {
            x0,
            y0,
            x1,
            y1,
            score: 0.0,
        }
    }

    #[test]
    fn distance_takes_the_better_orientation() {
        let a = seg(0.0, 0.0, 10.0, 0.0);
        assert_eq!(endpoint_distance(&a, &a.reversed()), 0.0);
        assert_eq!(endpoint_distance(&a, &seg(0.0, 3.0, 10.0, 4.0)), 4.0);
        assert_eq!(endpoint_distance(&a, &seg(10.0, 1.0, 0.0, 2.0)), 2.0);
    }

    #[test]
    fn matched_counts_within_and_exact() {
        let want = [seg(0.0, 0.0, 10.0, 0.0), seg(0.0, 5.0, 10.0, 5.0)];
        let have = [seg(0.0, 0.0, 10.0, 0.0), seg(0.0, 6.0, 10.0, 6.0)];
        assert_eq!(matched(&want, &have, 1.5), (2, 1));
        assert_eq!(matched(&want, &have, 0.5), (1, 1));
        assert_eq!(unmatched(&want, &have, 0.5), 1);
        assert_eq!(matched(&want, &[], 100.0), (0, 0));
        let moved = shifted(&want, 0.0, 1.0);
        assert_eq!(moved[0], seg(0.0, 1.0, 10.0, 1.0));
        assert_eq!(percent(1, 4), 25.0);
        assert_eq!(percent(0, 0), 0.0);
    }

    #[test]
    fn agreement_pools_both_ways() {
        let a = [seg(0.0, 0.0, 10.0, 0.0), seg(0.0, 5.0, 10.0, 5.0)];
        let b = [seg(0.0, 0.0, 10.0, 0.0)];
        let mut pooled = Agreement::new(1.0, 1e-3);
        let one = pooled.add(&a, &b);
        assert_eq!(
            (one.a, one.b, one.a_matched, one.b_matched, one.a_exact),
            (2, 1, 1, 1, 1)
        );
        assert!(!one.all_matched());
        pooled.add(&b, &b);
        assert_eq!((pooled.a, pooled.a_matched, pooled.b_matched), (3, 2, 2));
        assert_eq!(pooled.b_percent(), 100.0);
        assert!(pooled.describe("x", "y").contains("x matched 2/3 = 66.67%"));
    }
}
