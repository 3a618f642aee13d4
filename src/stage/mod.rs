//! The fixed-point pipeline stages, in the paper's order (design §1-9):
//!
//! | module | paper | what |
//! |---|---|---|
//! | [`smooth`] | paper §3.1 | 5x5 Gaussian, exact in integers (shared with the reference) |
//! | [`gradient`] | paper §3.1 | 2x2 gradient and L1 magnitude; the anchor pass's row ring |
//! | [`nms`] | paper §3.1 | regular anchors by interpolated NMS |
//! | [`anchors`] | paper §3.1 | the anchor pass: NMS states and group candidates |
//! | [`candidates`] | paper §3.1 | the candidate list and what a full one drops |
//! | [`order`] | paper §3.1 | the processing order (the pseudo-sort) of candidates and seeds |
//! | [`extract`] | paper §3.1 | the greedy group extraction |
//! | [`packed`] | | the packed words the stages pass through the workspace |
//! | [`state`] | | the per-pixel state byte |
//! | [`groups`] | paper §3.2 | group directions and members, cached for the walk |
//! | [`fit`] | paper §3.2 | exact least-squares line fits and line geometry |
//! | [`link`] | paper §3.2 | the walk from each seed group |
//! | [`validate`] | paper §3.3 | endpoints and the density validation |
//! | [`trim`] | | the longest part of a linking that passes ρ2 |
//! | [`extend`] | | endpoint extension along the line |
//! | [`merge`] | paper §3.3 | merging collinear fragments |
//! | [`raster`] | paper §3.3 | integer Bresenham |
//! | [`output`] | | Q8 segments: storage, clipping, the output frame |
//! | [`best`] | | the output slice as a bounded queue of the best scores |
//! | [`work`] | | the per-frame work limit |

/// A pixel position `(x, y)` (image sides are below 2^15).
pub(crate) type P = (i32, i32);

/// Zeroes `words`; in a build for size ([`SMALL`](crate::target::SMALL)) by
/// [`zero_bytes`], the one clearing loop.
#[inline(always)]
pub(crate) fn zero_words(words: &mut [u32]) {
    if crate::target::SMALL {
        zero_bytes(bytemuck::cast_slice_mut(words));
    } else {
        words.fill(0);
    }
}

/// Zeroes `bytes`. In a build for size, out of line and with a zero the
/// optimiser cannot see through (`black_box`), in words where aligned: it
/// would otherwise call the memory-clearing routine, which with its
/// helpers is half a kilobyte of a microcontroller's flash.
#[cfg_attr(aaglsd_small, inline(never))]
pub(crate) fn zero_bytes(bytes: &mut [u8]) {
    if crate::target::SMALL {
        let zero = core::hint::black_box(0u32);
        let (head, words, tail) = bytemuck::pod_align_to_mut::<u8, u32>(bytes);
        for w in words {
            *w = zero;
        }
        for b in head {
            *b = zero as u8;
        }
        for b in tail {
            *b = zero as u8;
        }
    } else {
        bytes.fill(0);
    }
}

pub(crate) mod anchors;
pub(crate) mod best;
pub(crate) mod candidates;
pub(crate) mod extend;
pub(crate) mod extract;
pub(crate) mod fit;
pub(crate) mod gradient;
pub(crate) mod groups;
pub(crate) mod link;
pub(crate) mod merge;
pub(crate) mod nms;
pub(crate) mod order;
pub(crate) mod output;
pub(crate) mod packed;
pub(crate) mod raster;
pub(crate) mod smooth;
pub(crate) mod state;
pub(crate) mod trim;
pub(crate) mod validate;
pub(crate) mod work;
