//! Picks the QEMU board for the build target: copies its memory layout
//! (`memory/BOARD.x`) to `OUT_DIR/memory.x`, where cortex-m-rt's `link.x`
//! includes it, and sets `cfg(fw_board = "BOARD")` for `src/board.rs` (the
//! timer that counts instructions).

use std::path::PathBuf;

/// Build target -> QEMU machine (the file stem in `memory/`).
const BOARDS: &[(&str, &str)] = &[
    ("thumbv7em-none-eabihf", "mps2-an386"),     // Cortex-M4
    ("thumbv8m.main-none-eabihf", "mps2-an505"), // Cortex-M33
    ("thumbv6m-none-eabi", "microbit"),          // Cortex-M0
];

fn main() {
    let target = std::env::var("TARGET").expect("cargo sets TARGET");
    let values: Vec<String> = BOARDS.iter().map(|(_, b)| format!("\"{b}\"")).collect();
    println!(
        "cargo::rustc-check-cfg=cfg(fw_board, values({}))",
        values.join(", ")
    );
    let Some(&(_, board)) = BOARDS.iter().find(|(t, _)| *t == target) else {
        let known: Vec<&str> = BOARDS.iter().map(|(t, _)| *t).collect();
        panic!(
            "no QEMU board for target {target}; known: {}",
            known.join(", ")
        );
    };
    let layout = format!("memory/{board}.x");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::copy(&layout, out.join("memory.x")).expect("copy the memory layout to OUT_DIR");
    println!("cargo::rustc-link-search={}", out.display());
    println!("cargo::rustc-cfg=fw_board=\"{board}\"");
    println!("cargo::rerun-if-changed={layout}");
    println!("cargo::rerun-if-changed=build.rs");
}
