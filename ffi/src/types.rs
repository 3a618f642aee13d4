//! The `#[repr(C)]` types of the C ABI and their conversions from and to
//! the core's types. Kept apart from the entry points (`capi.rs`) and free
//! of `no_mangle` functions, so that the WebAssembly crate includes the
//! same definitions (`wasm/src/lib.rs`) without exporting the C functions.

use core::ffi::CStr;
use core::mem::{align_of, offset_of, size_of};

use aaglsd::{Config, ConfigField, Error, Maxima, Reseed, Segment, Summary};

/// Result of every `aaglsd_*` function that can fail. `AAGLSD_STATUS_OK` is
/// 0; the values are stable. `aaglsd_status_str` names each one.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AaglsdStatus {
    /// Success.
    Ok = 0,
    /// Width or height is zero.
    ZeroDimension = 1,
    /// A side exceeds `AAGLSD_MAX_DIMENSION` or the pixel count exceeds
    /// `AAGLSD_MAX_PIXELS`.
    ImageTooLarge = 2,
    /// The row stride is smaller than the width.
    StrideTooSmall = 3,
    /// `pixels_len < stride * (height - 1) + width`.
    BufferTooShort = 4,
    /// `workspace_len` is below what `aaglsd_workspace_size` returns.
    WorkspaceTooSmall = 5,
    /// `out_capacity` is zero.
    OutputEmpty = 6,
    /// A configuration field is out of range or NaN; `aaglsd_config_validate`
    /// names the field.
    InvalidConfig = 7,
    /// A required pointer argument is NULL.
    NullPointer = 8,
    /// The output array is not aligned for `AaglsdSegment` (4 bytes).
    Misaligned = 9,
    /// Two of the pixel, workspace and output buffers overlap.
    BuffersOverlap = 10,
    /// An enumerated argument (e.g. a profile number) has no meaning.
    InvalidArgument = 11,
    /// An error of the Rust core that this version of the C API does not
    /// know (never returned while the two are built together).
    Unknown = 12,
}

/// Which `AaglsdConfig` field is out of range (`aaglsd_config_validate`).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AaglsdConfigField {
    /// No field: the configuration is valid.
    None = 0,
    /// `magnitude_threshold`
    MagnitudeThreshold = 1,
    /// `anchor_margin`
    AnchorMargin = 2,
    /// `align_tolerance_deg`
    AlignTolerance = 3,
    /// `dist_tolerance_px`
    DistTolerance = 4,
    /// `skip_min`, `skip_regular` or `skip_group`
    SkipSteps = 5,
    /// `min_length_px`
    MinLength = 6,
    /// `min_groups`
    MinGroups = 7,
    /// `anchor_density`
    AnchorDensity = 8,
    /// `aligned_density`
    AlignedDensity = 9,
    /// `merge_center_px`
    MergeCenter = 10,
    /// `merge_angle_deg`
    MergeAngle = 11,
    /// `merge_gap_px`
    MergeGap = 12,
    /// `candidates_per_mille`
    CandidateCapacity = 13,
    /// `max_link_pixels`
    LinkCapacity = 14,
    /// `extend_max_px`
    ExtendMax = 15,
    /// `work_per_mille`
    WorkLimit = 16,
    /// `bridge_px`
    BridgeMax = 17,
    /// `min_score`
    MinScore = 18,
    /// A field the Rust core reports but this version of the C API does not
    /// know (never returned while the two are built together).
    Unknown = 255,
}

/// Named parameter sets for `aaglsd_config_profile`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AaglsdProfile {
    /// `Config::DEFAULT`: the official thresholds with endpoint extension, merging and
    /// one round of reseeding for the groups of misfit lines.
    Default = 0,
    /// `Config::OFFICIAL`: the thresholds of the authors' released code.
    Official = 1,
    /// `Config::PAPER`: the paper's values, with merging (paper §3.3).
    Paper = 2,
}

