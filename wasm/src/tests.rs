//! Host tests of the validating functions, on a buffer standing for the
//! linear memory (the exports are these functions on `Memory::linear`).

use super::*;
use aaglsd_support::fixtures::rectangle;

/// A zeroed, 16-byte aligned buffer used as the memory, accessed only
/// through its base pointer.
struct Mem {
    _storage: Vec<u128>,
    base: *mut u8,
    len: usize,
}

impl Mem {
    fn new(len: usize) -> Self {
        let mut storage = vec![0u128; len.div_ceil(16)];
        let base = storage.as_mut_ptr().cast::<u8>();
        Self {
            _storage: storage,
            base,
            len,
        }
    }

    fn memory(&self) -> Memory {
        Memory::new(self.base, self.len)
    }

    fn addr(&self, off: usize) -> usize {
        self.base.addr() + off
    }

    fn put(&self, off: usize, bytes: &[u8]) {
        assert!(off + bytes.len() <= self.len);
        // SAFETY: inside the buffer (asserted); no reference to it exists.
        unsafe { ptr::copy_nonoverlapping(bytes.as_ptr(), self.base.add(off), bytes.len()) }
    }

    /// Writes `c` at [`CFG`].
    fn put_config(&self, c: &AaglsdConfig) {
        // SAFETY: AaglsdConfig is plain old data; its bytes are initialised
        // except for padding, which `put` copies as bytes (read_unaligned-safe
        // for the receiving side, which reads the struct whole).
        let bytes = unsafe {
            core::slice::from_raw_parts((&raw const *c).cast::<u8>(), size_of::<AaglsdConfig>())
        };
        self.put(CFG, bytes);
    }

    fn get<T: Copy>(&self, off: usize) -> T {
        assert!(off + size_of::<T>() <= self.len);
        // SAFETY: inside the buffer (asserted); plain-old-data types only.
        unsafe { ptr::read_unaligned(self.base.add(off).cast::<T>()) }
    }
}

fn castle() -> (usize, usize, Vec<u8>) {
    let px = include_bytes!("../../testdata/castle1_320x240.gray").to_vec();
    (320, 240, px)
}

fn core_detect(px: &[u8], w: usize, h: usize, cfg: &Config) -> Vec<[u32; 5]> {
    let img = GrayImage::new(px, w, h, w).unwrap();
    let mut slab = vec![0u8; Workspace::bytes_needed(w, h, cfg).unwrap()];
    let mut out = vec![Segment::ZERO; default_capacity(w, h)];
    let s = aaglsd::detect(&img, cfg, &mut Workspace::new(&mut slab), &mut out).unwrap();
    bits(&out[..s.segments])
}

/// Each segment's five fields, `x0 y0 x1 y1 score`, as `f32` bit patterns.
fn bits(s: &[Segment]) -> Vec<[u32; 5]> {
    s.iter()
        .map(|s| [s.x0, s.y0, s.x1, s.y1, s.score].map(f32::to_bits))
        .collect()
}

/// The scores of `bits`: integers below 2^24, most of them positive (so
/// the comparisons of the score column are not of zeros; a segment with
/// no pixel aligned within T_aligned/2 scores 0, design §8.1).
fn assert_scored(bits: &[[u32; 5]]) {
    let mut positive = 0;
    for b in bits {
        let score = f32::from_bits(b[4]);
        assert!(
            (0.0..16_777_216.0).contains(&score) && score.fract() == 0.0,
            "{score}"
        );
        positive += usize::from(score >= 1.0);
    }
    assert!(2 * positive > bits.len(), "{positive} of {}", bits.len());
}

/// Offsets of a detection's buffers in a `Mem`.
const CFG: usize = 16;
const SUMMARY: usize = 128;
const IMAGE: usize = 256;

