//! Small fixed test images that more than one crate's tests draw on.

/// The README's scene: a dark rectangle of gray `dark` (columns 16..48,
/// rows 12..36: 32 x 24 px) on a light (200) 64 x 48 image, as
/// `(width, height, pixels)` with the rows packed.
pub fn rectangle(dark: u8) -> (usize, usize, Vec<u8>) {
    let (w, h) = (64, 48);
    let mut px = vec![200u8; w * h];
    for row in px.chunks_exact_mut(w).skip(12).take(24) {
        row[16..48].fill(dark);
    }
    (w, h, px)
}
