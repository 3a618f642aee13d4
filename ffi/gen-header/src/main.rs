//! Writes `ffi/include/aaglsd.h`, or checks that the committed one is current.
//!
//! ```text
//! cargo run -p aaglsd-gen-header              # write the header (only when it changed)
//! cargo run -p aaglsd-gen-header -- --check   # write nothing; exit 1 when it is stale
//! ```
//!
//! The header is cbindgen's rendering of `ffi/src` (configured by
//! `ffi/cbindgen.toml`) with, after the includes, the compile-time
//! workspace-size macros (`AAGLSD_WORKSPACE_BYTES` and its variants). Those
//! are rendered from one expression tree ([`formula`]) whose constants come
//! from the core (`Workspace::ALIGN_SLACK` and the others, the profiles'
//! capacities), so regenerating the header follows a change of any of them.
//! Before it writes or checks anything, the generator evaluates the same
//! tree over a grid of sizes and capacities and stops when it disagrees with
//! `Workspace::bytes_needed*` (a change to the formula's shape); the C test
//! `ffi/tests/sizes.c` then compares the compiled macros with the library's
//! size functions.
//!
//! The C library does not depend on this crate: cross builds of `aaglsd-ffi`
//! never compile cbindgen, and nothing but this tool writes into the source
//! tree.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use aaglsd::{Config, MAX_DIMENSION, MAX_PIXELS, Workspace};

/// The macro parameters, in order.
const PARAMS: [&str; 4] = ["w", "h", "pm", "v"];

/// An unsigned integer expression over [`PARAMS`]: rendered as C (in
/// `unsigned long long`, at least 64 bits) and evaluated here.
#[derive(Clone, Debug)]
enum E {
    /// A macro parameter, by its index in [`PARAMS`].
    Param(usize),
    /// A constant.
    K(u64),
    /// 1 when the value exceeds `SIZE_MAX` (`usize::MAX` here), else 0.
    OverSizeMax(Box<E>),
    /// A binary operation.
    Op(Op, Box<E>, Box<E>),
    /// `if .0 != 0 { .1 } else { .2 }`.
    If(Box<E>, Box<E>, Box<E>),
    /// A sub-expression that C gets as a helper macro `AAGLSD_WS_<NAME>_`.
    Named(&'static str, Box<E>),
}

#[derive(Clone, Copy, Debug)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Max,
    Gt,
    Eq,
    Or,
}

impl E {
    fn k(n: usize) -> E {
        E::K(n as u64)
    }

    fn op(op: Op, a: E, b: E) -> E {
        E::Op(op, Box::new(a), Box::new(b))
    }

    fn named(name: &'static str, e: E) -> E {
        E::Named(name, Box::new(e))
    }

    fn iff(c: E, a: E, b: E) -> E {
        E::If(Box::new(c), Box::new(a), Box::new(b))
    }

    /// The value for the parameters `p`, or `None` on overflow.
    fn eval(&self, p: &[u64; 4]) -> Option<u128> {
        Some(match self {
            E::Param(i) => u128::from(p[*i]),
            E::K(n) => u128::from(*n),
            E::OverSizeMax(e) => u128::from(e.eval(p)? > usize::MAX as u128),
            E::Named(_, e) => e.eval(p)?,
            E::If(c, a, b) => {
                if c.eval(p)? != 0 {
                    a.eval(p)?
                } else {
                    b.eval(p)?
                }
            }
            E::Op(op, a, b) => {
                let (a, b) = (a.eval(p)?, b.eval(p)?);
                match op {
                    Op::Add => a.checked_add(b)?,
                    Op::Sub => a.checked_sub(b)?,
                    Op::Mul => a.checked_mul(b)?,
                    Op::Div => a.checked_div(b)?,
                    Op::Max => a.max(b),
                    Op::Gt => u128::from(a > b),
                    Op::Eq => u128::from(a == b),
                    Op::Or => u128::from(a != 0 || b != 0),
                }
            }
        })
    }

