//! `memory`: the workspace memory report.
//!
//! ```text
//! cargo run --release --example memory
//! ```
//!
//! Prints `Workspace::bytes_needed` at the default capacities for 320x240,
//! 640x480 and 1064x708, what each region costs, the largest 4:3 frame
//! that fits common microcontrollers' RAM, and (when `../shared` is
//! present) how full the capacity-bounded regions got on the 63 test images.
//!
//! The parts table counts the frame (smoothed in place, so the workspace is
//! `bytes_needed_in_place`), a 512-segment output and 4 KiB of stack. Its
//! frame times are estimates at one instruction per cycle from the
//! Cortex-M4 figure `--ipp N` (instructions per pixel, `firmware/run.sh`'s
//! York crop at opt-level 3; default the README's).

use aaglsd::{Config, Segment, Workspace, detect};
use aaglsd_support as support;

/// The default profile's Cortex-M4 instructions per pixel on the York crop
/// (opt-level 3), as the README reports it.
const DEFAULT_IPP: f64 = 445.1;

/// Parts: name, RAM in KiB, core clock in MHz.
const PARTS: [(&str, usize, u32); 9] = [
    ("STM32F407 (Cortex-M4)", 192, 168),
    ("STM32F427 (Cortex-M4)", 256, 180),
    ("nRF52840 (Cortex-M4)", 256, 64),
    ("STM32F746 (Cortex-M7)", 320, 216),
    ("RP2350 (Cortex-M33)", 512, 150),
    ("STM32F765 (Cortex-M7)", 512, 216),
    ("ESP32-S3 (Xtensa LX7)", 512, 240),
    ("STM32H743 (Cortex-M7)", 1024, 480),
    ("i.MX RT1062 (Cortex-M7)", 1024, 600),
];

/// The largest 4:3 frame (a multiple of 4 x 3) that fits `ram` bytes with
/// the frame, its in-place workspace, a 512-segment output and the stack.
fn largest_frame(ram: usize, cfg: &Config) -> Option<(usize, usize)> {
    let fixed = 512 * core::mem::size_of::<Segment>() + 4096;
    (1..=8191)
        .map(|k| (4 * k, 3 * k))
        .take_while(|&(w, h)| {
            Workspace::bytes_needed_in_place(w, h, cfg).is_some_and(|ws| w * h + ws + fixed <= ram)
        })
        .last()
}

fn parts_table(cfg: &Config, ipp: f64) {
    println!(
        "\nLargest 4:3 frame per part (frame smoothed in place + workspace + 512 segments + 4 KiB stack); \
         frame time estimated at {ipp} instructions per pixel, one per cycle\n"
    );
    println!("| part | RAM | largest 4:3 frame | frame time (estimate) |");
    println!("|---|---:|---|---:|");
    for (name, kib, mhz) in PARTS {
        match largest_frame(kib * 1024, cfg) {
            Some((w, h)) => {
                let ms = (w * h) as f64 * ipp / (f64::from(mhz) * 1e3);
                println!("| {name} | {kib} KiB | {w}x{h} | {ms:.0} ms at {mhz} MHz |");
            }
            None => println!("| {name} | {kib} KiB | none | |"),
        }
    }
}

fn main() {
    let cfg = Config::DEFAULT;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let ipp = match args.iter().position(|a| a == "--ipp") {
        Some(i) => match args.get(i + 1).and_then(|v| v.parse::<f64>().ok()) {
            Some(v) if v > 0.0 => v,
            _ => {
                eprintln!("memory: --ipp needs a positive number");
                std::process::exit(2);
            }
        },
        None => DEFAULT_IPP,
    };
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
    // The host's choice: the same regions, the group index and the
    // magnitude cache.
    print!("| total with the group index and magnitude cache (`Workspace::bytes_needed_fast`) |");
    for &(w, h) in &sizes {
        let b = Workspace::bytes_needed_fast(w, h, &cfg).expect("valid size");
        print!(" {b} ({:.3}) |", b as f64 / (w * h) as f64);
    }
    println!();
    parts_table(&cfg, ipp);

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
