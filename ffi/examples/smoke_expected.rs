//! Writes the input and the expected output of the C smoke test
//! (`ffi/tests/smoke.c`, run by `ffi/tests/run.sh`).
//!
//! `cargo run -p aaglsd-ffi --release --example smoke_expected -- OUT_DIR [IMAGE.png]`
//!
//! Decodes an image (default `testdata/castle1.png`), writes it to
//! `OUT_DIR/input.pgm`, runs the Rust core (`aaglsd::detect`, not the C ABI)
//! with the official and the paper profiles, and writes every summary and
//! segment to `OUT_DIR/expected.txt`, coordinates and score as `f32` bit
//! patterns so that the C side can compare them exactly.

use std::fmt::Write as _;

use aaglsd::Profile;
use aaglsd_support::fields::summary_fields;
use aaglsd_support::image::TestInput;
use aaglsd_support::run::detect_with_capacity;

/// The profiles run, by their `AaglsdProfile` numbers (ffi/include/aaglsd.h).
const RUNS: [Profile; 2] = [Profile::Official, Profile::Paper];
/// Output slots: room for every segment of the test image (a full output
/// is refused below; smoke.c sizes its own array from the expected file).
const CAPACITY: usize = 4096;

fn main() -> Result<(), String> {
    let input = TestInput::from_args(
        std::env::args_os().skip(1),
        "usage: smoke_expected OUT_DIR [IMAGE]",
    )?;
    let (gray, image) = (&input.gray, &input.image);
    let img = gray.image().map_err(|e| e.to_string())?;
    let mut text = String::new();
    writeln!(
        text,
        "# Expected output of aaglsd::detect (Rust) on input.pgm ({}), for ffi/tests/smoke.c.\n\
         # run PROFILE SEGMENTS DROPPED_SEGMENTS DROPPED_CANDIDATES TRUNCATED_LINKINGS CANDIDATES GROUPS MERGED\n\
         # then SEGMENTS lines: x0 y0 x1 y1 score as f32 bit patterns (hex), then as decimals",
        image.display()
    )
    .map_err(|e| e.to_string())?;
    for profile in RUNS {
        let d =
            detect_with_capacity(&img, &profile.config(), CAPACITY).map_err(|e| e.to_string())?;
        if d.summary.dropped_segments != 0 {
            return Err("output array too small for the expected file".into());
        }
        let _ = write!(text, "run {}", profile.code());
        for (_, v) in summary_fields(&d.summary) {
            let _ = write!(text, " {v}");
        }
        text.push('\n');
        for seg in &d.segments {
            let v = [seg.x0, seg.y0, seg.x1, seg.y1, seg.score];
            let [a, b, c, d, e] = v.map(f32::to_bits);
            let _ = writeln!(
                text,
                "{a:08x} {b:08x} {c:08x} {d:08x} {e:08x}  {} {} {} {} {}",
                v[0], v[1], v[2], v[3], v[4]
            );
        }
        eprintln!("profile {}: {} segments", profile.name(), d.segments.len());
    }
    let path = input.out_dir.join("expected.txt");
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {} and {}", input.pgm.display(), path.display());
    Ok(())
}
