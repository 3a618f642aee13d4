use super::*;

/// The spec called `name` in `split`.
fn spec(split: Split, name: &str) -> Spec {
    specs(split)
        .into_iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no scene {name}; {:?}", names(split)))
}

/// The level at `(x, y)`, bilinear between pixel centres.
fn bilinear(s: &Scene, x: f64, y: f64) -> f64 {
    let (x, y) = (
        x.clamp(0.0, s.width as f64 - 1.001),
        y.clamp(0.0, s.height as f64 - 1.001),
    );
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (fx, fy) = (x - x0 as f64, y - y0 as f64);
    let p = |dx: usize, dy: usize| f64::from(s.pixels[(y0 + dy) * s.width + x0 + dx]);
    (p(0, 0) * (1.0 - fx) + p(1, 0) * fx) * (1.0 - fy) + (p(0, 1) * (1.0 - fx) + p(1, 1) * fx) * fy
}

/// Points every px along `l` (1 px in from each end), with the unit
/// normal.
fn along(l: &[f32; 4]) -> impl Iterator<Item = ((f64, f64), (f64, f64))> {
    let [x0, y0, x1, y1] = l.map(f64::from);
    let len = (x1 - x0).hypot(y1 - y0);
    let (dx, dy) = ((x1 - x0) / len, (y1 - y0) / len);
    (1..len as usize).map(move |k| {
        let t = k as f64;
        ((x0 + t * dx, y0 + t * dy), (-dy, dx))
    })
}

/// The signed level difference across 1 px at `p + d n`.
fn step_at(s: &Scene, p: (f64, f64), n: (f64, f64), d: f64) -> f64 {
    let at = |e: f64| bilinear(s, p.0 + e * n.0, p.1 + e * n.1);
    at(d + 0.5) - at(d - 0.5)
}

/// Where across the line at `p` the edge is, from the line: the centroid
/// of the level steps of `p`'s sign within 1.25 px.
fn edge_offset(s: &Scene, p: (f64, f64), n: (f64, f64)) -> f64 {
    let sign = step_at(s, p, n, 0.0).signum();
    let (mut sum, mut weight) = (0.0, 0.0);
    for k in -5..=5 {
        let d = f64::from(k) / 4.0;
        let g = (sign * step_at(s, p, n, d)).max(0.0);
        sum += g * d;
        weight += g;
    }
    sum / weight
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn names_sizes_and_targets() {
    let (dev, holdout) = (names(Split::Dev), names(Split::Holdout));
    assert!((30..=40).contains(&dev.len()), "{}", dev.len());
    assert!((30..=40).contains(&holdout.len()), "{}", holdout.len());
    let mut all: Vec<&String> = dev.iter().chain(&holdout).collect();
    assert!(all.iter().all(|n| {
        n.bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b"-.".contains(&b))
    }));
    all.sort_unstable();
    for pair in all.windows(2) {
        assert_ne!(pair[0], pair[1], "a name repeats");
    }
    for split in [Split::Dev, Split::Holdout] {
        let specs = specs(split);
        let groups: Vec<&str> = specs.iter().map(|s| s.family.group()).collect();
        for g in Family::GROUPS {
            assert!(groups.contains(&g), "{} has no {g}", split.name());
        }
        for s in &specs {
            if let Family::Checker { square } = s.family {
                assert!((6.0..=32.0).contains(&square), "{}", s.name);
                assert!(!(12.0 < square && square < 16.0), "{}", s.name);
            }
        }
        let rotated = specs.iter().filter(|s| s.angle != 0.0).count();
        assert!(rotated >= 8, "{}: {rotated} rotated", split.name());
    }
    assert!(specs(Split::Dev).iter().all(|s| s.size == VGA));
    assert!(specs(Split::Holdout).iter().any(|s| s.size == SVGA));
    assert_eq!(Family::Checker { square: 6.0 }.recall_target(), None);
    assert_eq!(Family::Checker { square: 8.0 }.recall_target(), Some(0.6));
    assert_eq!(Family::Checker { square: 12.0 }.recall_target(), Some(0.6));
    assert_eq!(Family::Checker { square: 16.0 }.recall_target(), Some(0.9));
    assert_eq!(Family::Table { rule: 1.0 }.recall_target(), Some(0.9));
    assert_eq!(Split::from_name("holdout"), Some(Split::Holdout));
    assert_eq!(Split::from_name("test"), None);
}

#[test]
fn deterministic_and_sized() {
    for (split, name) in [
        (Split::Dev, "checker-16-a41-blur1.2-n2"),
        (Split::Holdout, "table-r1-frame3-shaded-sharp"),
    ] {
        let sp = spec(split, name);
        let (a, b) = (sp.render(), sp.render());
        assert_eq!(a, b, "{name}");
        assert_eq!(a.pixels.len(), a.width * a.height);
        assert_eq!((a.width, a.height), sp.size);
        assert!(!a.lines.is_empty());
    }
}

