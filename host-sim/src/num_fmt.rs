//! [`compact`]: the one way numbers are printed in messages. Values as a user would write
//! them: the shortest text that reads back to the same `f64`, in plain notation for ordinary
//! magnitudes and scientific notation at the extremes (`1e308`, not a 309-digit integer;
//! `5e-324`, not 300 zeros), so a message shows the value that was given.

use std::fmt;

/// `v` printed compactly (see the module docs): plain for 1e-4 <= |v| < 1e9 and 0,
/// otherwise scientific; `inf`, `-inf`, `NaN` as such.
#[must_use]
pub fn compact(v: f64) -> String {
    Compact(v).to_string()
}

/// A `Display` adapter printing an `f64` as [`compact`] does (for `format!` and thiserror).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compact(pub f64);

impl fmt::Display for Compact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let a = v.abs();
        if !v.is_finite() || a == 0.0 || (1e-4..1e9).contains(&a) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::compact;

    #[test]
    fn extremes_are_scientific_ordinary_values_plain() {
        assert_eq!(compact(1e308), "1e308");
        assert_eq!(compact(-1.7976931348623157e308), "-1.7976931348623157e308");
        assert_eq!(compact(5e-324), "5e-324");
        assert_eq!(compact(1e-9), "1e-9");
        assert_eq!(compact(2.5e-5), "2.5e-5");
        assert_eq!(compact(0.001), "0.001");
        assert_eq!(compact(2.0), "2");
        assert_eq!(compact(-40.25), "-40.25");
        assert_eq!(compact(6_371_000.0), "6371000");
        assert_eq!(compact(3.986004418e14), "3.986004418e14");
        assert_eq!(compact(0.0), "0");
        assert_eq!(compact(f64::INFINITY), "inf");
        assert_eq!(compact(f64::NAN), "NaN");
        // Reads back to the same value.
        for v in [1e308, 5e-324, 0.1 + 0.2, 123.456e20, -7.25e-12] {
            assert_eq!(compact(v).parse::<f64>().unwrap(), v);
        }
    }
}
