//! Writes the input and the expected output of the node test
//! (`wasm/tests/detect.test.mjs`, run by `wasm/tests/run.sh`).
//!
//! `cargo run -p aaglsd-wasm --release --example wasm_expected -- OUT_DIR [IMAGE.png]`
//!
//! Decodes an image (default `testdata/castle1.png`, at most
//! 640 x 480), writes it to `OUT_DIR/input.pgm`, runs the Rust core on the
//! host (`aaglsd::detect` with an output of `MAX_SEGMENTS`, as the module
//! has) for profiles 0, 1 and 2, and writes `OUT_DIR/expected.json`:
//! `{"width", "height", "runs": [{"profile", "count", "summary": [7 u32],
//! "bits": [[x0, y0, x1, y1] as f32 bit patterns, ...]}]}`.

use std::fmt::Write as _;

use aaglsd_support::image::TestInput;
use aaglsd_support::run::detect_with_capacity;
use aaglsd_wasm::{MAX_HEIGHT, MAX_SEGMENTS, MAX_WIDTH, profile_config, summary_words};

fn main() -> Result<(), String> {
    let input = TestInput::from_args(
        std::env::args_os().skip(1),
        "usage: wasm_expected OUT_DIR [IMAGE]",
    )?;
    let gray = &input.gray;
    let (w, h) = (gray.width, gray.height);
    if w > MAX_WIDTH || h > MAX_HEIGHT {
        return Err(format!(
            "{w}x{h} exceeds the module's {MAX_WIDTH}x{MAX_HEIGHT}"
        ));
    }
    let img = gray.image().map_err(|e| e.to_string())?;
    let mut runs = Vec::new();
    for profile in 0..3 {
        let cfg = profile_config(profile).ok_or("unknown profile")?;
        // The module's output capacity, so that a full output is reported
        // the same way on both sides.
        let d = detect_with_capacity(&img, &cfg, MAX_SEGMENTS).map_err(|e| e.to_string())?;
        let s = d.summary;
        let summary = summary_words(&s).map(|v| v.to_string()).join(",");
        let mut bits = String::new();
        for (i, seg) in d.segments.iter().enumerate() {
            let v = [seg.x0, seg.y0, seg.x1, seg.y1].map(f32::to_bits);
            let sep = if i == 0 { "" } else { "," };
            let _ = write!(bits, "{sep}\n    [{},{},{},{}]", v[0], v[1], v[2], v[3]);
        }
        runs.push(format!(
            "{{\"profile\":{profile},\"count\":{},\"summary\":[{summary}],\"bits\":[{bits}]}}",
            s.segments
        ));
        eprintln!("profile {profile}: {} segments", s.segments);
    }
    let json = format!(
        "{{\"width\":{w},\"height\":{h},\"runs\":[\n  {}\n]}}\n",
        runs.join(",\n  ")
    );
    let path = input.out_dir.join("expected.json");
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {} and {}", input.pgm.display(), path.display());
    Ok(())
}
