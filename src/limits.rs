//! The image limits (a leaf module: the entry checks in [`crate::image`],
//! the error messages and the workspace layout read them).

/// Largest accepted width or height, in pixels.
pub const MAX_DIMENSION: usize = 32_767;
/// Largest accepted pixel count (`width * height`): 2^26, e.g. 8192 x 8192.
///
/// Raster indices then fit in 26 bits, which the core packs with two 3-bit
/// neighbour codes into one `u32` (a group candidate, `stage::packed`).
pub const MAX_PIXELS: usize = 1 << 26;
