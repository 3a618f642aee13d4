//! The packed words that one stage writes into the workspace and another
//! reads, each with its bit diagram; every field is packed and unpacked
//! here only (`each_format_round_trips`).
//!
//! | word | written by | read by |
//! |---|---|---|
//! | [`candidate`] (`u32`) | the anchor pass | the candidate list, the extraction |
//! | [`record`] (`u32`) | the extraction | the group tables, the linking (which flags it) |
//! | [`index_entry`] (`u16`) | the group tables | the linking |
//! | [`point`] (`u32`) | the linking (its bridge list) | the validation |
//!
//! Neighbour codes are indices into [`crate::spec::NEIGHBOURS`] (3 bits).

/// A group candidate (design §3): a pixel that passed the
/// order-independent part of the group test, with its partners.
///
/// ```text
///  31      29 28      26 25                                        0
/// +----------+----------+-------------------------------------------+
/// |  K code  |  J code  |        raster index y·w + x (26 bits)     |
/// +----------+----------+-------------------------------------------+
/// ```
///
/// The index fits: an image has at most [`crate::MAX_PIXELS`] = 2^26
/// pixels.
pub(crate) mod candidate {
    /// The raster-index bits.
    const INDEX_MASK: u32 = 0x03FF_FFFF;
    /// Shift of the J partner's code, then K's.
    const J_SHIFT: u32 = 26;
    const K_SHIFT: u32 = 29;

    /// The neighbour codes of a candidate's J and K partners.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub(crate) struct Partners {
        pub j: u8,
        pub k: u8,
    }

    /// The candidate at raster index `index` (below 2^26) with partners `p`
    /// (codes below 8).
    pub(crate) const fn new(index: usize, p: Partners) -> u32 {
        index as u32 | (p.j as u32) << J_SHIFT | (p.k as u32) << K_SHIFT
    }

    /// The raster index of candidate `e`.
    pub(crate) const fn index(e: u32) -> usize {
        (e & INDEX_MASK) as usize
    }

    /// The neighbour codes of the J and K partners of candidate `e`.
    pub(crate) const fn partner_codes(e: u32) -> [usize; 2] {
        [((e >> J_SHIFT) & 7) as usize, ((e >> K_SHIFT) & 7) as usize]
    }
}

/// A group record (design §6): one per group, in raster order of the
/// centres, the centre's row given by the row index. The key orders the
/// seeds; the flags are the linking's.
///
/// ```text
///    31      30      29    28         21 20   18 17   15 14              0
/// +-------+-------+------+-------------+-------+-------+-----------------+
/// |retired|release|linked| key (8 bits)| K code| J code| centre column x |
/// +-------+-------+------+-------------+-------+-------+-----------------+
/// ```
///
/// The column fits: image sides are at most [`crate::MAX_DIMENSION`] =
/// 2^15 - 1.
pub(crate) mod record {
    /// The centre's column bits.
    const X_MASK: u32 = 0x7FFF;
    /// Shift of the J partner's neighbour code (3 bits), then K's.
    const J_SHIFT: u32 = 15;
    const K_SHIFT: u32 = 18;
    /// Shift of the key (8 bits).
    const KEY_SHIFT: u32 = 21;
    /// The group has been linked.
    pub(crate) const LINKED: u32 = 1 << 29;
    /// A weak linking released the group (see [`crate::Config::reseed`]).
    pub(crate) const RELEASED: u32 = 1 << 30;
    /// Released by a weak linking that retires its groups
    /// ([`crate::Reseed::retires`]): under [`crate::Reseed::Once`] and
    /// [`crate::Reseed::Misfit`] it may not seed.
    pub(crate) const RETIRED: u32 = 1 << 31;

    /// The record of a group centred in column `x` (below 2^15) with
    /// partner neighbour codes `[j, k]` and key `key`, no flag set.
    pub(crate) const fn new(x: usize, [j, k]: [usize; 2], key: u8) -> u32 {
        (x as u32 & X_MASK)
            | ((j as u32 & 7) << J_SHIFT)
            | ((k as u32 & 7) << K_SHIFT)
            | ((key as u32) << KEY_SHIFT)
    }

    /// The centre's column.
    pub(crate) const fn column(r: u32) -> u32 {
        r & X_MASK
    }

    /// The neighbour codes of the J and K partners.
    pub(crate) const fn partner_codes(r: u32) -> [u32; 2] {
        [(r >> J_SHIFT) & 7, (r >> K_SHIFT) & 7]
    }

    /// The key.
    pub(crate) const fn key(r: u32) -> u8 {
        (r >> KEY_SHIFT) as u8
    }
}

