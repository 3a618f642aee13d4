//! Man-made test scenes with their true lines (issue #39): checkerboards,
//! ruled tables and window grids, the content where a line detector must
//! find every straight edge, and the coverage metric that scores it.
//!
//! Every scene is a picture of axis-aligned rectangles of constant gray in
//! a scene frame, turned and shifted against the pixel grid, rendered
//! without randomness (noise is hashed from the scene's name and the pixel
//! position), so a scene is the same on every run.
//!
//! **Coordinates.** Pixel `(x, y)` covers `[x - 1/2, x + 1/2] x
//! [y - 1/2, y + 1/2]`: the 0-based pixel-centre frame of the detector's
//! output and of the CLI's text. True lines are `[x0, y0, x1, y1]` in that
//! frame.
//!
//! **Rendering** ([`Look`]): each pixel is the mean of its square, so a
//! boundary on a pixel edge (at `k + 1/2`) stays sharp and two-level, one
//! through pixel centres (at `k`) gives a column of the exact mid level,
//! and one at any other phase or angle the grays a camera's pixel would
//! integrate. A camera blur is a Gaussian applied to that area-averaged
//! image (so the optics' blur after the pixel's box); sensor noise an
//! about-normal hashed noise of a few gray levels. `aliased` scenes are
//! point-sampled instead, as a rasteriser without anti-aliasing draws.
//!
//! **True lines.** Wherever the picture's gray differs on the two sides of
//! a straight boundary, that boundary is a true line, in full: the lines
//! are the sides of the rectangles, collinear sides joined, kept where the
//! levels on either side differ, clipped to 1 px inside the outer pixel
//! centres (a gradient needs a pixel each side), pieces under 8 px left
//! out. So:
//! - *checkerboards*: every boundary between two rows (or columns) of
//!   squares is ONE true line across the whole board, although its
//!   polarity alternates square by square, because it is one straight
//!   edge (what a calibration tool fits); the board's outline is a true
//!   line too, the board lying on a ground of a third gray;
//! - *ruled tables*: each rule (a dark band of width 1 to 3 px on the
//!   page) gives its two edges, the page-to-rule boundaries, split where
//!   a crossing rule covers them; a 1-px rule's two edges are 1 px apart,
//!   and a detector's one line down its middle is within 1/2 px of both;
//! - *window grids*: a wall with a regular grid of windows (glass darker
//!   or lighter than the wall, some with a frame and 1-2 px muntins, some
//!   with sills, some below a sky): every edge of frame, glass, muntin and
//!   sill, and the wall's top against the sky.
//!
//! **Splits.** [`Split::Dev`] (37 images, 640x480) is the set the
//! `manmade` example prints and a detector may be tuned on;
//! [`Split::Holdout`] (37 images) has other square sizes, angles, phases,
//! contrasts, rule widths, blurs and image sizes (512x384 to 800x600), to
//! check that what was tuned on Dev holds on images it was not tuned on.
//! Square sizes from 13 to 15 px are in neither: the issue sets targets
//! for 8 to 12 px and for 16 px and up (see [`Family::recall_target`]).
//!
//! **Scoring**: [`coverage`] (recall and precision of length, 1 px and 3
//! degrees) and [`Coverage::handled`].
//!
//! ```
//! use aaglsd_support::manmade::{self, Split};
//! assert_eq!(manmade::names(Split::Dev)[0], "checker-32-centre");
//! let s = manmade::scene(Split::Dev, "table-r2-sharp").unwrap();
//! assert_eq!(s.pixels.len(), s.width * s.height);
//! let perfect = manmade::coverage(&s.lines, &s.lines);
//! assert_eq!((perfect.recall, perfect.precision), (1.0, 1.0));
//! ```

mod coverage;
mod paint;

pub use coverage::{Coverage, HANDLED_PRECISION, Tolerance, coverage, coverage_with};
use paint::{Picture, Rect};

use crate::corpus::fnv1a;

/// What a scene shows, with the size that sets its recall target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Family {
    /// A checkerboard of `square`-px squares.
    Checker {
        /// Side of a square, in px.
        square: f64,
    },
    /// A ruled table whose inner rules are `rule` px wide.
    Table {
        /// Width of the inner rules, in px.
        rule: f64,
    },
    /// A facade: a wall with a regular grid of windows.
    Grid,
}

impl Family {
    /// The issue's recall target: 0.6 for checkerboards of 8 to 12 px
    /// squares (a calibration board seen from afar: the X-junctions take
    /// a larger share of each edge), none below 8 px (nothing asked but
    /// some segments: [`Coverage::handled`]), 0.9 for every other scene.
    pub fn recall_target(&self) -> Option<f64> {
        match *self {
            Family::Checker { square } if square < 8.0 => None,
            Family::Checker { square } if square <= 12.0 => Some(0.6),
            _ => Some(0.9),
        }
    }

