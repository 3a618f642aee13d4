#![doc = include_str!("../README.md")]
//!
//! # Glossary
//!
//! - **AAG**, aligned anchor group: three neighbouring edge pixels J, C, K
//!   whose centre C is a strict magnitude maximum across the edge and
//!   whose gradient is aligned with a partner's (paper §3.1). Groups seed
//!   the linking and guide it.
//! - **Anchor**: an edge pixel the walk may link: a *regular anchor* (a
//!   pixel kept by non-maximum suppression, in no group) or a group pixel.
//! - **Binary angle**: an angle as a wrapping `u32`, 2^32 units per turn,
//!   so that sums and differences wrap correctly; one unit is 8.4e-8°.
//! - **Gradient grid**: the positions of the 2x2 gradient samples, half a
//!   pixel up and left of the pixel centres; the pipeline works in it and
//!   shifts its output to pixel centres at the end.
//! - **Qn**: fixed point with `n` fractional bits (Q8 = 1/256 px for
//!   segment coordinates, Q30 for unit vectors, Q32 for ratios).
//! - **Weak candidate**: a linking rejected for too few groups or too few
//!   aligned pixels; its links are released so its groups can seed again.
//!
//! `docs/design.md` in the repository describes every stage as this code
//! implements it.
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing,
        clippy::missing_errors_doc,
        clippy::missing_panics_doc
    )
)]

/// A `[$ty; $n]` table of integers whose entry `$i` is `$entry`, built at
/// compile time (a `const` item's initialiser). Defined before the modules
/// that use it.
macro_rules! const_table {
    ($ty:ty; $n:expr, |$i:ident| $entry:expr) => {{
        #[allow(clippy::indexing_slicing)] // const evaluation: an out-of-range index is a compile error
        const fn build() -> [$ty; $n] {
            let mut table: [$ty; $n] = [0; $n];
            let mut $i = 0;
            while $i < $n {
                table[$i] = $entry;
                $i += 1;
            }
            table
        }
        build()
    }};
}

mod config;
mod detect;
mod error;
mod image;
mod invariant;
mod limits;
mod num;
mod params;
mod segment;
mod spec;
mod stage;
mod target;
mod workspace;

#[cfg(feature = "reference")]
extern crate alloc;
#[cfg(feature = "reference")]
pub mod reference;

pub use config::{Config, Maxima, Profile, Reseed};
#[cfg(feature = "_unstable-hooks")]
pub use detect::{Part, detect_part};
pub use detect::{detect, detect_in_place, detect_into_vec};
pub use error::{ConfigField, Error};
pub use image::GrayImage;
pub use limits::{MAX_DIMENSION, MAX_PIXELS};
pub use segment::{Segment, Summary};
pub use workspace::Workspace;

/// A xorshift64 generator for the unit tests' pseudo-random inputs.
#[cfg(test)]
pub(crate) fn xorshift64(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
