//! Number systems of the fixed-point core: binary angles with LUT `atan2`
//! and `sin`/`cos` ([`trig`]), and Q8 fixed point with its rounding
//! divisions ([`q8`]).

pub(crate) mod q8;

mod tables;
pub(crate) mod trig;
