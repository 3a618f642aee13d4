//! Detector parameters in natural units, with the two named profiles.
//!
//! Every field maps to a symbol of the paper (Li & Shu, PRCV 2025, paper §3) or to
//! a constant of the authors' released code; [`Config::validate`] checks the
//! documented ranges. The fixed-point core converts a validated `Config` once,
//! at the top of [`detect`](crate::detect()), into integer thresholds (binary
//! angles, Q-format distances); nothing downstream touches a float field.

use crate::error::{ConfigField, Error};

/// Detector parameters. Start from a profile ([`Config::DEFAULT`],
/// [`Config::OFFICIAL`], [`Config::PAPER`]) and change fields as needed.
///
/// ```
/// let mut cfg = aaglsd::Config::DEFAULT;
/// cfg.min_length_px = 20.0; // only long segments
/// assert!(cfg.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Config {
    /// T_mag: L1 gradient magnitudes (`|gx| + |gy|` of the unnormalised 2x2
    /// mask, 0..=1020) below this are set to zero. Range 0..=1020; 5.22.
    pub magnitude_threshold: f32,
    /// T_anchor: an aligned-anchor-group centre must exceed the strongest
    /// across-edge neighbour of at least one side by this many L1 levels.
    /// Range 0..=1020; 3.
    pub anchor_margin: u16,
    /// T_aligned: tolerance between level-line / line directions, in degrees.
    /// Used by the group test (eq. 3), the group-link test, and the aligned
    /// density. Range (0, 90); 22.5.
    pub align_tolerance_deg: f32,
    /// T_dist: linking stops at a pixel farther than this from the current
    /// fitted line, in pixels. Range (0, 64]; 1.5.
    pub dist_tolerance_px: f32,
    /// S_min: gap steps allowed when a linking pass starts. Range 1..=255; 7.
    pub skip_min: u8,
    /// S_ra: gap steps allowed after a regular anchor. Range 1..=255; 7.
    pub skip_regular: u8,
    /// S_aag: gap steps allowed after an aligned anchor group. Range 1..=255; 7.
    pub skip_group: u8,
    /// T_len: shorter segments are discarded, in pixels. Range 0..=65536.
    pub min_length_px: f32,
    /// N_aag: a segment must contain at least this many aligned anchor
    /// groups, counting its seed (fewer makes it a weak candidate, whose
    /// links are released). Range 1..=255.
    pub min_groups: u8,
    /// ρ1: minimum fraction of the segment's raster pixels that are anchors
    /// (discarded below). Range 0..=1.
    pub anchor_density: f32,
    /// ρ2: minimum fraction of raster pixels whose gradient is within
    /// `align_tolerance_deg` of the segment normal (weak below). Range 0..=1.
    pub aligned_density: f32,
    /// The least score (design §8.1) of a reported segment: a segment that
    /// passes validation with a lower score is left out of the output (its
    /// groups stay linked, as a strong segment's). Not in the paper or the
    /// authors' code: 0 in `OFFICIAL` and `PAPER` keeps every segment.
    /// Scores sum the gradient across the segment over its pixels, so the
    /// floor drops short, faint segments first: 150 in `DEFAULT` (why this
    /// value: design §8.1).
    /// Range 0..=16,777,215 (the highest score, 2^24 − 1).
    pub min_score: u32,
    /// Whether the groups that a weak linking released may seed a linking
    /// of their own later (paper §3.3 and the authors' code: they may,
    /// [`Reseed::Always`]). Released groups can always still be linked into
    /// another seed's segment. `DEFAULT` uses [`Reseed::Misfit`]: along a
    /// long textured edge each released group otherwise walks the same
    /// pixels again, mostly for the same weak verdict. One round of
    /// reseeding ([`Reseed::Once`]) finds over half of what the unlimited
    /// rule finds at half its cost; of that round, the groups released by a
    /// linking with too few groups almost never seed a strong segment, and
    /// `Misfit` skips them (`docs/performance.md`).
    pub reseed: Reseed,
    /// Endpoint extension (design §8; not in the paper or the authors'
    /// code): each end of a strong segment moves along its line, one pixel of
    /// its major axis at a time, while the pixel under the line has a
    /// nonzero magnitude and a gradient within `align_tolerance_deg` of the
    /// segment normal (the aligned-density test), for at most this many
    /// pixels. The walk stops at its last anchor, short of where the edge
    /// ends. 0 disables it. Range 0..=1024.
    pub extend_max_px: u16,
    /// How the maximum tests of the anchors treat the profiles that are
    /// symmetric about a pixel (design §4-5): [`Maxima::Strict`] in the
    /// authors' code, where an edge centred on a pixel (anti-aliased
    /// graphics, symmetric blurs) and the inside of a 2-px line have no
    /// anchors; [`Maxima::Symmetric`] in `DEFAULT` and `PAPER`.
    pub maxima: Maxima,
    /// Bridging (design §7.5; the paper's search for an aligned group
    /// along the line, which the authors' code reduces to one pixel): when
    /// a linking pass ends, it looks up to this many pixels further along
    /// its line for a group aligned with it, links it and goes on; the
    /// bridged pixels are left out of the segment's densities. Walks then
    /// cross the junctions of checkerboards, tables and grids. 0 disables
    /// it. Range 0..=32; 6 in `DEFAULT`.
    pub bridge_px: u8,
    /// Paper §3.3: merge duplicate and collinear fragments (eqs. 6-7).
    pub merge: bool,
    /// A linking that fails the aligned density ρ2 keeps its longest part
    /// that passes it, between two aligned pixels, when that part holds
    /// `min_groups` groups and passes validation on its own (design §8.2;
    /// not in the paper or the authors' code, where the whole linking is
    /// weak). A walk that runs past the end of its line (a pane's edge
    /// across a window's muntin, a wall's edge across a pole) then keeps
    /// the line. Its other groups are released. `true` in `DEFAULT`.
    pub trim: bool,
    /// D_c: maximum perpendicular centre distance for merging, in pixels.
    /// Range (0, 64]; 1.5.
    pub merge_center_px: f32,
    /// D_a: maximum angle between merged segments, in degrees. Range (0, 90); 5.
    pub merge_angle_deg: f32,
    /// D_e: maximum endpoint gap between non-overlapping merged segments, in
    /// pixels. Range 0..=4096; 9.
    pub merge_gap_px: f32,
    /// Capacity of the group-candidate list, in candidates per 1000 pixels.
    /// Candidates beyond it (the weakest) are dropped and counted in
    /// [`Summary::dropped_candidates`](crate::Summary::dropped_candidates),
    /// as are groups beyond half of it. Range 1..=1000; 100 (the most seen
    /// on the 63 test images is 87, 94 on the firmware's dense 320x240
    /// castle crop and on York Urban with noise of σ 8). Costs 5 bytes per
    /// candidate of workspace.
    pub candidates_per_mille: u16,
    /// Capacity of the per-linking visited list, in pixels. A linking that
    /// visits more stops early and is counted in
    /// [`Summary::truncated_linkings`](crate::Summary::truncated_linkings).
    /// Range 16..=65_535 (the line fit's exact `i64` sums are proven for at
    /// most 2^16 points); 1024 (the longest linking on the 63 test images
    /// visits 604 pixels). Costs about 16/3 bytes per entry (with the undo
    /// list).
    pub max_link_pixels: u32,
    /// The frame's work limit, in work units per 1000 pixels: the linking,
    /// the validation, the endpoint extension and the merging stop when it
    /// is spent (design §13.1). One unit is one pixel visited by a walk, one
    /// pixel of a validated or extended segment, or one pair of segments
    /// compared by the merging. It bounds the worst case whatever the
    /// content: natural images use far less (the 51 York Urban images
    /// at most 0.87 units per pixel with the default profile, median 0.45).
    /// A unit costs at most about 900 x86-64 instructions (the README's
    /// worst-case table). Range 1..=100_000; 2000.
    pub work_per_mille: u32,
    /// A hard cap on the same work units for the whole frame, for callers
    /// with a deadline; 0 for none. Detection stops gracefully when it is
    /// reached (the seeds not linked yet are skipped, the merging ends) and
    /// [`Summary::work_cut`](crate::Summary::work_cut) counts what was cut.
    pub work_budget: u32,
}