    /// The group the summaries report: `checker >=16`, `checker 8-12`,
    /// `checker <8`, `table` or `grid` (boards of 13 to 15 px, in no
    /// split, count with `checker >=16`, as their target does).
    pub fn group(&self) -> &'static str {
        match (*self, self.recall_target()) {
            (Family::Checker { .. }, None) => "checker <8",
            (Family::Checker { .. }, Some(t)) if t < 0.9 => "checker 8-12",
            (Family::Checker { .. }, _) => "checker >=16",
            (Family::Table { .. }, _) => "table",
            (Family::Grid, _) => "grid",
        }
    }

    /// Every [`Family::group`], in report order.
    pub const GROUPS: [&'static str; 5] = [
        "checker >=16",
        "checker 8-12",
        "checker <8",
        "table",
        "grid",
    ];
}

/// How a scene's picture becomes pixels (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// Point-sampled at the pixel centres instead of area-averaged.
    pub aliased: bool,
    /// Standard deviation of the Gaussian blur, in px (0: none).
    pub blur: f64,
    /// Standard deviation of the sensor noise, in gray levels (0: none).
    pub noise: f64,
}

/// The two scene sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// The set to look at and tune on (640x480).
    Dev,
    /// Other parameters and sizes, to check on.
    Holdout,
}

impl Split {
    /// `dev` or `holdout`.
    pub fn name(self) -> &'static str {
        match self {
            Split::Dev => "dev",
            Split::Holdout => "holdout",
        }
    }

    /// The split called `name` ([`Split::name`]).
    pub fn from_name(name: &str) -> Option<Split> {
        [Split::Dev, Split::Holdout]
            .into_iter()
            .find(|s| s.name() == name)
    }
}

