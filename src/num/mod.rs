//! Number systems of the fixed-point core: binary angles with LUT `atan2`
//! and `sin`/`cos` ([`trig`]), and Q8 fixed point with its rounding
//! divisions ([`q8`]).

pub(crate) mod q8;

/// Whether the crate is built for size (opt-level `"s"` or `"z"`; `build.rs`
/// sets the `aaglsd_small` cfg). Such a build takes the smaller of two
/// forms that compute the same values: trig coefficients from node tables
/// (`tables::atan_step`), 64-bit division by a short loop
/// ([`q8::div_rem_u64`]), and so on. Each pair has a test that compares
/// its forms. A function marked `#[cfg_attr(aaglsd_small, inline(never))]`
/// is out of line in such a build only: for each, building the size probe
/// with it out of line measured a saving (`docs/performance.md`).
pub(crate) const SMALL: bool = cfg!(aaglsd_small);

mod tables;
pub(crate) mod trig;