/// What the aligned anchor groups that a weak linking released may do
/// later ([`Config::reseed`]). A linking is weak when its segment has too few
/// groups or too few aligned pixels; the groups it linked on the normal route
/// are then released, free to be linked again.
///
/// ```
/// use aaglsd::{Config, Reseed};
/// let cfg = Config { reseed: Reseed::Never, ..Config::DEFAULT }; // fastest
/// assert!(cfg.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum Reseed {
    /// They never seed a linking of their own.
    Never = 0,
    /// They may seed one when their turn comes, and so may the groups that
    /// such a linking releases, without limit (the authors' code).
    Always = 1,
    /// They may seed one when their turn comes; the groups that a weak
    /// linking *from a released seed* releases may not. Each group gets one
    /// second chance, not a chain of them.
    Once = 2,
    /// As [`Reseed::Once`], but only the groups released by a linking that
    /// had enough groups and failed on its aligned density (a line that
    /// does not fit them) get the second chance. A linking with too few
    /// groups has already walked their line and found too few groups along
    /// it: their own linkings would walk it again for the same verdict.
    /// Such a linking, never strong, also releases its groups without
    /// tracing its segment for the anchor density (which otherwise decides
    /// whether they stay linked), so they can still be linked into another
    /// seed's segment.
    Misfit = 3,
}