/// Detector parameters: a field-by-field mirror of `aaglsd::Config` (see
/// its documentation for each meaning and range). Fill it with
/// `aaglsd_config_default` or `aaglsd_config_profile`, then change fields.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AaglsdConfig {
    /// T_mag, L1 gradient levels, 0..=1020.
    pub magnitude_threshold: f32,
    /// T_anchor, L1 gradient levels, 0..=1020.
    pub anchor_margin: u16,
    /// T_aligned, degrees, (0, 90).
    pub align_tolerance_deg: f32,
    /// T_dist, pixels, (0, 64].
    pub dist_tolerance_px: f32,
    /// S_min, gap steps, 1..=255.
    pub skip_min: u8,
    /// S_ra, gap steps, 1..=255.
    pub skip_regular: u8,
    /// S_aag, gap steps, 1..=255.
    pub skip_group: u8,
    /// T_len, pixels, 0..=65536.
    pub min_length_px: f32,
    /// N_aag, 1..=255.
    pub min_groups: u8,
    /// rho1, 0..=1.
    pub anchor_density: f32,
    /// rho2, 0..=1.
    pub aligned_density: f32,
    /// The least score of a reported segment, 0..=16777215 (0 = every
    /// segment).
    pub min_score: u32,
    /// Endpoint extension limit, pixels, 0..=1024 (0 = off).
    pub extend_max_px: u16,
    /// Whether groups released by a weak linking may seed again
    /// (`aaglsd::Reseed`): 0 = never, 2 = once, 3 = misfit (the default), any other
    /// value = always (the authors' code; 1 as `Reseed::Always`).
    pub reseed: u8,
    /// How the anchors' maximum tests treat profiles symmetric about a
    /// pixel (`aaglsd::Maxima`): 1 = symmetric (the default), any other
    /// value = strict (the authors' code; 0 as `Maxima::Strict`).
    pub maxima: u8,
    /// Bridging along a linking's line, pixels, 0..=32 (0 = off).
    pub bridge_px: u8,
    /// Paper §3.3 merging: 0 = off, any other value = on.
    pub merge: u8,
    /// Keep the longest part of a linking that fails rho2 (design §8.2):
    /// 0 = off, any other value = on.
    pub trim: u8,
    /// D_c, pixels, (0, 64].
    pub merge_center_px: f32,
    /// D_a, degrees, (0, 90).
    pub merge_angle_deg: f32,
    /// D_e, pixels, 0..=4096.
    pub merge_gap_px: f32,
    /// Group-candidate capacity per 1000 pixels, 1..=1000.
    pub candidates_per_mille: u16,
    /// Visited-list capacity per linking, pixels, 16..=65535.
    pub max_link_pixels: u32,
    /// The frame's work limit, work units per 1000 pixels, 1..=100000.
    pub work_per_mille: u32,
    /// A hard cap on the frame's work units; 0 = none.
    pub work_budget: u32,
}

/// A detected segment in 0-based pixel-centre coordinates (pixel (col, row)
/// is centred at x = col, y = row). Same layout as `aaglsd::Segment`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AaglsdSegment {
    /// First endpoint, x (column).
    pub x0: f32,
    /// First endpoint, y (row).
    pub y0: f32,
    /// Second endpoint, x (column).
    pub x1: f32,
    /// Second endpoint, y (row).
    pub y1: f32,
    /// The score: the gradient contrast integrated along the segment
    /// (higher: likelier a true line). The brighter side lies on the left
    /// of (x0, y0) -> (x1, y1) as displayed (x right, y down).
    pub score: f32,
}

// The output array is handed to the core as `[aaglsd::Segment]`.
const _: () = {
    assert!(size_of::<AaglsdSegment>() == size_of::<Segment>());
    assert!(align_of::<AaglsdSegment>() == align_of::<Segment>());
    assert!(offset_of!(AaglsdSegment, x0) == offset_of!(Segment, x0));
    assert!(offset_of!(AaglsdSegment, y0) == offset_of!(Segment, y0));
    assert!(offset_of!(AaglsdSegment, x1) == offset_of!(Segment, x1));
    assert!(offset_of!(AaglsdSegment, y1) == offset_of!(Segment, y1));
    assert!(offset_of!(AaglsdSegment, score) == offset_of!(Segment, score));
};

