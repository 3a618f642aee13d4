//! `detect`: run the AAGLSD detector on an image (or a folder of images).
//!
//! ```text
//! cargo run --release --example detect                       # bundled image -> stdout + detect.svg
//! cargo run --release --example detect -- IMAGE [--svg OUT.svg] [--json] [--scores] [--stats]
//! cargo run --release --example detect -- DIR --out-dir PRED [--jobs 4]  # PRED/<stem>.txt
//! options: --profile default|official|paper   --set FIELD=VALUE   --reference
//! ```
//!
//! Segments are printed one per line as `x0 y0 x1 y1` in 0-based pixel-centre
//! coordinates (pixel (col, row) is centred at (col, row)); with `--scores`
//! the score follows as a fifth column. The brighter side of a segment lies
//! on the left of (x0, y0) -> (x1, y1) as the image is displayed (x right,
//! y down). JSON gives each segment as `[x0,y0,x1,y1,score]`.
//!
//! Exit status: 0 on success, 1 when an image cannot be read, decoded or
//! detected or an output cannot be written (one line `detect: FILE: why`
//! each), 2 for a bad command line (including a `--set` value out of range).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

use aaglsd::{Config, Profile, Segment, Summary};
use aaglsd_support::progress::Progress;
use aaglsd_support::segments::Format;
use aaglsd_support::{Gray, fields, image, svg};

const USAGE: &str =
    "usage: detect [IMAGE|DIR] [--out-dir DIR] [--json] [--scores] [--svg FILE] [--stats]
              [--profile default|official|paper] [--set FIELD=VALUE]... [--reference] [--jobs N]
  IMAGE          PGM (P5), PNG or JPEG; default: testdata/castle1.png (and --svg detect.svg)
  DIR            folder mode: every .jpg/.jpeg/.png/.pgm in DIR (needs --out-dir)
  output         one segment a line, `x0 y0 x1 y1` (0-based pixel centres), the brighter
                 side on the left of (x0,y0)->(x1,y1) as displayed (x right, y down)
  --out-dir D    write D/<stem>.txt (D/<stem>.json with --json) instead of printing
  --scores       a fifth column: the score (gradient contrast summed along the segment,
                 an integer; higher: likelier a true line)
  --json         JSON instead of text: {\"width\",\"height\",\"segments\":[[x0,y0,x1,y1,score],...]}
  --svg FILE     also write an SVG overlay of the segments on the image, each line's opacity
                 from its score (one image only; images over 2 megapixels are embedded
                 downscaled, segments stay exact)
  --stats        print the detector's Summary (what it found and dropped) to stderr
  --profile P    parameter profile (default: default)
  --set F=V      set Config field F after the profile (repeatable): magnitude_threshold,
                 anchor_margin, align_tolerance_deg, dist_tolerance_px, skip_min,
                 skip_regular, skip_group (skip sets all three), min_length_px, min_groups,
                 anchor_density, aligned_density, reseed (never/once/misfit/always), maxima
                 (strict/symmetric), bridge_px, merge (true/false), trim (true/false),
                 merge_center_px, merge_angle_deg, merge_gap_px, candidates_per_mille, max_link_pixels,
                 extend_max_px, work_per_mille, work_budget (0: none)
  --reference    use the float reference implementation instead of the fixed-point core
  --jobs N       folder mode: images detected in parallel (default 1; same output files)";

struct Args {
    input: PathBuf,
    out_dir: Option<PathBuf>,
    format: Format,
    svg: Option<PathBuf>,
    stats: bool,
    config: Config,
    reference: bool,
    jobs: usize,
}

/// `Err(None)`: help was asked for.
fn parse_args(args: impl IntoIterator<Item = String>) -> Result<Args, Option<String>> {
    let mut it = args.into_iter();
    let mut input = None;
    let mut profile = Profile::Default;
    let mut sets = Vec::new();
    let mut a = Args {
        input: PathBuf::new(),
        out_dir: None,
        format: Format::default(),
        svg: None,
        stats: false,
        config: Config::DEFAULT,
        reference: false,
        jobs: 1,
    };
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "-h" | "--help" => return Err(None),
            "--json" => a.format.json = true,
            "--scores" => a.format.scores = true,
            "--stats" => a.stats = true,
            "--reference" => a.reference = true,
            "--svg" => a.svg = Some(PathBuf::from(value("--svg")?)),
            "--out-dir" => a.out_dir = Some(PathBuf::from(value("--out-dir")?)),
            "--profile" => {
                let p = value("--profile")?;
                profile = Profile::from_name(&p).ok_or(format!("unknown profile {p:?}"))?;
            }
            "--set" => sets.push(value("--set")?),
            "--jobs" => {
                let v = value("--jobs")?;
                a.jobs = v
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or(format!("--jobs wants a positive integer, got {v:?}"))?;
            }
            s if s.starts_with('-') => return Err(Some(format!("unknown option {s:?}"))),
            s => {
                if input.replace(PathBuf::from(s)).is_some() {
                    return Err(Some("more than one input given".into()));
                }
            }
        }
    }
    a.config = profile.config();
    for s in &sets {
        fields::apply_set(&mut a.config, s).map_err(|e| format!("--set {s}: {e}"))?;
    }
    let bundled = input.is_none();
    a.input = input.unwrap_or_else(|| aaglsd_support::data::testdata().join("castle1.png"));
    if bundled && a.svg.is_none() && a.out_dir.is_none() {
        a.svg = Some(PathBuf::from("detect.svg"));
    }
    Ok(a)
}

