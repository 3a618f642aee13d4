//! The pipeline stages, in the paper's order (§3.1 anchors, §3.2 linking,
//! §3.3 validation and merging). Stages that are exact in integers are shared
//! with the float reference.

pub mod gradient;
pub mod smooth;
