//! `worst_case`: the detector's work counters on the adversarial corpus
//! (`aaglsd_support::corpus`) against those on York Urban.
//!
//! ```text
//! cargo run --release --example worst_case                     # the tables
//! cargo run --release --example worst_case -- --size 320x240 --all
//! cargo run --release --example worst_case -- --write DIR      # DIR/<pattern>.pgm only
//! bash benches/worst_case.sh [--quick]                         # instructions per pixel
//! ```
//!
//! For every profile, runs the fixed-point core on every corpus pattern
//! (640x480 unless `--size`) and on the York Urban images (`data/yorkurban`
//! of the dataset, `../shared` or `$AAGLSD_SHARED`; skipped when absent),
//! and prints a table of the `Summary` counters and the wall time: the York
//! median and maximum, the corpus pattern with the largest value, and that
//! value over the York median, per pixel (so the ratio stays meaningful
//! with `--size`). `--all` adds every pattern's work, segments and time.
//!
//! Why: on natural images the work is bounded by the edges present; the
//! corpus is made of what makes it unbounded (dense, short, periodic or
//! random edges). The counters here are exact and quick; instruction
//! counts, which the counters should track, come from the callgrind
//! script `benches/worst_case.sh`, which runs the CLI on the files
//! `--write` makes.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use aaglsd::{Profile, Summary};
use aaglsd_support::{Gray, corpus, data, fields};

const USAGE: &str = "usage: worst_case [--size WxH] [--all] [--write DIR]
  --size WxH   corpus image size (default 640x480)
  --all        also print every pattern's work, segments and time
  --write DIR  write the corpus as DIR/<pattern>.pgm and exit";

struct Args {
    size: (usize, usize),
    all: bool,
    write: Option<PathBuf>,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        size: (640, 480),
        all: false,
        write: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--all" => a.all = true,
            "--write" => a.write = Some(PathBuf::from(value("--write")?)),
            "--size" => {
                let v = value("--size")?;
                let dims = v
                    .split_once('x')
                    .and_then(|(w, h)| Some((w.parse::<usize>().ok()?, h.parse::<usize>().ok()?)));
                a.size = dims
                    .filter(|&(w, h)| w > 0 && h > 0)
                    .ok_or(format!("--size wants WxH, got {v:?}"))?;
            }
            "-h" | "--help" => return Err(String::new()),
            s => return Err(format!("unknown argument {s:?}")),
        }
    }
    Ok(a)
}

/// One detection: its summary and its wall time in ms.
#[derive(Clone, Copy, Default)]
struct Run {
    summary: Summary,
    ms: f64,
}

impl Run {
    /// The table's counters: every `Summary` field, then the time.
    fn counters(&self) -> Vec<(&'static str, f64)> {
        let mut v: Vec<_> = fields::summary_fields(&self.summary)
            .iter()
            .map(|&(n, x)| (n, x as f64))
            .collect();
        v.push(("time_ms", self.ms));
        v
    }
}

fn run(g: &Gray, profile: Profile) -> Run {
    let img = g
        .image()
        .expect("corpus and York images are within the limits");
    let t0 = Instant::now();
    let d = aaglsd_support::detect_fixed(&img, &profile.config()).expect("valid profile");
    Run {
        summary: d.summary,
        ms: t0.elapsed().as_secs_f64() * 1e3,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

fn num(v: f64) -> String {
    match v {
        v if v.is_nan() => "-".into(),
        v if v.fract() == 0.0 => format!("{v}"),
        v => format!("{v:.1}"),
    }
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("worst_case: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    let (w, h) = args.size;
    let patterns: Vec<(&str, Gray)> = corpus::patterns()
        .iter()
        .map(|p| {
            (
                p.name,
                Gray {
                    width: w,
                    height: h,
                    data: p.render(w, h),
                },
            )
        })
        .collect();
    if let Some(dir) = &args.write {
        let written = std::fs::create_dir_all(dir).and_then(|()| {
            for (name, g) in &patterns {
                std::fs::write(dir.join(format!("{name}.pgm")), g.to_pgm())?;
            }
            Ok(())
        });
        if let Err(e) = written {
            eprintln!("worst_case: {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
        eprintln!("{} patterns written to {}", patterns.len(), dir.display());
        return ExitCode::SUCCESS;
    }

    let york_dir = data::shared_location().join("data/yorkurban");
    let york: Vec<Gray> = aaglsd_support::images_in(&york_dir)
        .unwrap_or_default()
        .iter()
        .map(|p| aaglsd_support::load_gray(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
        .collect();
    if york.is_empty() {
        data::skip(
            "York Urban columns",
            &format!("no images in {}", york_dir.display()),
        );
    }
    let york_px = york.first().map_or(1.0, |g| (g.width * g.height) as f64);
    let corpus_px = (w * h) as f64;
    println!(
        "Corpus: {} patterns at {w}x{h}; York Urban: {} images.\n",
        patterns.len(),
        york.len()
    );

    let mut per_pattern = Vec::new();
    for profile in Profile::ALL {
        let on_york: Vec<Run> = york.iter().map(|g| run(g, profile)).collect();
        let on_corpus: Vec<Run> = patterns.iter().map(|(_, g)| run(g, profile)).collect();
        println!("### Profile `{}`\n", profile.name());
        println!("| counter | York median | York max | worst pattern | its value | ratio per px |");
        println!("|---|---|---|---|---|---|");
        for (row, (counter, _)) in Run::default().counters().into_iter().enumerate() {
            let york_values: Vec<f64> = on_york.iter().map(|r| r.counters()[row].1).collect();
            let york_max = york_values.iter().copied().fold(f64::NAN, f64::max);
            let york_median = median(york_values);
            // The first pattern with the largest value; none when all are 0.
            let (mut worst, mut value) = ("-", 0.0);
            for (r, (name, _)) in on_corpus.iter().zip(&patterns) {
                let v = r.counters()[row].1;
                if v > value {
                    (worst, value) = (name, v);
                }
            }
            let ratio = (value / corpus_px) / (york_median / york_px);
            let ratio = if ratio.is_finite() {
                format!("{ratio:.1}")
            } else {
                "-".into()
            };
            println!(
                "| {counter} | {} | {} | {worst} | {} | {ratio} |",
                num(york_median),
                num(york_max),
                num(value),
            );
        }
        println!();
        per_pattern.push(on_corpus);
    }

    if args.all {
        print!("| pattern |");
        for p in Profile::ALL {
            print!(" {0} work | {0} segments | {0} ms |", p.name());
        }
        println!("\n|---|{}", "---|---|---|".repeat(Profile::ALL.len()));
        for (i, (name, _)) in patterns.iter().enumerate() {
            print!("| {name} |");
            for runs in &per_pattern {
                let r = runs[i];
                print!(
                    " {} | {} | {:.1} |",
                    r.summary.work, r.summary.segments, r.ms
                );
            }
            println!();
        }
    }
    ExitCode::SUCCESS
}
