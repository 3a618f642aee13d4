//! Golden outputs on the committed fixtures (`testdata/`), so a fresh clone
//! without `../shared` still checks the whole pipeline end to end.
//!
//! `testdata/golden/<stem>.<profile>.txt` holds the fixed core's segments,
//! one `x0 y0 x1 y1 score` line each (Rust's shortest round-trip `f32` text, so
//! the comparison is exact). `REGENERATE=1 cargo test --test golden`
//! rewrites them; review the diff before committing.
//!
//! Repository-only (uses `aaglsd-support`; not in the published package).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use aaglsd::{Config, Segment};
use aaglsd_support::data::testdata;
use aaglsd_support::segments::to_text_scored;
use aaglsd_support::{detect_fixed, load_gray, matched};

const FIXTURES: [&str; 1] = ["castle1.png"];

fn profiles() -> [(&'static str, Config); 2] {
    [("default", Config::DEFAULT), ("paper", Config::PAPER)]
}

#[test]
fn fixed_core_matches_golden() {
    for f in FIXTURES {
        let g = load_gray(&testdata().join(f)).unwrap();
        let stem = f.split('.').next().unwrap();
        for (name, cfg) in profiles() {
            let segs = detect_fixed(&g.image().unwrap(), &cfg).unwrap().segments;
            let text = to_text_scored(&segs);
            let path = testdata().join(format!("golden/{stem}.{name}.txt"));
            if std::env::var_os("REGENERATE").is_some() {
                std::fs::write(&path, &text).unwrap();
                continue;
            }
            let want = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: {e} (run with REGENERATE=1)", path.display()));
            assert_eq!(
                text.lines().count(),
                want.lines().count(),
                "{stem}/{name}: segment count"
            );
            for (i, (a, b)) in text.lines().zip(want.lines()).enumerate() {
                assert_eq!(a, b, "{stem}/{name}: segment {i}");
            }
        }
    }
}

/// The differential check of `fixed_vs_reference.rs` on the committed
/// fixture alone (that test needs `../shared`).
#[test]
fn fixed_core_agrees_with_reference_on_fixture() {
    for f in FIXTURES {
        let g = load_gray(&testdata().join(f)).unwrap();
        let img = g.image().unwrap();
        for (name, cfg) in profiles() {
            let fixed = detect_fixed(&img, &cfg).unwrap().segments;
            let reference: Vec<Segment> = aaglsd::reference::detect(&img, &cfg).unwrap();
            let (rm, _) = matched(&reference, &fixed, 1.5);
            let (fm, _) = matched(&fixed, &reference, 1.5);
            let (r, x) = (reference.len(), fixed.len());
            assert!(r > 100, "{f}/{name}: only {r} reference segments");
            assert!(
                rm * 100 >= r * 97,
                "{f}/{name}: {rm}/{r} reference segments matched"
            );
            assert!(
                fm * 100 >= x * 97,
                "{f}/{name}: {fm}/{x} fixed segments matched"
            );
        }
    }
}
