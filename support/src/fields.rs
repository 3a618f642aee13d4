//! Every [`Config`] field by its Rust name, listed once: the parser behind
//! `--set FIELD=VALUE` (the CLI and the accuracy harness), and the field
//! table the fuzz targets pick from. Also the [`Summary`] fields by name.

use aaglsd::{Config, Maxima, Reseed, Summary};

/// The type of a [`Config`] field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `f32`.
    F32,
    /// `u8`.
    U8,
    /// `u16`.
    U16,
    /// `u32`.
    U32,
    /// `bool`.
    Bool,
    /// [`Reseed`].
    Reseed,
    /// [`Maxima`].
    Maxima,
}

/// A value of a [`Config`] field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// `f32`.
    F32(f32),
    /// `u8`.
    U8(u8),
    /// `u16`.
    U16(u16),
    /// `u32`.
    U32(u32),
    /// `bool`.
    Bool(bool),
    /// [`Reseed`].
    Reseed(Reseed),
    /// [`Maxima`].
    Maxima(Maxima),
}

macro_rules! config_fields {
    ($($name:ident: $kind:ident),* $(,)?) => {
        /// Every [`Config`] field: its Rust name and type, in declaration order.
        pub const FIELDS: [(&str, Kind); config_fields!(@count $($name)*)] =
            [$((stringify!($name), Kind::$kind)),*];

        // A field added to `Config` but not to this list fails to compile here.
        const _: fn(Config) = |c| {
            let Config { $($name: _),* } = c;
        };

        /// The value of field `name`, or `None` for an unknown name.
        pub fn get(cfg: &Config, name: &str) -> Option<Value> {
            match name {
                $(stringify!($name) => Some(Value::$kind(cfg.$name)),)*
                _ => None,
            }
        }

        /// Sets field `name` to `value` (no range check: see
        /// [`Config::validate`]).
        ///
        /// # Errors
        /// An unknown name, or a value of another type than the field's.
        pub fn set(cfg: &mut Config, name: &str, value: Value) -> Result<(), String> {
            match (name, value) {
                $((stringify!($name), Value::$kind(v)) => cfg.$name = v,)*
                _ => {
                    return Err(match kind(name) {
                        Some(k) => format!("{name} is {k:?}, not {value:?}"),
                        None => unknown(name),
                    })
                }
            }
            Ok(())
        }
    };
    (@count $($name:ident)*) => { 0 $(+ config_fields!(@one $name))* };
    (@one $name:ident) => { 1 };
}

config_fields! {
    magnitude_threshold: F32,
    anchor_margin: U16,
    align_tolerance_deg: F32,
    dist_tolerance_px: F32,
    skip_min: U8,
    skip_regular: U8,
    skip_group: U8,
    min_length_px: F32,
    min_groups: U8,
    anchor_density: F32,
    aligned_density: F32,
    min_score: U32,
    reseed: Reseed,
    extend_max_px: U16,
    maxima: Maxima,
    bridge_px: U8,
    merge: Bool,
    trim: Bool,
    merge_center_px: F32,
    merge_angle_deg: F32,
    merge_gap_px: F32,
    candidates_per_mille: U16,
    max_link_pixels: U32,
    work_per_mille: U32,
    work_budget: U32,
}

/// `--set skip=N` sets the three gap-step fields at once.
const SKIP_ALL: [&str; 3] = ["skip_min", "skip_regular", "skip_group"];

/// The type of field `name`, or `None` for an unknown name.
pub fn kind(name: &str) -> Option<Kind> {
    FIELDS.iter().find(|(n, _)| *n == name).map(|&(_, k)| k)
}

/// The names of the `f32` fields, in declaration order.
pub fn float_fields() -> impl Iterator<Item = &'static str> {
    FIELDS
        .iter()
        .filter(|(_, k)| *k == Kind::F32)
        .map(|&(n, _)| n)
}

fn unknown(name: &str) -> String {
    let names: Vec<&str> = FIELDS.iter().map(|&(n, _)| n).collect();
    format!(
        "unknown Config field {name:?} (fields: {}; skip sets skip_min, skip_regular and skip_group)",
        names.join(", ")
    )
}

