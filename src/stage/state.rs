//! The per-pixel state byte (design §14): what the anchor pass and the group
//! extraction found at a pixel, and the linking's marks.
//!
//! | bits | meaning | written by |
//! |---|---|---|
//! | 0-1 | [`Class`] | anchor pass (none / regular), extraction (centre / member) |
//! | 2-4 | on a member: the neighbour code of its group's centre | extraction |
//! | 5 | on a centre: the group has been linked | linking |
//! | 6 | in the current linking's visited set | linking (cleared per seed) |
//! | 7 | the group test must run here (the row pass's gate) | anchor pass, transient |
//!
//! A group is identified by its centre pixel: a member finds it through its
//! back code, so no group ids are stored. The workspace keeps the bytes as
//! `[u8]`; this type is the only code that knows the bit layout.

use crate::spec::NEIGHBOURS;

/// What a pixel is for the linking (bits 0-1 of the state byte).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Class {
    /// Neither an anchor nor in a group.
    None,
    /// An NMS pixel that is in no group (a regular anchor).
    Regular,
    /// The centre of an aligned anchor group.
    Centre,
    /// A partner (J or K) of a group.
    Member,
}

/// One pixel's state byte.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PixelState(u8);

const CLASS_MASK: u8 = 0b11;
const CODE_SHIFT: u32 = 2;
const CODE_MASK: u8 = 0b111 << CODE_SHIFT;
const LINKED: u8 = 1 << 5;
const VISITED: u8 = 1 << 6;
const GATE: u8 = 1 << 7;

impl PixelState {
    /// Nothing found here.
    pub const NONE: Self = Self(0);
    /// A group centre, not linked.
    pub const CENTRE: Self = Self(2);
    /// [`PixelState::GATE`]'s bit alone, for word-parallel scans of a row.
    pub const GATE_BIT: u8 = GATE;

    /// The state byte as stored.
    #[inline(always)]
    pub const fn from_byte(b: u8) -> Self {
        Self(b)
    }

    /// The byte to store.
    #[inline(always)]
    pub const fn byte(self) -> u8 {
        self.0
    }

    /// A group partner at neighbour code `code` of its centre (stored with
    /// the opposite code, which points back to the centre).
    #[inline(always)]
    pub const fn member(code: usize) -> Self {
        Self(3 | (((code + 4) % 8) as u8) << CODE_SHIFT)
    }

    /// The regular-anchor state or none, with the row pass's gate bit.
    #[inline(always)]
    pub const fn nms(regular: bool, gate: bool) -> Self {
        Self((regular as u8) | ((gate as u8) * GATE))
    }

    /// The pixel's class.
    #[inline(always)]
    pub const fn class(self) -> Class {
        match self.0 & CLASS_MASK {
            0 => Class::None,
            1 => Class::Regular,
            2 => Class::Centre,
            _ => Class::Member,
        }
    }

    /// An anchor of either kind (regular, or in a group).
    #[inline(always)]
    pub const fn is_anchor(self) -> bool {
        self.0 & CLASS_MASK != 0
    }

    /// In a group (centre or member): the greedy extraction's "used".
    #[inline(always)]
    pub const fn in_group(self) -> bool {
        self.0 & CLASS_MASK >= 2
    }

    /// On a member: the offset from it to its group's centre.
    #[inline(always)]
    pub fn to_centre(self) -> (i32, i32) {
        NEIGHBOURS
            .get(usize::from((self.0 & CODE_MASK) >> CODE_SHIFT))
            .copied()
            .unwrap_or((0, 0))
    }

    /// Class and back code equal those of `other` (a member of the same
    /// group position), whatever the marks.
    #[inline(always)]
    pub const fn same_member(self, other: Self) -> bool {
        (self.0 ^ other.0) & (CLASS_MASK | CODE_MASK) == 0
    }

    /// On a centre: the group has been linked.
    #[inline(always)]
    pub const fn linked(self) -> bool {
        self.0 & LINKED != 0
    }

    /// With the linked mark set or cleared.
    #[inline(always)]
    pub const fn with_linked(self, on: bool) -> Self {
        if on {
            Self(self.0 | LINKED)
        } else {
            Self(self.0 & !LINKED)
        }
    }

    /// In the current linking's visited set.
    #[inline(always)]
    pub const fn visited(self) -> bool {
        self.0 & VISITED != 0
    }

    /// With the visited mark set or cleared.
    #[inline(always)]
    pub const fn with_visited(self, on: bool) -> Self {
        if on {
            Self(self.0 | VISITED)
        } else {
            Self(self.0 & !VISITED)
        }
    }

    /// Without the row pass's gate bit.
    #[inline(always)]
    pub const fn without_gate(self) -> Self {
        Self(self.0 & !GATE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_are_independent() {
        for (code, &(dx, dy)) in NEIGHBOURS.iter().enumerate() {
            let m = PixelState::member(code);
            assert_eq!(m.class(), Class::Member);
            assert_eq!(m.to_centre(), (-dx, -dy));
            let marked = m.with_visited(true).with_linked(true);
            assert!(marked.visited() && marked.linked() && marked.same_member(m));
            assert_eq!(marked.with_visited(false).with_linked(false), m);
            assert!(m.in_group() && m.is_anchor());
        }
        let regular = PixelState::nms(true, false);
        assert!(!regular.in_group() && regular.is_anchor());
        assert!(!PixelState::NONE.is_anchor());
        let g = PixelState::nms(true, true);
        assert_eq!(g.class(), Class::Regular);
        assert_eq!(g.without_gate(), regular);
        assert_eq!(g.byte() & PixelState::GATE_BIT, PixelState::GATE_BIT);
        assert_eq!(PixelState::CENTRE.class(), Class::Centre);
    }
}
