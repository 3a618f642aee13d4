//! Writes the inputs and the expected outputs of the wasm tests (the node
//! test `wasm/tests/detect.test.mjs`, run by `wasm/tests/run.sh`, and the
//! browser test of the demo, `wasm/demo/test/run.sh`).
//!
//! `cargo run -p aaglsd-wasm --release --example wasm_expected -- OUT_DIR [IMAGE.png]`
//!
//! Decodes an image (default `testdata/castle1.png`), writes it to
//! `OUT_DIR/input.pgm`, runs the Rust core on the host (`aaglsd::detect`
//! with an output of `default_capacity`, as the JS wrapper has) and writes
//! `OUT_DIR/expected.json`: `{"width", "height", "runs": [RUN, ...],
//! "synthetic": RUN}` where a RUN is `{"profile", "set": {field: value},
//! "width", "height", "count", "summary": [9 numbers], "bits": [[x0, y0,
//! x1, y1, score] as f32 bit patterns, ...]}`. The runs are the three profiles and
//! one custom configuration on the PNG; `synthetic` is the 4000 x 3000
//! image of [`synthetic_pixel`] (12 megapixels), which the node test makes
//! with the same formula.

use aaglsd::{Config, GrayImage, Profile, Segment, Workspace};
use aaglsd_support::image::TestInput;
use aaglsd_wasm::{AaglsdSummary, default_capacity};

/// The 12-megapixel test image: 250-pixel checks of 60 and 190 with a
/// small texture. `wasm/tests/detect.test.mjs` has the same formula.
fn synthetic_pixel(x: usize, y: usize) -> u8 {
    let check = if (x / 250 + y / 250).is_multiple_of(2) {
        60
    } else {
        190
    };
    (check + (x * 3 + y * 5) % 7) as u8
}

/// One run as JSON (see the module docs); `set` is already JSON.
fn run(
    px: &[u8],
    w: usize,
    h: usize,
    profile: Profile,
    cfg: &Config,
    set: &str,
) -> Result<String, String> {
    let img = GrayImage::new(px, w, h, w).map_err(|e| e.to_string())?;
    let mut slab = vec![0u8; Workspace::bytes_needed(w, h, cfg).ok_or("image too large")?];
    let mut out = vec![Segment::ZERO; default_capacity(w, h)];
    let s = aaglsd::detect(&img, cfg, &mut Workspace::new(&mut slab), &mut out)
        .map_err(|e| e.to_string())?;
    // The fields in the order of `AaglsdSummary` (`#[repr(C)]`), the layout
    // the module writes and JS reads as 9 words.
    let summary = AaglsdSummary::from(s).values();
    let summary = summary.map(|v| v.to_string()).join(",");
    let bits: Vec<String> = out[..s.segments]
        .iter()
        .map(|g| {
            let [x0, y0, x1, y1, score] = [g.x0, g.y0, g.x1, g.y1, g.score].map(f32::to_bits);
            format!("\n    [{x0},{y0},{x1},{y1},{score}]")
        })
        .collect();
    let bits = bits.join(",");
    eprintln!(
        "{w}x{h} profile {} {set}: {} segments",
        profile.name(),
        s.segments
    );
    Ok(format!(
        "{{\"profile\":{},\"set\":{set},\"width\":{w},\"height\":{h},\"count\":{},\
         \"summary\":[{summary}],\"bits\":[{bits}]}}",
        profile.code(),
        s.segments
    ))
}

fn main() -> Result<(), String> {
    let input = TestInput::from_args(
        std::env::args_os().skip(1),
        "usage: wasm_expected OUT_DIR [IMAGE]",
    )?;
    let (w, h, pixels) = (input.gray.width, input.gray.height, &input.gray.data);
    let (out_dir, pgm_path) = (&input.out_dir, &input.pgm);

    let mut runs = Vec::new();
    for p in Profile::ALL {
        runs.push(run(pixels, w, h, p, &p.config(), "{}")?);
    }
    // A configuration no profile has, set field by field from JS.
    let mut custom = Config::PAPER;
    custom.min_length_px = 20.0;
    custom.magnitude_threshold = 10.0;
    custom.merge = false;
    let set = r#"{"min_length_px":20,"magnitude_threshold":10,"merge":0}"#;
    runs.push(run(pixels, w, h, Profile::Paper, &custom, set)?);

    let (sw, sh) = (4000, 3000);
    let synthetic: Vec<u8> = (0..sw * sh)
        .map(|i| synthetic_pixel(i % sw, i / sw))
        .collect();
    let synthetic = run(&synthetic, sw, sh, Profile::Default, &Config::DEFAULT, "{}")?;

    let json = format!(
        "{{\"width\":{w},\"height\":{h},\"runs\":[\n  {}\n],\n\"synthetic\":{synthetic}}}\n",
        runs.join(",\n  ")
    );
    let path = out_dir.join("expected.json");
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {} and {}", pgm_path.display(), path.display());
    Ok(())
}
