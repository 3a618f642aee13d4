//! Generates `include/aaglsd.h` from `src/lib.rs` with cbindgen.
//!
//! Two modes:
//! - default: write the header when its content changed (the file is
//!   committed, so a stale header shows up in `git diff`);
//! - `AAGLSD_VERIFY_HEADER=1`: write nothing and fail the build when the
//!   committed header differs from what cbindgen generates (for CI).

use std::path::PathBuf;

fn main() {
    let dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let header = dir.join("include").join("aaglsd.h");
    println!("cargo:rerun-if-changed=src");
    println!("cargo:rerun-if-changed=cbindgen.toml");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed={}", header.display());
    println!("cargo:rerun-if-env-changed=AAGLSD_VERIFY_HEADER");

    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml"))
        .expect("ffi/cbindgen.toml is readable and valid");
    let bindings = cbindgen::Builder::new()
        .with_crate(&dir)
        .with_config(config)
        .generate()
        .expect("cbindgen could not generate the header from ffi/src/lib.rs");
    let mut fresh = Vec::new();
    bindings.write(&mut fresh);
    let committed = std::fs::read(&header).unwrap_or_default();
    if committed == fresh {
        return;
    }
    let verify =
        std::env::var_os("AAGLSD_VERIFY_HEADER").is_some_and(|v| !v.is_empty() && v != "0");
    if verify {
        eprintln!(
            "error: {} is stale: it differs from what cbindgen generates from \
             ffi/src/lib.rs. Build without AAGLSD_VERIFY_HEADER to regenerate it, \
             then commit it.",
            header.display()
        );
        std::process::exit(1);
    }
    std::fs::create_dir_all(header.parent().expect("include/ has a parent"))
        .expect("can create ffi/include");
    std::fs::write(&header, fresh).expect("can write ffi/include/aaglsd.h");
}
