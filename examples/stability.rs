//! `stability`: the York Urban repeatability harness (issue #14).
//!
//! How far the detections move when the image changes a little: each of
//! `../shared/data/yorkurban/*.jpg` is decoded once to luma (as the accuracy
//! harness does), changed ten ways, and the detector run on the original and
//! on each change. Repeatability is `lseval.py repeat`'s
//! (`../shared/design/evaluation.md`, section 7): the original's segments are the
//! reference (warped by the change's homography, identity but for the
//! shift), λ 0.75, D_c 1 px, D_a 3°; per image the mean over the ten
//! changes, then the mean over images.
//!
//! ```text
//! cargo run --release --example stability                     # Config::DEFAULT, fixed core
//! cargo run --release --example stability -- --quick          # the first 12 images
//! cargo run --release --example stability -- --profile paper --set merge=false --reference
//! cargo run --release --example stability -- --check          # fail below ELSED's 0.712
//! ```
//!
//! Options: `--profile NAME`, `--set FIELD=VALUE` (repeatable), `--reference`
//! (the float reference instead of the fixed core), `--name NAME` (the
//! output folder; by default one made of the options), `--quick`, `--check`,
//! `--pgm` (also write each image the detector saw, `<k>.pgm`).
//!
//! The changes, numbered as their detection files `2.txt` … `11.txt` (the
//! original is `1.txt`), each rounded to nearest (ties away from zero) and
//! clamped to 0..=255 (`aaglsd_support::perturb`):
//!
//! | k | change |
//! |---|---|
//! | 2, 3 | gamma 0.5, 2.0: `255 * (v / 255)^g` (0.5 brightens, 2.0 darkens) |
//! | 4 | contrast x0.5 about mid-grey: `128 + 0.5 * (v - 128)` |
//! | 5, 6 | brightness +40, -40 |
//! | 7, 8 | additive Gaussian noise σ 3, 8: SplitMix64 and Box–Muller, seeded with the FNV-1a hash of `<stem>/<k>` |
//! | 9 | JPEG quality 30 (jpeg-encoder, gray baseline), decoded by the support crate |
//! | 10 | shifted by +1 px in x (column 0 repeated); homography `H_1_10` the translation (+1, 0) |
//! | 11 | 3x3 box blur (mean, border replicated) |
//!
//! Writes `target/stability/<variant>/<stem>/{1..11}.txt` and `H_1_2` …
//! `H_1_11` beside them (each image folder is a sequence of `repeat`, their
//! parent its `--pred`), then runs `lseval.py repeat` once, in-process from a
//! short Python snippet that also records each value `repeat` averages: the
//! per-change column comes from those, and their mean must be the mean
//! `repeat` prints.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use aaglsd::reference::{Quirks, detect_traced};
use aaglsd::{Config, Profile, Segment};
use aaglsd_support::{self as support, Gray, fields, perturb, segments};

/// The images `--quick` keeps.
const QUICK_IMAGES: usize = 12;
/// ELSED's mean repeatability on this measure (issue #14): `--check`'s floor.
const ELSED: f64 = 0.712;
/// The matching thresholds of the measure: λ, D_c (px), D_a (degrees).
const LAMBDA: &str = "0.75";
const DC: &str = "1";
const DA_DEG: &str = "3";

/// One change of the image: its label and how it is made from the original
/// (with the per-image seed the noise uses).
struct Change {
    label: &'static str,
    make: fn(&Gray, u64) -> Result<Gray, String>,
    /// The translation (dx, dy) from the original to the changed image.
    shift: (isize, isize),
}

