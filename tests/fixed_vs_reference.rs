//! The fixed-point core against the float reference.
//!
//! On the 12 readme images and the 51 York Urban images, pooled, at least 97%
//! of the reference's segments must be matched by a fixed-core segment with
//! both endpoints within 1.5 px, and vice versa; the exact-match rate
//! (endpoints within 0.01 px) is printed. Runs for the default and the paper
//! profile (which merges). Skipped, with a `SKIPPED:` line in the test
//! output, without `../shared` (or `$AAGLSD_SHARED`).
//!
//! Repository-only (uses `aaglsd-support`; not in the published package).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use aaglsd::Config;
use aaglsd_support::data::{README_STEMS, shared_or_skip};
use aaglsd_support::matching::Agreement;
use aaglsd_support::{Gray, detect_fixed, images_in, load_gray};

fn compare(images: &[(String, Gray)], cfg: &Config) -> Agreement {
    let mut pooled = Agreement::new(1.5, 0.01);
    for (name, g) in images {
        let img = g.image().unwrap();
        let r = aaglsd::reference::detect(&img, cfg).unwrap();
        let f = detect_fixed(&img, cfg).unwrap();
        assert!(f.summary.is_complete(), "{name}: {:?}", f.summary);
        let one = pooled.add(&r, &f.segments);
        if !one.all_matched() {
            println!(
                "  {name}: reference {} fixed {} unmatched {} / {}",
                one.a,
                one.b,
                one.a - one.a_matched,
                one.b - one.b_matched
            );
        }
    }
    pooled
}

fn load_sets(test: &str) -> Option<Vec<(String, Gray)>> {
    let shared = shared_or_skip(test)?;
    let mut v = Vec::new();
    for stem in README_STEMS {
        let p = shared.join(format!("data/readme-images/gray/{stem}.pgm"));
        v.push((stem.to_string(), load_gray(&p).unwrap()));
    }
    for p in images_in(&shared.join("data/yorkurban")).unwrap() {
        let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
        v.push((stem, load_gray(&p).unwrap()));
    }
    Some(v)
}

fn check(cfg: &Config, label: &str) {
    let Some(images) = load_sets(&format!("fixed_vs_reference, {label} profile")) else {
        return;
    };
    assert_eq!(images.len(), 63);
    let a = compare(&images, cfg);
    println!("{label}: {}", a.describe("reference", "fixed"));
    assert!(a.a_percent() >= 97.0, "{a:?}");
    assert!(a.b_percent() >= 97.0, "{a:?}");
}

#[test]
fn default_profile_agrees() {
    check(&Config::DEFAULT, "default");
}

#[test]
fn paper_profile_agrees() {
    check(&Config::PAPER, "paper");
}