/// What an `aaglsd_detect` call did: a mirror of `aaglsd::Summary`.
/// Zeroed when the call fails.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AaglsdSummary {
    /// Segments written to the front of the output array.
    pub segments: usize,
    /// Segments found but not written because the output array was full.
    pub dropped_segments: usize,
    /// Group candidates dropped because the candidate list was full.
    pub dropped_candidates: usize,
    /// Linkings stopped early because the visited list was full.
    pub truncated_linkings: usize,
    /// Group candidates kept for extraction.
    pub candidates: usize,
    /// Aligned anchor groups extracted.
    pub groups: usize,
    /// Segments removed by merging (0 when merging is off).
    pub merged: usize,
    /// Work units spent by the linking, validation, extension and merging.
    pub work: usize,
    /// Seeds and segment pairs left unprocessed at the work limit or budget.
    pub work_cut: usize,
}

/// `From` both ways between `Config` and `AaglsdConfig`, for the fields
/// listed once here (the same name and type on both sides), the flags (a
/// `bool` in Rust, a `uint8_t` in C), `reseed` and `maxima` (a [`Reseed`]
/// and a [`Maxima`] in Rust, `uint8_t`s in C). Both sides are
/// destructured, so that a field added to either one fails to compile
/// here.
macro_rules! config_conversions {
    ($($field:ident),* $(,)?; $($flag:ident),* $(,)?) => {
        impl From<&Config> for AaglsdConfig {
            fn from(c: &Config) -> Self {
                let Config { $($field,)* $($flag,)* reseed, maxima } = *c;
                Self {
                    $($field,)*
                    $($flag: u8::from($flag),)*
                    reseed: reseed.code(),
                    maxima: maxima.code(),
                }
            }
        }

        impl From<&AaglsdConfig> for Config {
            fn from(c: &AaglsdConfig) -> Self {
                let AaglsdConfig { $($field,)* $($flag,)* reseed, maxima } = *c;
                // Every byte means something: before `Once` existed, any
                // nonzero byte meant "yes"; an unknown byte is the
                // authors' behaviour.
                let reseed = Reseed::from_code(reseed).unwrap_or(Reseed::Always);
                let maxima = Maxima::from_code(maxima).unwrap_or(Maxima::Strict);
                Self { $($field,)* $($flag: $flag != 0,)* reseed, maxima }
            }
        }
    };
}

config_conversions!(
    magnitude_threshold,
    anchor_margin,
    align_tolerance_deg,
    dist_tolerance_px,
    skip_min,
    skip_regular,
    skip_group,
    min_length_px,
    min_groups,
    anchor_density,
    aligned_density,
    min_score,
    extend_max_px,
    bridge_px,
    merge_center_px,
    merge_angle_deg,
    merge_gap_px,
    candidates_per_mille,
    max_link_pixels,
    work_per_mille,
    work_budget;
    merge,
    trim,
);

/// `AaglsdSummary`'s fields, in order: the struct, its `From<Summary>` and
/// [`AaglsdSummary::values`] from one list.
macro_rules! summary_fields {
    ($($field:ident),* $(,)?) => {
        impl From<Summary> for AaglsdSummary {
            fn from(s: Summary) -> Self {
                // `Summary` is non-exhaustive; `every_summary_field_is_mirrored`
                // catches a counter missing here.
                let Summary { $($field,)* .. } = s;
                Self { $($field,)* }
            }
        }

        impl AaglsdSummary {
            /// The fields in declaration order (the `#[repr(C)]` layout).
            pub fn values(&self) -> [usize; 9] {
                [$(self.$field,)*]
            }
        }
    };
}

summary_fields!(
    segments,
    dropped_segments,
    dropped_candidates,
    truncated_linkings,
    candidates,
    groups,
    merged,
    work,
    work_cut,
);

