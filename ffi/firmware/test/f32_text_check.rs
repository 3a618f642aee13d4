//! Rust's `{}` of the sequence f32_text_check.c prints (see there).
//! Built with plain `rustc -O` by run.sh --check.
use std::io::Write;

fn main() {
    let a: Vec<u64> = std::env::args()
        .skip(1)
        .map(|s| match s.strip_prefix("0x") {
            Some(h) => u64::from_str_radix(h, 16).unwrap(),
            None => s.parse().unwrap(),
        })
        .collect();
    let (step, lo, n) = (a[0], a[1] as u32, a[2] as u32);
    let mut o = std::io::BufWriter::new(std::io::stdout().lock());
    let mut b = 0u64;
    while b <= 0xffff_ffff {
        writeln!(o, "{}", f32::from_bits(b as u32)).unwrap();
        b += step;
    }
    for i in 0..n {
        writeln!(o, "{}", f32::from_bits(lo + i)).unwrap();
    }
    for s in [
        0x0000_0000u32, 0x8000_0000, 0x7f80_0000, 0xff80_0000, 0x7fc0_0000, 0x0000_0001,
        0x807f_ffff, 0x0080_0000, 0x7f7f_ffff, 0x4b80_0000, 0x4c00_0000, 0x3f80_0000,
    ] {
        writeln!(o, "{}", f32::from_bits(s)).unwrap();
    }
}
