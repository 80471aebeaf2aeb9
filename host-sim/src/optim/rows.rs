//! The CSV files of a run, one serde row type per file, written (and read back) through the
//! `csv` crate: [`RecordRow`] (generations.csv of a re-entry run), [`PopulationRow`]
//! (population.csv, population/gen_NNNN.csv and a re-entry run's front.csv), [`FrontRow`]
//! (front.csv of a test-problem run) and [`ChromosomeRow`] (population.csv of a
//! variable-length run). [`write_csv`] writes a header and rows; [`read_records`] and
//! [`read_population`] read the files back.
//!
//! Numbers are written as [`Exp`] (Rust's `{:e}`: `5e-1`, `2.5e-1`, `0e0`) or, for the
//! feasible fraction, [`Dec`] (Rust's `{}`: `0.75`, `1`): both the shortest text that reads
//! back to the same `f64`, and NaN and the infinities as `NaN`, `inf` and `-inf`, which read
//! back as such (a generation without a feasible member has NaN best and mean values and an
//! infinite smallest violation only if the population is empty).

use std::fmt;
use std::str::FromStr;

use serde::de::{self, Deserializer, Visitor};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

/// Failures of writing or reading a run's CSV file; each names the line and column.
#[derive(Debug, thiserror::Error)]
pub enum RowsError {
    /// The csv crate refused a row (a row of another length than the header) or the text.
    #[error("CSV: {0}")]
    Csv(#[from] csv::Error),
    /// A field that is not a number (or list of numbers) of its column.
    #[error("line {line}, column {column}: {value:?} is not {expected}")]
    Field {
        /// Line number, from 1 (the header is line 1).
        line: u64,
        /// The column's header.
        column: String,
        /// The field's text.
        value: String,
        /// What the column holds.
        expected: &'static str,
    },
    /// A header that is not the file's.
    #[error("header {found:?}: expected {expected}")]
    Header {
        /// The header found.
        found: String,
        /// What it must be.
        expected: &'static str,
    },
}

/// Parse a number as written by [`Exp`] or [`Dec`] (also any other text Rust's `f64` parser
/// takes: `NaN`, `inf`, `-inf`, `infinity`, `0.5`, `5e-1`).
fn parse_f64(s: &str) -> Option<f64> {
    s.trim().parse().ok()
}

macro_rules! float_field {
    ($name:ident, $fmt:literal, $what:literal) => {
        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, $fmt, self.0)
            }
        }

        impl FromStr for $name {
            type Err = ();
            fn from_str(s: &str) -> Result<Self, ()> {
                parse_f64(s).map(Self).ok_or(())
            }
        }

        impl Serialize for $name {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_str(self)
            }
        }

        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct V;
                impl Visitor<'_> for V {
                    type Value = $name;
                    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                        f.write_str($what)
                    }
                    fn visit_str<E: de::Error>(self, v: &str) -> Result<$name, E> {
                        v.parse()
                            .map_err(|()| E::invalid_value(de::Unexpected::Str(v), &self))
                    }
                }
                d.deserialize_str(V)
            }
        }
    };
}

/// An `f64` field in Rust's `{:e}` form (`5e-1`, `-1.25e2`, `NaN`, `inf`), which reads back
/// bit for bit (NaN as a NaN).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exp(pub f64);
float_field!(Exp, "{:e}", "a number, NaN, inf or -inf");

/// An `f64` field in Rust's `{}` form (`0.75`, `1`, `NaN`), which reads back bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dec(pub f64);
float_field!(Dec, "{}", "a number, NaN, inf or -inf");

/// A `;`-separated list in one field (`1e0;2.5e-1`; empty: no element).
#[derive(Clone, Debug, PartialEq)]
pub struct Semi<T>(pub Vec<T>);

impl<T: fmt::Display> fmt::Display for Semi<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, v) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(";")?;
            }
            write!(f, "{v}")?;
        }
        Ok(())
    }
}

impl<T: fmt::Display> Serialize for Semi<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<T: FromStr> FromStr for Semi<T> {
    type Err = ();
    fn from_str(s: &str) -> Result<Self, ()> {
        if s.is_empty() {
            return Ok(Self(Vec::new()));
        }
        s.split(';')
            .map(|v| v.parse().map_err(|_| ()))
            .collect::<Result<_, _>>()
            .map(Self)
    }
}

impl<'de, T: FromStr> Deserialize<'de> for Semi<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T>(std::marker::PhantomData<T>);
        impl<T: FromStr> Visitor<'_> for V<T> {
            type Value = Semi<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a ;-separated list of numbers")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Semi<T>, E> {
                v.parse()
                    .map_err(|()| E::invalid_value(de::Unexpected::Str(v), &self))
            }
        }
        d.deserialize_str(V(std::marker::PhantomData))
    }
}

