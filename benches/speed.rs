//! Speed benchmark (plain harness): `cargo bench --bench speed`.
//!
//! Times, per York Urban image and with `Config::DEFAULT`, the fixed-point
//! core (on a workspace of `Workspace::bytes_needed_fast` bytes, and again
//! on one of `bytes_needed`, without the group index), the float
//! reference, the blur + gradient floor, the core's front end (everything
//! before the linking: `detect_part(Part::FrontEnd, ..)`), and (through
//! `benches/opencv_speed.py`, in-process in Python) OpenCV's LSD and
//! EdgeDrawing/EDLines, and ELSED (`pyelsed.detect` with its defaults) where
//! its Python module imports. Every image is decoded once before any timing; each
//! method gets one warm-up run then `REPS` timed runs per image, the median
//! of those, then the median over images. The methods are interleaved image
//! by image (the Python process times image `i` when asked), so load from
//! elsewhere affects every row alike. Everything runs on one thread. The
//! headline ratio is issue #14's: the median over images of each image's
//! time ratio to EDLines (the table's ratios divide the medians), and
//! likewise to ELSED when it ran.
//!
//! Environment:
//! - `AAGLSD_BENCH_DATA` (or the first non-flag argument): the image folder,
//!   default `../shared/data/yorkurban` relative to the crate root;
//! - `AAGLSD_BENCH_IMAGES=N`: only the first `N` images (e.g. for profiling);
//! - `AAGLSD_BENCH_REPS=N`: timed repetitions per image (default 7);
//! - `AAGLSD_BENCH_ONLY=fixed,compact,reference,floor,front,opencv`: a subset of methods
//!   (`opencv` is every Python-timed peer, ELSED included);
//! - `AAGLSD_BENCH_ELSED_PY=DIR`: a folder holding ELSED's Python module `pyelsed`
//!   (a build of its own; without one importable there is no ELSED row);
//! - `AAGLSD_BENCH_PROFILE=official|paper`, `AAGLSD_BENCH_SET="field=value ..."`:
//!   another configuration than `Config::DEFAULT`.

use aaglsd_support as support;
use std::hint::black_box;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::time::Instant;

use aaglsd::{Config, Part, Segment, Workspace};

const DEFAULT_REPS: usize = 7;
const OUTPUT_SLOTS: usize = 20_000;

