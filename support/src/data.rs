//! Where the data is: the dataset beside the repository (`../shared`, or
//! `$AAGLSD_SHARED`) and the committed fixtures (`testdata/`).

use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Overrides the dataset location (the folder that holds `data/`).
pub const SHARED_ENV: &str = "AAGLSD_SHARED";

/// The 12 readme image stems (`data/readme-images/gray/<stem>.pgm`,
/// `data/aaglsd-cpp/<stem>.txt`).
pub const README_STEMS: [&str; 12] = [
    "book1", "book2", "book3", "book4", "book5", "book6", "castle1", "castle2", "castle3",
    "castle4", "castle5", "castle6",
];

/// The repository's root folder.
pub fn repo_root() -> &'static Path {
    // This crate sits in `<root>/support`.
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// `testdata/` of the repository.
pub fn testdata() -> PathBuf {
    repo_root().join("testdata")
}

/// Where the dataset is looked for: `$AAGLSD_SHARED` when set and not
/// empty, else `../shared` beside the repository.
pub fn shared_location() -> PathBuf {
    match std::env::var_os(SHARED_ENV) {
        Some(p) if !p.is_empty() => PathBuf::from(p),
        _ => repo_root().join("../shared"),
    }
}

/// The dataset folder, when it holds `data/`.
pub fn shared_dir() -> Option<PathBuf> {
    let p = shared_location();
    p.join("data").is_dir().then_some(p)
}

/// The York Urban images (`data/yorkurban`) and the scorer
/// (`tools/lseval.py`) of the dataset folder, for the harnesses that score
/// detections on them.
///
/// # Errors
/// Either is missing (both paths named).
pub fn york_urban_and_lseval() -> Result<(PathBuf, PathBuf), String> {
    let shared = shared_location();
    let (images, lseval) = (
        shared.join("data/yorkurban"),
        shared.join("tools/lseval.py"),
    );
    if images.is_dir() && lseval.is_file() {
        Ok((images, lseval))
    } else {
        Err(format!(
            "{} or {} not found",
            images.display(),
            lseval.display()
        ))
    }
}

/// The dataset folder; without it, says so on the terminal and returns
/// `None` (the caller returns, and the test passes).
///
/// The message goes straight to the process's stderr, not through
/// `eprintln!`: the test harness captures the print macros of a passing
/// test, and a skip that only `--nocapture` shows would read as a pass.
pub fn shared_or_skip(what: &str) -> Option<PathBuf> {
    let dir = shared_dir();
    if dir.is_none() {
        skip(
            what,
            &format!(
                "{} not found (put the dataset there, or set {SHARED_ENV})",
                shared_location().join("data").display()
            ),
        );
    }
    dir
}

/// Writes `SKIPPED: <what>: <why>` as one line to stderr, uncaptured.
pub fn skip(what: &str, why: &str) {
    let line = format!("SKIPPED: {what}: {why}\n");
    let _ = std::io::stderr().lock().write_all(line.as_bytes());
}
