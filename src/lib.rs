#![doc = include_str!("../README.md")]
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

mod config;
mod detect;
mod error;
mod image;
mod num;
mod params;
mod segment;
mod stage;
mod workspace;

#[cfg(feature = "reference")]
extern crate alloc;
#[cfg(feature = "reference")]
pub mod reference;

pub use config::{Config, Profile};
#[cfg(feature = "_unstable-hooks")]
pub use detect::{blur_gradient_floor, detect_front_end};
pub use detect::{detect, detect_into_vec};
pub use error::{ConfigField, Error};
pub use image::{GrayImage, MAX_DIMENSION, MAX_PIXELS};
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