    /// The C text; the helper macros it calls are added to `defs` (each
    /// once, after those it calls).
    fn c(&self, defs: &mut Vec<(&'static str, String)>) -> String {
        match self {
            E::Param(i) => format!("AAGLSD_WS_U_({})", PARAMS[*i]),
            E::K(n) => format!("{n}ull"),
            // Halved on both sides: `x > SIZE_MAX` is the same test, but
            // where size_t has 64 bits GCC's -Wtype-limits calls it always
            // false.
            E::OverSizeMax(e) => format!("({} / 2ull > SIZE_MAX / 2)", e.c(defs)),
            E::Named(name, e) => {
                if !defs.iter().any(|(n, _)| n == name) {
                    let body = e.c(defs);
                    defs.push((name, body));
                }
                format!("AAGLSD_WS_{name}_({})", PARAMS.join(", "))
            }
            E::If(c, a, b) => format!("({} ? {} : {})", c.c(defs), a.c(defs), b.c(defs)),
            E::Op(Op::Max, a, b) => {
                let (a, b) = (a.c(defs), b.c(defs));
                format!("({a} > {b} ? {a} : {b})")
            }
            E::Op(op, a, b) => {
                let sym = match op {
                    Op::Add => "+",
                    Op::Sub => "-",
                    Op::Mul => "*",
                    Op::Div => "/",
                    Op::Gt => ">",
                    Op::Eq => "==",
                    Op::Or => "||",
                    Op::Max => unreachable!("rendered above"),
                };
                format!("({} {sym} {})", a.c(defs), b.c(defs))
            }
        }
    }
}

/// `+ - * /` on expressions build the operation's node.
macro_rules! binary_ops {
    ($($trait_:ident $method:ident $op:ident),*) => {
        $(impl std::ops::$trait_ for E {
            type Output = E;
            fn $method(self, b: E) -> E {
                E::op(Op::$op, self, b)
            }
        })*
    };
}
binary_ops!(Add add Add, Sub sub Sub, Mul mul Mul, Div div Div);

fn ceil_div(a: E, b: usize) -> E {
    (a + E::k(b - 1)) / E::k(b)
}

/// Which size.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    /// `Workspace::bytes_needed` (`aaglsd_workspace_size`).
    Plain,
    /// `Workspace::bytes_needed_in_place` (`aaglsd_workspace_size_in_place`).
    InPlace,
    /// `Workspace::bytes_needed_fast` (`aaglsd_workspace_size_fast`).
    Fast,
}

impl Kind {
    const ALL: [Kind; 3] = [Kind::Plain, Kind::InPlace, Kind::Fast];

    /// The core's size, 0 where it has none (as the C functions write).
    fn core(self, w: usize, h: usize, cfg: &Config) -> usize {
        let f = match self {
            Kind::Plain => Workspace::bytes_needed,
            Kind::InPlace => Workspace::bytes_needed_in_place,
            Kind::Fast => Workspace::bytes_needed_fast,
        };
        f(w, h, cfg).unwrap_or(0)
    }

    /// The macro name's suffix.
    fn suffix(self) -> &'static str {
        match self {
            Kind::Plain => "",
            Kind::InPlace => "_IN_PLACE",
            Kind::Fast => "_FAST",
        }
    }
}

/// The workspace size (`Workspace`'s documented formula), 0 for the
/// dimensions and capacities the core refuses (as the C size functions
/// write on error).
fn formula(kind: Kind) -> E {
    let (w, h, pm, v) = (E::Param(0), E::Param(1), E::Param(2), E::Param(3));
    let pixels = E::named("PIXELS", w.clone() * h.clone());
    let reserve = E::k(Workspace::CANDIDATE_RESERVE);
    let cands = E::named(
        "CANDIDATES",
        pixels.clone() * pm.clone() / E::k(1000) + reserve.clone(),
    );
    let lists = v.clone() + v.clone() / E::k(3) + E::k(1) + E::k(2) * (v / E::k(6));
    let words = cands.clone() + (h.clone() + E::k(1)) + lists + E::k(Workspace::SORT_WORDS);
    let row_words = ceil_div(E::k(Workspace::ROW_SCRATCH_PER_COLUMN) * w.clone(), 2);
    // The class map (2 bits a pixel) and the visited bit map, rows padded
    // to a byte; the candidates' keys use the latter before the linking.
    let classes = ceil_div(E::k(2) * w.clone(), 8) * h.clone();
    let bitmap = ceil_div(w.clone(), 8) * h.clone();
    let visited = E::op(Op::Max, bitmap, cands - reserve);
    let common = E::named(
        "COMMON",
        E::k(Workspace::ALIGN_SLACK)
            + E::k(4) * words
            + E::k(4) * row_words
            + classes
            + visited
            + w.clone(),
    );
    let total = match kind {
        Kind::InPlace => common,
        Kind::Plain => E::named("PLAIN", common + pixels.clone()),
        Kind::Fast => {
            let index = E::k(4) * ceil_div(pixels.clone(), 2) + pixels.clone();
            let fits = E::op(Op::Gt, E::k(Workspace::INDEX_MAX_WIDTH + 1), w.clone());
            E::named("PLAIN", common + pixels.clone()) + E::iff(fits, index, E::K(0))
        }
    };
    let or = |a, b| E::op(Op::Or, a, b);
    let gt = |a, b| E::op(Op::Gt, a, b);
    let bad = E::named(
        "BAD",
        or(
            or(
                or(
                    E::op(Op::Eq, w.clone(), E::K(0)),
                    E::op(Op::Eq, h.clone(), E::K(0)),
                ),
                or(gt(w, E::k(MAX_DIMENSION)), gt(h, E::k(MAX_DIMENSION))),
            ),
            or(
                gt(pixels.clone(), E::k(MAX_PIXELS)),
                // The candidate count's product overflows a 32-bit size_t
                // before the total does.
                E::OverSizeMax(Box::new(pixels * pm)),
            ),
        ),
    );
    E::iff(
        or(bad, E::OverSizeMax(Box::new(total.clone()))),
        E::K(0),
        total,
    )
}