/// Parses `text` as a value of type `kind` (bools: `true`, `false`, `1`,
/// `0`; [`Reseed`]: `never`, `once`, `misfit`, `always`, or `false` and
/// `true` for never and always; [`Maxima`]: `strict`, `symmetric`).
///
/// # Errors
/// What a value of `kind` looks like, e.g. `"an integer 0..=255"`.
pub fn parse_value(kind: Kind, text: &str) -> Result<Value, &'static str> {
    Ok(match kind {
        Kind::F32 => Value::F32(text.parse().map_err(|_| "a number")?),
        Kind::U8 => Value::U8(text.parse().map_err(|_| "an integer 0..=255")?),
        Kind::U16 => Value::U16(text.parse().map_err(|_| "an integer 0..=65535")?),
        Kind::U32 => Value::U32(text.parse().map_err(|_| "an integer 0..=4294967295")?),
        Kind::Bool => Value::Bool(match text {
            "true" | "1" => true,
            "false" | "0" => false,
            _ => return Err("true, false, 1 or 0"),
        }),
        Kind::Reseed => Value::Reseed(match text {
            "false" => Reseed::Never,
            "true" => Reseed::Always,
            _ => RESEED_NAMES
                .iter()
                .find(|(_, n)| *n == text)
                .map(|&(r, _)| r)
                .ok_or("never, once, misfit or always")?,
        }),
        Kind::Maxima => Value::Maxima(
            MAXIMA_NAMES
                .iter()
                .find(|(_, n)| *n == text)
                .map(|&(t, _)| t)
                .ok_or("strict or symmetric")?,
        ),
    })
}

/// Each [`Maxima`] with the name [`parse_value`] takes for it.
const MAXIMA_NAMES: [(Maxima, &str); 2] =
    [(Maxima::Strict, "strict"), (Maxima::Symmetric, "symmetric")];

/// The name [`parse_value`] takes for a [`Maxima`]: `strict` or `symmetric`.
pub fn maxima_name(t: Maxima) -> &'static str {
    MAXIMA_NAMES
        .iter()
        .find(|(v, _)| *v == t)
        .map_or("strict", |&(_, n)| n)
}

/// Each [`Reseed`] with the name [`parse_value`] takes for it.
const RESEED_NAMES: [(Reseed, &str); 4] = [
    (Reseed::Never, "never"),
    (Reseed::Once, "once"),
    (Reseed::Misfit, "misfit"),
    (Reseed::Always, "always"),
];

/// The name [`parse_value`] takes for a [`Reseed`]: `never`, `once`,
/// `misfit` or `always`.
pub fn reseed_name(r: Reseed) -> &'static str {
    RESEED_NAMES
        .iter()
        .find(|(v, _)| *v == r)
        .map_or("always", |&(_, n)| n)
}

/// Applies one `FIELD=VALUE` assignment (`FIELD` as written in Rust, or
/// `skip` for the three gap-step fields), then checks the result with
/// [`Config::validate`]. On error `cfg` is unchanged.
///
/// # Errors
/// A message that names the field (callers add the assignment itself): no
/// `=`, an unknown field, a value that does not parse as the field's type,
/// or one out of the field's range.
pub fn apply_set(cfg: &mut Config, assignment: &str) -> Result<(), String> {
    let (name, text) = assignment.split_once('=').ok_or("expected FIELD=VALUE")?;
    let names: &[&str] = if name == "skip" {
        &SKIP_ALL
    } else {
        std::slice::from_ref(&name)
    };
    let mut next = *cfg;
    for n in names {
        let k = kind(n).ok_or_else(|| unknown(n))?;
        let v = parse_value(k, text).map_err(|what| format!("{name} wants {what}"))?;
        set(&mut next, n, v)?;
    }
    match next.validate() {
        Ok(()) => {
            *cfg = next;
            Ok(())
        }
        // Names the field ("config field ... out of range").
        Err(e) => Err(e.to_string()),
    }
}