/// The ten changes, in target order: `CHANGES[i]` is target `i + 2`.
const CHANGES: [Change; 10] = {
    const fn same_frame(
        label: &'static str,
        make: fn(&Gray, u64) -> Result<Gray, String>,
    ) -> Change {
        Change {
            label,
            make,
            shift: (0, 0),
        }
    }
    [
        same_frame("gamma 0.5", |g, _| Ok(perturb::gamma(g, 0.5))),
        same_frame("gamma 2.0", |g, _| Ok(perturb::gamma(g, 2.0))),
        same_frame("contrast x0.5", |g, _| Ok(perturb::contrast(g, 0.5))),
        same_frame("brightness +40", |g, _| Ok(perturb::brightness(g, 40))),
        same_frame("brightness -40", |g, _| Ok(perturb::brightness(g, -40))),
        same_frame("noise σ 3", |g, s| Ok(perturb::gaussian_noise(g, 3.0, s))),
        same_frame("noise σ 8", |g, s| Ok(perturb::gaussian_noise(g, 8.0, s))),
        same_frame("JPEG q30", |g, _| perturb::jpeg_round_trip(g, 30)),
        Change {
            label: "shift +1 px x",
            make: |g, _| Ok(perturb::translate(g, 1, 0)),
            shift: (1, 0),
        },
        same_frame("box blur 3x3", |g, _| Ok(perturb::box_blur3(g))),
    ]
};

/// FNV-1a (64-bit): a fixed, documented hash for the noise seeds, so an
/// image gets the same noise whatever else is run with it.
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xCBF2_9CE4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

struct Options {
    name: Option<String>,
    config: Config,
    /// What `--profile` and `--set` said, in order, for the default name
    /// (`default` first unless a profile came first).
    described: Vec<String>,
    reference: bool,
    quick: bool,
    check: bool,
    pgm: bool,
}

impl Options {
    fn parse(mut args: impl Iterator<Item = String>) -> Result<Self, String> {
        let mut o = Options {
            name: None,
            config: Config::DEFAULT,
            described: Vec::new(),
            reference: false,
            quick: false,
            check: false,
            pgm: false,
        };
        while let Some(a) = args.next() {
            let mut value = || args.next().ok_or(format!("{a} needs a value"));
            match a.as_str() {
                "--profile" => {
                    let p = value()?;
                    o.config = Profile::from_name(&p)
                        .ok_or(format!("unknown profile {p:?}"))?
                        .config();
                    o.described.push(p);
                }
                "--set" => {
                    let kv = value()?;
                    fields::apply_set(&mut o.config, &kv)
                        .map_err(|e| format!("--set {kv}: {e}"))?;
                    if o.described.is_empty() {
                        o.described.push("default".into());
                    }
                    o.described.push(kv);
                }
                "--name" => o.name = Some(value()?),
                "--reference" => o.reference = true,
                "--quick" => o.quick = true,
                "--check" => o.check = true,
                "--pgm" => o.pgm = true,
                _ => return Err(format!("unknown option {a:?}")),
            }
        }
        Ok(o)
    }

    /// `--name`, or the options: `default`, `default merge=true`,
    /// `paper merge=false (reference)`.
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| {
            let mut n = if self.described.is_empty() {
                "default".to_string()
            } else {
                self.described.join(" ")
            };
            if self.reference {
                n.push_str(" (reference)");
            }
            n
        })
    }

    fn detect(&self, g: &Gray) -> Result<Vec<Segment>, String> {
        let img = g.image().map_err(|e| e.to_string())?;
        if self.reference {
            let t = detect_traced(&img, &self.config, Quirks::default());
            return t.map(|t| t.segments).map_err(|e| e.to_string());
        }
        let d = support::detect_fixed(&img, &self.config).map_err(|e| e.to_string())?;
        // A full output or scratch region would cut detections and read as
        // instability: fail rather than score it.
        if !d.summary.is_complete() {
            return Err(format!(
                "detection incomplete: {}",
                fields::summary_line(&d.summary)
            ));
        }
        Ok(d.segments)
    }
}

fn write(path: &Path, contents: impl AsRef<[u8]>) -> Result<(), String> {
    std::fs::write(path, contents).map_err(|e| format!("{}: {e}", path.display()))
}

