//! Per-pixel state (design §13): what the anchor pass and the group
//! extraction found at each pixel, as two bits ([`ClassMap`]), and the
//! current linking's visited set, as one bit ([`BitMap`]).
//!
//! A group is identified by its centre pixel; a member finds its centre
//! among its eight neighbours (the group records of [`super::groups`] hold
//! each centre's partner codes), so no group ids and no back-pointers are
//! stored per pixel. Both maps pad each row to a whole byte, so that a row
//! can be written as bytes and a pixel is found from `(x, y)` without a
//! division.

/// What a pixel is for the linking.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Class {
    /// Neither an anchor nor in a group.
    None = 0,
    /// An NMS pixel that is in no group (a regular anchor).
    Regular = 1,
    /// The centre of an aligned anchor group.
    Centre = 2,
    /// A partner (J or K) of a group.
    Member = 3,
}

impl Class {
    /// The class of the two low bits of `b`.
    #[inline(always)]
    const fn of_bits(b: u8) -> Self {
        match b & 3 {
            0 => Self::None,
            1 => Self::Regular,
            2 => Self::Centre,
            _ => Self::Member,
        }
    }

    /// An anchor of either kind (regular, or in a group).
    #[inline(always)]
    pub const fn is_anchor(self) -> bool {
        !matches!(self, Self::None)
    }

    /// In a group (centre or member): the greedy extraction's "used".
    #[inline(always)]
    pub const fn in_group(self) -> bool {
        matches!(self, Self::Centre | Self::Member)
    }
}

/// Bytes per row of a map with `bits` bits per pixel.
pub(crate) const fn row_bytes(w: usize, bits: usize) -> usize {
    (w * bits).div_ceil(8)
}

/// The [`Class`] of every pixel, 2 bits each, 4 pixels a byte, rows padded
/// to a byte.
pub(crate) struct ClassMap<'a> {
    bytes: &'a mut [u8],
    stride: usize,
}

impl<'a> ClassMap<'a> {
    /// A map over `bytes` for images `w` pixels wide.
    pub fn new(bytes: &'a mut [u8], w: usize) -> Self {
        Self {
            bytes,
            stride: row_bytes(w, 2),
        }
    }

    /// The class at `(x, y)`, an in-image pixel (anything else reads as
    /// [`Class::None`]).
    #[cfg_attr(not(aaglsd_small), inline(always))]
    #[cfg_attr(aaglsd_small, inline(never))]
    pub fn get(&self, x: usize, y: usize) -> Class {
        let b = self
            .bytes
            .get(y * self.stride + (x >> 2))
            .copied()
            // Outside the map: the documented `Class::None`.
            .unwrap_or(0);
        Class::of_bits(b >> ((x & 3) * 2))
    }

    /// Sets the class at `(x, y)`.
    #[inline(always)]
    pub fn set(&mut self, x: usize, y: usize, c: Class) {
        if let Some(b) = self.bytes.get_mut(y * self.stride + (x >> 2)) {
            let shift = (x & 3) * 2;
            *b = (*b & !(3 << shift)) | ((c as u8) << shift);
        }
    }

    /// Writes row `y` from one class value (0..=3) per byte of `classes`.
    pub fn write_row(&mut self, y: usize, classes: &[u8]) {
        let start = y * self.stride;
        let Some(row) = self.bytes.get_mut(start..start + self.stride) else {
            return;
        };
        // Eight classes a word: byte k's two bits move to bits 2k..2k+2 of
        // the low byte of its half (bytes 0 and 4 are kept; the shifted
        // copies in the other bytes are dropped).
        let (eights, rest) = classes.as_chunks::<8>();
        let (head, tail) = row.split_at_mut((2 * eights.len()).min(row.len()));
        for (out, &eight) in head.as_chunks_mut::<2>().0.iter_mut().zip(eights) {
            let v = u64::from_le_bytes(eight) & 0x0303_0303_0303_0303;
            let v = v | (v >> 6);
            let v = v | (v >> 12);
            *out = [v as u8, (v >> 32) as u8];
        }
        // The last one to seven classes, four to a byte.
        for (out, four) in tail.iter_mut().zip(rest.chunks(4)) {
            let mut q = [0u8; 4];
            for (d, &s) in q.iter_mut().zip(four) {
                *d = s & 3;
            }
            let v = u32::from_le_bytes(q);
            *out = ((v | (v >> 6) | (v >> 12) | (v >> 18)) & 0xFF) as u8;
        }
    }
}