fn main() -> ExitCode {
    let args = match parse_args(std::env::args().skip(1)) {
        Ok(a) => a,
        Err(e) => {
            if let Some(e) = e {
                eprintln!("detect: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    let r = if args.input.is_dir() {
        run_folder(&args)
    } else {
        run_image(&args)
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => {
            eprintln!("detect: {e}\n{USAGE}");
            ExitCode::from(2)
        }
        Err(Failure::Run(e)) => {
            eprintln!("detect: {e}");
            ExitCode::FAILURE
        }
    }
}

enum Failure {
    /// A bad command line (exit status 2).
    Usage(String),
    /// A file that could not be read, decoded, detected or written (1).
    Run(String),
}

/// What one image gave.
struct Found {
    gray: Gray,
    segments: Vec<Segment>,
    /// `None` for the float reference, which keeps no summary.
    summary: Option<Summary>,
}

/// Loads and detects one image. Errors name the file.
fn detect_file(path: &Path, args: &Args) -> Result<Found, String> {
    let at = |e: String| format!("{}: {e}", path.display());
    let gray = image::load_gray(path).map_err(at)?;
    let img = gray.image().map_err(|e| at(e.to_string()))?;
    let (segments, summary) = if args.reference {
        let segs = aaglsd::reference::detect(&img, &args.config).map_err(|e| at(e.to_string()))?;
        (segs, None)
    } else {
        let d = aaglsd_support::detect_fixed(&img, &args.config).map_err(|e| at(e.to_string()))?;
        (d.segments, Some(d.summary))
    };
    Ok(Found {
        gray,
        segments,
        summary,
    })
}

/// The segment file's text and extension.
fn output(found: &Found, format: Format) -> (String, &'static str) {
    format.write(found.gray.width, found.gray.height, &found.segments)
}

fn write(path: &Path, contents: &str) -> Result<(), String> {
    std::fs::write(path, contents).map_err(|e| format!("{}: {e}", path.display()))
}

fn create_dir(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))
}

fn stem(path: &Path) -> &str {
    path.file_stem().and_then(|s| s.to_str()).unwrap_or("image")
}

/// The lines `--stats` and an incomplete detection add, after `prefix`.
fn notes(prefix: &str, found: &Found, stats: bool) -> Vec<String> {
    let mut v = Vec::new();
    match found.summary {
        Some(s) if stats => v.push(format!("{prefix}stats: {}", fields::summary_line(&s))),
        None if stats => v.push(format!(
            "{prefix}stats: segments={} (the float reference keeps no Summary)",
            found.segments.len()
        )),
        _ => {}
    }
    if let Some(s) = found.summary.filter(|s| !s.is_complete()) {
        v.push(format!(
            "{prefix}warning: detection incomplete: {}",
            fields::summary_line(&s)
        ));
    }
    v
}

fn run_image(args: &Args) -> Result<(), Failure> {
    let found = detect_file(&args.input, args).map_err(Failure::Run)?;
    let (text, ext) = output(&found, args.format);
    if let Some(dir) = &args.out_dir {
        create_dir(dir).map_err(Failure::Run)?;
        let p = dir.join(format!("{}.{ext}", stem(&args.input)));
        write(&p, &text).map_err(Failure::Run)?;
    } else {
        print!("{text}");
    }
    for line in notes("", &found, args.stats) {
        eprintln!("{line}");
    }
    let n = found.segments.len();
    if let Some(path) = &args.svg {
        write(path, &svg::to_svg(&found.gray, &found.segments)).map_err(Failure::Run)?;
        eprintln!("{n} segments; overlay written to {}", path.display());
    } else {
        eprintln!("{n} segments");
    }
    Ok(())
}

/// Folder mode: every image of the folder, `--jobs` at a time. Each image's
/// file is written by the job that detected it, so the files do not depend
/// on the number of jobs; the messages are printed in file order.
fn run_folder(args: &Args) -> Result<(), Failure> {
    let out = args
        .out_dir
        .as_ref()
        .ok_or_else(|| Failure::Usage("folder mode needs --out-dir".into()))?;
    if args.svg.is_some() {
        return Err(Failure::Usage("--svg takes a single image".into()));
    }
    create_dir(out).map_err(Failure::Run)?;
    let files = image::images_in(&args.input).map_err(Failure::Run)?;
    if files.is_empty() {
        return Err(Failure::Run(format!(
            "{}: no images found",
            args.input.display()
        )));
    }
    let progress = Progress::new(files.len());
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel();
    let (mut failed, mut total) = (0, 0);
    std::thread::scope(|scope| {
        for _ in 0..args.jobs.min(files.len()) {
            let (tx, next, files) = (tx.clone(), &next, &files);
            scope.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(f) = files.get(i) else { return };
                    let r = detect_file(f, args).and_then(|found| {
                        let (text, ext) = output(&found, args.format);
                        write(&out.join(format!("{}.{ext}", stem(f))), &text)?;
                        // The report needs the count and the notes, not the pixels.
                        Ok((found.segments.len(), notes("", &found, args.stats)))
                    });
                    if tx.send((i, r)).is_err() {
                        return;
                    }
                }
            });
        }
        drop(tx);
        // Messages in file order, whatever order the jobs finish in.
        let mut pending = BTreeMap::new();
        let mut shown = 0;
        for (i, r) in rx {
            progress.inc(&files[i].display().to_string());
            pending.insert(i, r);
            while let Some(r) = pending.remove(&shown) {
                let f = files[shown].display();
                shown += 1;
                match r {
                    Ok((n, notes)) => {
                        total += n;
                        if !progress.is_visible() {
                            progress.println(&format!("{f}: {n} segments"));
                        }
                        for line in notes {
                            progress.println(&format!("{f}: {line}"));
                        }
                    }
                    Err(e) => {
                        failed += 1;
                        progress.println(&format!("detect: {e}"));
                    }
                }
            }
        }
    });
    progress.finish();
    eprintln!(
        "{} of {} images detected, {total} segments, written to {}",
        files.len() - failed,
        files.len(),
        out.display()
    );
    if failed > 0 {
        return Err(Failure::Run(format!(
            "{failed} of {} images failed",
            files.len()
        )));
    }
    Ok(())
}