/// Decodes `image`, detects on it and on its ten changes, and writes
/// `root/<stem>/{1..11}.txt` and `root/<stem>/H_1_{2..11}`: that folder and
/// the eleven segment counts.
fn run_image(o: &Options, image: &Path, root: &Path) -> Result<(PathBuf, [usize; 11]), String> {
    let stem = image
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or(format!("{}: no file stem", image.display()))?;
    let g = &support::load_gray(image).map_err(|e| format!("{}: {e}", image.display()))?;
    let dir = root.join(stem);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut counts = [0; 11];
    for (i, count) in counts.iter_mut().enumerate() {
        let k = i + 1;
        let changed;
        let (img, label) = if k == 1 {
            (g, "original")
        } else {
            let c = &CHANGES[k - 2];
            changed = (c.make)(g, fnv1a(&format!("{stem}/{k}")))
                .map_err(|e| format!("{}: {e}", c.label))?;
            let (dx, dy) = c.shift;
            write(
                &dir.join(format!("H_1_{k}")),
                format!("1 0 {dx}\n0 1 {dy}\n0 0 1\n"),
            )?;
            (&changed, c.label)
        };
        if o.pgm {
            write(&dir.join(format!("{k}.pgm")), img.to_pgm())?;
        }
        let segs = o.detect(img).map_err(|e| format!("{label}: {e}"))?;
        *count = segs.len();
        write(&dir.join(format!("{k}.txt")), segments::to_text(&segs))?;
    }
    Ok((dir, counts))
}

/// [`run_image`] on every image, on as many threads as there are cores
/// (the detections are independent; the order of the result is `images`').
fn run_images(
    o: &Options,
    images: &[PathBuf],
    root: &Path,
) -> Result<Vec<(PathBuf, [usize; 11])>, String> {
    let next = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut done: Vec<_> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads.min(images.len()))
            .map(|_| {
                scope.spawn(|| {
                    let mut mine = Vec::new();
                    while let Some(p) = images.get(next.fetch_add(1, Ordering::Relaxed)) {
                        mine.push((p, run_image(o, p, root)));
                    }
                    mine
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a detection thread panicked"))
            .collect()
    });
    done.sort_by(|a, b| a.0.cmp(b.0));
    done.into_iter()
        .map(|(p, r)| r.map_err(|e| format!("{}: {e}", p.display())))
        .collect()
}

/// Runs `lseval.py repeat` (its `main`, with the arguments after `--`) with
/// its `repeatability` wrapped to print each value it returns, as `value V`
/// after repeat's own output: `run_repeat` calls it once per scored image
/// and target, images in the order given, targets in order, so one run gives
/// both the mean and the per-target values.
const REPEAT_RECORDING: &str = r#"
import importlib.util, sys
spec = importlib.util.spec_from_file_location("lseval", sys.argv[1])
ls = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ls)
values, inner = [], ls.repeatability
def recording(*args, **kwargs):
    values.append(inner(*args, **kwargs))
    return values[-1]
ls.repeatability = recording
ls.main(sys.argv[sys.argv.index("--") + 1:])
for v in values:
    print("value", repr(v))
"#;

/// What `lseval.py repeat` measured.
struct Scores {
    /// Its mean (printed to 3 decimals).
    printed_mean: f64,
    /// Per scored image (those with reference detections), its ten values
    /// in target order.
    per_image: Vec<[f64; 10]>,
}