/// One generation of a two-objective run (generations.csv; the header is the field names).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RecordRow {
    /// Generation (0: the initial population).
    pub generation: u64,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Fraction of feasible individuals.
    pub feasible_fraction: Dec,
    /// Hypervolume of the feasible front.
    pub hypervolume: Exp,
    /// Smallest violation in the population.
    pub min_violation: Exp,
    /// Best feasible first objective (NaN: none feasible).
    pub best_f1: Exp,
    /// Best feasible second objective.
    pub best_f2: Exp,
    /// Mean feasible first objective.
    pub mean_f1: Exp,
    /// Mean feasible second objective.
    pub mean_f2: Exp,
    /// Points of the feasible front.
    pub front_size: usize,
}

/// The header of [`RecordRow`]'s file.
pub const RECORD_HEADER: &str = "generation,evaluations,feasible_fraction,hypervolume,min_violation,best_f1,best_f2,mean_f1,mean_f2,front_size";

/// One individual (population.csv): header `x1..xn,f1..fm,g1..gc,violation`; a decision
/// shorter than the longest (SCEA's flat genes) is padded with empty fields.
#[derive(Clone, Debug, Serialize)]
pub struct PopulationRow {
    /// Decision variables, `None` past the individual's length.
    pub x: Vec<Option<Exp>>,
    /// Objectives.
    pub f: Vec<Exp>,
    /// Constraint values.
    pub g: Vec<Exp>,
    /// Total violation.
    pub violation: Exp,
}

/// The header of a population file with `n` decision variables, `m` objectives and `c`
/// constraints.
#[must_use]
pub fn population_header(n: usize, m: usize, c: usize) -> Vec<String> {
    (1..=n)
        .map(|i| format!("x{i}"))
        .chain((1..=m).map(|i| format!("f{i}")))
        .chain((1..=c).map(|i| format!("g{i}")))
        .chain(["violation".into()])
        .collect()
}

/// One front point of a test-problem run (front.csv): header `f1..fm`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FrontRow {
    /// Objectives.
    pub f: Vec<Exp>,
}

/// One chromosome of a variable-length run (population.csv): header
/// `f1..fm,g1..gc,violation,x,nodes,genes`.
#[derive(Clone, Debug, Serialize)]
pub struct ChromosomeRow {
    /// Objectives.
    pub f: Vec<Exp>,
    /// Constraint values.
    pub g: Vec<Exp>,
    /// Total violation.
    pub violation: Exp,
    /// Fixed genes.
    pub x: Semi<Exp>,
    /// Node count of each leg.
    pub nodes: Semi<usize>,
    /// All node genes, leg after leg.
    pub genes: Semi<Exp>,
}

