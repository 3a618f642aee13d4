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
/// coordinates. Interior pixels take one bounds check (a `w + 2` window).
#[inline]
pub fn gradient_at(b: &[u8], w: usize, x: usize, y: usize) -> (i32, i32) {
    if x > 0 && y > 0 {
        let i = y * w + x;
        if let Some(win) = b.get(i - w - 1..=i) {
            let at = |k: usize| i32::from(win.get(k).copied().unwrap_or(0));
            let (d, u, l, a) = (at(0), at(1), at(w), at(w + 1));
            return (a + u - l - d, a + l - u - d);
        }
    }
    gradient_at_border(b, w, x, y)
}

/// [`gradient_at`] for row 0 and column 0 (replicate borders).
#[cold]
fn gradient_at_border(b: &[u8], w: usize, x: usize, y: usize) -> (i32, i32) {
    let xm = x.saturating_sub(1);
    let ym = y.saturating_sub(1);
    let px = |xx: usize, yy: usize| i32::from(b.get(yy * w + xx).copied().unwrap_or(0));
    let a = px(x, y); // B(x, y)
    let l = px(xm, y); // B(x-1, y)
    let u = px(x, ym); // B(x, y-1)
    let d = px(xm, ym); // B(x-1, y-1)
    (a + u - l - d, a + l - u - d)
}
