//! The text of one detection, as the firmware prints it: one line per
//! segment, then a `summary ...` line. `host-tools detect` includes this
//! file, so the host's and the firmware's outputs come from the same code
//! and `run.sh` can diff them for bit-exactness.

use core::fmt;

use aaglsd::{Segment, Summary};

/// `x0 y0 x1 y1 score` (shortest round-trip decimal), then the five `f32`
/// bit patterns in hex.
pub struct SegmentLine<'a>(pub &'a Segment);

impl fmt::Display for SegmentLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.0;
        let v = [s.x0, s.y0, s.x1, s.y1, s.score];
        for x in v {
            write!(f, "{x} ")?;
        }
        let [a, b, c, d, e] = v.map(f32::to_bits);
        write!(f, "{a:08x} {b:08x} {c:08x} {d:08x} {e:08x}")
    }
}

/// `summary segments=N dropped_segments=N ...`: every `Summary` field.
pub struct SummaryLine<'a>(pub &'a Summary);

impl fmt::Display for SummaryLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.0;
        write!(
            f,
            "summary segments={} dropped_segments={} dropped_candidates={} truncated_linkings={} candidates={} groups={} merged={}",
            s.segments,
            s.dropped_segments,
            s.dropped_candidates,
            s.truncated_linkings,
            s.candidates,
            s.groups,
            s.merged
        )
    }
}
