//! What the size-measurement binaries share (`size_probe`, `size_probe_cfg`,
//! `size_baseline`; built, never run): the firmware's 320x240 buffers as
//! `.bss` statics, and a panic handler that only loops, so that no
//! `core::fmt` is linked. Each binary includes this file and gives
//! [`probe_main!`] the function it runs on the buffers.

use core::hint::black_box;

use aaglsd::{Config, GrayImage, Segment, Workspace, detect};

/// Image width, as in the firmware.
pub const W: usize = 320;
/// Image height, as in the firmware.
pub const H: usize = 240;
/// Workspace bytes, as in the firmware.
pub const SLAB_BYTES: usize = Workspace::bytes_needed_default(W, H);
/// Output capacity, as in the firmware.
pub const MAX_SEGMENTS: usize = 512;

/// The image buffer.
pub type Image = [u8; W * H];
/// The workspace buffer.
pub type Slab = [u8; SLAB_BYTES];
/// The output buffer.
pub type Out = [Segment; MAX_SEGMENTS];

/// Defines the entry point: the image, workspace and output buffers as
/// `static`s in `.bss` (cortex-m-rt hands them out as `&'static mut`), a
/// call of `$body(image, slab, out)`, then an idle loop. The image is not in
/// flash, so `.text + .rodata` is code and tables only.
macro_rules! probe_main {
    ($body:expr) => {
        #[cortex_m_rt::entry]
        fn main() -> ! {
            static mut IMAGE: probe::Image = [0; probe::W * probe::H];
            static mut SLAB: probe::Slab = [0; probe::SLAB_BYTES];
            static mut OUT: probe::Out = [aaglsd::Segment::ZERO; probe::MAX_SEGMENTS];
            $body(IMAGE, SLAB, OUT);
            loop {
                core::hint::spin_loop();
            }
        }
    };
}
pub(crate) use probe_main;

/// `detect` with [`Config::DEFAULT`] on the image, with its data and
/// dimensions `black_box`ed (read, so LTO keeps the buffers, and unknown,
/// so nothing is specialised to them); the result is `black_box`ed too.
/// With `OPAQUE_CONFIG` the config is `black_box`ed as well, so nothing in
/// it is constant-folded.
#[inline(always)]
#[allow(dead_code)] // `size_baseline` is the probe without it
pub fn detect_black_boxed<const OPAQUE_CONFIG: bool>(
    image: &Image,
    slab: &mut Slab,
    out: &mut Out,
) {
    let pixels: &[u8] = black_box(&image[..]);
    let (w, h) = (black_box(W), black_box(H));
    if let Ok(img) = GrayImage::new(pixels, w, h, w) {
        let r = if OPAQUE_CONFIG {
            detect(
                &img,
                &black_box(Config::DEFAULT),
                &mut Workspace::new(slab),
                out,
            )
        } else {
            detect(&img, &Config::DEFAULT, &mut Workspace::new(slab), out)
        };
        black_box(r.map(|s| s.segments).unwrap_or(0));
    }
    black_box(&out[..]);
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
