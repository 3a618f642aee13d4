//! Panic-freedom proof (link-time): `detect` on fully `black_box`ed inputs
//! (image data, dimensions, stride, config, workspace, output), with a panic
//! handler that calls a function that exists nowhere. If any panic path in
//! the core survives optimisation, the release link fails with
//! `undefined symbol: aaglsd_panic_path_reachable`; if it links, no panic is
//! reachable from `detect` (nor from `GrayImage::new`,
//! `Workspace::bytes_needed` and `detect_into_vec`, called here too).
//! Built by `run.sh` (and CI); never run.

#![no_std]
#![no_main]

use core::hint::black_box;
use core::panic::PanicInfo;

use aaglsd::{Config, GrayImage, Segment, Workspace, detect, detect_into_vec};
use cortex_m_rt::entry;

const BYTES: usize = 64 * 1024;
#[entry]
fn main() -> ! {
    static mut PIXELS: [u8; BYTES] = [0; BYTES];
    static mut SLAB: [u8; BYTES] = [0; BYTES];
    static mut OUT: [Segment; 64] = [Segment::ZERO; 64];

    let pixels: &[u8] = black_box(&PIXELS[..]);
    let (w, h, stride) = (black_box(100), black_box(100), black_box(100));
    let cfg: Config = black_box(Config::DEFAULT);
    let needed = Workspace::bytes_needed(black_box(w), black_box(h), &cfg);
    black_box(needed);
    if let Ok(img) = GrayImage::new(pixels, w, h, stride) {
        let slab: &mut [u8] = black_box(&mut SLAB[..]);
        let r = detect(
            &img,
            &cfg,
            &mut Workspace::new(slab),
            black_box(&mut OUT[..]),
        );
        black_box(r.map(|s| s.segments).unwrap_or(0));
        let mut v: heapless::Vec<Segment, 8> = heapless::Vec::new();
        let r = detect_into_vec(
            &img,
            &cfg,
            &mut Workspace::new(black_box(&mut SLAB[..])),
            &mut v,
        );
        black_box((r.is_ok(), v.len()));
    }
    black_box(&OUT[..]);
    loop {
        core::hint::spin_loop();
    }
}

unsafe extern "C" {
    /// Deliberately undefined: referencing it from the panic handler makes
    /// the link fail exactly when a panic is reachable.
    fn aaglsd_panic_path_reachable() -> !;
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    // SAFETY: never executed when the binary links (see the module docs).
    unsafe { aaglsd_panic_path_reachable() }
}
