//! `detect`: run the AAGLSD detector on an image (or a folder of images).
//!
//! ```text
//! cargo run --release --example detect                       # bundled image -> stdout + detect.svg
//! cargo run --release --example detect -- IMAGE [--svg OUT.svg] [--json]
//! cargo run --release --example detect -- DIR --out-dir PRED  # folder mode: PRED/<stem>.txt
//! options: --profile default|official|paper   --reference (float reference instead of the fixed core)
//! ```
//!
//! Segments are printed one per line as `x0 y0 x1 y1` in 0-based pixel-centre
//! coordinates (pixel (col, row) is centred at (col, row)).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use aaglsd::{Config, Segment};
use aaglsd_support::{self as support, segments};

const USAGE: &str = "usage: detect [IMAGE|DIR] [--out-dir DIR] [--json] [--svg FILE] \
[--profile default|official|paper] [--reference]
  IMAGE        PGM (P5), PNG or JPEG; default: testdata/castle1.png
  DIR          folder mode: every .jpg/.jpeg/.png/.pgm in DIR (needs --out-dir)
  --out-dir D  folder mode: write D/<stem>.txt (and D/<stem>.json with --json)
  --json       JSON instead of text
  --svg FILE   also write an SVG overlay of the segments on the image
  --profile P  parameter profile (default: default)
  --reference  use the float reference implementation instead of the fixed-point core";

struct Args {
    input: PathBuf,
    out_dir: Option<PathBuf>,
    json: bool,
    svg: Option<PathBuf>,
    config: Config,
    reference: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut input = None;
    let mut a = Args {
        input: PathBuf::new(),
        out_dir: None,
        json: false,
        svg: None,
        config: Config::DEFAULT,
        reference: false,
    };
    let mut svg_default = true;
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "-h" | "--help" => return Err(String::new()),
            "--json" => a.json = true,
            "--reference" => a.reference = true,
            "--svg" => a.svg = Some(PathBuf::from(value("--svg")?)),
            "--out-dir" => a.out_dir = Some(PathBuf::from(value("--out-dir")?)),
            "--profile" => {
                a.config = match value("--profile")?.as_str() {
                    "default" => Config::DEFAULT,
                    "official" => Config::OFFICIAL,
                    "paper" => Config::PAPER,
                    other => return Err(format!("unknown profile {other:?}")),
                }
            }
            s if s.starts_with('-') => return Err(format!("unknown option {s:?}")),
            s => {
                if input.replace(PathBuf::from(s)).is_some() {
                    return Err("more than one input given".into());
                }
                svg_default = false;
            }
        }
    }
    a.input =
        input.unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("testdata/castle1.png"));
    if svg_default && a.svg.is_none() && a.out_dir.is_none() {
        a.svg = Some(PathBuf::from("detect.svg"));
    }
    Ok(a)
}

fn run_one(img: &support::Gray, args: &Args) -> Result<Vec<Segment>, String> {
    let img = img.image().map_err(|e| e.to_string())?;
    if args.reference {
        return aaglsd::reference::detect(&img, &args.config).map_err(|e| e.to_string());
    }
    let d = support::detect_fixed(&img, &args.config).map_err(|e| e.to_string())?;
    if !d.summary.is_complete() {
        eprintln!("warning: detection incomplete: {:?}", d.summary);
    }
    Ok(d.segments)
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("detect: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("detect: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<(), String> {
    if args.input.is_dir() {
        let out = args.out_dir.as_ref().ok_or("folder mode needs --out-dir")?;
        std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
        let files = support::images_in(&args.input)?;
        if files.is_empty() {
            return Err(format!("{}: no images found", args.input.display()));
        }
        let mut failed = 0;
        for f in &files {
            let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("image");
            let result = support::load_gray(f)
                .and_then(|img| Ok((run_one(&img, args)?, img)))
                .map_err(|e| format!("{}: {e}", f.display()));
            match result {
                Ok((segs, img)) => {
                    let (name, text) = if args.json {
                        (
                            format!("{stem}.json"),
                            segments::to_json(img.width, img.height, &segs),
                        )
                    } else {
                        (format!("{stem}.txt"), segments::to_text(&segs))
                    };
                    let p = out.join(name);
                    std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))?;
                    eprintln!("{}: {} segments", f.display(), segs.len());
                }
                Err(e) => {
                    eprintln!("detect: {e}");
                    failed += 1;
                }
            }
        }
        if failed > 0 {
            return Err(format!("{failed} of {} images failed", files.len()));
        }
        return Ok(());
    }
    let at = |e: String| format!("{}: {e}", args.input.display());
    let img = support::load_gray(&args.input).map_err(at)?;
    let segs = run_one(&img, args).map_err(at)?;
    let text = if args.json {
        segments::to_json(img.width, img.height, &segs)
    } else {
        segments::to_text(&segs)
    };
    if let Some(dir) = &args.out_dir {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let stem = args
            .input
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("image");
        let ext = if args.json { "json" } else { "txt" };
        let p = dir.join(format!("{stem}.{ext}"));
        std::fs::write(&p, &text).map_err(|e| format!("{}: {e}", p.display()))?;
    } else {
        print!("{text}");
    }
    if let Some(svg) = &args.svg {
        std::fs::write(svg, support::svg::to_svg(&img, &segs))
            .map_err(|e| format!("{}: {e}", svg.display()))?;
        eprintln!(
            "{} segments; overlay written to {}",
            segs.len(),
            svg.display()
        );
    } else {
        eprintln!("{} segments", segs.len());
    }
    Ok(())
}
