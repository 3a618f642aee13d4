//! The pipeline stages, in the paper's order (§3.1 anchors, §3.2 linking,
//! §3.3 validation and merging). Stages that are exact in integers
//! (smoothing, gradient) are shared with the float reference.

pub(crate) mod anchors;
pub mod gradient;
pub(crate) mod link;
pub(crate) mod merge;
pub mod raster;
pub mod smooth;