fn env_usize(name: &str) -> Option<usize> {
    let v = std::env::var(name).ok()?;
    match v.trim().parse() {
        Ok(n) => Some(n),
        Err(_) => {
            eprintln!("warning: ignoring {name}={v:?} (not a number)");
            None
        }
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// One warm-up call, then the median of `reps` timed calls, in ms.
fn time_median(reps: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    median(&mut t)
}

/// The number after `"key":` in a flat JSON object.
fn json_number(json: &str, key: &str) -> Option<f64> {
    let pat = format!("\"{key}\"");
    let rest = &json[json.find(&pat)? + pat.len()..];
    let rest = rest.trim_start().strip_prefix(':')?.trim_start();
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
        .unwrap_or(rest.len());
    rest[..end].parse().ok()
}

/// The string after `"key":` in a flat JSON object (no escapes).
fn json_string(json: &str, key: &str) -> Option<String> {
    let pat = format!("\"{key}\"");
    let rest = &json[json.find(&pat)? + pat.len()..];
    let rest = rest.trim_start().strip_prefix(':')?.trim_start();
    Some(rest.strip_prefix('"')?.split('"').next()?.to_string())
}

/// `benches/opencv_speed.py --serve`: decodes the same images itself, then
/// times LSD and EDLines (and ELSED if it has it) on the image index it is
/// sent, so that the Rust and Python timings of each image are taken back
/// to back.
struct OpenCv {
    child: Child,
    stdin: Option<ChildStdin>,
    stdout: BufReader<ChildStdout>,
    version: String,
    /// The version of the OpenCV that ELSED links, if ELSED is timed.
    elsed: Option<String>,
}

/// One image's OpenCV (and ELSED) medians (ms) and segment counts.
struct OpenCvTimes {
    lsd_ms: f64,
    ed_ms: f64,
    lsd_segments: usize,
    ed_segments: usize,
    elsed: Option<(f64, usize)>,
}

impl OpenCv {
    fn start(dir: &Path, images: usize, reps: usize) -> Result<Self, String> {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/opencv_speed.py");
        let mut child = Command::new("python3")
            .arg(&script)
            .arg(dir)
            .arg(images.to_string())
            .arg(reps.to_string())
            .arg("--serve")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(|e| format!("cannot run python3: {e}"))?;
        let (Some(stdin), Some(stdout)) = (child.stdin.take(), child.stdout.take()) else {
            return Err("no pipes to python3".into());
        };
        let mut cv = OpenCv {
            child,
            stdin: Some(stdin),
            stdout: BufReader::new(stdout),
            version: String::new(),
            elsed: None,
        };
        let ready = cv.read_line()?;
        if json_number(&ready, "images").map(|n| n as usize) != Some(images) {
            return Err(format!(
                "{} decoded a different image set: {ready}",
                script.display()
            ));
        }
        if json_number(&ready, "threads") != Some(1.0) {
            eprintln!("warning: OpenCV does not report a single thread: {ready}");
        }
        cv.version = json_string(&ready, "opencv").unwrap_or_else(|| "?".into());
        cv.elsed = json_string(&ready, "elsed_opencv");
        if cv.elsed.is_some() && json_number(&ready, "elsed_threads") != Some(1.0) {
            eprintln!("warning: ELSED's OpenCV does not report a single thread: {ready}");
        }
        Ok(cv)
    }

    fn read_line(&mut self) -> Result<String, String> {
        let mut line = String::new();
        match self.stdout.read_line(&mut line) {
            Ok(0) => Err(format!(
                "opencv_speed.py exited ({}), see its messages above",
                self.child
                    .wait()
                    .map_or_else(|e| e.to_string(), |s| s.to_string())
            )),
            Ok(_) => Ok(line),
            Err(e) => Err(format!("reading from opencv_speed.py: {e}")),
        }
    }

    fn time_image(&mut self, i: usize) -> Result<OpenCvTimes, String> {
        let stdin = self.stdin.as_mut().ok_or("python3 stdin closed")?;
        writeln!(stdin, "{i}")
            .and_then(|()| stdin.flush())
            .map_err(|e| format!("writing to opencv_speed.py: {e}"))?;
        let line = self.read_line()?;
        let get = |k: &str| {
            json_number(&line, k).ok_or_else(|| format!("no {k} in opencv_speed.py output: {line}"))
        };
        if get("i")? as usize != i {
            return Err(format!(
                "opencv_speed.py answered for another image: {line}"
            ));
        }
        Ok(OpenCvTimes {
            lsd_ms: get("lsd_ms")?,
            ed_ms: get("edlines_ms")?,
            lsd_segments: get("lsd_segments")? as usize,
            ed_segments: get("edlines_segments")? as usize,
            elsed: match self.elsed {
                Some(_) => Some((get("elsed_ms")?, get("elsed_segments")? as usize)),
                None => None,
            },
        })
    }
}

impl Drop for OpenCv {
    fn drop(&mut self) {
        // Closing stdin ends the script's loop.
        drop(self.stdin.take());
        let _ = self.child.wait();
    }
}

fn opencv_note(e: &str) {
    eprintln!();
    eprintln!("=== NOTE: OpenCV rows skipped: {e} ===");
    eprintln!("=== (needs python3 with opencv-contrib-python; Rust rows only) ===");
    eprintln!();
}

/// The 1-minute load average (Linux), to flag a busy machine.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

struct Row {
    name: String,
    ms: f64,
    segments: Option<usize>,
}

fn main() {
    let default_dir = support::data::shared_location().join("data/yorkurban");
    let dir: PathBuf = std::env::var_os("AAGLSD_BENCH_DATA")
        .map(PathBuf::from)
        .or_else(|| {
            std::env::args()
                .skip(1)
                .find(|a| !a.starts_with('-'))
                .map(PathBuf::from)
        })
        .unwrap_or(default_dir);
    let reps = env_usize("AAGLSD_BENCH_REPS")
        .unwrap_or(DEFAULT_REPS)
        .max(1);
    let only = std::env::var("AAGLSD_BENCH_ONLY").unwrap_or_default();
    let want = |m: &str| only.is_empty() || only.split(',').any(|s| s.trim() == m);

    let mut paths = match support::images_in(&dir) {
        Ok(p) if !p.is_empty() => p,
        Ok(_) | Err(_) => {
            support::data::skip(
                "speed benchmark",
                &format!(
                    "no images in {} (set AAGLSD_BENCH_DATA or pass the folder as an argument)",
                    dir.display()
                ),
            );
            return;
        }
    };
    if let Some(n) = env_usize("AAGLSD_BENCH_IMAGES").filter(|&n| n > 0) {
        paths.truncate(n);
    }

    let load_before = load_average();
    // Decode everything once, before any timing.
    let images: Vec<support::Gray> = paths
        .iter()
        .map(|p| support::load_gray(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
        .collect();
    let mut sizes: Vec<String> = images
        .iter()
        .map(|g| format!("{}x{}", g.width, g.height))
        .collect();
    sizes.sort();
    sizes.dedup();

    // AAGLSD_BENCH_PROFILE=name and AAGLSD_BENCH_SET="field=value ..."
    // time another configuration (the README's row is the default).
    let mut cfg = match std::env::var("AAGLSD_BENCH_PROFILE") {
        Ok(name) => aaglsd::Profile::from_name(&name)
            .unwrap_or_else(|| panic!("AAGLSD_BENCH_PROFILE: unknown profile {name:?}"))
            .config(),
        Err(_) => Config::DEFAULT,
    };
    let mut label = String::from("Config::DEFAULT");
    if let Ok(name) = std::env::var("AAGLSD_BENCH_PROFILE") {
        label = format!("profile {name}");
    }
    if let Ok(set) = std::env::var("AAGLSD_BENCH_SET") {
        for a in set.split_whitespace() {
            support::fields::apply_set(&mut cfg, a)
                .unwrap_or_else(|e| panic!("AAGLSD_BENCH_SET {a:?}: {e}"));
        }
        label = format!("{label} with {set}");
    }
    let max_bytes = images
        .iter()
        .map(|g| Workspace::bytes_needed_fast(g.width, g.height, &cfg).expect("image too large"))
        .max()
        .unwrap_or(0);
    // Allocated once, outside every timed region.
    let mut slab = vec![0u8; max_bytes];
    let mut out = vec![Segment::default(); OUTPUT_SLOTS];

    // OpenCV runs in a python3 process started now (its own decoding is
    // not timed) and is driven image by image, interleaved with the Rust
    // methods, so that a change in machine load affects every row alike.
    let mut opencv = if want("opencv") {
        OpenCv::start(&dir, images.len(), reps)
            .map_err(|e| opencv_note(&e))
            .ok()
    } else {
        None
    };

    let (mut t_fixed, mut t_ref, mut t_floor) = (Vec::new(), Vec::new(), Vec::new());
    let mut t_front = Vec::new();
    let (mut t_compact, mut n_compact) = (Vec::new(), 0);
    let (mut t_lsd, mut t_ed, mut t_elsed) = (Vec::new(), Vec::new(), Vec::new());
    let (mut n_fixed, mut n_ref, mut n_lsd, mut n_ed, mut n_elsed) = (0, 0, 0, 0, 0);
    let mut incomplete = 0usize;
    for (i, g) in images.iter().enumerate() {
        let img = g.image().expect("a test image within the core's limits");
        if want("fixed") {
            let mut last = None;
            t_fixed.push(time_median(reps, || {
                let s = aaglsd::detect(
                    black_box(&img),
                    &cfg,
                    &mut Workspace::new(&mut slab),
                    &mut out,
                )
                .expect("detect");
                last = Some(black_box(s));
            }));
            if let Some(s) = last {
                n_fixed += s.segments;
                incomplete += usize::from(!s.is_complete());
            }
        }
        if want("compact") {
            // The same call on a workspace of `bytes_needed` bytes: no
            // group index.
            let n = Workspace::bytes_needed(g.width, g.height, &cfg).expect("image too large");
            let mut last = 0;
            t_compact.push(time_median(reps, || {
                let s = aaglsd::detect(
                    black_box(&img),
                    &cfg,
                    &mut Workspace::new(&mut slab[..n]),
                    &mut out,
                )
                .expect("detect");
                last = black_box(s).segments;
            }));
            n_compact += last;
        }
        if want("reference") {
            let mut last = 0;
            t_ref.push(time_median(reps, || {
                let v = aaglsd::reference::detect(black_box(&img), &cfg).expect("reference");
                last = black_box(v).len();
            }));
            n_ref += last;
        }
        if want("floor") {
            t_floor.push(time_median(reps, || {
                let sum = aaglsd::detect_part(
                    Part::Floor,
                    black_box(&img),
                    &cfg,
                    &mut Workspace::new(&mut slab),
                )
                .expect("floor");
                black_box(sum);
            }));
        }
        if want("front") {
            t_front.push(time_median(reps, || {
                let img = black_box(&img);
                let groups =
                    aaglsd::detect_part(Part::FrontEnd, img, &cfg, &mut Workspace::new(&mut slab))
                        .expect("front end");
                black_box(groups);
            }));
        }
        if let Some(cv) = opencv.as_mut() {
            match cv.time_image(i) {
                Ok(t) => {
                    t_lsd.push(t.lsd_ms);
                    t_ed.push(t.ed_ms);
                    n_lsd += t.lsd_segments;
                    n_ed += t.ed_segments;
                    if let Some((ms, n)) = t.elsed {
                        t_elsed.push(ms);
                        n_elsed += n;
                    }
                }
                Err(e) => {
                    opencv_note(&e);
                    opencv = None;
                }
            }
        }
    }
    let version = opencv.as_ref().map(|cv| cv.version.clone());
    let elsed_version = opencv.as_ref().and_then(|cv| cv.elsed.clone());
    drop(opencv);

    // Issue #14's protocol: the median over images of each image's time
    // ratio (the methods ran on the same image back to back). Computed
    // before the medians below sort the time lists.
    let per_image = |t: &[f64], peer: &[f64]| -> Option<f64> {
        (!t.is_empty() && t.len() == peer.len()).then(|| {
            let mut r: Vec<f64> = t.iter().zip(peer).map(|(a, b)| a / b).collect();
            median(&mut r)
        })
    };
    let fixed_per_image = per_image(&t_fixed, &t_ed);
    let compact_per_image = per_image(&t_compact, &t_ed);
    let fixed_per_elsed = elsed_version
        .as_ref()
        .and_then(|_| per_image(&t_fixed, &t_elsed));

    let mut rows: Vec<Row> = Vec::new();
    let mut push = |name: String, t: &mut Vec<f64>, segments: Option<usize>| {
        if !t.is_empty() {
            rows.push(Row {
                name,
                ms: median(t),
                segments,
            });
        }
    };
    push(
        "aaglsd fixed core (`detect`)".into(),
        &mut t_fixed,
        Some(n_fixed),
    );
    push(
        "aaglsd fixed core, smaller workspace (`detect`, `bytes_needed`)".into(),
        &mut t_compact,
        Some(n_compact),
    );
    push(
        "aaglsd float reference (`reference::detect`)".into(),
        &mut t_ref,
        Some(n_ref),
    );
    push(
        "floor: blur + gradient (`Part::Floor`)".into(),
        &mut t_floor,
        None,
    );
    push(
        "front end: `detect` before the linking (`Part::FrontEnd`)".into(),
        &mut t_front,
        None,
    );
    // Only complete OpenCV series (an error midway drops both rows).
    if let Some(v) = &version {
        push(
            format!("OpenCV {v} LSD (`lsd.detect`)"),
            &mut t_lsd,
            Some(n_lsd),
        );
        push(
            format!("OpenCV {v} EDLines (`detectEdges` + `detectLines`)"),
            &mut t_ed,
            Some(n_ed),
        );
    }
    if let (Some(_), Some(v)) = (&version, &elsed_version) {
        push(
            format!("ELSED (`pyelsed.detect`, its defaults; on OpenCV {v})"),
            &mut t_elsed,
            Some(n_elsed),
        );
    }
    let med = |t: &mut Vec<f64>| (!t.is_empty()).then(|| median(t));
    let fixed_ms = med(&mut t_fixed);
    let floor_ms = med(&mut t_floor);
    let front_ms = med(&mut t_front);
    let ed_ms = version.as_ref().and_then(|_| med(&mut t_ed));

    let ratio = |a: f64, b: Option<f64>| match b {
        Some(b) if b > 0.0 => format!("{:.2}", a / b),
        _ => "n/a".to_string(),
    };
    println!();
    println!(
        "aaglsd speed: {} images ({}) from {}, {} timed repetitions per image after 1 warm-up,",
        images.len(),
        sizes.join(", "),
        dir.display(),
        reps
    );
    println!(
        "median per image, then median over images; methods interleaved image by image; single-threaded"
    );
    println!(
        "(Rust: one thread; OpenCV: in-process in python3, cv2.setNumThreads(1), decoding not timed); {label}."
    );
    if elsed_version.is_some() {
        println!(
            "(ELSED: pyelsed in the same python3 process; the OpenCV it links set to one thread too.)"
        );
    }
    println!();
    println!("| method | median ms / image | / EDLines | / floor | segments (all images) |");
    println!("|---|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {:.3} | {} | {} | {} |",
            r.name,
            r.ms,
            ratio(r.ms, ed_ms),
            ratio(r.ms, floor_ms),
            r.segments.map_or("-".to_string(), |s| s.to_string())
        );
    }
    println!();
    if let Some(r) = fixed_per_image {
        println!("fixed core / EDLines, median of the per-image ratios = {r:.3} (target <= 0.70)");
    }
    if let Some(r) = fixed_per_elsed {
        println!("fixed core / ELSED, median of the per-image ratios = {r:.3}");
    }
    if let Some(r) = compact_per_image {
        println!("smaller workspace / EDLines, median of the per-image ratios = {r:.3}");
    }
    if let Some(f) = fixed_ms {
        println!(
            "fixed core / EDLines = {} (ratio of the medians)",
            ratio(f, ed_ms)
        );
        println!("fixed core / floor = {}", ratio(f, floor_ms));
    }
    if let Some(fr) = front_ms {
        println!(
            "front end / EDLines = {} (what the core costs before linking one seed)",
            ratio(fr, ed_ms)
        );
        if let Some(f) = fixed_ms.filter(|&f| f > 0.0) {
            println!(
                "linking, validation and merging: {:.3} ms per image, {:.0}% of the core",
                f - fr,
                100.0 * (f - fr) / f
            );
        }
    }
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    if let (Some(a), Some(b)) = (load_before, load_average()) {
        println!("load average (1 min) before {a:.2}, after {b:.2}, on {cores} core(s)");
        if a.max(b) > 0.5 * cores as f64 {
            println!(
                "WARNING: the machine was busy: absolute times are inflated; the methods are interleaved per image, so ratios suffer less"
            );
        }
    }
    if incomplete > 0 {
        println!(
            "note: {incomplete} image(s) had an incomplete fixed-core detection (dropped segments or candidates)"
        );
    }
}