impl AaglsdStatus {
    /// Every status and its `aaglsd_status_str` text.
    pub(crate) const TEXT: [(Self, &'static CStr); 13] = [
        (Self::Ok, c"ok"),
        (Self::ZeroDimension, c"image width or height is zero"),
        (Self::ImageTooLarge, c"image dimensions exceed the limits"),
        (
            Self::StrideTooSmall,
            c"row stride is smaller than the width",
        ),
        (Self::BufferTooShort, c"pixel buffer is too short"),
        (Self::WorkspaceTooSmall, c"workspace is too small"),
        (Self::OutputEmpty, c"output array has no capacity"),
        (
            Self::InvalidConfig,
            c"a configuration field is out of range",
        ),
        (Self::NullPointer, c"a required pointer is NULL"),
        (Self::Misaligned, c"output array is not 4-byte aligned"),
        (
            Self::BuffersOverlap,
            c"pixel, workspace and output buffers overlap",
        ),
        (Self::InvalidArgument, c"invalid enumerated argument"),
        (Self::Unknown, c"unknown error of the core library"),
    ];

    /// The statuses from `ZeroDimension` to `InvalidConfig` mirror the core's
    /// error kinds: their values are the core's [`Error::code`]
    /// (`status_values_are_the_core_codes`); the later ones are the C
    /// API's own.
    const fn mirrors_core(self) -> bool {
        let v = self as i32;
        v >= Self::ZeroDimension as i32 && v <= Self::InvalidConfig as i32
    }
}

impl From<Error> for AaglsdStatus {
    fn from(e: Error) -> Self {
        Self::by_value(e.code())
            .map(|(s, _)| s)
            .filter(|s| s.mirrors_core())
            .unwrap_or(Self::Unknown)
    }
}

impl AaglsdConfigField {
    /// Every value and its `aaglsd_config_field_str` text. The fields (all
    /// but `None` and `Unknown`) have the core's [`ConfigField::code`] as
    /// value (`status_values_are_the_core_codes`).
    pub(crate) const TEXT: [(Self, &'static CStr); 20] = [
        (Self::None, c"none"),
        (Self::MagnitudeThreshold, c"magnitude_threshold"),
        (Self::AnchorMargin, c"anchor_margin"),
        (Self::AlignTolerance, c"align_tolerance_deg"),
        (Self::DistTolerance, c"dist_tolerance_px"),
        (Self::SkipSteps, c"skip_min/skip_regular/skip_group"),
        (Self::MinLength, c"min_length_px"),
        (Self::MinGroups, c"min_groups"),
        (Self::AnchorDensity, c"anchor_density"),
        (Self::AlignedDensity, c"aligned_density"),
        (Self::MergeCenter, c"merge_center_px"),
        (Self::MergeAngle, c"merge_angle_deg"),
        (Self::MergeGap, c"merge_gap_px"),
        (Self::CandidateCapacity, c"candidates_per_mille"),
        (Self::LinkCapacity, c"max_link_pixels"),
        (Self::ExtendMax, c"extend_max_px"),
        (Self::WorkLimit, c"work_per_mille"),
        (Self::BridgeMax, c"bridge_px"),
        (Self::MinScore, c"min_score"),
        (Self::Unknown, c"unknown field"),
    ];
}

impl From<ConfigField> for AaglsdConfigField {
    fn from(f: ConfigField) -> Self {
        Self::by_value(f.code())
            .map(|(c, _)| c)
            .filter(|c| !matches!(c, Self::None | Self::Unknown))
            .unwrap_or(Self::Unknown)
    }
}

/// `by_value` for the enums with a `TEXT` table.
macro_rules! by_value {
    ($($enum:ident),*) => {$(
        impl $enum {
            /// The variant whose C value is `value`, with its text from
            /// `TEXT`; `None` for a value no variant has.
            pub(crate) fn by_value(value: i32) -> Option<(Self, &'static CStr)> {
                Self::TEXT.into_iter().find(|&(v, _)| v as i32 == value)
            }
        }
    )*};
}

by_value!(AaglsdStatus, AaglsdConfigField);