#[test]
fn checkerboard_lines_cross_the_board() {
    let s = spec(Split::Dev, "checker-32-centre").render();
    // 18 x 13 squares of 32 px fit in 592 x 432: 19 + 14 lines, each the
    // whole board's width or height, through pixel centres.
    assert_eq!(s.lines.len(), 19 + 14);
    for l in &s.lines {
        let len = f64::from(l[2] - l[0]).hypot(f64::from(l[3] - l[1]));
        let vertical = l[0] == l[2];
        assert!(vertical || l[1] == l[3], "{l:?}");
        assert_eq!(len, if vertical { 13.0 * 32.0 } else { 18.0 * 32.0 });
        assert_eq!(l[0].fract(), 0.0);
        assert_eq!(l[1].fract(), 0.0);
    }
    // The mid-gray pixel on each edge: 40 and 200 average to 120.
    let px = |x: f32, y: f32| s.pixels[y as usize * s.width + x as usize];
    // On the outline, half way between a square and the ground (120).
    for l in s.lines.iter().filter(|l| l[0] == l[2]) {
        let outline = l[0] == 32.0 || l[0] == 32.0 + 18.0 * 32.0;
        let (mid, dark_end, light_end) = (px(l[0], l[1] + 5.0), 80, 160);
        assert!(
            if outline {
                mid == dark_end || mid == light_end
            } else {
                mid == 120
            },
            "{l:?}: {mid}"
        );
    }
    // A board filling the frame has no outline: lines end at the clip.
    let fill = spec(Split::Dev, "checker-24-fill-sharp").render();
    assert!(fill.lines.iter().all(|l| {
        let ends = [l[0], l[2]].iter().any(|&x| x == 1.0 || x == 638.0)
            || [l[1], l[3]].iter().any(|&y| y == 1.0 || y == 478.0);
        ends && l.iter().all(|v| v.fract() == 0.5 || v.fract() == 0.0)
    }));
}

#[test]
fn thin_rules_give_two_edges_1_px_apart() {
    let s = spec(Split::Dev, "table-r1-sharp").render();
    let mut ys: Vec<f32> = s
        .lines
        .iter()
        .filter(|l| l[1] == l[3])
        .map(|l| l[1])
        .collect();
    ys.sort_by(f32::total_cmp);
    ys.dedup();
    assert!(ys.len() >= 20, "{ys:?}");
    for pair in ys.chunks(2) {
        assert_eq!(pair[1] - pair[0], 1.0, "{ys:?}");
        assert_eq!(pair[0].fract(), 0.5, "rule edges on pixel edges");
    }
}

#[test]
fn true_lines_lie_on_the_edges() {
    let cases = [
        (Split::Dev, "checker-32-centre"),
        (Split::Dev, "checker-6-sharp"),
        (Split::Dev, "checker-16-a23-blur1"),
        (Split::Dev, "checker-16-a41-aliased"),
        (Split::Dev, "checker-24-centre-n2-low"),
        (Split::Holdout, "checker-17.5-aa0.4-0.1-800x600"),
        (Split::Holdout, "checker-22-a58-fill-blur0.9-512x384"),
        (Split::Dev, "table-r3-sharp"),
        (Split::Dev, "table-r1-aa0.35-0.6"),
        (Split::Dev, "grid-6x4-muntins-sharp"),
        (Split::Dev, "grid-7x4-sky-aa0.25-0.75"),
    ];
    for (split, name) in cases {
        let s = spec(split, name).render();
        assert!(!s.lines.is_empty(), "{name}");
        let wide = matches!(s.family, Family::Checker { .. }) || name.starts_with("table-r3");
        let mut on = Vec::new();
        let mut off = Vec::new();
        for l in &s.lines {
            let points: Vec<_> = along(l).collect();
            let mean_step = |shift: f64| {
                let sum: f64 = points
                    .iter()
                    .map(|&(p, n)| step_at(&s, p, n, shift).abs())
                    .sum();
                sum / points.len() as f64
            };
            on.push(mean_step(0.0));
            off.push(mean_step(4.5));
            // Every line has a clear level step across it.
            assert!(mean_step(0.0) >= 20.0, "{name}: {l:?}: {}", mean_step(0.0));
            if wide {
                // And sits on the edge, not half a pixel beside it
                // (the median leaves out the points near crossings).
                let at = median(points.iter().map(|&(p, n)| edge_offset(&s, p, n)).collect());
                let tol = if s.look.aliased { 0.25 } else { 0.1 };
                assert!(at.abs() <= tol, "{name}: {l:?}: edge {at:+.3} px off");
            }
        }
        // 4.5 px beside the lines, mostly flat.
        let (on, off) = (median(on), median(off));
        assert!(off < on / 4.0, "{name}: {on} on the lines, {off} beside");
    }
}
