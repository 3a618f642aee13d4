//! `memory`: the workspace memory report.
//!
//! ```text
//! cargo run --release --example memory
//! ```
//!
//! Prints `Workspace::bytes_needed` at the default capacities for 320x240,
//! 640x480 and 1064x708, what each region costs, and (when `../shared` is
//! present) how full the capacity-bounded regions got on the 63 test images.

use aaglsd::{Config, Segment, Workspace, detect};
use aaglsd_support as support;

fn main() {
    let cfg = Config::DEFAULT;
    let sizes = [(320usize, 240usize), (640, 480), (1064, 708)];
    println!("Workspace at Config::DEFAULT (bytes; bytes per pixel in parentheses)\n");
    print!("| region |");
    for (w, h) in sizes {
        print!(" {w}x{h} |");
    }
    println!("\n|---|{}", "---|".repeat(sizes.len()));
    let reports: Vec<_> = sizes
        .iter()
        .map(|&(w, h)| Workspace::region_bytes(w, h, &cfg).expect("valid size"))
        .collect();
    for row in 0..reports[0].len() {
        print!("| {} |", reports[0][row].0);
        for (r, &(w, h)) in reports.iter().zip(&sizes) {
            let b = r[row].1;
            print!(" {b} ({:.3}) |", b as f64 / (w * h) as f64);
        }
        println!();
    }
    print!("| **total** (`Workspace::bytes_needed`) |");
    for &(w, h) in &sizes {
        let b = Workspace::bytes_needed(w, h, &cfg).expect("valid size");
        let sum: usize = Workspace::region_bytes(w, h, &cfg)
            .expect("valid")
            .iter()
            .map(|r| r.1)
            .sum();
        assert_eq!(b, sum, "regions must add up to bytes_needed");
        print!(" **{b} ({:.3})** |", b as f64 / (w * h) as f64);
    }
    println!();

    // Occupancy of the capacity-bounded regions on the test images.
    let shared = support::data::shared_location();
    let dirs = [
        shared.join("data/yorkurban"),
        shared.join("data/readme-images/gray"),
    ];
    let mut images = Vec::new();
    for d in &dirs {
        if let Ok(files) = support::images_in(d) {
            images.extend(files);
        }
    }
    if images.is_empty() {
        println!(
            "\n(no images under {}: occupancy skipped)",
            shared.join("data").display()
        );
        return;
    }
    let (mut worst_c, mut worst_g, mut incomplete) = (0f64, 0f64, 0);
    for p in &images {
        let g = support::load_gray(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let mut slab = vec![0u8; Workspace::bytes_needed(g.width, g.height, &cfg).expect("size")];
        let mut out = vec![Segment::default(); 100_000];
        let img = g.image().expect("test images are within the core's limits");
        let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).expect("detect");
        let px = (g.width * g.height) as f64;
        worst_c = worst_c.max(s.candidates as f64 / px);
        worst_g = worst_g.max(s.groups as f64 / px);
        if !s.is_complete() {
            incomplete += 1;
        }
    }
    println!(
        "\nOn {} test images: candidates at most {:.2}% of the pixels (capacity {:.1}%), groups at most {:.2}%; {} run(s) dropped or truncated anything.",
        images.len(),
        100.0 * worst_c,
        f64::from(cfg.candidates_per_mille) / 10.0,
        100.0 * worst_g,
        incomplete
    );
}