/// How the anchors' maximum tests treat profiles symmetric about a pixel
/// ([`Config::maxima`]).
///
/// An edge whose profile is symmetric about a pixel centre (an
/// anti-aliased render, half the edges of a checkerboard, a symmetric
/// blur) gives two pixels of exactly equal gradient magnitude across it:
/// the 2x2 gradient samples the edge half a pixel to each side. A dark or
/// light line 2 px wide gives a pixel of zero gradient between its edges.
///
/// ```
/// use aaglsd::{Config, Maxima};
/// assert_eq!(Config::DEFAULT.maxima, Maxima::Symmetric);
/// assert_eq!(Config::OFFICIAL.maxima, Maxima::Strict); // the authors' code
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum Maxima {
    /// The authors' code: a maximum must exceed every neighbour it is
    /// compared with, and a group centre needs a nonzero neighbour on each
    /// side. Of two equal pixels across an edge neither is a maximum, so an
    /// edge centred on a pixel has no anchors, nor has either edge of a
    /// 2-px line.
    Strict = 0,
    /// Equal pixels are resolved (design §5): the regular anchor is the
    /// left one of the two (an edge closer to vertical) or the upper one
    /// (closer to horizontal); the group centre is the one nearer the
    /// profile's peak (the left or upper one when the profile is
    /// symmetric), and a plateau on a rising slope has none. A group
    /// centre's side may be all zero when it is the inside of a thin line
    /// (the edge beyond it has the opposite polarity).
    Symmetric = 1,
}

impl Maxima {
    /// The C ABI's byte: 0 strict, 1 symmetric.
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The variant of a [`Maxima::code`], or `None` for another byte.
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            0 => Some(Self::Strict),
            1 => Some(Self::Symmetric),
            _ => None,
        }
    }
}

impl Reseed {
    /// The C ABI's byte: 0 never, 1 always, 2 once, 3 misfit.
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// Whether a group not linked yet may seed: one never released always
    /// may; a released one by the rule, a retired one (released by a weak
    /// linking from a released seed) only under [`Reseed::Always`]. The
    /// core and the float reference share this.
    pub(crate) const fn permits(self, released: bool, retired: bool) -> bool {
        !released
            || match self {
                Self::Never => false,
                Self::Always => true,
                Self::Once | Self::Misfit => !retired,
            }
    }

