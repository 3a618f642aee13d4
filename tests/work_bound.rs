//! The work limit on the adversarial corpus (`aaglsd_support::corpus`):
//! whatever the content, a frame spends at most the documented bound of
//! work units (design §13), and a hard budget stops it gracefully.
//!
//! Repository-only (uses `aaglsd-support`; not in the published package).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use aaglsd::{Config, GrayImage, Profile, Segment, Summary, Workspace, detect};
use aaglsd_support::corpus::patterns;

const W: usize = 320;
const H: usize = 240;

fn run(px: &[u8], cfg: &Config) -> Summary {
    let img = GrayImage::new(px, W, H, W).unwrap();
    let mut slab = vec![0u8; Workspace::bytes_needed(W, H, cfg).unwrap()];
    let mut out = vec![Segment::ZERO; 4096];
    detect(&img, cfg, &mut Workspace::new(&mut slab), &mut out).unwrap()
}

/// The documented bound: the limit, plus what one linking started just
/// below it can add (its visits, its bridges' probes, the pixels of its
/// segment and of its part, and its extension at both ends).
fn bound(limit: usize, cfg: &Config) -> usize {
    let v = cfg.max_link_pixels as usize;
    let probes = usize::from(cfg.bridge_px) * (v / 6 + 2);
    let traces = (1 + usize::from(cfg.trim)) * W.max(H);
    limit + v + probes + traces + 2 * usize::from(cfg.extend_max_px)
}

#[test]
fn every_pattern_stays_within_the_work_limit() {
    let mut cut_somewhere = false;
    // Each profile as it is, and with a limit low enough to bite.
    let tight = |c: Config| Config {
        work_per_mille: 300,
        ..c
    };
    let configs = Profile::ALL.map(|p| (p, p.config()));
    for (profile, cfg) in configs
        .into_iter()
        .chain(configs.map(|(p, c)| (p, tight(c))))
    {
        let limit = W * H * cfg.work_per_mille as usize / 1000;
        for p in patterns() {
            let s = run(&p.render(W, H), &cfg);
            assert!(
                s.work <= bound(limit, &cfg),
                "{} ({}) / {}: {} units, limit {limit}",
                profile.name(),
                cfg.work_per_mille,
                p.name,
                s.work
            );
            if s.work_cut > 0 {
                assert!(!s.is_complete(), "{}: {s:?}", p.name);
                cut_somewhere = true;
            }
        }
    }
    // The tight limit is reached somewhere.
    assert!(cut_somewhere);
}

#[test]
fn a_budget_stops_detection_gracefully() {
    let budget = 5_000;
    let mut stopped = 0;
    for p in patterns() {
        let px = p.render(W, H);
        let free = run(&px, &Config::DEFAULT);
        let cfg = Config {
            work_budget: budget,
            ..Config::DEFAULT
        };
        let s = run(&px, &cfg);
        assert!(
            s.work <= bound(budget as usize, &cfg),
            "{}: {}",
            p.name,
            s.work
        );
        if free.work < budget as usize {
            // Never reached: the same detection.
            assert_eq!(s, free, "{}", p.name);
        } else if s.work_cut > 0 {
            // Cut short, and said so.
            assert!(!s.is_complete(), "{}: {s:?}", p.name);
            stopped += 1;
        } else {
            // Its last linking crossed the budget: nothing was left.
            assert_eq!(s, free, "{}", p.name);
        }
    }
    assert!(stopped > 0);
}
