//! Check once, then infallible.
//!
//! The entry checks ([`crate::Error`]) settle everything the input can get
//! wrong: dimensions, stride, buffer and workspace sizes, the configuration.
//! After them, an index out of range or an empty `Option` inside the core is
//! a logic error, never bad input. The core still does not panic on one (the
//! release build links without a panic path), but it must not hide one either:
//! every such fallback goes through [`Invariant::or_broken`], which returns the
//! fallback in a release build and fails loudly in the unit tests, in a debug
//! build, under Miri and in the fuzz targets (built with debug assertions), so
//! that a broken invariant is a failing test rather than a quietly different
//! output.
//!
//! A fallback that is a legitimate outcome (a division whose divisor may be
//! zero by design, a lookup that may miss) keeps `unwrap_or` and says why.

/// A value the core's invariants guarantee, with the value to use if they do
/// not hold.
pub(crate) trait Invariant<T> {
    /// The value; `fallback` (after a failed debug assertion) if the
    /// invariant is broken.
    fn or_broken(self, fallback: T) -> T;
}

impl<T> Invariant<T> for Option<T> {
    #[inline(always)]
    #[track_caller]
    fn or_broken(self, fallback: T) -> T {
        match self {
            Some(v) => v,
            None => {
                broken();
                fallback
            }
        }
    }
}

impl<T, E> Invariant<T> for Result<T, E> {
    #[inline(always)]
    #[track_caller]
    fn or_broken(self, fallback: T) -> T {
        match self {
            Ok(v) => v,
            Err(_) => {
                broken();
                fallback
            }
        }
    }
}

/// Reports a broken invariant where someone is looking: a no-op in a release
/// build, so that the shipped core has no panic path.
#[inline(always)]
#[track_caller]
#[allow(clippy::panic)] // only where someone is looking: never in a release build
fn broken() {
    #[cfg(any(test, miri, debug_assertions))]
    panic!("aaglsd: a core invariant does not hold");
}

#[cfg(test)]
mod tests {
    use super::Invariant;

    #[test]
    fn a_held_invariant_gives_the_value() {
        assert_eq!(Some(3).or_broken(0), 3);
        assert_eq!(Ok::<u8, ()>(4).or_broken(0), 4);
    }

    #[test]
    #[should_panic(expected = "invariant does not hold")]
    fn a_broken_invariant_fails_the_tests() {
        let _ = None::<u8>.or_broken(0);
    }

    #[test]
    #[should_panic(expected = "invariant does not hold")]
    fn a_broken_result_fails_the_tests() {
        let _ = Err::<u8, ()>(()).or_broken(0);
    }
}