/// Lays out config, summary, image, workspace and output in a `Mem` and
/// returns it with the `DetectArgs` for them.
fn layout(w: usize, h: usize, px: &[u8], cfg: &Config, cap: usize) -> (Mem, DetectArgs) {
    let ws_len = Workspace::bytes_needed(w, h, cfg).unwrap();
    let ws = (IMAGE + px.len()).next_multiple_of(16);
    let out = (ws + ws_len).next_multiple_of(16);
    let m = Mem::new(out + cap * SEGMENT_BYTES + 64);
    m.put(IMAGE, px);
    m.put_config(&AaglsdConfig::from(cfg));
    let a = DetectArgs {
        image: m.addr(IMAGE),
        image_len: px.len(),
        width: w,
        height: h,
        stride: w,
        cfg: m.addr(CFG),
        workspace: m.addr(ws),
        workspace_len: ws_len,
        out: m.addr(out),
        out_capacity: cap,
        summary: m.addr(SUMMARY),
    };
    (m, a)
}

/// The `n` segments at `a.out`, read as the JS wrapper reads them: five
/// words every [`SEGMENT_BYTES`].
fn segments_at(m: &Mem, a: &DetectArgs, n: usize) -> Vec<[u32; 5]> {
    (0..n)
        .map(|i| m.get::<[u32; 5]>(a.out - m.addr(0) + SEGMENT_BYTES * i))
        .collect()
}

#[test]
fn detect_in_equals_the_core_bit_for_bit() {
    for (w, h, px) in [rectangle(40), castle()] {
        for p in Profile::ALL {
            let cfg = p.config();
            let want = core_detect(&px, w, h, &cfg);
            assert_scored(&want);
            let (m, a) = layout(w, h, &px, &cfg, default_capacity(w, h));
            // SAFETY: `m` is a live buffer that nothing else references.
            let n = unsafe { detect_in(m.memory(), a) };
            assert_eq!(n, want.len() as i32, "{w}x{h} {p:?}");
            assert_eq!(segments_at(&m, &a, want.len()), want);
            let summary: AaglsdSummary = m.get(SUMMARY);
            assert_eq!(summary.segments, want.len());
        }
    }
}

#[test]
fn a_custom_config_and_a_padded_stride_work() {
    let (w, h, px) = castle();
    let mut cfg = Config::PAPER;
    cfg.min_length_px = 20.0;
    cfg.magnitude_threshold = 10.0;
    let want = core_detect(&px, w, h, &cfg);
    assert!(!want.is_empty() && want != core_detect(&px, w, h, &Config::PAPER));
    // Rows padded to 333 bytes.
    let stride = 333;
    let mut padded = vec![7u8; stride * (h - 1) + w];
    for y in 0..h {
        padded[y * stride..y * stride + w].copy_from_slice(&px[y * w..(y + 1) * w]);
    }
    let (m, mut a) = layout(w, h, &padded, &cfg, 4096);
    a.stride = stride;
    // SAFETY: as above.
    let n = unsafe { detect_in(m.memory(), a) };
    assert_eq!(segments_at(&m, &a, n as usize), want);
}

#[test]
fn a_short_output_keeps_the_best_scores() {
    // The official profile does not merge, so the three kept are the three
    // best of the full output.
    let (w, h, px) = castle();
    let cfg = Config::OFFICIAL;
    let full = core_detect(&px, w, h, &cfg);
    let (m, a) = layout(w, h, &px, &cfg, 3);
    // SAFETY: `m` is a live buffer that nothing else references.
    let n = unsafe { detect_in(m.memory(), a) };
    assert_eq!(n, 3);
    let kept = segments_at(&m, &a, 3);
    let summary: AaglsdSummary = m.get(SUMMARY);
    assert_eq!(summary.dropped_segments, full.len() - 3);
    let score = |b: &[u32; 5]| f32::from_bits(b[4]);
    let rest: Vec<_> = full.iter().filter(|b| !kept.contains(b)).collect();
    assert_eq!(
        rest.len(),
        full.len() - 3,
        "the kept are segments of the full run"
    );
    let best_rest = rest.iter().map(|b| score(b)).fold(0.0, f32::max);
    assert!(
        kept.windows(2).all(|k| score(&k[0]) >= score(&k[1])),
        "best first"
    );
    assert!(score(&kept[2]) >= best_rest);
}

