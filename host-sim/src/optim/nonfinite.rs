//! Serde for `f64` values that may be non-finite, shared by every checkpoint and record
//! (JSON has no NaN or infinity: `serde_json` writes them as `null` and then refuses to read
//! them back).
//!
//! A finite value is written as a JSON number, as before; NaN as the string `"NaN"`, the
//! infinities as `"inf"` and `"-inf"`. Reading accepts numbers, those strings (also
//! `"Infinity"`, `"-Infinity"`, `"+inf"`) and `null`, which files written before this format
//! hold for a NaN (a record's best and mean of a generation without a feasible member).
//!
//! Use with `#[serde(with = "crate::optim::nonfinite::scalar")]` (one `f64`), `vec`
//! (`Vec<f64>`), `vec2` (`Vec<Vec<f64>>`) or `option` (`Option<f64>`).

use std::fmt;

use serde::de::{self, Deserializer, Visitor};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

/// One `f64` with the non-finite encoding of this module.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F64(pub f64);

impl Serialize for F64 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let v = self.0;
        if v.is_finite() {
            s.serialize_f64(v)
        } else if v.is_nan() {
            s.serialize_str("NaN")
        } else if v > 0.0 {
            s.serialize_str("inf")
        } else {
            s.serialize_str("-inf")
        }
    }
}

struct F64Visitor;

impl Visitor<'_> for F64Visitor {
    type Value = F64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number, \"NaN\", \"inf\" or \"-inf\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<F64, E> {
        Ok(F64(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<F64, E> {
        Ok(F64(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<F64, E> {
        Ok(F64(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<F64, E> {
        match v {
            "NaN" | "nan" => Ok(F64(f64::NAN)),
            "inf" | "+inf" | "Infinity" | "+Infinity" => Ok(F64(f64::INFINITY)),
            "-inf" | "-Infinity" => Ok(F64(f64::NEG_INFINITY)),
            _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
        }
    }

    fn visit_unit<E: de::Error>(self) -> Result<F64, E> {
        Ok(F64(f64::NAN))
    }

    fn visit_none<E: de::Error>(self) -> Result<F64, E> {
        Ok(F64(f64::NAN))
    }
}

impl<'de> Deserialize<'de> for F64 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(F64Visitor)
    }
}

/// One `f64`.
pub mod scalar {
    use super::{Deserialize, Deserializer, F64, Serialize, Serializer};

    /// Serialize `v` (non-finite as a string).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        F64(*v).serialize(s)
    }

    /// Deserialize a number, a non-finite string or `null` (NaN).
    ///
    /// # Errors
    /// Any other value.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        F64::deserialize(d).map(|v| v.0)
    }
}

/// `Vec<f64>`.
pub mod vec {
    use super::{Deserialize, Deserializer, F64, Serializer};

    /// Serialize `v` (non-finite values as strings).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|&x| F64(x)))
    }

    /// Deserialize a list of numbers, non-finite strings or `null`s.
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<F64>::deserialize(d).map(|v| v.into_iter().map(|x| x.0).collect())
    }
}

/// `Vec<Vec<f64>>`.
pub mod vec2 {
    use super::{Deserialize, Deserializer, F64, Serializer};

    /// Serialize `v` (non-finite values as strings).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(v: &[Vec<f64>], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(
            v.iter()
                .map(|row| row.iter().map(|&x| F64(x)).collect::<Vec<_>>()),
        )
    }

    /// Deserialize a list of lists of numbers, non-finite strings or `null`s.
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vec<f64>>, D::Error> {
        Vec::<Vec<F64>>::deserialize(d).map(|v| {
            v.into_iter()
                .map(|r| r.into_iter().map(|x| x.0).collect())
                .collect()
        })
    }
}

/// `Option<f64>` (`None` is `null`; a NaN is `"NaN"`).
pub mod option {
    use super::{Deserialize, Deserializer, F64, Serialize, Serializer};

    /// Serialize `v`.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        v.map(F64).serialize(s)
    }

    /// Deserialize `null` (None), a number or a non-finite string.
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Option::<F64>::deserialize(d).map(|v| v.map(|x| x.0))
    }
}

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Debug, Serialize, Deserialize)]
    struct R {
        #[serde(with = "super::scalar")]
        a: f64,
        #[serde(with = "super::vec")]
        b: Vec<f64>,
        #[serde(with = "super::vec2")]
        c: Vec<Vec<f64>>,
        #[serde(with = "super::option")]
        d: Option<f64>,
    }

    fn same(x: f64, y: f64) -> bool {
        x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
    }

    #[test]
    fn non_finite_values_survive_a_json_round_trip() {
        let r = R {
            a: f64::NAN,
            b: vec![
                1.5,
                f64::INFINITY,
                f64::NEG_INFINITY,
                -0.0,
                f64::MAX,
                5e-324,
            ],
            c: vec![vec![f64::NAN, 0.1], vec![]],
            d: Some(f64::INFINITY),
        };
        let text = serde_json::to_string(&r).unwrap();
        let back: R = serde_json::from_str(&text).unwrap();
        assert!(same(back.a, r.a), "{text}");
        assert_eq!(back.b.len(), r.b.len());
        assert!(back.b.iter().zip(&r.b).all(|(x, y)| same(*x, *y)), "{text}");
        assert!(same(back.c[0][0], f64::NAN) && back.c[0][1] == 0.1 && back.c[1].is_empty());
        assert_eq!(back.d, Some(f64::INFINITY));
        // Finite values are plain numbers, as before.
        assert!(text.contains("1.5,\"inf\",\"-inf\",-0.0,"), "{text}");
        let none: R = serde_json::from_str(r#"{"a":1,"b":[],"c":[],"d":null}"#).unwrap();
        assert_eq!(none.d, None);
    }

    #[test]
    fn legacy_null_reads_as_nan_and_other_strings_are_refused() {
        let r: R =
            serde_json::from_str(r#"{"a":null,"b":[null,2],"c":[[null]],"d":"NaN"}"#).unwrap();
        assert!(r.a.is_nan() && r.b[0].is_nan() && r.b[1] == 2.0 && r.c[0][0].is_nan());
        assert!(r.d.is_some_and(f64::is_nan));
        let e = serde_json::from_str::<R>(r#"{"a":"big","b":[],"c":[],"d":null}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("big"), "{e}");
    }
}
