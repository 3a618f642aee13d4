//! The fixed-point core against the float reference.
//!
//! On the 12 readme images and the 51 York Urban images, pooled, at least 97%
//! of the reference's segments must be matched by a fixed-core segment with
//! both endpoints within 1.5 px, and vice versa; the exact-match rate
//! (endpoints within 0.01 px) is printed. Runs for the default and the paper
//! profile (which merges). Skipped (with a message) without `../shared`.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

mod common;
#[path = "../examples/support/mod.rs"]
mod support;

use aaglsd::{Config, Segment, Workspace, detect};
use common::*;

/// Pooled agreement counters.
#[derive(Default, Debug)]
struct Agreement {
    reference: usize,
    fixed: usize,
    ref_matched: usize,
    fixed_matched: usize,
    exact: usize,
}

fn fixed_detect(img: &aaglsd::GrayImage<'_>, cfg: &Config) -> Vec<Segment> {
    let mut slab = vec![0u8; Workspace::bytes_needed(img.width(), img.height(), cfg).unwrap()];
    let mut out = vec![Segment::default(); 100_000];
    let s = detect(img, cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
    assert!(s.is_complete(), "{s:?}");
    out.truncate(s.segments);
    out
}

fn compare(images: &[(String, support::Gray)], cfg: &Config) -> Agreement {
    let mut a = Agreement::default();
    for (name, g) in images {
        let img = g.image();
        let r = aaglsd::reference::detect(&img, cfg).unwrap();
        let f = fixed_detect(&img, cfg);
        let (rm, exact) = matched(&r, &f, 1.5);
        let (fm, _) = matched(&f, &r, 1.5);
        if rm < r.len() || fm < f.len() {
            println!(
                "  {name}: reference {} fixed {} unmatched {} / {}",
                r.len(),
                f.len(),
                r.len() - rm,
                f.len() - fm
            );
        }
        a.reference += r.len();
        a.fixed += f.len();
        a.ref_matched += rm;
        a.fixed_matched += fm;
        let (ex, _) = matched(&r, &f, 0.01);
        a.exact += ex;
        let _ = exact;
    }
    a
}

fn load_sets() -> Option<Vec<(String, support::Gray)>> {
    let shared = shared_dir()?;
    let mut v = Vec::new();
    for stem in README_STEMS {
        let p = shared.join(format!("data/readme-images/gray/{stem}.pgm"));
        v.push((stem.to_string(), support::load_gray(&p).unwrap()));
    }
    for p in support::images_in(&shared.join("data/yorkurban")).unwrap() {
        let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
        v.push((stem, support::load_gray(&p).unwrap()));
    }
    Some(v)
}

fn check(cfg: &Config, label: &str) {
    let Some(images) = load_sets() else {
        eprintln!("SKIPPED: ../shared/data not found");
        return;
    };
    assert_eq!(images.len(), 63);
    let a = compare(&images, cfg);
    let pct = |x: usize, n: usize| 100.0 * x as f64 / n.max(1) as f64;
    println!(
        "{label}: reference {} fixed {}; reference matched {:.2}%, fixed matched {:.2}% (1.5 px); exact (0.01 px) {:.2}%",
        a.reference,
        a.fixed,
        pct(a.ref_matched, a.reference),
        pct(a.fixed_matched, a.fixed),
        pct(a.exact, a.reference)
    );
    assert!(pct(a.ref_matched, a.reference) >= 97.0, "{a:?}");
    assert!(pct(a.fixed_matched, a.fixed) >= 97.0, "{a:?}");
}

#[test]
fn default_profile_agrees() {
    check(&Config::DEFAULT, "default");
}

#[test]
fn paper_profile_agrees() {
    check(&Config::PAPER, "paper");
}