#[test]
fn bad_pointers_and_sizes_get_their_status() {
    use AaglsdStatus as S;
    let (w, h, px) = rectangle(40);
    let cfg = Config::DEFAULT;
    let (m, good) = layout(w, h, &px, &cfg, 64);
    let mem = m.memory();
    let end = m.addr(m.len);
    let status = |s: S| Status::C(s).ret();
    let (null, oob) = (Status::C(S::NullPointer), Status::OutOfBounds);
    type Edit = fn(&mut DetectArgs, usize);
    let cases: [(&str, Edit, Status); 17] = [
        ("null image", |a, _| a.image = 0, null),
        ("null cfg", |a, _| a.cfg = 0, null),
        ("null workspace", |a, _| a.workspace = 0, null),
        ("null out", |a, _| a.out = 0, null),
        ("null summary", |a, _| a.summary = 0, null),
        ("image past the end", |a, end| a.image = end - 10, oob),
        ("image before the start", |a, _| a.image = 1, oob),
        ("huge length", |a, _| a.image_len = usize::MAX, oob),
        ("cfg past the end", |a, end| a.cfg = end - 4, oob),
        ("summary past the end", |a, end| a.summary = end, oob),
        ("huge output", |a, _| a.out_capacity = usize::MAX / 8, oob),
        (
            "misaligned out",
            |a, _| a.out += 2,
            Status::C(S::Misaligned),
        ),
        (
            "overlap",
            |a, _| a.workspace = a.image + 8,
            Status::C(S::BuffersOverlap),
        ),
        (
            "zero width",
            |a, _| a.width = 0,
            Status::C(S::ZeroDimension),
        ),
        (
            "stride",
            |a, _| a.stride = a.width - 1,
            Status::C(S::StrideTooSmall),
        ),
        (
            "short image",
            |a, _| a.image_len -= 1,
            Status::C(S::BufferTooShort),
        ),
        (
            "short workspace",
            |a, _| a.workspace_len -= 1,
            Status::C(S::WorkspaceTooSmall),
        ),
    ];
    for (name, edit, want) in cases {
        // SAFETY: `m` is live and unreferenced.
        let n = unsafe { detect_in(mem, good) };
        assert_eq!(n, 4, "{name}: a summary to clear");
        let mut a = good;
        edit(&mut a, end);
        // SAFETY: as above.
        assert_eq!(unsafe { detect_in(mem, a) }, want.ret(), "{name}");
        if a.summary == good.summary {
            assert_eq!(
                m.get::<AaglsdSummary>(SUMMARY),
                AaglsdSummary::default(),
                "{name}"
            );
        }
    }
    let mut a = good;
    a.out_capacity = 0;
    // SAFETY: as above.
    let r = unsafe { detect_in(mem, a) };
    assert_eq!(r, status(S::OutputEmpty));
    let mut bad = AaglsdConfig::from(&cfg);
    bad.min_groups = 0;
    let (m2, a2) = layout(w, h, &px, &cfg, 64);
    m2.put_config(&bad);
    // SAFETY: as above.
    unsafe {
        assert_eq!(detect_in(m2.memory(), a2), status(S::InvalidConfig));
        assert_eq!(
            config_validate_in(m2.memory(), a2.cfg),
            ConfigField::MinGroups.code()
        );
        assert_eq!(
            workspace_size_in(m2.memory(), w, h, a2.cfg),
            status(S::InvalidConfig)
        );
    }
}

