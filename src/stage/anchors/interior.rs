//! The interior pixels of an interior row of the anchor pass (its NMS and
//! group test, paper §3.1), in one of two forms that give the same classes
//! and candidates in the same order (`row_and_pixel_strategies_agree`):
//! the row pass, a
//! branch-free NMS over the whole row and then the group test at the gated
//! pixels (for a core with SIMD lanes, where the compiler vectorises it),
//! and the pixel pass, one pixel at a time skipping zero magnitudes (for a
//! core without, where that runs fewer instructions).

use super::{CandidateList, RowCtx};
use crate::invariant::Invariant;
use crate::stage::nms::{GATE_BIT, nms_row};

impl RowCtx<'_> {
    /// The interior pixels `inner` (columns `1..w - 1`) of an interior row,
    /// in two passes over the whole row: for a core with SIMD lanes.
    #[inline(always)]
    pub(super) fn row_pass(&self, list: &mut CandidateList<'_>, inner: &mut [u8]) {
        let [m_up, m_cur, m_dn] = self.rows_m;
        let ([_, gx_cur, _], [_, gy_cur, _]) = (self.rows_gx, self.rows_gy);
        // Pass 1, branch-free over the whole row (the compiler vectorises
        // it): the NMS state of every interior pixel, with the group test's
        // necessary condition in the GATE bit.
        nms_row([m_up, m_cur, m_dn], gx_cur, gy_cur, self.gate, inner);
        // Pass 2, in raster order: the group test where the gate holds. The
        // gate is rare and random, so each span's gated positions are first
        // gathered without a branch (eight states a word, their gate bits
        // as a byte mask, the mask's positions from a table), then visited
        // in one loop: a loop over each word's set bits would end on a
        // mispredicted branch at most words with a gate.
        let mut gated = [0u8; GATE_SPAN + 8];
        for (s, span) in inner.chunks(GATE_SPAN).enumerate() {
            let n = gate_positions(span, &mut gated);
            for &i in gated.get(..n).or_broken(&[]) {
                let x = s * GATE_SPAN + usize::from(i) + 1;
                let (Some(&mc), Some(&gx), Some(&gy)) =
                    (m_cur.get(x), gx_cur.get(x), gy_cur.get(x))
                else {
                    continue;
                };
                self.group_at(list, x, mc, (i32::from(gx as i16), i32::from(gy as i16)));
            }
        }
    }

    /// The interior pixels `inner` of an interior row pixel by pixel,
    /// skipping zero magnitudes: for a core without SIMD, where that runs
    /// fewer instructions. The 3x3 windows come from `array_windows` (no
    /// bounds checks).
    #[inline(always)]
    pub(super) fn pixel_pass(&self, list: &mut CandidateList<'_>, inner: &mut [u8]) {
        let [m_up, m_cur, m_dn] = self.rows_m;
        let ([_, gx_cur, _], [_, gy_cur, _]) = (self.rows_gx, self.rows_gy);
        let windows = m_up
            .array_windows::<3>()
            .zip(m_cur.array_windows::<3>())
            .zip(m_dn.array_windows::<3>());
        let grads = gx_cur.iter().zip(gy_cur).skip(1);
        for (x0, (((&[a0, a1, a2], &[b0, mc, b2]), &[c0, c1, c2]), ((&gx, &gy), s))) in
            windows.zip(grads.zip(inner.iter_mut())).enumerate()
        {
            if mc == 0 {
                continue;
            }
            let g = (i32::from(gx as i16), i32::from(gy as i16));
            let nb = [a0, a1, a2, b0, mc, b2, c0, c1, c2];
            self.interior(list, x0 + 1, s, mc, g, &nb);
        }
    }
}

/// Gathers the positions in `span` (NMS states of at most [`GATE_SPAN`]
/// interior pixels) whose GATE bit is set into `gated`, in order, without
/// a branch per state; returns how many. The span's last few states are
/// gathered byte by byte (none but in the row's last span: an empty word
/// adds no position).
#[inline(always)]
fn gate_positions(span: &[u8], gated: &mut [u8; GATE_SPAN + 8]) -> usize {
    let (words, tail) = span.as_chunks::<8>();
    let tail_word = tail
        .iter()
        .rev()
        .fold(0u64, |w, &b| (w << 8) | u64::from(b));
    let words = words.iter().map(|&b| u64::from_le_bytes(b));
    let mut n = 0;
    for (c, word) in words.chain(core::iter::once(tail_word)).enumerate() {
        let mask = gate_mask(word);
        let base = (c as u64 * 8).wrapping_mul(BYTES_ONE);
        let positions = GATE_POSITIONS.get(mask).copied().or_broken(0);
        if let Some(dst) = gated.get_mut(n..n + 8) {
            dst.copy_from_slice(&positions.wrapping_add(base).to_le_bytes());
        }
        n += mask.count_ones() as usize;
    }
    n
}

/// The states of [`classify_row`](super::classify_row)'s second pass gathered per span: their
/// positions fit a byte.
const GATE_SPAN: usize = 256;

/// `0x01` in each byte.
const BYTES_ONE: u64 = u64::from_le_bytes([1; 8]);

/// The [`GATE_BIT`]s of eight states (byte `i` of `word`) as bit `i` of a
/// byte mask: the multiplication moves bit 7 of byte `i` to bit `56 + i`,
/// no two partial products meeting in a bit (`gate_mask_is_exact`).
#[inline(always)]
fn gate_mask(word: u64) -> usize {
    const GATES: u64 = u64::from_le_bytes([GATE_BIT; 8]);
    ((word & GATES).wrapping_mul(0x0002_0408_1020_4081) >> 56) as usize
}

/// For each byte mask, the positions of its set bits, in increasing order,
/// one per byte from the lowest (the rest zero).
static GATE_POSITIONS: [u64; 256] = const_table!(u64; 256, |mask| positions_of(mask));

/// The entry of [`GATE_POSITIONS`] for `mask`.
const fn positions_of(mask: usize) -> u64 {
    let (mut positions, mut k, mut bit) = (0u64, 0, 0);
    while bit < 8 {
        if (mask >> bit) & 1 != 0 {
            positions |= (bit as u64) << (8 * k);
            k += 1;
        }
        bit += 1;
    }
    positions
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    /// `gate_mask` gathers exactly the gate bits, whatever the other bits,
    /// and `GATE_POSITIONS` lists each mask's set bits in order.
    #[test]
    fn gate_mask_is_exact() {
        let mut next = crate::xorshift64(0x6A7E_B175);
        for (mask, entry) in GATE_POSITIONS.iter().enumerate() {
            let positions: std::vec::Vec<u64> = (0..8).filter(|i| mask >> i & 1 != 0).collect();
            let table = entry.to_le_bytes();
            for (k, &p) in positions.iter().enumerate() {
                assert_eq!(u64::from(table[k]), p, "mask {mask:#x}");
            }
            assert!(
                table[positions.len()..].iter().all(|&b| b == 0),
                "mask {mask:#x}"
            );
            for _ in 0..64 {
                let word = (0..8).fold(next() & !u64::from_le_bytes([GATE_BIT; 8]), |w, i| {
                    w | (u64::from(mask >> i & 1 != 0) * u64::from(GATE_BIT)) << (8 * i)
                });
                assert_eq!(gate_mask(word), mask, "word {word:#018x}");
            }
        }
    }
}