/// The CSV text of `header` and `rows` (`\n` line ends; every row as long as the header).
///
/// # Errors
/// [`RowsError::Csv`] if a row's length differs from the header's.
pub fn write_csv<R: Serialize>(
    header: &[String],
    rows: impl IntoIterator<Item = R>,
) -> Result<String, RowsError> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    w.write_record(header)?;
    for r in rows {
        w.serialize(r)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    // Only ASCII numbers and the header's names are written.
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Read generations.csv back.
///
/// # Errors
/// [`RowsError`] naming the line and column.
pub fn read_records(text: &str) -> Result<Vec<RecordRow>, RowsError> {
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let head = r.headers()?.clone();
    if head.iter().collect::<Vec<_>>().join(",") != RECORD_HEADER {
        return Err(RowsError::Header {
            found: head.iter().collect::<Vec<_>>().join(","),
            expected: RECORD_HEADER,
        });
    }
    let mut rows = Vec::new();
    for rec in r.records() {
        let rec = rec?;
        let row = rec
            .deserialize(Some(&head))
            .map_err(|e| field_error(&e, &rec, &head))?;
        rows.push(row);
    }
    Ok(rows)
}

/// The field named by a deserialisation error of `rec`, as a [`RowsError::Field`].
fn field_error(e: &csv::Error, rec: &csv::StringRecord, head: &csv::StringRecord) -> RowsError {
    let line = rec.position().map_or(0, csv::Position::line);
    if let csv::ErrorKind::Deserialize { err, .. } = e.kind()
        && let Some(k) = err.field()
    {
        let k = usize::try_from(k).unwrap_or(usize::MAX);
        return RowsError::Field {
            line,
            column: head.get(k).unwrap_or("").to_string(),
            value: rec.get(k).unwrap_or("").to_string(),
            expected: "a number of its column",
        };
    }
    RowsError::Field {
        line,
        column: String::new(),
        value: rec.iter().collect::<Vec<_>>().join(","),
        expected: "a row of the header's length",
    }
}

/// Read a population file back: its rows and the decision, objective and constraint counts
/// `(n, m, c)` of its header.
///
/// # Errors
/// [`RowsError`] naming the line and column.
pub fn read_population(text: &str) -> Result<(Vec<PopulationRow>, [usize; 3]), RowsError> {
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let head = r.headers()?.clone();
    let count = |p: char| head.iter().filter(|h| h.starts_with(p)).count();
    let (n, m, c) = (count('x'), count('f'), count('g'));
    if population_header(n, m, c).iter().ne(head.iter()) {
        return Err(RowsError::Header {
            found: head.iter().collect::<Vec<_>>().join(","),
            expected: "x1..xn,f1..fm,g1..gc,violation",
        });
    }
    let mut rows = Vec::new();
    for rec in r.records() {
        let rec = rec?;
        let line = rec.position().map_or(0, csv::Position::line);
        let cell = |k: usize| -> Result<Option<Exp>, RowsError> {
            let v = rec.get(k).unwrap_or("");
            if v.is_empty() && k < n {
                return Ok(None);
            }
            v.parse().map(Some).map_err(|()| RowsError::Field {
                line,
                column: head.get(k).unwrap_or("").to_string(),
                value: v.to_string(),
                expected: "a number, NaN, inf or -inf",
            })
        };
        let all = (0..head.len()).map(cell).collect::<Result<Vec<_>, _>>()?;
        let num = |k: usize| all[k].unwrap_or(Exp(f64::NAN));
        rows.push(PopulationRow {
            x: all[..n].to_vec(),
            f: (n..n + m).map(num).collect(),
            g: (n + m..n + m + c).map(num).collect(),
            violation: num(n + m + c),
        });
    }
    Ok((rows, [n, m, c]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(v: &[Exp]) -> Vec<u64> {
        v.iter().map(|e| e.0.to_bits()).collect()
    }

    #[test]
    fn numbers_are_written_shortest_and_read_back_bit_for_bit() {
        let values = [
            0.0,
            -0.0,
            0.1,
            1.0 / 3.0,
            -1.25e2,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let text: Vec<String> = values.iter().map(|&v| Exp(v).to_string()).collect();
        assert_eq!(text[0], "0e0");
        assert_eq!(text[2], "1e-1");
        assert_eq!(text[8..], ["NaN", "inf", "-inf"]);
        for (v, t) in values.iter().zip(&text) {
            let back: Exp = t.parse().unwrap();
            if v.is_nan() {
                assert!(back.0.is_nan());
            } else {
                assert_eq!(back.0.to_bits(), v.to_bits(), "{t}");
            }
            let d: Dec = Dec(*v).to_string().parse().unwrap();
            assert!(d.0.to_bits() == v.to_bits() || v.is_nan() && d.0.is_nan());
        }
        assert_eq!(Dec(1.0).to_string(), "1");
        assert_eq!(Dec(0.75).to_string(), "0.75");
        assert!("1,5".parse::<Exp>().is_err());
        assert_eq!(
            "1e0;2.5e-1".parse::<Semi<Exp>>().unwrap(),
            Semi(vec![Exp(1.0), Exp(0.25)])
        );
        assert_eq!("".parse::<Semi<usize>>().unwrap(), Semi(vec![]));
    }

    #[test]
    fn population_rows_round_trip_with_padding_and_non_finite_values() {
        let rows = vec![
            PopulationRow {
                x: vec![Some(Exp(0.1)), Some(Exp(-2.5))],
                f: vec![Exp(f64::NAN), Exp(f64::NAN)],
                g: vec![Exp(f64::NEG_INFINITY)],
                violation: Exp(f64::INFINITY),
            },
            PopulationRow {
                x: vec![Some(Exp(3.0)), None],
                f: vec![Exp(0.25), Exp(1.0 / 3.0)],
                g: vec![Exp(-1e-300)],
                violation: Exp(0.0),
            },
        ];
        let text = write_csv(&population_header(2, 2, 1), rows.clone()).unwrap();
        assert_eq!(
            text,
            "x1,x2,f1,f2,g1,violation\n1e-1,-2.5e0,NaN,NaN,-inf,inf\n\
             3e0,,2.5e-1,3.333333333333333e-1,-1e-300,0e0\n"
        );
        let (back, dims) = read_population(&text).unwrap();
        assert_eq!(dims, [2, 2, 1]);
        assert_eq!(back[1].x, rows[1].x);
        for (a, b) in rows.iter().zip(&back) {
            assert_eq!(bits(&a.f), bits(&b.f));
            assert_eq!(bits(&a.g), bits(&b.g));
            assert_eq!(a.violation.0.to_bits(), b.violation.0.to_bits());
        }
        assert_eq!(write_csv(&population_header(2, 2, 1), back).unwrap(), text);
        // A row of another length than the header is refused when written and when read.
        assert!(write_csv(&population_header(1, 2, 1), rows).is_err());
        assert!(read_population("x1,f1,violation\n1e0,2e0\n").is_err());
        let e = read_population("x1,f1,violation\n1e0,oops,0e0\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2, column f1: \"oops\""), "{e}");
        let e = read_population("x1,y1,violation\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("header \"x1,y1,violation\""), "{e}");
    }
}
