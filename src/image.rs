//! Borrowed 8-bit grayscale images.

use crate::Error;
use crate::limits::{MAX_DIMENSION, MAX_PIXELS};

/// A borrowed 8-bit luma image: `height` rows of `width` bytes, each row
/// starting `stride` bytes after the previous one.
///
/// Built only through [`GrayImage::new`], which checks every field, so a
/// `GrayImage` can always be indexed without bounds failures.
#[derive(Clone, Copy, Debug)]
pub struct GrayImage<'a> {
    data: &'a [u8],
    width: usize,
    height: usize,
    stride: usize,
}

/// Checks image dimensions alone: zero, per-side limit, pixel-count limit.
pub(crate) const fn check_dimensions(width: usize, height: usize) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::ZeroDimension { width, height });
    }
    if width > MAX_DIMENSION || height > MAX_DIMENSION || width * height > MAX_PIXELS {
        // Both sides are <= 32767 here, so the product cannot overflow.
        return Err(Error::ImageTooLarge { width, height });
    }
    Ok(())
}

impl<'a> GrayImage<'a> {
    /// Wraps `data` as a `width` x `height` image with rows `stride` bytes apart.
    ///
    /// # Errors
    /// In this order: [`Error::ZeroDimension`], [`Error::ImageTooLarge`],
    /// [`Error::StrideTooSmall`], [`Error::BufferTooShort`] (the buffer must
    /// hold `stride * (height - 1) + width` bytes; the last row needs no
    /// padding).
    pub const fn new(
        data: &'a [u8],
        width: usize,
        height: usize,
        stride: usize,
    ) -> Result<Self, Error> {
        if let Err(e) = check_dimensions(width, height) {
            return Err(e);
        }
        if stride < width {
            return Err(Error::StrideTooSmall { stride, width });
        }
        let needed = match stride.checked_mul(height - 1) {
            Some(v) => match v.checked_add(width) {
                Some(n) => n,
                None => usize::MAX,
            },
            None => usize::MAX,
        };
        if data.len() < needed {
            return Err(Error::BufferTooShort {
                needed,
                got: data.len(),
            });
        }
        Ok(Self {
            data,
            width,
            height,
            stride,
        })
    }

    /// Width in pixels.
    pub const fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub const fn height(&self) -> usize {
        self.height
    }

    /// Row stride in bytes.
    pub const fn stride(&self) -> usize {
        self.stride
    }

    /// Row `y` (`width` bytes). Returns an empty slice when `y >= height`.
    pub fn row(&self, y: usize) -> &'a [u8] {
        let start = y.saturating_mul(self.stride);
        // Past the last row: the documented empty row.
        self.data
            .get(start..start.saturating_add(self.width))
            .unwrap_or(&[])
    }

    /// Pixel `(x, y)`, or `None` outside the image.
    pub fn get(&self, x: usize, y: usize) -> Option<u8> {
        if x >= self.width {
            return None;
        }
        self.row(y).get(x).copied()
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for GrayImage<'_> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "GrayImage {{ width: {}, height: {}, stride: {} }}",
            self.width,
            self.height,
            self.stride
        );
    }
}