#[test]
fn config_exports() {
    let m = Mem::new(256);
    let mem = m.memory();
    for p in Profile::ALL {
        // SAFETY: `m` is live and unreferenced.
        unsafe {
            assert_eq!(config_profile_in(mem, p.code(), m.addr(16)), 0);
            assert_eq!(config_validate_in(mem, m.addr(16)), 0);
            assert_eq!(
                workspace_size_in(mem, 640, 480, m.addr(16)),
                Workspace::bytes_needed(640, 480, &p.config()).unwrap() as i32
            );
            assert_eq!(
                workspace_size_in(mem, 0, 480, m.addr(16)),
                Status::from(AaglsdStatus::ZeroDimension).ret()
            );
            assert_eq!(
                workspace_size_in(mem, 40_000, 1, m.addr(16)),
                Status::from(AaglsdStatus::ImageTooLarge).ret()
            );
        }
        assert_eq!(Config::from(&m.get::<AaglsdConfig>(16)), p.config());
    }
    // SAFETY: as above.
    unsafe {
        assert_eq!(
            config_profile_in(mem, 3, m.addr(16)),
            Status::from(AaglsdStatus::InvalidArgument).ret()
        );
        assert_eq!(
            config_profile_in(mem, 0, 0),
            Status::from(AaglsdStatus::NullPointer).ret()
        );
        assert_eq!(
            config_profile_in(mem, 0, m.addr(250)),
            Status::OutOfBounds.ret()
        );
        assert_eq!(
            config_validate_in(mem, m.addr(250)),
            Status::OutOfBounds.ret()
        );
        assert_eq!(
            workspace_size_in(mem, 8, 8, 0),
            Status::from(AaglsdStatus::NullPointer).ret()
        );
    }
    // The offsets follow the declaration order, and the names cover every
    // field the core can report.
    assert!(FIELD_OFFSETS.windows(2).all(|w| w[0] < w[1]));
    assert!(FIELD_OFFSETS[16] < size_of::<AaglsdConfig>());
    assert_eq!(
        FIELD_OFFSETS[FIELD_NAMES.iter().position(|&n| n == "merge").unwrap()],
        offset_of!(AaglsdConfig, merge)
    );
    for f in ConfigField::ALL {
        assert!(
            f.name().split('/').all(|n| FIELD_NAMES.contains(&n)),
            "{f:?}"
        );
    }
}

#[test]
fn names_and_statuses() {
    let m = Mem::new(64);
    let mem = m.memory();
    // SAFETY: `m` is live and unreferenced.
    unsafe {
        assert_eq!(copy_name(mem, Some("out_of_bounds"), m.addr(0), 64), 13);
        assert_eq!(&m.get::<[u8; 13]>(0), b"out_of_bounds");
        assert_eq!(
            copy_name(mem, Some("invalid_config"), m.addr(0), 4),
            14,
            "full length"
        );
        assert_eq!(
            copy_name(mem, None, m.addr(0), 4),
            Status::from(AaglsdStatus::InvalidArgument).ret()
        );
        assert_eq!(
            copy_name(mem, Some("x"), m.addr(60), 8),
            Status::OutOfBounds.ret()
        );
    }
    // The C codes are stable: spot checks by number.
    for (code, name) in [
        (14, "max_link_pixels"),
        (16, "work_per_mille"),
        (17, "bridge_px"),
        (18, "min_score"),
    ] {
        assert_eq!(config_field_str(code), Some(name), "code {code}");
    }
    assert_eq!((config_field_str(0), config_field_str(19)), (None, None));
    // Status numbers: the C ones, then this module's, each named.
    for s in [
        AaglsdStatus::Ok,
        AaglsdStatus::ZeroDimension,
        AaglsdStatus::InvalidConfig,
        AaglsdStatus::NullPointer,
        AaglsdStatus::Unknown,
    ] {
        assert_eq!(Status::C(s).code(), s as i32);
    }
    assert_eq!(
        STATUS_NAMES[Status::OutOfBounds.code() as usize],
        "out_of_bounds"
    );
    assert_eq!(
        STATUS_NAMES[Status::OutOfMemory.code() as usize],
        "out_of_memory"
    );
    assert_eq!(STATUS_NAMES[AaglsdStatus::Unknown as usize], "unknown");
    assert_eq!(STATUS_NAMES.len(), Status::OutOfMemory.code() as usize + 1);
    assert_eq!(default_capacity(320, 240), 4800);
    assert_eq!(default_capacity(8, 8), 64);
}
