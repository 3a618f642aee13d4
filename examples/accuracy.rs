//! `accuracy`: the York Urban accuracy harness.
//!
//! Runs detector variants over `../shared/data/yorkurban/*.jpg`, writes one
//! prediction file per image to `target/accuracy/<variant>/<stem>.txt`, scores
//! each variant with `python3 ../shared/tools/lseval.py` against both ground
//! truths (`.yud.txt`, `.yuld.txt`; pooled, D_c = 1 px, D_a = 3°, λ = 0.5 and
//! 0.9) and prints one table of F-scores (`--full`: AP, AR, IoU too).
//!
//! Each variant is scored, like every peer in the comparison protocol, at its
//! best frame shift: `--pred-shift S S` for S in -1, -0.5 and 0, chosen per
//! ground truth by F at λ 0.9; the table prints the shift. (The annotations
//! of the two ground truths sit in different half-pixel frames.)
//!
//! ```text
//! cargo run --release --example accuracy                 # the README table
//! cargo run --release --example accuracy -- --quick      # default profile only
//! cargo run --release --example accuracy -- --profile paper --set merge=false --reference
//! cargo run --release --example accuracy -- --quick --check  # CI: fail below the official scores
//! cargo run --release --example accuracy -- --quick --ranked # the README's ranking table
//! ```
//!
//! `--ranked` also scores each variant as a ranking (`lseval.py --score-col
//! 4`, at the shift chosen above): the area under the pooled
//! precision-recall curve swept over the segments' score (AP) and the best
//! F over score thresholds (F-max), at λ 0.5 and 0.9, ranked by the score
//! and, for comparison, by length; and the share of segments of 10 px or
//! more whose brighter side is on their left ([`brighter_left`]).
//!
//! `--check` fails when the first variant (the default profile on the fixed
//! core) scores below the official AAGLSD output on any column
//! (YUD 0.276 / 0.161, YULD 0.404 / 0.221: the issue's "must").

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use aaglsd::reference::{Quirks, detect_traced};
use aaglsd::{Config, Profile, Segment};
use aaglsd_support::{self as support, fields, segments};

/// F-scores of the official AAGLSD output on these 51 images (the floor
/// `--check` enforces): YUD λ 0.5, 0.9; YULD λ 0.5, 0.9.
const OFFICIAL_F: [(&str, f64); 4] = [
    ("YUD λ0.5", 0.276),
    ("YUD λ0.9", 0.161),
    ("YULD λ0.5", 0.404),
    ("YULD λ0.9", 0.221),
];

#[derive(Clone)]
struct Variant {
    name: String,
    config: Config,
    reference: bool,
    quirks: Quirks,
}

fn readme_variants() -> Vec<Variant> {
    let v = |name: &str, config: Config, reference: bool, quirks: Quirks| Variant {
        name: name.to_string(),
        config,
        reference,
        quirks,
    };
    let bug = Quirks {
        orientation_bug: true,
        ..Quirks::default()
    };
    let official_frame = Quirks {
        orientation_bug: true,
        official_frame: true,
    };
    let no_merge = Config {
        merge: false,
        ..Config::PAPER
    };
    vec![
        v(
            "default (fixed core)",
            Config::DEFAULT,
            false,
            Quirks::default(),
        ),
        v(
            "default (reference)",
            Config::DEFAULT,
            true,
            Quirks::default(),
        ),
        v(
            "official profile",
            Config::OFFICIAL,
            true,
            Quirks::default(),
        ),
        v("official, orientation bug", Config::OFFICIAL, true, bug),
        v(
            "official, bug, official frame",
            Config::OFFICIAL,
            true,
            official_frame,
        ),
        v("paper profile", Config::PAPER, true, Quirks::default()),
        v("paper, merging off", no_merge, true, Quirks::default()),
    ]
}

fn detect(v: &Variant, img: &support::Gray) -> Result<Vec<Segment>, aaglsd::Error> {
    let img = img.image()?;
    if v.reference {
        detect_traced(&img, &v.config, v.quirks).map(|t| t.segments)
    } else {
        let d = support::detect_fixed(&img, &v.config)?;
        if !d.summary.is_complete() {
            eprintln!(
                "warning: detection incomplete: {}",
                fields::summary_line(&d.summary)
            );
        }
        Ok(d.segments)
    }
}

