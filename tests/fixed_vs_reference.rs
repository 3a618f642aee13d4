//! The fixed-point core against the float reference.
//!
//! On the 12 readme images and the 51 York Urban images, pooled, at least 97%
//! of the reference's segments must be matched by a fixed-core segment with
//! both endpoints within 1.5 px, and vice versa; the exact-match rate
//! (endpoints within 0.01 px) is printed. Runs for the default and the paper
//! profile (which merges). Skipped, with a `SKIPPED:` line in the test
//! output, without `../shared` (or `$AAGLSD_SHARED`).
//!
//! The man-made scenes (`aaglsd_support::manmade`, both splits; no dataset
//! needed) are compared the same way, with the candidate capacity and the
//! work limit lifted (the reference has neither), and with the coverage F
//! of each within 0.005 of the other's.
//!
//! Repository-only (uses `aaglsd-support`; not in the published package).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use aaglsd::{Config, GrayImage, Segment};
use aaglsd_support::data::{README_STEMS, shared_or_skip};
use aaglsd_support::matching::{Agreement, Attributes, attributes_agree};
use aaglsd_support::{Gray, detect_fixed, images_in, load_gray};

/// The reference's and the fixed core's segments for the image `name`
/// (the fixed core's summary must be complete); their agreement is added
/// to `pooled`, with a line for an image where a segment is unmatched.
fn detect_both(
    name: &str,
    img: &GrayImage<'_>,
    cfg: &Config,
    pooled: &mut Agreement,
) -> (Vec<Segment>, Vec<Segment>) {
    let r = aaglsd::reference::detect(img, cfg).unwrap();
    let f = detect_fixed(img, cfg).unwrap();
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
    (r, f.segments)
}

fn compare(images: &[(String, Gray)], cfg: &Config) -> (Agreement, Attributes) {
    let mut pooled = Agreement::new(1.5, 0.01);
    let mut attrs = Attributes::default();
    for (name, g) in images {
        let img = g.image().unwrap();
        let (r, f) = detect_both(name, &img, cfg, &mut pooled);
        attrs += attributes_agree(&r, &f, 1.5);
    }
    (pooled, attrs)
}

/// The matched pairs' polarities agree but where the sums across a
/// segment balance to within the two number systems (0.1%), and so do the
/// exactly matched pairs' scores (both sum over the same pixels: the
/// reference validates on the core's Q8 grid) but where an alignment test
/// ties within them.
fn check_attributes(label: &str, a: Attributes) {
    println!(
        "{label}: of {} matched pairs, {} run the same way; of {} exact pairs, {} have the same score",
        a.pairs, a.same_way, a.exact, a.same_score
    );
    assert!(
        a.same_way * 1000 >= a.pairs * 999,
        "{label}: polarity {a:?}"
    );
    assert!(
        a.same_score * 1000 >= a.exact * 999,
        "{label}: scores {a:?}"
    );
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
    let (a, attrs) = compare(&images, cfg);
    println!("{label}: {}", a.describe("reference", "fixed"));
    check_attributes(label, attrs);
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

#[test]
fn default_profile_agrees_on_man_made_scenes() {
    use aaglsd_support::manmade::{self, Coverage, Split};
    let cfg = Config {
        candidates_per_mille: 1000,
        work_per_mille: 100_000,
        ..Config::DEFAULT
    };
    let as_arrays =
        |s: &[Segment]| -> Vec<[f32; 4]> { s.iter().map(|s| [s.x0, s.y0, s.x1, s.y1]).collect() };
    for split in [Split::Dev, Split::Holdout] {
        let mut pooled = Agreement::new(1.5, 0.01);
        let (mut cov_r, mut cov_f) = (Vec::new(), Vec::new());
        for scene in manmade::scenes(split) {
            let img =
                GrayImage::new(&scene.pixels, scene.width, scene.height, scene.width).unwrap();
            let (r, f) = detect_both(&scene.name, &img, &cfg, &mut pooled);
            cov_r.push(manmade::coverage(&scene.lines, &as_arrays(&r)));
            cov_f.push(manmade::coverage(&scene.lines, &as_arrays(&f)));
        }
        let (fr, ff) = (
            Coverage::pooled(&cov_r).f_score(),
            Coverage::pooled(&cov_f).f_score(),
        );
        println!(
            "{} man-made: {}; coverage F reference {fr:.4}, fixed {ff:.4}",
            split.name(),
            pooled.describe("reference", "fixed")
        );
        assert!(pooled.a_percent() >= 97.0, "{pooled:?}");
        assert!(pooled.b_percent() >= 97.0, "{pooled:?}");
        assert!((fr - ff).abs() <= 0.005, "{fr} vs {ff}");
    }
}
