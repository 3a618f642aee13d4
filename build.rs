//! Sets the `aaglsd_small` cfg when the crate is built for size
//! (`opt-level = "s"` or `"z"`, as a firmware's size profile has it): a
//! few tables and loops then take their smaller forms. Both forms compute
//! the same values (each has a test comparing them), so the output does
//! not depend on the opt-level.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(aaglsd_small)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=OPT_LEVEL");
    if matches!(std::env::var("OPT_LEVEL").as_deref(), Ok("s" | "z")) {
        println!("cargo::rustc-cfg=aaglsd_small");
    }
}