/// One rendered scene and its true lines.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Unique, file-safe name (a file stem), which says what is drawn.
    pub name: String,
    /// What is drawn.
    pub family: Family,
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width * height` gray levels, row by row.
    pub pixels: Vec<u8>,
    /// The true line segments, `[x0, y0, x1, y1]` in the pixel-centre
    /// frame (see the module documentation for what they are).
    pub lines: Vec<[f32; 4]>,
    /// Rotation of the scene frame against the image axes, in degrees
    /// (towards +y, clockwise on screen).
    pub angle_deg: f64,
    /// How it was rendered.
    pub look: Look,
}

/// Every scene of `split`, rendered, in a fixed order.
pub fn scenes(split: Split) -> Vec<Scene> {
    let specs = specs(split);
    // Scenes are independent: render them on every core, taking every
    // n-th each (neighbours in the list cost alike), then back in order.
    let n = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut done: Vec<(usize, Scene)> = std::thread::scope(|scope| {
        let specs = &specs;
        let jobs: Vec<_> = (0..n)
            .map(|t| {
                scope.spawn(move || {
                    (t..specs.len())
                        .step_by(n)
                        .map(|i| (i, specs[i].render()))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        jobs.into_iter()
            .flat_map(|j| j.join().expect("rendering does not panic"))
            .collect()
    });
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, s)| s).collect()
}

/// The scene of `split` called `name`, rendered alone.
pub fn scene(split: Split, name: &str) -> Option<Scene> {
    specs(split)
        .iter()
        .find(|s| s.name == name)
        .map(Spec::render)
}

/// The names of `split`'s scenes, in [`scenes`] order, without rendering.
pub fn names(split: Split) -> Vec<String> {
    specs(split).into_iter().map(|s| s.name).collect()
}

/// A scene before rendering.
struct Spec {
    name: String,
    family: Family,
    size: (usize, usize),
    angle: f64,
    look: Look,
    picture: Picture,
}

impl Spec {
    fn render(&self) -> Scene {
        let (w, h) = self.size;
        Scene {
            name: self.name.clone(),
            family: self.family,
            width: w,
            height: h,
            pixels: self
                .picture
                .render(w, h, &self.look, fnv1a(self.name.as_bytes())),
            lines: self.picture.true_lines(w, h),
            angle_deg: self.angle,
            look: self.look,
        }
    }
}

/// `base`, then the image size unless 640x480.
fn named(base: String, size: (usize, usize)) -> String {
    if size == VGA {
        base
    } else {
        format!("{base}-{}x{}", size.0, size.1)
    }
}

/// A number as a name shows it: `16`, `1.5`, `0.75`.
fn num(x: f64) -> String {
    format!("{}", (x * 100.0).round() / 100.0)
}

/// Where the layout sits against the pixel grid: for an unrotated scene,
/// `Edges` puts the boundaries of a checkerboard and the edges of a table's
/// rules on pixel edges (sharp, two-level), `Shift(dx, dy)` moves them
/// by that much from there (`CENTRES`: through the pixel centres).
#[derive(Clone, Copy, Debug)]
enum Align {
    Edges,
    Shift(f64, f64),
}

const CENTRES: Align = Align::Shift(0.5, 0.5);

impl Align {
    /// The name's tag for an unblurred area-averaged render.
    fn tag(self, angle: f64) -> String {
        match self {
            _ if angle != 0.0 => "aa".into(),
            Align::Edges => "sharp".into(),
            Align::Shift(dx, dy) if dx == 0.5 && dy == 0.5 => "centre".into(),
            Align::Shift(dx, dy) => format!("aa{}-{}", num(dx), num(dy)),
        }
    }

    /// `origin` moved to the alignment: its fractional part made `edge`
    /// (where, modulo 1, the layout's boundaries fall relative to its
    /// origin is `edge`'s complement), then shifted.
    fn place(self, origin: (f64, f64), edge: f64) -> (f64, f64) {
        let snap = |o: f64| o.floor() + edge;
        let (dx, dy) = match self {
            Align::Edges => (0.0, 0.0),
            Align::Shift(dx, dy) => (dx, dy),
        };
        (snap(origin.0) + dx, snap(origin.1) + dy)
    }
}

const AA: Look = Look {
    aliased: false,
    blur: 0.0,
    noise: 0.0,
};

const ALIASED: Look = Look {
    aliased: true,
    ..AA
};

/// A camera: blur of `blur` px, noise of `noise` levels.
const fn cam(blur: f64, noise: f64) -> Look {
    Look {
        aliased: false,
        blur,
        noise,
    }
}

/// The render tag of a name: `aliased`, `blur1.2`, or the [`Align`] tag;
/// then `-n2` for noise of 2 levels.
fn look_tag(look: &Look, align: Align, angle: f64) -> String {
    let base = if look.aliased {
        "aliased".to_string()
    } else if look.blur > 0.0 {
        format!("blur{}", num(look.blur))
    } else {
        align.tag(angle)
    };
    if look.noise > 0.0 {
        format!("{base}-n{}", num(look.noise))
    } else {
        base
    }
}

/// The image point that is `(u, v)` from `centre` in a frame turned by
/// `angle` degrees: where a layout's origin goes so that its middle is at
/// `centre`.
fn origin_for(centre: (f64, f64), angle: f64, half: (f64, f64)) -> (f64, f64) {
    let (s, c) = angle.to_radians().sin_cos();
    (
        centre.0 - half.0 * c + half.1 * s,
        centre.1 - half.0 * s - half.1 * c,
    )
}

/// The image's middle, moved by `offset`.
fn middle(size: (usize, usize), offset: (f64, f64)) -> (f64, f64) {
    (
        (size.0 as f64 - 1.0) / 2.0 + offset.0,
        (size.1 as f64 - 1.0) / 2.0 + offset.1,
    )
}

/// How much of the image a checkerboard takes.
#[derive(Clone, Copy, Debug)]
enum Board {
    /// As many squares as fit with this margin (px) all round.
    Fit(f64),
    /// This many squares across and down.
    Squares(usize, usize),
    /// Beyond the image on every side: no outline in view.
    Fill,
}

/// A checkerboard scene.
#[derive(Clone, Copy, Debug)]
struct Checker {
    size: (usize, usize),
    /// Dark square, light square, ground around the board.
    levels: [f64; 3],
    /// The board's middle, from the image's middle, in px.
    offset: (f64, f64),
    square: f64,
    angle: f64,
    board: Board,
    align: Align,
    look: Look,
}

/// The usual checkerboard: 40 / 200 on a ground of 120, centred.
const fn board(
    size: (usize, usize),
    square: f64,
    angle: f64,
    board: Board,
    align: Align,
    look: Look,
) -> Checker {
    Checker {
        size,
        square,
        angle,
        board,
        align,
        look,
        levels: [40.0, 200.0, 120.0],
        offset: (0.0, 0.0),
    }
}

impl Checker {
    /// With these dark, light and ground levels.
    const fn levels(self, levels: [f64; 3]) -> Self {
        Self { levels, ..self }
    }

    /// With the board's middle moved by `(dx, dy)` px.
    const fn offset(self, dx: f64, dy: f64) -> Self {
        Self {
            offset: (dx, dy),
            ..self
        }
    }

    /// Squares across and down: the board's turned bounding box within
    /// the image less the margin, the largest area; at least 2 x 2.
    fn count(&self) -> (usize, usize) {
        let (w, h) = (self.size.0 as f64, self.size.1 as f64);
        let (s, c) = self.angle.to_radians().sin_cos();
        let (s, c) = (s.abs() * self.square, c.abs() * self.square);
        match self.board {
            Board::Squares(nx, ny) => (nx, ny),
            Board::Fill => {
                let n = (w.hypot(h) / self.square).ceil() as usize + 2;
                (n, n)
            }
            Board::Fit(m) => {
                // Turned, nx x ny squares take nx c + ny s across and
                // nx s + ny c down.
                let (aw, ah) = (w - 2.0 * m, h - 2.0 * m);
                let mut best = (2, 2);
                for ny in 2..1000usize {
                    let ny_f = ny as f64;
                    let by_h = if s > 1e-9 {
                        (ah - ny_f * c) / s
                    } else if ny_f * c <= ah {
                        f64::INFINITY
                    } else {
                        -1.0
                    };
                    let nx = ((aw - ny_f * s) / c).min(by_h).floor();
                    if nx < 2.0 {
                        break;
                    }
                    if nx as usize * ny > best.0 * best.1 {
                        best = (nx as usize, ny);
                    }
                }
                best
            }
        }
    }

    fn spec(&self) -> Spec {
        let (nx, ny) = self.count();
        let q = self.square;
        let half = (nx as f64 * q / 2.0, ny as f64 * q / 2.0);
        let raw = origin_for(middle(self.size, self.offset), self.angle, half);
        let origin = self.align.place(raw, 0.5);
        let [dark, light, ground] = self.levels;
        let mut rects = vec![Rect {
            u0: 0.0,
            v0: 0.0,
            u1: nx as f64 * q,
            v1: ny as f64 * q,
            level: light,
        }];
        for j in 0..ny {
            for i in (j % 2..nx).step_by(2) {
                let (u, v) = (i as f64 * q, j as f64 * q);
                rects.push(Rect {
                    u0: u,
                    v0: v,
                    u1: u + q,
                    v1: v + q,
                    level: dark,
                });
            }
        }
        let board = match self.board {
            Board::Fit(_) => String::new(),
            Board::Squares(nx, ny) => format!("-{nx}x{ny}"),
            Board::Fill => "-fill".into(),
        };
        let contrast = if (light - dark).abs() < 100.0 {
            "-low"
        } else {
            ""
        };
        let angle = if self.angle == 0.0 {
            String::new()
        } else {
            format!("-a{}", num(self.angle))
        };
        Spec {
            name: named(
                format!(
                    "checker-{}{angle}{board}-{}{contrast}",
                    num(q),
                    look_tag(&self.look, self.align, self.angle)
                ),
                self.size,
            ),
            family: Family::Checker { square: q },
            size: self.size,
            angle: self.angle,
            look: self.look,
            picture: Picture::new(origin, self.angle, ground, rects),
        }
    }
}

/// A ruled table scene: rules of `rule` px between cells, an outer frame
/// of `frame` px, dark ink on a light page, centred.
#[derive(Clone, Debug)]
struct Table {
    size: (usize, usize),
    rule: f64,
    frame: f64,
    /// Column widths and row heights (rule centre to rule centre).
    cols: Vec<f64>,
    rows: Vec<f64>,
    /// Vertical rules (else only horizontal ones: a "booktabs" table).
    verticals: bool,
    /// The gray of a shaded header row, if any.
    shade: Option<f64>,
    angle: f64,
    align: Align,
    look: Look,
    /// Ink, page.
    levels: [f64; 2],
}

/// Widths taken from `pattern` in turn while the total stays within
/// `room`.
fn widths(pattern: &[f64], room: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut total = 0.0;
    for &w in pattern.iter().cycle() {
        if total + w > room {
            break;
        }
        total += w;
        out.push(w);
    }
    out
}

/// A table with a header row of `header` px and body rows of `row` px,
/// columns from `cols`, filling the image less a margin of 40 px.
fn table(size: (usize, usize), rule: f64, cols: &[f64], header: f64, row: f64) -> Table {
    let (w, h) = (size.0 as f64 - 80.0, size.1 as f64 - 80.0);
    let mut rows = vec![header];
    rows.extend(widths(&[row], h - header));
    Table {
        size,
        rule,
        frame: rule,
        cols: widths(cols, w),
        rows,
        verticals: true,
        shade: None,
        angle: 0.0,
        align: Align::Edges,
        look: AA,
        levels: [30.0, 235.0],
    }
}

impl Table {
    /// With an outer frame of `frame` px.
    fn frame(self, frame: f64) -> Self {
        Self { frame, ..self }
    }

    /// With horizontal rules only.
    fn hrules(self) -> Self {
        Self {
            verticals: false,
            ..self
        }
    }

    /// With the header row shaded `level`.
    fn shade(self, level: f64) -> Self {
        Self {
            shade: Some(level),
            ..self
        }
    }

    /// With these ink and page levels.
    fn ink(self, ink: f64, page: f64) -> Self {
        Self {
            levels: [ink, page],
            ..self
        }
    }

    /// Turned by `angle` degrees.
    fn turned(self, angle: f64) -> Self {
        Self { angle, ..self }
    }

    /// Placed at `align`.
    fn at(self, align: Align) -> Self {
        Self { align, ..self }
    }

    /// Rendered as `look` says.
    fn look(self, look: Look) -> Self {
        Self { look, ..self }
    }

    fn spec(&self) -> Spec {
        let xs: Vec<f64> = prefix_sums(&self.cols);
        let ys: Vec<f64> = prefix_sums(&self.rows);
        let (tw, th) = (xs[xs.len() - 1], ys[ys.len() - 1]);
        let [ink, page] = self.levels;
        let f = self.frame / 2.0;
        let mut rects = Vec::new();
        if let Some(level) = self.shade {
            rects.push(Rect {
                u0: 0.0,
                v0: 0.0,
                u1: tw,
                v1: ys[1],
                level,
            });
        }
        let outer = |i: usize, n: usize| i == 0 || i + 1 == n;
        // Outer rules reach over the frame's corners; inner ones end in
        // the frame (or, with no verticals, at the table's sides).
        let reach = if self.verticals { f } else { 0.0 };
        for (i, &y) in ys.iter().enumerate() {
            let (half, ext) = if outer(i, ys.len()) {
                (f, reach)
            } else {
                (self.rule / 2.0, 0.0)
            };
            rects.push(Rect {
                u0: -ext,
                v0: y - half,
                u1: tw + ext,
                v1: y + half,
                level: ink,
            });
        }
        for (i, &x) in xs.iter().enumerate().filter(|_| self.verticals) {
            let (half, ext) = if outer(i, xs.len()) {
                (f, f)
            } else {
                (self.rule / 2.0, 0.0)
            };
            rects.push(Rect {
                u0: x - half,
                v0: -ext,
                u1: x + half,
                v1: th + ext,
                level: ink,
            });
        }
        let raw = origin_for(
            middle(self.size, (0.0, 0.0)),
            self.angle,
            (tw / 2.0, th / 2.0),
        );
        // Rule edges at the origin +- rule/2 must fall on pixel edges.
        let origin = self
            .align
            .place(raw, (0.5 - self.rule / 2.0).rem_euclid(1.0));
        let mut tags = String::new();
        if self.frame != self.rule {
            tags += &format!("-frame{}", num(self.frame));
        }
        if !self.verticals {
            tags += "-hrules";
        }
        if self.shade.is_some() {
            tags += "-shaded";
        }
        if self.angle != 0.0 {
            tags += &format!("-a{}", num(self.angle));
        }
        Spec {
            name: named(
                format!(
                    "table-r{}{tags}-{}",
                    num(self.rule),
                    look_tag(&self.look, self.align, self.angle)
                ),
                self.size,
            ),
            family: Family::Table { rule: self.rule },
            size: self.size,
            angle: self.angle,
            look: self.look,
            picture: Picture::new(origin, self.angle, page, rects),
        }
    }
}

/// `[0, a, a + b, ...]`.
fn prefix_sums(v: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0];
    for &x in v {
        out.push(out[out.len() - 1] + x);
    }
    out
}

/// A facade: `count` windows of `window` px, `pitch` px apart, centred on
/// a wall.
#[derive(Clone, Copy, Debug)]
struct Facade {
    size: (usize, usize),
    count: (usize, usize),
    window: (f64, f64),
    pitch: (f64, f64),
    /// Wall, glass, frame and muntins.
    levels: [f64; 3],
    /// Frame width (0: none).
    frame: f64,
    /// Muntins across and down, and their width.
    muntins: (usize, usize, f64),
    /// A sill under each window: its height (0: none).
    sill: f64,
    /// The sky's gray and the wall's top, in px above the first row of
    /// windows (none: the wall fills the image).
    sky: Option<(f64, f64)>,
    angle: f64,
    align: Align,
    look: Look,
    /// A name tag saying what kind of facade.
    tag: &'static str,
}

/// A facade of `count` plain dark windows of `window` px on a wall,
/// `tag` saying what kind in its name.
const fn facade(
    size: (usize, usize),
    count: (usize, usize),
    window: (f64, f64),
    tag: &'static str,
) -> Facade {
    Facade {
        size,
        count,
        window,
        pitch: (window.0 * 2.0, window.1 * 1.6),
        levels: [150.0, 55.0, 225.0],
        frame: 0.0,
        muntins: (0, 0, 0.0),
        sill: 0.0,
        sky: None,
        angle: 0.0,
        align: Align::Edges,
        look: AA,
        tag,
    }
}

impl Facade {
    /// With these wall, glass and frame levels.
    const fn levels(self, levels: [f64; 3]) -> Self {
        Self { levels, ..self }
    }

    /// With a frame of `frame` px and muntins (across, down, width).
    const fn framed(self, frame: f64, muntins: (usize, usize, f64)) -> Self {
        Self {
            frame,
            muntins,
            ..self
        }
    }

    /// With a sill of `height` px under each window.
    const fn sill(self, height: f64) -> Self {
        Self {
            sill: height,
            ..self
        }
    }

    /// Below a sky of `level`, the wall's top `above` px over the windows.
    const fn sky(self, level: f64, above: f64) -> Self {
        Self {
            sky: Some((level, above)),
            ..self
        }
    }

    /// With windows `(dx, dy)` px apart.
    const fn pitch(self, dx: f64, dy: f64) -> Self {
        Self {
            pitch: (dx, dy),
            ..self
        }
    }

    /// Turned by `angle` degrees.
    const fn turned(self, angle: f64) -> Self {
        Self { angle, ..self }
    }

    /// Placed at `align`.
    const fn at(self, align: Align) -> Self {
        Self { align, ..self }
    }

    /// Rendered as `look` says.
    const fn look(self, look: Look) -> Self {
        Self { look, ..self }
    }

    fn spec(&self) -> Spec {
        let [wall, glass, bars] = self.levels;
        let (nx, ny) = self.count;
        let (ww, wh) = self.window;
        let (gw, gh) = (
            (nx - 1) as f64 * self.pitch.0 + ww,
            (ny - 1) as f64 * self.pitch.1 + wh,
        );
        let mut rects = Vec::new();
        let background = match self.sky {
            Some((sky, above)) => {
                let far = (self.size.0 + self.size.1) as f64 * 2.0;
                rects.push(Rect {
                    u0: -far,
                    v0: -above,
                    u1: far,
                    v1: far,
                    level: wall,
                });
                sky
            }
            None => wall,
        };
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (i as f64 * self.pitch.0, j as f64 * self.pitch.1);
                self.window_rects(x, y, &mut rects, glass, bars);
            }
        }
        let raw = origin_for(
            middle(self.size, (0.0, 0.0)),
            self.angle,
            (gw / 2.0, gh / 2.0),
        );
        let origin = self.align.place(raw, 0.5);
        Spec {
            name: named(
                format!(
                    "grid-{nx}x{ny}{}-{}",
                    self.tag,
                    look_tag(&self.look, self.align, self.angle)
                ),
                self.size,
            ),
            family: Family::Grid,
            size: self.size,
            angle: self.angle,
            look: self.look,
            picture: Picture::new(origin, self.angle, background, rects),
        }
    }

    /// The rectangles of the window whose top-left corner is `(x, y)`:
    /// sill, frame, glass, then muntins across the glass, each at whole
    /// pixels from the glass's corner.
    fn window_rects(&self, x: f64, y: f64, rects: &mut Vec<Rect>, glass: f64, bars: f64) {
        let (ww, wh) = self.window;
        let r = |u0: f64, v0: f64, u1: f64, v1: f64, level: f64| Rect {
            u0,
            v0,
            u1,
            v1,
            level,
        };
        if self.sill > 0.0 {
            rects.push(r(x - 4.0, y + wh, x + ww + 4.0, y + wh + self.sill, bars));
        }
        if self.frame > 0.0 {
            rects.push(r(x, y, x + ww, y + wh, bars));
        }
        let f = self.frame;
        let (g0, g1) = ((x + f, y + f), (x + ww - f, y + wh - f));
        rects.push(r(g0.0, g0.1, g1.0, g1.1, glass));
        let (mx, my, b) = self.muntins;
        for k in 1..=mx {
            let at = g0.0 + ((g1.0 - g0.0) * k as f64 / (mx + 1) as f64 - b / 2.0).round();
            rects.push(r(at, g0.1, at + b, g1.1, bars));
        }
        for k in 1..=my {
            let at = g0.1 + ((g1.1 - g0.1) * k as f64 / (my + 1) as f64 - b / 2.0).round();
            rects.push(r(g0.0, at, g1.0, at + b, bars));
        }
    }
}

const VGA: (usize, usize) = (640, 480);
const SVGA: (usize, usize) = (800, 600);
const SMALL: (usize, usize) = (512, 384);
const MID: (usize, usize) = (720, 540);

fn specs(split: Split) -> Vec<Spec> {
    match split {
        Split::Dev => dev(),
        Split::Holdout => holdout(),
    }
}

/// The Dev scenes: the issue's kinds at 640x480 (32, 24, 16-px boards
/// with the mid-gray pixel on each edge; 8 to 12-px boards seen from
/// afar; 16-px boards turned 23 or 41 degrees and blurred; sharp 2-px and
/// 1-px rule tables; window grids), and around them the other renders.
fn dev() -> Vec<Spec> {
    use Align::{Edges, Shift};
    use Board::{Fill, Fit, Squares};
    let s = VGA;
    let checkers = [
        board(s, 32.0, 0.0, Fit(24.0), CENTRES, AA),
        board(s, 24.0, 0.0, Fit(24.0), CENTRES, AA),
        board(s, 16.0, 0.0, Fit(24.0), CENTRES, AA),
        board(s, 32.0, 0.0, Fit(40.0), Edges, AA),
        board(s, 24.0, 0.0, Fill, Edges, AA),
        board(s, 20.0, 0.0, Fit(30.0), Shift(0.3, 0.7), AA),
        board(s, 12.0, 0.0, Squares(10, 7), CENTRES, AA),
        board(s, 10.0, 0.0, Squares(9, 6), Edges, AA),
        board(s, 8.0, 0.0, Squares(11, 8), CENTRES, AA),
        board(s, 8.0, 0.0, Fill, Edges, AA),
        board(s, 12.0, 0.0, Fit(30.0), Shift(0.25, 0.6), cam(0.8, 0.0)),
        board(s, 6.0, 0.0, Fit(20.0), Edges, AA),
        board(s, 6.0, 0.0, Squares(12, 9), CENTRES, AA),
        board(s, 16.0, 23.0, Fit(24.0), Edges, cam(1.0, 0.0)),
        board(s, 16.0, 41.0, Fit(24.0), Edges, cam(1.2, 2.0)),
        board(s, 16.0, 23.0, Fit(24.0), Edges, AA),
        board(s, 24.0, 41.0, Fill, Edges, cam(0.8, 0.0)),
        board(s, 32.0, 23.0, Squares(9, 6), Edges, cam(1.5, 1.0)),
        board(s, 12.0, 41.0, Fit(24.0), Edges, cam(0.8, 0.0)),
        board(s, 10.0, 23.0, Squares(10, 7), Edges, AA),
        board(s, 16.0, 41.0, Fit(24.0), Edges, ALIASED),
        board(s, 16.0, 0.0, Squares(9, 7), Edges, AA).offset(-120.0, 60.0),
        board(s, 24.0, 0.0, Fit(24.0), CENTRES, cam(0.0, 2.0)).levels([90.0, 160.0, 210.0]),
    ];
    let cols = [120.0, 80.0, 150.0, 96.0];
    let tables = [
        table(s, 2.0, &cols, 40.0, 28.0),
        table(s, 1.0, &cols, 36.0, 24.0),
        table(s, 3.0, &[140.0, 100.0, 70.0], 44.0, 32.0).frame(3.0),
        table(s, 1.0, &[90.0, 130.0, 60.0], 30.0, 22.0).at(Shift(0.35, 0.6)),
        table(s, 2.0, &[110.0, 70.0, 160.0], 36.0, 26.0)
            .at(Shift(0.2, 0.2))
            .look(cam(0.8, 0.0)),
        table(s, 1.0, &[200.0, 120.0, 150.0], 34.0, 26.0)
            .frame(3.0)
            .hrules(),
        table(s, 2.0, &[100.0, 100.0, 140.0, 80.0], 40.0, 30.0).shade(200.0),
        table(s, 1.5, &[130.0, 90.0, 110.0], 34.0, 28.0)
            .turned(2.0)
            .look(cam(0.7, 2.0)),
    ];
    let facades = [
        facade(s, (8, 5), (36.0, 48.0), "-dark"),
        facade(s, (7, 5), (40.0, 50.0), "-light")
            .levels([70.0, 215.0, 40.0])
            .at(Shift(0.4, 0.3)),
        facade(s, (6, 4), (48.0, 64.0), "-muntins").framed(3.0, (1, 1, 1.0)),
        facade(s, (6, 4), (54.0, 60.0), "-muntins")
            .framed(2.0, (2, 1, 2.0))
            .look(cam(1.0, 2.0)),
        facade(s, (7, 4), (40.0, 52.0), "-sky")
            .framed(2.0, (0, 0, 0.0))
            .sill(5.0)
            .sky(235.0, 36.0)
            .at(Shift(0.25, 0.75)),
        facade(s, (19, 12), (22.0, 24.0), "-office")
            .pitch(30.0, 34.0)
            .look(cam(0.8, 0.0)),
    ];
    collect(&checkers, &tables, &facades)
}

/// The Holdout scenes: other sizes, square sides, angles, phases,
/// contrasts, rule widths and blurs than Dev.
fn holdout() -> Vec<Spec> {
    use Align::{Edges, Shift};
    use Board::{Fill, Fit, Squares};
    let checkers = [
        board(SVGA, 28.0, 0.0, Fit(30.0), CENTRES, AA),
        board(SMALL, 18.0, 0.0, Fit(20.0), CENTRES, AA),
        board(MID, 20.0, 0.0, Squares(8, 6), Edges, AA),
        board(VGA, 30.0, 0.0, Fill, Edges, AA),
        board(SVGA, 17.5, 0.0, Fit(40.0), Shift(0.4, 0.1), AA),
        board(SVGA, 11.0, 0.0, Squares(9, 7), CENTRES, AA),
        board(SMALL, 9.0, 0.0, Fit(16.0), Edges, AA),
        board(
            VGA,
            9.5,
            0.0,
            Squares(12, 8),
            Shift(0.15, 0.85),
            cam(0.9, 0.0),
        ),
        board(MID, 11.0, 0.0, Fill, Edges, AA),
        board(VGA, 7.0, 0.0, Fit(30.0), CENTRES, AA),
        board(VGA, 7.0, 0.0, Squares(14, 10), Edges, cam(0.7, 0.0)),
        board(SVGA, 18.0, 7.0, Fit(30.0), Edges, cam(1.1, 0.0)),
        board(VGA, 20.0, 15.0, Fit(24.0), Edges, AA),
        board(MID, 16.0, 33.0, Fit(30.0), Edges, cam(1.3, 2.0)),
        board(SMALL, 22.0, 58.0, Fill, Edges, cam(0.9, 0.0)),
        board(SVGA, 28.0, 33.0, Squares(8, 6), Edges, cam(1.4, 0.0)),
        board(VGA, 11.0, 15.0, Fit(24.0), Edges, cam(0.7, 0.0)),
        board(SVGA, 9.0, 58.0, Squares(10, 8), Edges, AA),
        board(MID, 18.0, 7.0, Fit(30.0), Edges, ALIASED),
        board(SMALL, 16.0, 75.0, Fit(20.0), Edges, cam(1.0, 0.0)),
        board(
            VGA,
            32.0,
            0.0,
            Squares(6, 5),
            Shift(0.5, 0.0),
            cam(1.0, 0.0),
        ),
        board(VGA, 26.0, 0.0, Fit(30.0), CENTRES, cam(0.0, 3.0)).levels([100.0, 170.0, 40.0]),
        board(SVGA, 10.0, 0.0, Squares(8, 6), Edges, cam(0.0, 1.0))
            .offset(150.0, -90.0)
            .levels([20.0, 230.0, 140.0]),
    ];
    let tables = [
        table(MID, 1.0, &[100.0, 140.0, 90.0, 120.0], 32.0, 22.0),
        table(SVGA, 2.0, &[180.0, 90.0, 120.0], 44.0, 34.0).at(Shift(0.3, 0.45)),
        table(VGA, 3.0, &[150.0, 110.0], 48.0, 36.0).look(cam(1.0, 0.0)),
        table(VGA, 1.5, &[85.0, 125.0, 100.0], 30.0, 24.0).at(Shift(0.2, 0.7)),
        table(SVGA, 2.5, &[160.0, 130.0, 95.0], 40.0, 30.0)
            .frame(4.0)
            .look(cam(0.7, 0.0)),
        table(SMALL, 1.0, &[140.0, 90.0, 120.0], 30.0, 20.0)
            .frame(2.0)
            .hrules()
            .look(cam(0.8, 2.0)),
        table(VGA, 1.0, &[120.0, 90.0, 130.0], 34.0, 26.0)
            .shade(190.0)
            .frame(3.0)
            .ink(60.0, 220.0),
        table(SVGA, 1.0, &[110.0, 150.0, 80.0, 120.0], 36.0, 26.0).turned(-1.0),
    ];
    let facades = [
        facade(SVGA, (10, 6), (34.0, 46.0), "-dark").levels([120.0, 40.0, 200.0]),
        facade(SMALL, (6, 4), (30.0, 40.0), "-light")
            .levels([60.0, 190.0, 30.0])
            .look(cam(0.9, 0.0)),
        facade(MID, (7, 4), (44.0, 66.0), "-muntins")
            .framed(2.0, (1, 2, 2.0))
            .at(CENTRES),
        facade(VGA, (6, 4), (50.0, 56.0), "-muntins")
            .framed(3.0, (1, 0, 1.0))
            .sill(4.0)
            .look(cam(1.2, 1.0)),
        facade(SVGA, (8, 4), (42.0, 58.0), "-sky")
            .levels([170.0, 80.0, 240.0])
            .framed(2.0, (0, 0, 0.0))
            .sky(90.0, 50.0),
        facade(MID, (24, 15), (18.0, 20.0), "-office")
            .pitch(26.0, 30.0)
            .turned(1.5),
    ];
    collect(&checkers, &tables, &facades)
}

fn collect(checkers: &[Checker], tables: &[Table], facades: &[Facade]) -> Vec<Spec> {
    let mut out: Vec<Spec> = checkers.iter().map(Checker::spec).collect();
    out.extend(tables.iter().map(Table::spec));
    out.extend(facades.iter().map(Facade::spec));
    out
}

#[cfg(test)]
mod tests;