/// One bit per pixel (the visited set), rows padded to a byte.
pub(crate) struct BitMap<'a> {
    bytes: &'a mut [u8],
    stride: usize,
}

impl<'a> BitMap<'a> {
    /// A map over `bytes` for images `w` pixels wide, all bits cleared.
    pub fn new_cleared(bytes: &'a mut [u8], w: usize) -> Self {
        super::zero_bytes(bytes);
        Self {
            bytes,
            stride: row_bytes(w, 1),
        }
    }

    /// The bit at the in-image pixel `(x, y)`.
    #[inline(always)]
    pub fn get(&self, x: usize, y: usize) -> bool {
        self.bytes
            .get(self.byte_index(x, y))
            .is_some_and(|&b| b & (1 << (x & 7)) != 0)
    }

    /// Sets the bit at `(x, y)`; returns whether it was set before.
    #[inline(always)]
    pub fn test_and_set(&mut self, x: usize, y: usize) -> bool {
        match self.bytes.get_mut(self.byte_index(x, y)) {
            Some(b) => {
                let m = 1 << (x & 7);
                let was = *b & m != 0;
                *b |= m;
                was
            }
            None => true,
        }
    }

    /// The index of the byte holding the bit of `(x, y)`, for
    /// [`BitMap::clear_byte`].
    #[inline(always)]
    pub fn byte_index(&self, x: usize, y: usize) -> usize {
        y * self.stride + (x >> 3)
    }

    /// Clears every bit of byte [`BitMap::byte_index`] `i`: for a caller
    /// that clears all the set bits of the map (the bits the byte shares
    /// are being cleared too), one store and no read.
    #[inline(always)]
    pub fn clear_byte(&mut self, i: usize) {
        if let Some(b) = self.bytes.get_mut(i) {
            *b = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn class_map_round_trips_any_width() {
        for w in [1usize, 3, 4, 5, 8, 13, 16, 17, 30] {
            let h = 3;
            let mut bytes = vec![0xA5u8; row_bytes(w, 2) * h];
            let mut m = ClassMap::new(&mut bytes, w);
            let class = |x: usize, y: usize| Class::of_bits((x * 7 + y * 3) as u8);
            for y in 0..h {
                let row: Vec<u8> = (0..w).map(|x| (x % 2) as u8).collect();
                m.write_row(y, &row);
                for x in 0..w {
                    assert_eq!(m.get(x, y) as u8, (x % 2) as u8, "{w}: ({x}, {y})");
                }
            }
            for y in 0..h {
                for x in 0..w {
                    m.set(x, y, class(x, y));
                }
            }
            for y in 0..h {
                for x in 0..w {
                    assert_eq!(m.get(x, y), class(x, y), "{w}: ({x}, {y})");
                }
            }
            assert_eq!(m.get(w, h), Class::None);
        }
        assert!(Class::Member.in_group() && Class::Centre.is_anchor());
        assert!(!Class::Regular.in_group() && !Class::None.is_anchor());
    }

    #[test]
    fn bit_map_sets_and_clears() {
        let (w, h) = (11, 2);
        let mut bytes = vec![0xFFu8; row_bytes(w, 1) * h];
        let mut m = BitMap::new_cleared(&mut bytes, w);
        assert!(!m.test_and_set(10, 1));
        assert!(m.test_and_set(10, 1));
        assert!(m.get(10, 1) && !m.get(9, 1) && !m.get(10, 0));
        assert!(!m.test_and_set(3, 1));
        m.clear_byte(m.byte_index(10, 1));
        assert!(!m.get(10, 1) && m.get(3, 1));
        m.clear_byte(m.byte_index(3, 1));
        assert!(!m.get(3, 1));
        assert!(bytes.iter().all(|&b| b == 0));
    }
}