/// Checks [`formula`] against the core over a grid of sizes and
/// capacities, for every [`Kind`].
fn check_formula() -> Result<usize, String> {
    let mut sides: Vec<usize> = (0..=40).collect();
    sides.extend([
        63, 64, 65, 127, 128, 129, 240, 241, 320, 479, 480, 640, 708, 1064, 2048, 4095, 4096, 4097,
        8191, 8192, 8193, 16384, 32767, 32768, 65536,
    ]);
    let mut configs = vec![Config::DEFAULT, Config::OFFICIAL, Config::PAPER];
    for (pm, v) in [(1, 16), (1000, 65_535), (500, 333), (7, 17)] {
        configs.push(Config {
            candidates_per_mille: pm,
            max_link_pixels: v,
            ..Config::DEFAULT
        });
    }
    let mut checked = 0;
    for kind in Kind::ALL {
        let e = formula(kind);
        for cfg in &configs {
            for &w in &sides {
                for &h in &sides {
                    let p = [
                        w as u64,
                        h as u64,
                        cfg.candidates_per_mille.into(),
                        cfg.max_link_pixels.into(),
                    ];
                    let got = e.eval(&p);
                    let want = kind.core(w, h, cfg);
                    if got != Some(want as u128) {
                        return Err(format!(
                            "the {kind:?} formula gives {got:?} for {w}x{h} \
                             (candidates_per_mille {}, max_link_pixels {}), the core {want}: \
                             update `formula` in ffi/gen-header/src/main.rs to \
                             Workspace's documented formula",
                            cfg.candidates_per_mille, cfg.max_link_pixels
                        ));
                    }
                    checked += 1;
                }
            }
        }
    }
    Ok(checked)
}

/// The profiles, by the names the macros use (`AaglsdProfile`'s).
const PROFILES: [(&str, Config); 3] = [
    ("DEFAULT", Config::DEFAULT),
    ("OFFICIAL", Config::OFFICIAL),
    ("PAPER", Config::PAPER),
];

