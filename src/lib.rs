//! AAGLSD line segment detector (crate docs: see README.md).
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod config;
mod error;
mod image;
mod segment;
pub mod stage;

#[cfg(feature = "reference")]
extern crate alloc;
#[cfg(feature = "reference")]
pub mod reference;

pub use config::Config;
pub use error::{ConfigField, Error};
pub use image::{GrayImage, MAX_DIMENSION, MAX_PIXELS};
pub use segment::{Segment, Summary};