    /// Whether a linking with too few groups, never strong, is weak
    /// without a trace of its segment: under [`Reseed::Misfit`]. Under the
    /// other rules the trace decides, as in the authors' code, between weak
    /// (its groups released) and discarded (they stay linked). The core and
    /// the float reference share this.
    pub(crate) const fn skips_trace_of_few(self) -> bool {
        matches!(self, Self::Misfit)
    }

    /// Whether a weak linking retires the groups it releases (see
    /// [`Reseed::permits`]): always when its own seed had been released,
    /// and under [`Reseed::Misfit`] also when it linked too few groups
    /// (`few_groups`). The core and the float reference share this.
    pub(crate) const fn retires(self, seed_released: bool, few_groups: bool) -> bool {
        seed_released || (few_groups && matches!(self, Self::Misfit))
    }

    /// The variant of a [`Reseed::code`], or `None` for another byte.
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            0 => Some(Self::Never),
            1 => Some(Self::Always),
            2 => Some(Self::Once),
            3 => Some(Self::Misfit),
            _ => None,
        }
    }
}

impl Config {
    /// The thresholds of the authors' released C++ code: T_len 5, ρ1 0.5,
    /// ρ2 0.9, at least 3 group links (4 groups with the seed), no merging.
    pub const OFFICIAL: Self = Self {
        magnitude_threshold: 5.22,
        anchor_margin: 3,
        align_tolerance_deg: 22.5,
        dist_tolerance_px: 1.5,
        skip_min: 7,
        skip_regular: 7,
        skip_group: 7,
        min_length_px: 5.0,
        min_groups: 4,
        anchor_density: 0.5,
        aligned_density: 0.9,
        min_score: 0,
        reseed: Reseed::Always,
        extend_max_px: 0,
        maxima: Maxima::Strict,
        bridge_px: 0,
        merge: false,
        trim: false,
        merge_center_px: 1.5,
        merge_angle_deg: 5.0,
        merge_gap_px: 9.0,
        candidates_per_mille: 100,
        max_link_pixels: 1024,
        work_per_mille: 2000,
        work_budget: 0,
    };

    /// The paper's values (paper §3.3 and paper §4): T_len 9, N_aag 3, ρ1 = ρ2 = 0.5, and
    /// merging with D_c 1.5 px, D_a π/36 (5°), D_e 9 px; profiles symmetric
    /// about a pixel keep their anchors ([`Maxima::Symmetric`]: the paper's
    /// maxima are undefined there).
    pub const PAPER: Self = Self {
        min_length_px: 9.0,
        min_groups: 3,
        anchor_density: 0.5,
        aligned_density: 0.5,
        maxima: Maxima::Symmetric,
        merge: true,
        ..Self::OFFICIAL
    };

    /// The default profile: the authors' thresholds ([`Config::OFFICIAL`])
    /// with the endpoint extension (up to 64 px per end), the paper's
    /// merging (D_c 1.5 px, D_a 5°, D_e 9 px) and one round of reseeding
    /// for the groups of misfit lines ([`Reseed::Misfit`]), anchors on
    /// profiles symmetric about a pixel ([`Maxima::Symmetric`]), walks
    /// bridging up to 6 px ([`Config::bridge_px`]), the longest passing part
    /// of a linking that fails ρ2 ([`Config::trim`]) and segments scoring at
    /// least 150 ([`Config::min_score`]). More accurate and steadier than
    /// either profile (the README's accuracy and stability tables).
    pub const DEFAULT: Self = Self {
        extend_max_px: 64,
        min_score: 150,
        maxima: Maxima::Symmetric,
        bridge_px: 6,
        merge: true,
        trim: true,
        reseed: Reseed::Misfit,
        ..Self::OFFICIAL
    };

