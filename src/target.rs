//! What the build and the target choose between: the three constants that
//! pick a tuned form of a stage over its plain form (a leaf module: every
//! stage may read them). Each pair of forms computes the same values and
//! has a test that compares them, so the output never depends on these.

/// The crate is built for size (opt-level `"s"` or `"z"`; `build.rs` sets
/// the `aaglsd_small` cfg). Such a build takes the smaller of two forms
/// (trig coefficients from node tables, 64-bit division by a loop, one
/// copy of a loop instead of one per case), because a microcontroller's
/// flash, not its speed, is what that build is for. A function marked
/// `#[cfg_attr(aaglsd_small, inline(never))]` is out of line in that build
/// only: it has several callers, and one copy is less flash than one per
/// caller.
pub(crate) const SMALL: bool = cfg!(aaglsd_small);

/// The target has 64-bit registers: interpolations multiply in 64 bits and
/// divide natively, where a 32-bit core (a Cortex-M) keeps to 32-bit
/// operations, which it runs in one instruction each.
pub(crate) const WIDE: bool = cfg!(target_pointer_width = "64");

/// The target has SIMD lanes the compiler vectorises into (SSE2, NEON,
/// SIMD128), and an out-of-order core that speculates. The per-pixel passes
/// then run branch-free over whole rows in 16-bit lanes (the anchor pass's
/// row pass, the smoothing's vertical pass, the gradient row), and stores
/// whose target is data-dependent go through a select instead of a branch
/// that would mispredict. A core without SIMD (a Cortex-M4) runs the plain
/// per-pixel forms, which execute fewer instructions there.
pub(crate) const SIMD: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "neon",
    target_feature = "simd128"
));
