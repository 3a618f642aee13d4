#[path = "support/mod.rs"]
mod support;
use aaglsd::*;
fn main() {
    let mut worst = 0f64;
    let mut worst_g = 0f64;
    let mut sum = 0f64;
    let mut n = 0;
    for dir in [
        "../shared/data/yorkurban",
        "../shared/data/readme-images/gray",
    ] {
        for p in support::images_in(std::path::Path::new(dir)).unwrap() {
            let g = support::load_gray(&p).unwrap();
            let img = g.image();
            let cfg = Config::DEFAULT;
            let mut slab = vec![0u8; Workspace::bytes_needed(g.width, g.height, &cfg).unwrap()];
            let mut out = vec![Segment::default(); 100000];
            let s = detect(&img, &cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
            let px = (g.width * g.height) as f64;
            worst = worst.max(s.candidates as f64 / px);
            worst_g = worst_g.max(s.groups as f64 / px);
            sum += s.candidates as f64 / px;
            n += 1;
        }
    }
    println!(
        "candidates/pixel: max {:.4} mean {:.4}; groups/pixel max {:.4}",
        worst,
        sum / n as f64,
        worst_g
    );
    for (w, h) in [(320, 240), (640, 480), (1064, 708)] {
        let b = Workspace::bytes_needed(w, h, &Config::DEFAULT).unwrap();
        println!("{w}x{h}: {b} bytes = {:.3} B/px", b as f64 / (w * h) as f64);
    }
}