/// Scores the sequences `seqs`, whose detections are in `pred/<name>/`.
fn score(lseval: &Path, pred: &Path, seqs: &[PathBuf]) -> Result<Scores, String> {
    let out = Command::new("python3")
        .args(["-c", REPEAT_RECORDING])
        .arg(lseval)
        .args(["--", "repeat", "--pred"])
        .arg(pred)
        .arg("--seqs")
        .args(seqs)
        // `--prefix ''`: every folder given is a sequence (expand_seqs
        // keeps a folder whose name starts with the prefix as it is).
        .args(["--prefix", "", "--targets"])
        .args((2..=11).map(|k| k.to_string()))
        .args(["--lambda", LAMBDA, "--dc", DC, "--da-deg", DA_DEG])
        .output()
        .map_err(|e| format!("python3: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(format!(
            "lseval.py repeat failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    // Repeat's warnings (an image without reference detections, left out).
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    let bad = || format!("unexpected lseval.py repeat output:\n{text}");
    // "repeatability over N sequences ...", the column header, then
    // "lambda D_c rep".
    let images: usize = text
        .lines()
        .find_map(|l| l.strip_prefix("repeatability over "))
        .and_then(|l| l.split_whitespace().next()?.parse().ok())
        .ok_or_else(bad)?;
    let printed_mean = text
        .lines()
        .rfind(|l| !l.starts_with("value "))
        .and_then(|l| l.split_whitespace().nth(2)?.parse().ok())
        .ok_or_else(bad)?;
    let values = text
        .lines()
        .filter_map(|l| l.strip_prefix("value "))
        .map(|v| v.parse::<f64>().map_err(|_| bad()))
        .collect::<Result<Vec<_>, _>>()?;
    if values.len() != images * 10 {
        return Err(format!(
            "lseval.py repeat returned {} values for {images} images and 10 targets",
            values.len()
        ));
    }
    let per_image = values
        .chunks_exact(10)
        .map(|c| c.try_into().expect("chunks of 10"))
        .collect();
    Ok(Scores {
        printed_mean,
        per_image,
    })
}

fn mean(v: impl IntoIterator<Item = f64>) -> f64 {
    let (sum, n) = v
        .into_iter()
        .fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

fn main() -> ExitCode {
    if let Err(e) = run() {
        eprintln!("stability: {e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

fn run() -> Result<(), String> {
    let o = Options::parse(std::env::args().skip(1))?;
    let (data, lseval) = support::data::york_urban_and_lseval()?;
    let mut images = support::images_in(&data)?;
    if o.quick {
        images.truncate(QUICK_IMAGES);
    }
    let name = o.name();
    let slug: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let root = support::data::repo_root()
        .join("target/stability")
        .join(slug);
    // Stale images of an earlier, longer run would not be scored (the
    // sequences are passed by name) but would mislead whoever reads them.
    if root.exists() {
        std::fs::remove_dir_all(&root).map_err(|e| format!("{}: {e}", root.display()))?;
    }

    let started = Instant::now();
    let (seqs, counts): (Vec<PathBuf>, Vec<[usize; 11]>) =
        run_images(&o, &images, &root)?.into_iter().unzip();
    let detected = started.elapsed();
    let s = score(&lseval, &root, &seqs)?;
    eprintln!(
        "stability: {} images, detection {:.1} s, scoring {:.1} s",
        images.len(),
        detected.as_secs_f64(),
        (started.elapsed() - detected).as_secs_f64()
    );

    let n = s.per_image.len();
    let per_target: Vec<f64> = (0..10)
        .map(|i| mean(s.per_image.iter().map(|v| v[i])))
        .collect();
    // Repeat's mean: per image over the ten targets, then over images.
    let overall = mean(s.per_image.iter().map(|v| mean(v.iter().copied())));
    if (overall - s.printed_mean).abs() > 0.0005 + 1e-9 {
        return Err(format!(
            "the recorded values average {overall:.4}, lseval.py repeat printed {:.3}",
            s.printed_mean
        ));
    }
    let segs = |k: usize| mean(counts.iter().map(|c| c[k] as f64));

    println!(
        "Stability: {name}, York Urban, {n} images; repeatability against the original's \
         detections (lseval.py repeat: λ {LAMBDA}, D_c {DC} px, D_a {DA_DEG}°)\n"
    );
    println!("| change | repeatability | segments (mean per image) |");
    println!("|---|---|---|");
    println!("| original | | {:.1} |", segs(0));
    for (i, c) in CHANGES.iter().enumerate() {
        println!(
            "| {} | {:.3} | {:.1} |",
            c.label,
            per_target[i],
            segs(i + 1)
        );
    }
    println!(
        "| mean of the 10 | {overall:.3} | {:.1} |",
        mean((1..=10).map(segs))
    );
    if o.check && overall < ELSED {
        return Err(format!(
            "mean repeatability {overall:.3} is below ELSED's {ELSED}"
        ));
    }
    Ok(())
}
