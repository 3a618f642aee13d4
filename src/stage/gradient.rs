//! Paper §3.1: gradient by the LSD 2x2 mask, unnormalised, placed "backward".
//!
//! With replicate borders (row -1 reads row 0, column -1 reads column 0):
//!
//! ```text
//! gx(x,y) = B(x,y) + B(x,y-1) - B(x-1,y) - B(x-1,y-1)
//! gy(x,y) = B(x,y) + B(x-1,y) - B(x,y-1) - B(x-1,y-1)
//! ```
//!
//! Both are integers in `-510..=510`, so the L1 magnitude `|gx| + |gy|` is in
//! `0..=1020`. The sample at index `(x, y)` measures the change between
//! pixels `x-1` and `x` (and rows `y-1`, `y`): it sits at the pixel corner
//! `(x - 0.5, y - 0.5)` in pixel-centre coordinates. Both implementations
//! work in this "gradient grid" and shift their output by -0.5 px at the end.
//!
//! Exact in integers, shared by the fixed core and the float reference.

/// The gradient at `(x, y)` of the `w`-wide blurred image `b`, with
/// replicate borders. Out-of-range reads return 0; callers pass in-image
/// coordinates.
#[inline]
pub fn gradient_at(b: &[u8], w: usize, x: usize, y: usize) -> (i32, i32) {
    let xm = x.saturating_sub(1);
    let ym = y.saturating_sub(1);
    let px = |xx: usize, yy: usize| i32::from(b.get(yy * w + xx).copied().unwrap_or(0));
    let a = px(x, y); // B(x, y)
    let l = px(xm, y); // B(x-1, y)
    let u = px(x, ym); // B(x, y-1)
    let d = px(xm, ym); // B(x-1, y-1)
    (a + u - l - d, a + l - u - d)
}
