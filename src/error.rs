//! Errors: `Copy`, numbers not strings, one variant per failed check.

use core::fmt;

/// Which [`Config`](crate::Config) field is out of range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ConfigField {
    /// [`Config::magnitude_threshold`](crate::Config::magnitude_threshold)
    MagnitudeThreshold,
    /// [`Config::anchor_margin`](crate::Config::anchor_margin)
    AnchorMargin,
    /// [`Config::align_tolerance_deg`](crate::Config::align_tolerance_deg)
    AlignTolerance,
    /// [`Config::dist_tolerance_px`](crate::Config::dist_tolerance_px)
    DistTolerance,
    /// [`Config::skip_min`](crate::Config::skip_min),
    /// [`Config::skip_regular`](crate::Config::skip_regular) or
    /// [`Config::skip_group`](crate::Config::skip_group)
    SkipSteps,
    /// [`Config::min_length_px`](crate::Config::min_length_px)
    MinLength,
    /// [`Config::min_groups`](crate::Config::min_groups)
    MinGroups,
    /// [`Config::anchor_density`](crate::Config::anchor_density)
    AnchorDensity,
    /// [`Config::aligned_density`](crate::Config::aligned_density)
    AlignedDensity,
    /// [`Config::merge_center_px`](crate::Config::merge_center_px)
    MergeCenter,
    /// [`Config::merge_angle_deg`](crate::Config::merge_angle_deg)
    MergeAngle,
    /// [`Config::merge_gap_px`](crate::Config::merge_gap_px)
    MergeGap,
    /// [`Config::candidates_per_mille`](crate::Config::candidates_per_mille)
    CandidateCapacity,
    /// [`Config::max_link_pixels`](crate::Config::max_link_pixels)
    LinkCapacity,
    /// [`Config::extend_max_px`](crate::Config::extend_max_px)
    ExtendMax,
    /// [`Config::work_per_mille`](crate::Config::work_per_mille)
    WorkLimit,
    /// [`Config::bridge_px`](crate::Config::bridge_px)
    BridgeMax,
    /// [`Config::min_score`](crate::Config::min_score)
    MinScore,
}

impl ConfigField {
    /// Every field, in [`ConfigField::code`] order.
    pub const ALL: [Self; 18] = [
        Self::MagnitudeThreshold,
        Self::AnchorMargin,
        Self::AlignTolerance,
        Self::DistTolerance,
        Self::SkipSteps,
        Self::MinLength,
        Self::MinGroups,
        Self::AnchorDensity,
        Self::AlignedDensity,
        Self::MergeCenter,
        Self::MergeAngle,
        Self::MergeGap,
        Self::CandidateCapacity,
        Self::LinkCapacity,
        Self::ExtendMax,
        Self::WorkLimit,
        Self::BridgeMax,
        Self::MinScore,
    ];

    /// A stable number for the field, 1 to 18 (0 is left for "no field"):
    /// the values of `AaglsdConfigField` in the C header. New fields get new
    /// numbers; a number is never reused.
    pub const fn code(self) -> i32 {
        match self {
            Self::MagnitudeThreshold => 1,
            Self::AnchorMargin => 2,
            Self::AlignTolerance => 3,
            Self::DistTolerance => 4,
            Self::SkipSteps => 5,
            Self::MinLength => 6,
            Self::MinGroups => 7,
            Self::AnchorDensity => 8,
            Self::AlignedDensity => 9,
            Self::MergeCenter => 10,
            Self::MergeAngle => 11,
            Self::MergeGap => 12,
            Self::CandidateCapacity => 13,
            Self::LinkCapacity => 14,
            Self::ExtendMax => 15,
            Self::WorkLimit => 16,
            Self::BridgeMax => 17,
            Self::MinScore => 18,
        }
    }

    /// The field's name as written in Rust source.
    pub const fn name(self) -> &'static str {
        match self {
            Self::MagnitudeThreshold => "magnitude_threshold",
            Self::AnchorMargin => "anchor_margin",
            Self::AlignTolerance => "align_tolerance_deg",
            Self::DistTolerance => "dist_tolerance_px",
            Self::SkipSteps => "skip_min/skip_regular/skip_group",
            Self::MinLength => "min_length_px",
            Self::MinGroups => "min_groups",
            Self::AnchorDensity => "anchor_density",
            Self::AlignedDensity => "aligned_density",
            Self::MergeCenter => "merge_center_px",
            Self::MergeAngle => "merge_angle_deg",
            Self::MergeGap => "merge_gap_px",
            Self::CandidateCapacity => "candidates_per_mille",
            Self::LinkCapacity => "max_link_pixels",
            Self::ExtendMax => "extend_max_px",
            Self::WorkLimit => "work_per_mille",
            Self::BridgeMax => "bridge_px",
            Self::MinScore => "min_score",
        }
    }
}