/// The macro block that follows the header's includes.
fn macros() -> String {
    let mut defs = Vec::new();
    let tops: Vec<(Kind, String)> = Kind::ALL
        .iter()
        .map(|&k| (k, formula(k).c(&mut defs)))
        .collect();
    let mut s = String::new();
    s.push_str(
        "
// Compile-time workspace sizes: integer constant expressions, usable as a
// static array length, equal to what the size functions write:
//   AAGLSD_WORKSPACE_BYTES(w, h)           aaglsd_workspace_size, default profile
//   AAGLSD_WORKSPACE_BYTES_IN_PLACE(w, h)  aaglsd_workspace_size_in_place, default profile
//   AAGLSD_WORKSPACE_BYTES_FAST(w, h)      aaglsd_workspace_size_fast, default profile
//   AAGLSD_WORKSPACE_BYTES_PROFILE(P, w, h) and ..._IN_PLACE_PROFILE, ..._FAST_PROFILE:
//       the same for the profile P (DEFAULT, OFFICIAL or PAPER)
//   AAGLSD_WORKSPACE_BYTES_FOR(w, h, candidates_per_mille, max_link_pixels) and
//       ..._IN_PLACE_FOR, ..._FAST_FOR: for any configuration with those
//       capacities (the only fields the size depends on)
// Each is 0 where the function fails (a zero or too large dimension, or a
// size over SIZE_MAX), so declaring an array of it fails to compile. The
// arguments are evaluated more than once. Generated from the core's
// `Workspace` formula (docs/design.md, section 13) by ffi/gen-header;
// ffi/tests/sizes.c compares them with the functions.
#define AAGLSD_WS_U_(x) ((unsigned long long)(x))
",
    );
    for (name, body) in &defs {
        s.push_str(&format!(
            "#define AAGLSD_WS_{name}_({}) {body}\n",
            PARAMS.join(", ")
        ));
    }
    for (kind, body) in &tops {
        let sfx = kind.suffix();
        s.push_str(&format!(
            "#define AAGLSD_WORKSPACE_BYTES{sfx}_FOR(width, height, candidates_per_mille, \
             max_link_pixels) \\\n  ((size_t)AAGLSD_WS_SIZE{sfx}_((width), (height), \
             (candidates_per_mille), (max_link_pixels)))\n#define AAGLSD_WS_SIZE{sfx}_({}) {body}\n",
            PARAMS.join(", ")
        ));
    }
    for (name, cfg) in &PROFILES {
        s.push_str(&format!(
            "#define AAGLSD_{name}_CANDIDATES_PER_MILLE {}\n#define AAGLSD_{name}_MAX_LINK_PIXELS {}\n",
            cfg.candidates_per_mille, cfg.max_link_pixels
        ));
    }
    for kind in Kind::ALL {
        let sfx = kind.suffix();
        s.push_str(&format!(
            "#define AAGLSD_WORKSPACE_BYTES{sfx}_PROFILE(profile, width, height) \\\n  \
             AAGLSD_WORKSPACE_BYTES{sfx}_FOR(width, height, AAGLSD_##profile##_CANDIDATES_PER_MILLE, \
             AAGLSD_##profile##_MAX_LINK_PIXELS)\n\
             #define AAGLSD_WORKSPACE_BYTES{sfx}(width, height) \
             AAGLSD_WORKSPACE_BYTES{sfx}_PROFILE(DEFAULT, width, height)\n"
        ));
    }
    s
}

/// The header's text, from the `ffi` crate in `ffi_dir`, and the number of
/// sizes on which the macros' formula was checked.
fn generate(ffi_dir: &Path) -> Result<(Vec<u8>, usize), String> {
    let checked = check_formula()?;
    let mut config = cbindgen::Config::from_file(ffi_dir.join("cbindgen.toml"))
        .map_err(|e| format!("ffi/cbindgen.toml: {e}"))?;
    config.after_includes = Some(macros());
    let bindings = cbindgen::Builder::new()
        .with_crate(ffi_dir)
        .with_config(config)
        .generate()
        .map_err(|e| format!("cbindgen: {e}"))?;
    let mut out = Vec::new();
    bindings.write(&mut out);
    Ok((out, checked))
}

fn ffi_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("ffi"), Path::to_path_buf)
}

fn main() -> ExitCode {
    let check = match std::env::args().nth(1).as_deref() {
        None => false,
        Some("--check") => true,
        Some(_) => {
            eprintln!("usage: gen-header [--check]");
            return ExitCode::from(2);
        }
    };
    let dir = ffi_dir();
    let header = dir.join("include").join("aaglsd.h");
    let fresh = match generate(&dir) {
        Ok((h, checked)) => {
            println!("size formula checked against the core on {checked} sizes: ok");
            h
        }
        Err(e) => {
            eprintln!("gen-header: {e}");
            return ExitCode::FAILURE;
        }
    };
    let committed = std::fs::read(&header).unwrap_or_default();
    if committed == fresh {
        println!("{}: up to date", header.display());
        return ExitCode::SUCCESS;
    }
    if check {
        eprintln!(
            "gen-header: {} is stale: run `cargo run -p aaglsd-gen-header` and commit it",
            header.display()
        );
        return ExitCode::FAILURE;
    }
    if let Err(e) = std::fs::write(&header, fresh) {
        eprintln!("gen-header: {}: {e}", header.display());
        return ExitCode::FAILURE;
    }
    println!("{}: written", header.display());
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formula_matches_the_core() {
        let n = check_formula().unwrap();
        assert!(n > 10_000, "{n}");
    }

    /// `cargo test --workspace` fails on a stale header too.
    #[test]
    fn committed_header_is_current() {
        let dir = ffi_dir();
        let (fresh, _) = generate(&dir).unwrap();
        let committed = std::fs::read(dir.join("include").join("aaglsd.h")).unwrap();
        assert!(
            committed == fresh,
            "ffi/include/aaglsd.h is stale: run `cargo run -p aaglsd-gen-header` and commit it"
        );
    }
}