/// The frame shifts of the protocol, in pixels.
const SHIFTS: [&str; 3] = ["-1", "-0.5", "0"];

/// [`score`] at each of [`SHIFTS`]: the shift with the best F at λ 0.9, and
/// its scores.
fn score_best(
    lseval: &Path,
    gt: &Path,
    suffix: &str,
    pred: &Path,
) -> Result<(&'static str, [[f64; 4]; 2]), String> {
    let mut best: Option<(&str, [[f64; 4]; 2])> = None;
    for shift in SHIFTS {
        let s = score(lseval, gt, suffix, pred, shift)?;
        if best.is_none_or(|(_, b)| s[1][3] > b[1][3]) {
            best = Some((shift, s));
        }
    }
    best.ok_or_else(|| "no shift scored".to_string())
}

/// lseval's CSV rows (those starting `0.`, one per λ: 0.5 and 0.9) for
/// `pred` against `gt`, the predictions shifted by `shift` px on both axes,
/// with `extra` arguments; each row at least `width` numbers.
fn lseval_rows(
    lseval: &Path,
    (gt, suffix): (&Path, &str),
    pred: &Path,
    shift: &str,
    extra: &[&str],
    width: usize,
) -> Result<Vec<Vec<f64>>, String> {
    let out = Command::new("python3")
        .arg(lseval)
        .args(["--gt"])
        .arg(gt)
        .args(["--gt-suffix", suffix, "--pred"])
        .arg(pred)
        .args([
            "--lambda", "0.5", "0.9", "--dc", "1", "--da-deg", "3", "--csv",
        ])
        .args(["--pred-shift", shift, shift])
        .args(extra)
        .output()
        .map_err(|e| format!("python3: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| l.starts_with("0."))
        .map(|l| l.split(',').filter_map(|s| s.parse().ok()).collect())
        .collect();
    if !out.status.success() || rows.len() != 2 || rows.iter().any(|r| r.len() < width) {
        return Err(format!(
            "unexpected lseval output:\n{text}{}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(rows)
}

/// lseval's CSV: `lambda,AP,AR,IoU,F` rows -> [[AP, AR, IoU, F]; 2], with
/// the predictions shifted by `shift` px on both axes.
fn score(
    lseval: &Path,
    gt: &Path,
    suffix: &str,
    pred: &Path,
    shift: &str,
) -> Result<[[f64; 4]; 2], String> {
    let rows = lseval_rows(lseval, (gt, suffix), pred, shift, &[], 5)?;
    let r = |k: usize| [rows[k][1], rows[k][2], rows[k][3], rows[k][4]];
    Ok([r(0), r(1)])
}

/// lseval's ranking CSV (`--score-col 4`): `lambda,AParea,Fmax,...` rows
/// -> [[F-max, AP]; 2] at λ 0.5 and 0.9, with the predictions shifted by
/// `shift` px on both axes.
fn ranked(
    lseval: &Path,
    gt: &Path,
    suffix: &str,
    pred: &Path,
    shift: &str,
) -> Result<[[f64; 2]; 2], String> {
    let rows = lseval_rows(lseval, (gt, suffix), pred, shift, &["--score-col", "4"], 3)?;
    Ok([[rows[0][2], rows[0][1]], [rows[1][2], rows[1][1]]])
}

/// Whether the left side (as displayed, y down) of a segment of 10 px or
/// more is the brighter: the image, bilinear, 2 px to each side at 1/4,
/// 1/2 and 3/4 of the length, summed (the probe issue #40 uses for OpenCV
/// LSD's 0.97). `None` for shorter segments.
fn brighter_left(img: &support::Gray, s: &Segment) -> Option<bool> {
    let (w, h) = (img.width as f64, img.height as f64);
    let at = |x: f64, y: f64| {
        let (x, y) = (x.clamp(0.0, w - 1.001), y.clamp(0.0, h - 1.001));
        let (x0, y0) = (x as usize, y as usize);
        let (fx, fy) = (x - x0 as f64, y - y0 as f64);
        let p = |dx: usize, dy: usize| f64::from(img.data[(y0 + dy) * img.width + x0 + dx]);
        p(0, 0) * (1.0 - fx) * (1.0 - fy)
            + p(1, 0) * fx * (1.0 - fy)
            + p(0, 1) * (1.0 - fx) * fy
            + p(1, 1) * fx * fy
    };
    let (x0, y0, x1, y1) = (
        f64::from(s.x0),
        f64::from(s.y0),
        f64::from(s.x1),
        f64::from(s.y1),
    );
    let len = (x1 - x0).hypot(y1 - y0);
    if len < 10.0 {
        return None;
    }
    // The left normal as displayed: (dy, -dx) for a unit direction.
    let (nx, ny) = ((y1 - y0) / len * 2.0, -(x1 - x0) / len * 2.0);
    let (mut left, mut right) = (0.0, 0.0);
    for t in [0.25, 0.5, 0.75] {
        let (px, py) = (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
        left += at(px + nx, py + ny);
        right += at(px - nx, py - ny);
    }
    Some(left > right)
}

/// `segs` with each score replaced by the segment's length.
fn by_length(segs: &[Segment]) -> Vec<Segment> {
    segs.iter()
        .map(|s| Segment {
            score: s.length(),
            ..*s
        })
        .collect()
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("accuracy: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let root = support::data::repo_root();
    let shared = support::data::shared_location();
    let data = shared.join("data/yorkurban");
    let lseval = shared.join("tools/lseval.py");
    if !data.is_dir() || !lseval.is_file() {
        return Err(format!(
            "{} or {} not found",
            data.display(),
            lseval.display()
        ));
    }
    let mut args = std::env::args().skip(1);
    let mut ranked_too = false;
    let (mut full, mut custom, mut quick, mut check) = (false, None::<Variant>, false, false);
    let fresh = || Variant {
        name: "custom".into(),
        config: Config::DEFAULT,
        reference: false,
        quirks: Quirks::default(),
    };
    while let Some(a) = args.next() {
        match a.as_str() {
            "--full" => full = true,
            "--quick" => quick = true,
            "--check" => check = true,
            "--ranked" => ranked_too = true,
            "--profile" => {
                let p = args.next().ok_or("--profile needs a value")?;
                custom.get_or_insert_with(fresh).config = Profile::from_name(&p)
                    .ok_or(format!("unknown profile {p:?}"))?
                    .config();
            }
            "--set" => {
                let kv = args.next().ok_or("--set needs field=value")?;
                fields::apply_set(&mut custom.get_or_insert_with(fresh).config, &kv)
                    .map_err(|e| format!("--set {kv}: {e}"))?;
            }
            "--reference" => custom.get_or_insert_with(fresh).reference = true,
            "--bug" => custom.get_or_insert_with(fresh).quirks.orientation_bug = true,
            "--official-frame" => custom.get_or_insert_with(fresh).quirks.official_frame = true,
            "--name" => {
                custom.get_or_insert_with(fresh).name = args.next().ok_or("--name needs a value")?
            }
            _ => return Err(format!("unknown option {a:?}")),
        }
    }
    let variants = match (custom, quick) {
        (Some(c), _) => vec![c],
        (None, true) => readme_variants().into_iter().take(1).collect(),
        (None, false) => readme_variants(),
    };
    let images: Vec<PathBuf> = support::images_in(&data)?;
    let gray: Vec<(String, support::Gray)> = images
        .iter()
        .map(|p| {
            let stem = p
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("x")
                .to_string();
            support::load_gray(p)
                .map(|g| (stem, g))
                .map_err(|e| format!("{}: {e}", p.display()))
        })
        .collect::<Result<_, _>>()?;
    println!(
        "York Urban, {} images; pooled; D_c = 1 px, D_a = 3 deg; F-score at lambda 0.5 / 0.9",
        gray.len()
    );
    let header = if full {
        "| variant | GT | shift | λ | AP | AR | IoU | F |\n|---|---|---|---|---|---|---|---|"
            .to_string()
    } else {
        "| variant | segments | YUD F@0.5 | YUD F@0.9 | YULD F@0.5 | YULD F@0.9 | shift YUD / YULD |\n|---|---|---|---|---|---|---|"
            .to_string()
    };
    println!("{header}");
    let mut failures = Vec::new();
    let mut rankings = Vec::new();
    let mut polarities = Vec::new();
    for (vi, v) in variants.iter().enumerate() {
        let slug: String = v
            .name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        let dir = root.join("target/accuracy").join(slug);
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let by_len = dir.with_extension("by_length");
        std::fs::create_dir_all(&by_len).map_err(|e| format!("{}: {e}", by_len.display()))?;
        let mut count = 0;
        let mut polarity = [0usize; 2];
        for (stem, img) in &gray {
            let segs = detect(v, img).map_err(|e| format!("{stem}: {e}"))?;
            count += segs.len();
            for left in segs.iter().filter_map(|s| brighter_left(img, s)) {
                polarity[usize::from(left)] += 1;
            }
            for (d, segs) in [(&dir, segs.clone()), (&by_len, by_length(&segs))] {
                let p = d.join(format!("{stem}.txt"));
                std::fs::write(&p, segments::to_text_scored(&segs))
                    .map_err(|e| format!("{}: {e}", p.display()))?;
            }
        }
        let (shift_yud, yud) = score_best(&lseval, &data, ".yud.txt", &dir)?;
        let (shift_yuld, yuld) = score_best(&lseval, &data, ".yuld.txt", &dir)?;
        if full {
            for (gt, shift, s) in [("YUD", shift_yud, yud), ("YULD", shift_yuld, yuld)] {
                for (lam, r) in [("0.5", s[0]), ("0.9", s[1])] {
                    println!(
                        "| {} | {gt} | {shift} | {lam} | {:.3} | {:.3} | {:.3} | {:.3} |",
                        v.name, r[0], r[1], r[2], r[3]
                    );
                }
            }
        } else {
            println!(
                "| {} | {count} | {:.3} | {:.3} | {:.3} | {:.3} | {shift_yud} / {shift_yuld} |",
                v.name, yud[0][3], yud[1][3], yuld[0][3], yuld[1][3]
            );
        }
        if ranked_too {
            let long = polarity[0] + polarity[1];
            polarities.push(format!(
                "| {} | {} / {long} = {:.3} |",
                v.name,
                polarity[1],
                polarity[1] as f64 / long.max(1) as f64
            ));
            for (how, d) in [("score", &dir), ("length", &by_len)] {
                let a = ranked(&lseval, &data, ".yud.txt", d, shift_yud)?;
                let b = ranked(&lseval, &data, ".yuld.txt", d, shift_yuld)?;
                let f = |r: [f64; 2]| format!("{:.3} | {:.3}", r[0], r[1]);
                rankings.push(format!(
                    "| {}, by {how} | {} | {} | {} | {} |",
                    v.name,
                    f(a[0]),
                    f(a[1]),
                    f(b[0]),
                    f(b[1])
                ));
            }
        }
        if check && vi == 0 {
            let got = [yud[0][3], yud[1][3], yuld[0][3], yuld[1][3]];
            for ((name, floor), f) in OFFICIAL_F.iter().zip(got) {
                if f < *floor {
                    failures.push(format!("{}: {name} F {f:.4} < official {floor}", v.name));
                }
            }
        }
    }
    if ranked_too {
        println!(
            "\nRanked (lseval --score-col 4, each ground truth at the shift above): F-max and AP\n\n\
             | variant, ranked | YUD F-max@0.5 | AP@0.5 | F-max@0.9 | AP@0.9 | YULD F-max@0.5 | AP@0.5 | F-max@0.9 | AP@0.9 |\n\
             |---|---|---|---|---|---|---|---|---|"
        );
        for r in &rankings {
            println!("{r}");
        }
        println!(
            "\nPolarity: segments of 10 px or more whose left side is the brighter\n\n\
             | variant | brighter left |\n|---|---|"
        );
        for r in &polarities {
            println!("{r}");
        }
    }
    if !failures.is_empty() {
        return Err(failures.join("; "));
    }
    Ok(())
}
