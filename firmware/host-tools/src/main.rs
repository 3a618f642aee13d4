//! Host side of the firmware check (`firmware/run.sh`).
//!
//! ```text
//! host-tools crop IN X Y OUT    320x240 crop at column X, row Y of a PGM, PNG or
//!                               JPEG (decoded to its luma), written as raw 8-bit gray
//! host-tools detect IN          aaglsd::detect (Config::DEFAULT) on a 320x240 raw
//!                               gray file, printed exactly as the firmware prints it
//! host-tools corpus NAME OUT    the adversarial pattern NAME (`aaglsd_support::corpus`)
//!                               at 320x240, written as raw 8-bit gray
//! host-tools corpus --list      the pattern names, one a line
//! ```

#[path = "../../src/report.rs"]
mod report;

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use aaglsd::{Config, GrayImage, Segment, Workspace, detect};
use report::{SegmentLine, SummaryLine};

/// Image width, as in the firmware.
const W: usize = 320;
/// Image height, as in the firmware.
const H: usize = 240;
/// Output capacity, as in the firmware (a full output must be reported the
/// same way on both sides).
const MAX_SEGMENTS: usize = 512;

const USAGE: &str = "usage: host-tools crop IN X Y OUT | host-tools detect IN | host-tools corpus NAME OUT | host-tools corpus --list";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = match argv.as_slice() {
        ["crop", input, x, y, output] => crop(Path::new(input), x, y, Path::new(output)),
        ["detect", input] => run_detect(Path::new(input)),
        ["corpus", "--list"] => {
            for p in aaglsd_support::corpus::patterns() {
                println!("{}", p.name);
            }
            Ok(())
        }
        ["corpus", name, output] => corpus(name, Path::new(output)),
        _ => Err(USAGE.to_string()),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("host-tools: {e}");
            ExitCode::FAILURE
        }
    }
}

fn crop(input: &Path, x: &str, y: &str, output: &Path) -> Result<(), String> {
    let x0: usize = x.parse().map_err(|_| format!("bad X {x:?}"))?;
    let y0: usize = y.parse().map_err(|_| format!("bad Y {y:?}"))?;
    let at = |e: String| format!("{}: {e}", input.display());
    let img = aaglsd_support::load_gray(input).map_err(at)?;
    let window = img.crop(x0, y0, W, H).map_err(at)?;
    std::fs::write(output, &window.data).map_err(|e| format!("{}: {e}", output.display()))
}

fn corpus(name: &str, output: &Path) -> Result<(), String> {
    let px = aaglsd_support::corpus::render(name, W, H).ok_or_else(|| {
        format!("unknown corpus pattern {name:?} (`host-tools corpus --list` names them)")
    })?;
    std::fs::write(output, &px).map_err(|e| format!("{}: {e}", output.display()))
}

fn run_detect(input: &Path) -> Result<(), String> {
    let data = std::fs::read(input).map_err(|e| format!("{}: {e}", input.display()))?;
    if data.len() != W * H {
        return Err(format!(
            "{}: {} bytes; expected a {W}x{H} raw 8-bit gray image ({} bytes)",
            input.display(),
            data.len(),
            W * H
        ));
    }
    let img = GrayImage::new(&data, W, H, W).map_err(|e| e.to_string())?;
    // The same sizing as the firmware's `static` workspace.
    let mut slab = vec![0u8; Workspace::bytes_needed_default(W, H)];
    let mut out = [Segment::default(); MAX_SEGMENTS];
    let summary = detect(
        &img,
        &Config::DEFAULT,
        &mut Workspace::new(&mut slab),
        &mut out,
    )
    .map_err(|e| e.to_string())?;
    let mut text = String::new();
    for s in &out[..summary.segments] {
        let _ = writeln!(text, "{}", SegmentLine(s));
    }
    let _ = writeln!(text, "{}", SummaryLine(&summary));
    print!("{text}");
    Ok(())
}
