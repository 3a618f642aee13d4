//! The integer tables of the algorithm (design §4 and design §7): neighbour codes, the
//! across- and along-edge neighbourhoods of each orientation class, and the
//! walk's candidate steps. Both implementations read them from here, the
//! fixed core in [`crate::stage`] and the float reference in
//! `crate::reference`, so the two cannot disagree on a table; they differ
//! only in how they compute the class that picks a row (integer tests on
//! the gradient there, `f32` degrees in the reference).

/// A pixel offset `(dx, dy)`, `y` pointing down.
pub(crate) type Offset = (i32, i32);

/// The 8-neighbour codes 0..8 as offsets, counter-clockwise on screen
/// from "right": code `c` and code `(c + 4) % 8` point in opposite
/// directions.
pub(crate) const NEIGHBOURS: [Offset; 8] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
];

/// The neighbour code of `(dx, dy)` (both in -1..=1, not both 0).
pub(crate) const fn code_of(dx: i32, dy: i32) -> u8 {
    match (dx, dy) {
        (1, 0) => 0,
        (1, 1) => 1,
        (0, 1) => 2,
        (-1, 1) => 3,
        (-1, 0) => 4,
        (-1, -1) => 5,
        (0, -1) => 6,
        _ => 7,
    }
}

/// The orientation class of a gradient (design §4): which neighbourhood the
/// group test reads. The gradient orientation `o` is folded to [0°, 180°].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Orientation {
    /// `22.5° <= o < 67.5°`.
    D45 = 0,
    /// `67.5° <= o < 112.5°`: a vertical gradient, a horizontal edge.
    V = 1,
    /// `112.5° <= o < 157.5°`.
    D135 = 2,
    /// The rest: a horizontal gradient, a vertical edge.
    H = 3,
}

/// Across-edge neighbourhoods by [`Orientation`]: side A (offsets 1-3), then
/// side B (4-6), in the order the group test visits them.
pub(crate) const ACROSS: [[Offset; 6]; 4] = [
    [(0, -1), (-1, -1), (-1, 0), (0, 1), (1, 1), (1, 0)],
    [(1, -1), (0, -1), (-1, -1), (-1, 1), (0, 1), (1, 1)],
    [(-1, 0), (-1, 1), (0, 1), (1, 0), (1, -1), (0, -1)],
    [(-1, -1), (-1, 0), (-1, 1), (1, 1), (1, 0), (1, -1)],
];

/// Along-edge neighbourhoods by [`Orientation`]: side J (offsets 1-3), then
/// side K (4-6).
pub(crate) const ALONG: [[Offset; 6]; 4] = [
    [(-1, 0), (-1, 1), (0, 1), (1, 0), (1, -1), (0, -1)],
    [(-1, -1), (-1, 0), (-1, 1), (1, 1), (1, 0), (1, -1)],
    [(0, -1), (-1, -1), (-1, 0), (0, 1), (1, 1), (1, 0)],
    [(1, -1), (0, -1), (-1, -1), (-1, 1), (0, 1), (1, 1)],
];

/// Walk-step classes of a line angle (design §7.2): `[-67.5°, -22.5°)`,
/// `[-22.5°, 22.5°)`, `[22.5°, 67.5°)`, the rest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WalkClass {
    N45,
    Hz,
    P45,
    Vt,
}

/// The walk's candidate offsets, by table index `2·class + (0 forward, 1
/// backward)` (see [`walk_table`]), in the order they are tried.
pub(crate) const WALK: [[Offset; 3]; 8] = [
    // N45
    [(1, 0), (1, -1), (0, -1)],
    [(-1, 0), (-1, 1), (0, 1)],
    // Hz
    [(1, -1), (1, 0), (1, 1)],
    [(-1, -1), (-1, 0), (-1, 1)],
    // P45
    [(0, 1), (1, 1), (1, 0)],
    [(0, -1), (-1, -1), (-1, 0)],
    // Vt
    [(-1, 1), (0, 1), (1, 1)],
    [(-1, -1), (0, -1), (1, -1)],
];

/// The [`WALK`] table index of a class and direction. The reverse flag
/// (design §7.2) swaps the directions of the two classes whose candidates
/// it affects.
pub(crate) const fn walk_table(class: WalkClass, forward: bool, reverse: bool) -> u8 {
    let (base, swappable) = match class {
        WalkClass::N45 => (0, true),
        WalkClass::Hz => (2, false),
        WalkClass::P45 => (4, false),
        WalkClass::Vt => (6, true),
    };
    let fwd = forward != (reverse && swappable);
    base + if fwd { 0 } else { 1 }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    #[test]
    fn neighbour_codes_round_trip() {
        for (c, &(dx, dy)) in NEIGHBOURS.iter().enumerate() {
            assert_eq!(code_of(dx, dy) as usize, c);
            let back = NEIGHBOURS[(c + 4) % 8];
            assert_eq!(back, (-dx, -dy));
        }
    }

    /// Each neighbourhood row holds six distinct 8-neighbours; a backward
    /// walk row holds the opposites of its forward row.
    #[test]
    fn tables_are_neighbourhoods() {
        for row in ACROSS.iter().chain(&ALONG) {
            for (i, a) in row.iter().enumerate() {
                assert!(NEIGHBOURS.contains(a));
                assert!(!row[i + 1..].contains(a));
            }
        }
        for pair in WALK.chunks(2) {
            for f in pair[0] {
                assert!(NEIGHBOURS.contains(&f));
                assert!(pair[1].contains(&(-f.0, -f.1)), "{pair:?}");
            }
        }
    }
}
