//! An allowed interval of a scene key, and numbers written the way error
//! messages and the key reference show them.

use std::fmt;

/// One end of an allowed interval.
#[derive(Clone, Copy, Debug)]
enum End {
    Incl(f64),
    Excl(f64),
}

/// An allowed interval, written the way error messages show it.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    lo: End,
    hi: End,
}

impl Bounds {
    pub const fn closed(lo: f64, hi: f64) -> Self {
        Bounds {
            lo: End::Incl(lo),
            hi: End::Incl(hi),
        }
    }

    /// `lo < v <= hi`: for quantities that must be positive.
    pub const fn positive(hi: f64) -> Self {
        Bounds {
            lo: End::Excl(0.0),
            hi: End::Incl(hi),
        }
    }

    /// `0 < v < hi`.
    pub const fn open(hi: f64) -> Self {
        Bounds {
            lo: End::Excl(0.0),
            hi: End::Excl(hi),
        }
    }

    /// False for NaN, so a `nan` in a file is always rejected.
    pub fn contains(self, v: f64) -> bool {
        let above = match self.lo {
            End::Incl(lo) => v >= lo,
            End::Excl(lo) => v > lo,
        };
        let below = match self.hi {
            End::Incl(hi) => v <= hi,
            End::Excl(hi) => v < hi,
        };
        above && below
    }
}

impl fmt::Display for Bounds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = |end: End| match end {
            End::Incl(v) | End::Excl(v) => number_text(v),
        };
        let (lo, hi) = (value(self.lo), value(self.hi));
        match (self.lo, self.hi) {
            (End::Incl(_), End::Incl(_)) => write!(f, "{lo} ..= {hi}"),
            (End::Incl(_), End::Excl(_)) => write!(f, ">= {lo} and < {hi}"),
            (End::Excl(_), End::Incl(_)) => write!(f, "> {lo} and <= {hi}"),
            (End::Excl(_), End::Excl(_)) => write!(f, "> {lo} and < {hi}"),
        }
    }
}

/// A number as a message shows it: in full where that is short, else in
/// exponent form (`1e308`, not 309 digits).
pub(super) fn number_text(v: f64) -> String {
    let huge_or_tiny = v.abs() >= 1e16 || (v != 0.0 && v.abs() < 1e-6);
    if v.is_finite() && huge_or_tiny {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// The `f64` with the same shortest decimal form as `v`: 0.09 rather than
/// 0.09000000357627869, so that messages and bounds derived from `f32` keys
/// show the numbers as they were written.
pub(super) fn widen(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(f64::from(v))
}
