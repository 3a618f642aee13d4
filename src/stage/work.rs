//! The per-frame work limit (design §13.1).
//!
//! One work unit is a pixel the walk visits, a Bresenham pixel the
//! validation traces, a pixel the extension tests, or a pair the merging
//! compares. The limit is settled between units of bounded size: a linking
//! starts only while units remain (and then runs to its end, so the spend
//! can exceed the limit by one linking), and each merge comparison is
//! paid before it is made. What the limit prevents is counted in `cut`.

/// Work spent and the limit it may reach.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Work {
    pub spent: u64,
    pub limit: u64,
    /// Seeds not linked and merge candidates not compared for want of work.
    pub cut: usize,
}

impl Work {
    /// The limit for a `pixels`-pixel frame: `pixels · per_mille / 1000`,
    /// and at most `budget` when that is nonzero.
    pub fn new(pixels: usize, per_mille: u32, budget: u32) -> Self {
        let by_size = (pixels as u64).saturating_mul(u64::from(per_mille)) / 1000;
        let limit = if budget == 0 {
            by_size
        } else {
            by_size.min(u64::from(budget))
        };
        Self {
            spent: 0,
            limit,
            cut: 0,
        }
    }

    /// Whether any unit remains.
    #[inline]
    pub fn left(&self) -> bool {
        self.spent < self.limit
    }

    #[cfg_attr(not(aaglsd_small), inline)]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn spend(&mut self, units: usize) {
        self.spent = self.spent.saturating_add(units as u64);
    }
}