/// A group-index entry (design §6, only in the larger workspace): at each
/// group centre and member pixel, which record is its group's, as the
/// record's rank among the records of the centre's row; at a member, also
/// the neighbour code that leads from the centre to it.
///
/// ```text
///  15                              4     3      2      0
/// +---------------------------------+--------+----------+
/// |  rank in the centre's row (12)  | centre | code     |
/// +---------------------------------+--------+----------+
/// ```
///
/// A row holds at most one centre per column, so the rank fits in 12 bits
/// for images up to [`MAX_WIDTH`](index_entry::MAX_WIDTH) wide.
pub(crate) mod index_entry {
    /// Shift of the rank.
    const RANK_SHIFT: u32 = 4;
    /// Set at a centre (the code bits are then 0).
    const CENTRE: u16 = 8;

    /// The widest image whose ranks fit an entry: `2^12`.
    pub(crate) const MAX_WIDTH: usize = 1 << (16 - RANK_SHIFT);

    /// The entry at the centre of the group of rank `rank` (below 2^12).
    pub(crate) const fn centre(rank: u16) -> u16 {
        rank << RANK_SHIFT | CENTRE
    }

    /// The entry at a member of the group of rank `rank`, which lies at
    /// neighbour code `code` (below 8) from the centre.
    pub(crate) const fn member(rank: u16, code: u32) -> u16 {
        rank << RANK_SHIFT | code as u16
    }

    /// The rank of entry `v`.
    pub(crate) const fn rank(v: u16) -> usize {
        (v >> RANK_SHIFT) as usize
    }

    /// The neighbour code from the centre to the member of entry `v`, or
    /// `None` at a centre.
    pub(crate) const fn member_code(v: u16) -> Option<usize> {
        if v & CENTRE != 0 {
            None
        } else {
            Some((v & 7) as usize)
        }
    }
}

/// An in-image position (design §7.5: a bridge's ends, two words each in
/// the linking's bridge list, which the validation reads).
///
/// ```text
///  31                             16 15                              0
/// +---------------------------------+---------------------------------+
/// |               y                 |               x                 |
/// +---------------------------------+---------------------------------+
/// ```
///
/// Both fit: an image side is at most [`crate::MAX_DIMENSION`] < 2^15.
pub(crate) mod point {
    use crate::stage::P;

    /// The word of the in-image position `(x, y)`.
    pub(crate) const fn pack((x, y): P) -> u32 {
        (x as u32 & 0xFFFF) | (y as u32) << 16
    }

    /// The position of a [`pack`]ed word.
    pub(crate) const fn unpack(v: u32) -> P {
        ((v & 0xFFFF) as i32, (v >> 16) as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{MAX_DIMENSION, MAX_PIXELS};

    /// Every field of every format reads back what was packed, at the
    /// extremes of each field, and the fields do not overlap.
    #[test]
    fn each_format_round_trips() {
        let codes = 0..8u8;
        for j in codes.clone() {
            for k in codes.clone() {
                for index in [0, 1, 12_345, MAX_PIXELS - 1] {
                    let e = candidate::new(index, candidate::Partners { j, k });
                    assert_eq!(candidate::index(e), index);
                    assert_eq!(
                        candidate::partner_codes(e),
                        [usize::from(j), usize::from(k)]
                    );
                }
                for x in [0, 1, 4321, MAX_DIMENSION] {
                    for key in [0u8, 1, 200, 255] {
                        let r = record::new(x, [usize::from(j), usize::from(k)], key);
                        assert_eq!(record::column(r) as usize, x);
                        assert_eq!(record::partner_codes(r), [u32::from(j), u32::from(k)]);
                        assert_eq!(record::key(r), key);
                        let flags = record::LINKED | record::RELEASED | record::RETIRED;
                        assert_eq!(r & flags, 0);
                        let f = r | flags;
                        assert_eq!(record::column(f), record::column(r));
                        assert_eq!(record::partner_codes(f), record::partner_codes(r));
                        assert_eq!(record::key(f), key);
                    }
                }
            }
        }
        for x in [0, 1, 4321, MAX_DIMENSION as i32] {
            for y in [0, 1, 1234, MAX_DIMENSION as i32] {
                assert_eq!(point::unpack(point::pack((x, y))), (x, y));
            }
        }
        assert_eq!(index_entry::MAX_WIDTH, 4096);
        for rank in [0u16, 1, 77, (index_entry::MAX_WIDTH - 1) as u16] {
            let c = index_entry::centre(rank);
            assert_eq!(
                (index_entry::rank(c), index_entry::member_code(c)),
                (rank.into(), None)
            );
            for code in 0..8 {
                let m = index_entry::member(rank, code);
                assert_eq!(index_entry::rank(m), usize::from(rank));
                assert_eq!(index_entry::member_code(m), Some(code as usize));
            }
        }
    }
}