    /// Checks every field against its documented range (NaN is out of range).
    ///
    /// # Errors
    /// [`Error::InvalidConfig`] naming the first offending field.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |f| Err(Error::InvalidConfig(f));
        let within = |v: f32, lo: f32, hi: f32| v >= lo && v <= hi; // false for NaN
        if !within(self.magnitude_threshold, 0.0, 1020.0) {
            return bad(ConfigField::MagnitudeThreshold);
        }
        if self.anchor_margin > 1020 {
            return bad(ConfigField::AnchorMargin);
        }
        if !(self.align_tolerance_deg > 0.0 && self.align_tolerance_deg < 90.0) {
            return bad(ConfigField::AlignTolerance);
        }
        if !(self.dist_tolerance_px > 0.0 && self.dist_tolerance_px <= 64.0) {
            return bad(ConfigField::DistTolerance);
        }
        if self.skip_min == 0 || self.skip_regular == 0 || self.skip_group == 0 {
            return bad(ConfigField::SkipSteps);
        }
        if !within(self.min_length_px, 0.0, 65536.0) {
            return bad(ConfigField::MinLength);
        }
        if self.min_groups == 0 {
            return bad(ConfigField::MinGroups);
        }
        if !within(self.anchor_density, 0.0, 1.0) {
            return bad(ConfigField::AnchorDensity);
        }
        if !within(self.aligned_density, 0.0, 1.0) {
            return bad(ConfigField::AlignedDensity);
        }
        if self.min_score > (1 << 24) - 1 {
            return bad(ConfigField::MinScore);
        }
        if self.extend_max_px > 1024 {
            return bad(ConfigField::ExtendMax);
        }
        if self.bridge_px > 32 {
            return bad(ConfigField::BridgeMax);
        }
        if !(self.merge_center_px > 0.0 && self.merge_center_px <= 64.0) {
            return bad(ConfigField::MergeCenter);
        }
        if !(self.merge_angle_deg > 0.0 && self.merge_angle_deg < 90.0) {
            return bad(ConfigField::MergeAngle);
        }
        if !within(self.merge_gap_px, 0.0, 4096.0) {
            return bad(ConfigField::MergeGap);
        }
        if self.candidates_per_mille == 0 || self.candidates_per_mille > 1000 {
            return bad(ConfigField::CandidateCapacity);
        }
        if self.max_link_pixels < 16 || self.max_link_pixels > 65_535 {
            return bad(ConfigField::LinkCapacity);
        }
        if self.work_per_mille == 0 || self.work_per_mille > 100_000 {
            return bad(ConfigField::WorkLimit);
        }
        Ok(())
    }
}

/// The named parameter sets, as a value: for interfaces that pick a profile
/// by number or by name (the C ABI, the WASM exports, command lines).
///
/// ```
/// use aaglsd::{Config, Profile};
/// assert_eq!(Profile::from_name("paper"), Some(Profile::Paper));
/// assert_eq!(Profile::Paper.config(), Config::PAPER);
/// assert_eq!(Profile::from_code(Profile::Official.code()), Some(Profile::Official));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Profile {
    /// [`Config::DEFAULT`].
    Default,
    /// [`Config::OFFICIAL`].
    Official,
    /// [`Config::PAPER`].
    Paper,
}

impl Profile {
    /// Every profile, in [`Profile::code`] order.
    pub const ALL: [Self; 3] = [Self::Default, Self::Official, Self::Paper];

    /// The profile's parameters.
    pub const fn config(self) -> Config {
        match self {
            Self::Default => Config::DEFAULT,
            Self::Official => Config::OFFICIAL,
            Self::Paper => Config::PAPER,
        }
    }

    /// A stable number: 0 default, 1 official, 2 paper (the values of
    /// `AaglsdProfile` in the C header).
    pub const fn code(self) -> u32 {
        match self {
            Self::Default => 0,
            Self::Official => 1,
            Self::Paper => 2,
        }
    }

    /// The profile of a [`Profile::code`], or `None` for an unknown number.
    pub const fn from_code(code: u32) -> Option<Self> {
        match code {
            0 => Some(Self::Default),
            1 => Some(Self::Official),
            2 => Some(Self::Paper),
            _ => None,
        }
    }

    /// The lower-case name: `"default"`, `"official"` or `"paper"`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Default => "default",
            Self::Official => "official",
            Self::Paper => "paper",
        }
    }

    /// The profile of a [`Profile::name`], or `None`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

impl Default for Config {
    fn default() -> Self {
        Self::DEFAULT
    }
}