/// The [`Summary`] fields by name, in declaration order.
pub fn summary_fields(s: &Summary) -> [(&'static str, usize); 9] {
    [
        ("segments", s.segments),
        ("dropped_segments", s.dropped_segments),
        ("dropped_candidates", s.dropped_candidates),
        ("truncated_linkings", s.truncated_linkings),
        ("candidates", s.candidates),
        ("groups", s.groups),
        ("merged", s.merged),
        ("work", s.work),
        ("work_cut", s.work_cut),
    ]
}

/// `segments=N dropped_segments=N ...`: every [`Summary`] field, one line.
pub fn summary_line(s: &Summary) -> String {
    summary_fields(s)
        .iter()
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_field_round_trips_through_its_name() {
        // Setting each field to the value of another profile changes exactly
        // that field, through the name alone.
        let a = Config::OFFICIAL;
        let b = Config {
            extend_max_px: 64,
            reseed: Reseed::Never,
            bridge_px: 4,
            min_score: 250,
            trim: true,
            work_per_mille: 500,
            work_budget: 1000,
            ..Config::PAPER
        };
        let mut seen = 0;
        for (name, _) in FIELDS {
            let want = get(&b, name).unwrap();
            let mut c = a;
            set(&mut c, name, want).unwrap();
            assert_eq!(get(&c, name), Some(want), "{name}");
            for (other, _) in FIELDS.iter().filter(|(o, _)| *o != name) {
                assert_eq!(get(&c, other), get(&a, other), "{name} touched {other}");
            }
            seen += 1;
        }
        assert_eq!(seen, 25);
        assert_eq!(float_fields().count(), 9);
    }

    #[test]
    fn apply_set_parses_each_type() {
        let mut c = Config::DEFAULT;
        apply_set(&mut c, "magnitude_threshold=7.5").unwrap();
        apply_set(&mut c, "anchor_margin=12").unwrap();
        apply_set(&mut c, "merge=true").unwrap();
        apply_set(&mut c, "max_link_pixels=4096").unwrap();
        apply_set(&mut c, "skip=3").unwrap();
        apply_set(&mut c, "maxima=strict").unwrap();
        assert_eq!(c.maxima, Maxima::Strict);
        apply_set(&mut c, "maxima=symmetric").unwrap();
        assert_eq!(c.maxima, Maxima::Symmetric);
        apply_set(&mut c, "bridge_px=3").unwrap();
        assert_eq!(c.bridge_px, 3);
        assert_eq!(c.magnitude_threshold, 7.5);
        assert_eq!(c.anchor_margin, 12);
        assert!(c.merge);
        assert_eq!(c.max_link_pixels, 4096);
        assert_eq!((c.skip_min, c.skip_regular, c.skip_group), (3, 3, 3));
        apply_set(&mut c, "merge=0").unwrap();
        assert!(!c.merge);
    }

    #[test]
    fn apply_set_errors_name_the_field_and_leave_the_config() {
        let start = Config::PAPER;
        for (arg, needle) in [
            ("min_groups", "FIELD=VALUE"),
            ("skip=x", "skip wants an integer"),
            ("no_such_field=1", "\"no_such_field\""),
            ("anchor_margin=70000", "anchor_margin"),
            ("anchor_margin=-1", "anchor_margin"),
            ("merge=yes", "merge"),
            ("maxima=upper", "maxima wants strict or symmetric"),
            ("bridge_px=33", "bridge_px"),
            ("min_score=16777216", "min_score"),
            ("dist_tolerance_px=abc", "dist_tolerance_px"),
            ("align_tolerance_deg=90", "align_tolerance_deg"),
            ("magnitude_threshold=NaN", "magnitude_threshold"),
            ("skip_group=0", "skip_group"),
            ("max_link_pixels=15", "max_link_pixels"),
        ] {
            let mut c = start;
            let e = apply_set(&mut c, arg).unwrap_err();
            assert!(e.contains(needle), "{arg}: {e}");
            assert_eq!(c, start, "{arg} changed the config");
        }
    }

    #[test]
    fn summary_line_lists_every_field() {
        // Non-exhaustive: set each counter on a default.
        let mut s = Summary::default();
        for (k, field) in [
            &mut s.segments,
            &mut s.dropped_segments,
            &mut s.dropped_candidates,
            &mut s.truncated_linkings,
            &mut s.candidates,
            &mut s.groups,
            &mut s.merged,
            &mut s.work,
            &mut s.work_cut,
        ]
        .into_iter()
        .enumerate()
        {
            *field = k + 1;
        }
        assert_eq!(
            summary_line(&s),
            "segments=1 dropped_segments=2 dropped_candidates=3 truncated_linkings=4 \
             candidates=5 groups=6 merged=7 work=8 work_cut=9"
        );
    }
}
