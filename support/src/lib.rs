//! Host-side helpers of the aaglsd repository, in one place: the CLI and the
//! other examples, the benches, the repository-only integration tests, the
//! C and WASM expected-output generators, the firmware's host tools and the
//! fuzz targets all use these instead of their own copies. Not published,
//! and not part of the library: the core never decodes images or allocates.
//!
//! - [`image`]: PGM (P5), PNG and JPEG to 8-bit gray, truncated-JPEG
//!   detection, the PGM writer (feature `images`);
//! - [`svg`]: the segment overlay (feature `images`);
//! - [`perturb`]: deterministic image changes for the stability harness
//!   (feature `images`; the JPEG round trip needs `jpeg-encode`);
//! - [`segments`]: segment text files (write and read) and JSON;
//! - [`matching`]: endpoint distance and pooled matching of segment lists;
//! - [`fields`]: every [`aaglsd::Config`] field by its Rust name
//!   (`--set FIELD=VALUE`) and the [`aaglsd::Summary`] fields;
//! - [`run`]: the fixed-point core with heap buffers sized for the image;
//! - [`corpus`]: the adversarial test images (noise, stripes, tiles, ...)
//!   of the worst-case measurements;
//! - [`fixtures`]: small fixed test images shared by the crates' tests
//!   (the README's rectangle);
//! - [`manmade`]: checkerboards, ruled tables and window grids with their
//!   true lines, and the coverage metric that scores a detector on them;
//! - [`data`]: where the dataset (`../shared`) and `testdata/` are;
//! - [`progress`]: a progress bar that shows only on a terminal (feature
//!   `progress`).
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod corpus;
pub mod data;
pub mod fields;
pub mod fixtures;
#[cfg(feature = "images")]
pub mod image;
pub mod manmade;
pub mod matching;
#[cfg(feature = "images")]
pub mod perturb;
#[cfg(feature = "progress")]
pub mod progress;
pub mod run;
pub mod segments;
#[cfg(feature = "images")]
pub mod svg;

#[cfg(feature = "images")]
pub use image::{Gray, images_in, load_gray};
pub use matching::{endpoint_distance, matched};
pub use run::{Detection, detect_fixed};
