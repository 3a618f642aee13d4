//! C ABI for the `aaglsd` line segment detector.
//!
//! Builds `libaaglsd.a` (staticlib) and `libaaglsd.so` (cdylib); the header
//! `ffi/include/aaglsd.h` is generated from this crate by `ffi/gen-header`
//! (cbindgen, plus the compile-time workspace sizes) and committed. The
//! functions wrap the fixed-point [`aaglsd::detect`]: the caller owns all
//! memory (pixels, one workspace slab, one output array), nothing is
//! allocated.
//!
//! Contract of every function:
//! - every pointer argument is checked for NULL ([`AaglsdStatus::NullPointer`]);
//! - every length is validated by the core (the same checks, in the same
//!   order, as the Rust API), and lengths above `PTRDIFF_MAX` bytes, which
//!   no real buffer can have, are clamped to it;
//! - nothing panics or unwinds: errors are [`AaglsdStatus`] values, and the
//!   core is panic-free by construction (its lints deny every panicking
//!   construct). Were one to happen anyway, it would end in this crate's
//!   trapping panic handler (no_std builds) or abort the process at the
//!   `extern "C"` boundary (std builds), never unwind into C.
//!
//! Structs passed in by pointer may be unaligned and are read by copy;
//! every bit pattern of [`AaglsdConfig`] is a valid value (the `merge` flag
//! is a byte, not a `bool`), so reading one is always defined.
// no_std whenever the panic strategy is `abort`: always on bare-metal
// targets, and on hosts built with `panic = "abort"`. A no_std final
// artifact cannot use the host default `panic = "unwind"` (rustc: "unwinding
// panics are not supported without std"), so such builds link std instead;
// a panic there aborts at the `extern "C"` boundary. See ffi/README.md.
#![cfg_attr(all(not(test), panic = "abort"), no_std)]
#![deny(missing_docs, unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

// The C API lives in `capi.rs` so that Rust harnesses (the `ffi` fuzz
// target) can compile it into a std binary without this crate's panic
// handler.
mod capi;
pub use capi::*;

/// The panic handler of the no_std staticlib/cdylib. Nothing in this crate or
/// the core panics (both deny every panicking construct), so this is a
/// backstop: it executes a trap instruction (SIGILL on a host, a HardFault on
/// Cortex-M, `unreachable` on wasm) instead of unwinding into C.
#[cfg(all(not(test), panic = "abort"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    // SAFETY: `ud2` raises an invalid-opcode exception and never returns.
    unsafe {
        core::arch::asm!("ud2", options(noreturn, nomem, nostack))
    }
    #[cfg(any(target_arch = "arm", target_arch = "aarch64"))]
    // SAFETY: `udf` is a permanently undefined instruction; it never returns.
    unsafe {
        core::arch::asm!("udf #0", options(noreturn, nomem, nostack))
    }
    #[cfg(any(target_arch = "riscv32", target_arch = "riscv64"))]
    // SAFETY: `unimp` raises an illegal-instruction exception; it never returns.
    unsafe {
        core::arch::asm!("unimp", options(noreturn, nomem, nostack))
    }
    #[cfg(target_arch = "wasm32")]
    core::arch::wasm32::unreachable();
    #[cfg(not(any(
        target_arch = "x86",
        target_arch = "x86_64",
        target_arch = "arm",
        target_arch = "aarch64",
        target_arch = "riscv32",
        target_arch = "riscv64",
        target_arch = "wasm32"
    )))]
    loop {
        core::hint::spin_loop();
    }
}

/// The unwinder's personality routine, which the precompiled `core` of
/// hosted targets (built with `panic = "unwind"`) still references from its
/// unwind tables. This library never unwinds (`panic = "abort"` and a
/// trapping panic handler), so the routine is never called; without it the
/// no_std cdylib has an undefined symbol and linking the staticlib needs
/// `-Wl,--gc-sections`. Bare-metal targets ship an abort-only `core` and do
/// not need it.
#[cfg(all(not(test), panic = "abort", not(target_os = "none")))]
#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

#[cfg(test)]
mod tests;
