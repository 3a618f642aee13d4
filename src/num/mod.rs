//! Number systems of the fixed-point core: binary angles with LUT `atan2`
//! and `sin`/`cos` ([`trig`]), and integer geometry helpers.

mod tables;
pub mod trig;