/// Everything that can go wrong. Checked at the entry, in this order; after
/// the checks nothing can fail (running out of an internal capacity is not an
/// error: it is counted in [`Summary`](crate::Summary)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// Width or height is zero.
    ZeroDimension {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// A dimension exceeds [`MAX_DIMENSION`](crate::MAX_DIMENSION) or the
    /// pixel count exceeds [`MAX_PIXELS`](crate::MAX_PIXELS).
    ImageTooLarge {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// The row stride is smaller than the width.
    StrideTooSmall {
        /// Requested stride in bytes.
        stride: usize,
        /// Image width in pixels.
        width: usize,
    },
    /// The pixel buffer is shorter than `stride * (height - 1) + width`.
    BufferTooShort {
        /// Bytes required.
        needed: usize,
        /// Bytes given.
        got: usize,
    },
    /// The workspace is smaller than [`Workspace::bytes_needed`](crate::Workspace::bytes_needed).
    WorkspaceTooSmall {
        /// Bytes required (including alignment slack).
        needed: usize,
        /// Bytes given.
        got: usize,
    },
    /// The output slice has no room for a single segment.
    OutputEmpty,
    /// A configuration field is out of its documented range (or NaN).
    InvalidConfig(ConfigField),
}

impl Error {
    /// A stable number for the kind of error, 1 to 7 (0 is left for
    /// success): the values of `AaglsdStatus` in the C header and of the
    /// WASM exports' negative results. New kinds get new numbers; a number
    /// is never reused.
    ///
    /// ```
    /// use aaglsd::{Error, GrayImage};
    /// let e = GrayImage::new(&[], 0, 4, 0).unwrap_err();
    /// assert_eq!((e, e.code()), (Error::ZeroDimension { width: 0, height: 4 }, 1));
    /// ```
    pub const fn code(&self) -> i32 {
        match self {
            Self::ZeroDimension { .. } => 1,
            Self::ImageTooLarge { .. } => 2,
            Self::StrideTooSmall { .. } => 3,
            Self::BufferTooShort { .. } => 4,
            Self::WorkspaceTooSmall { .. } => 5,
            Self::OutputEmpty => 6,
            Self::InvalidConfig(_) => 7,
        }
    }

    /// A short, fixed description of the kind of error (without the
    /// numbers that [`Display`](fmt::Display) adds), for interfaces that
    /// need a `&'static str`, such as a C `aaglsd_status_str`.
    pub const fn kind_str(&self) -> &'static str {
        match self {
            Self::ZeroDimension { .. } => "image width or height is zero",
            Self::ImageTooLarge { .. } => "image exceeds the size limits",
            Self::StrideTooSmall { .. } => "row stride is smaller than the width",
            Self::BufferTooShort { .. } => "pixel buffer is too short for the image",
            Self::WorkspaceTooSmall { .. } => "workspace is smaller than needed",
            Self::OutputEmpty => "output has no room for a segment",
            Self::InvalidConfig(_) => "a configuration field is out of range",
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::ZeroDimension { width, height } => {
                write!(f, "image has a zero dimension ({width}x{height})")
            }
            Self::ImageTooLarge { width, height } => write!(
                f,
                "image {width}x{height} exceeds the limits ({} per side, {} pixels)",
                crate::MAX_DIMENSION,
                crate::MAX_PIXELS
            ),
            Self::StrideTooSmall { stride, width } => {
                write!(f, "stride {stride} is smaller than width {width}")
            }
            Self::BufferTooShort { needed, got } => {
                write!(f, "pixel buffer too short: need {needed} bytes, got {got}")
            }
            Self::WorkspaceTooSmall { needed, got } => {
                write!(f, "workspace too small: need {needed} bytes, got {got}")
            }
            Self::OutputEmpty => f.write_str("output slice is empty"),
            Self::InvalidConfig(field) => write!(f, "config field {} out of range", field.name()),
        }
    }
}

impl core::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_distinct_and_in_range() {
        let errors = [
            Error::ZeroDimension {
                width: 0,
                height: 0,
            },
            Error::ImageTooLarge {
                width: 0,
                height: 0,
            },
            Error::StrideTooSmall {
                stride: 0,
                width: 0,
            },
            Error::BufferTooShort { needed: 0, got: 0 },
            Error::WorkspaceTooSmall { needed: 0, got: 0 },
            Error::OutputEmpty,
            Error::InvalidConfig(ConfigField::MinGroups),
        ];
        for (i, e) in errors.iter().enumerate() {
            assert_eq!(e.code(), i as i32 + 1, "{e:?}");
            assert!(!e.kind_str().is_empty());
        }
        for (i, f) in ConfigField::ALL.iter().enumerate() {
            assert_eq!(f.code(), i as i32 + 1, "{f:?}");
        }
    }
}
