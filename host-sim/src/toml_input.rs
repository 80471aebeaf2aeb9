//! The one TOML reading path of host-sim's input files (scenarios, vehicles): the text is
//! parsed, then deserialised into the caller's serde structs (which reject unknown fields)
//! with the dotted path of any failing field (`serde_path_to_error`), and the value as written
//! is looked up for the message. Callers wrap [`TomlInputError`] in their own typed error
//! with the file name, so every message names the file, the field and the value.

use serde::de::DeserializeOwned;
use toml::{Table, Value};

/// A number as written in a file: a TOML integer or float (range checks are the caller's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl<'de> serde::Deserialize<'de> for Num {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = Num;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E>(self, v: f64) -> Result<Num, E> {
                Ok(Num(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<Num, E> {
                Ok(Num(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<Num, E> {
                Ok(Num(v as f64))
            }
        }
        d.deserialize_any(V)
    }
}

/// A TOML syntax error: the parser's own error (line, column and the offending text), shown
/// without its trailing newline.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TomlSyntax(pub Box<toml::de::Error>);

impl std::fmt::Display for TomlSyntax {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0.to_string().trim_end())
    }
}

impl std::error::Error for TomlSyntax {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&*self.0)
    }
}

/// Why a TOML input could not be read into its structs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TomlInputError {
    /// Not valid TOML: the parser's message (line, column and the offending text).
    Syntax(TomlSyntax),
    /// A field is unknown, missing or of the wrong type.
    Field {
        /// Dotted path, e.g. `entry.altitude_km` or `aero.cl[1]`.
        field: String,
        /// The value as written, or `(missing)`.
        value: String,
        /// What is wrong.
        reason: String,
    },
}

/// A TOML value as written in messages (strings quoted).
#[must_use]
pub fn fmt_value(v: &Value) -> String {
    match v {
        Value::String(s) => format!("{s:?}"),
        other => other.to_string(),
    }
}

/// The value at a serde path in a parsed document, if there is one.
fn value_at<'v>(doc: &'v Table, path: &serde_path_to_error::Path) -> Option<&'v Value> {
    use serde_path_to_error::Segment;
    let mut segs = path.iter();
    let first = match segs.next()? {
        Segment::Map { key } => doc.get(key)?,
        _ => return None,
    };
    segs.try_fold(first, |v, s| match (s, v) {
        (Segment::Map { key }, Value::Table(t)) => t.get(key),
        (Segment::Seq { index }, Value::Array(a)) => a.get(*index),
        _ => None,
    })
}

/// serde's "invalid type: string \"x\", expected a number" as "must be a number".
fn reason_of(message: &str) -> String {
    match message.split_once(", expected ") {
        Some((head, expected)) if head.starts_with("invalid type") => format!("must be {expected}"),
        _ => message.to_string(),
    }
}

/// Parse `text` and deserialise it into `T`; also returns the parsed document (to show values
/// in later range-check messages).
///
/// # Errors
/// [`TomlInputError::Syntax`] for malformed TOML, [`TomlInputError::Field`] naming the field,
/// its value and the reason for an unknown, missing or mistyped field.
pub fn parse<T: DeserializeOwned>(text: &str) -> Result<(T, Table), TomlInputError> {
    let doc: Table = text
        .parse()
        .map_err(|e: toml::de::Error| TomlInputError::Syntax(TomlSyntax(Box::new(e))))?;
    let value: T = serde_path_to_error::deserialize(doc.clone()).map_err(|e| {
        let message = e.inner().message().to_string();
        let mut field = e.path().to_string();
        // A missing field: serde reports it at the enclosing table.
        if let Some(key) = message
            .strip_prefix("missing field `")
            .and_then(|r| r.split('`').next())
        {
            field = if field == "." {
                key.to_string()
            } else {
                format!("{field}.{key}")
            };
            return TomlInputError::Field {
                field,
                value: "(missing)".into(),
                reason: "required".into(),
            };
        }
        TomlInputError::Field {
            value: value_at(&doc, e.path()).map_or_else(|| "(missing)".to_string(), fmt_value),
            field,
            reason: reason_of(&message),
        }
    })?;
    Ok((value, doc))
}

/// The value of dotted `field` (`a.b`, `a.b[2]`) in `doc` as written, or `(missing)`.
#[must_use]
pub fn shown(doc: &Table, field: &str) -> String {
    let mut v: Option<&Value> = None;
    for (i, part) in field.split('.').enumerate() {
        let (key, index) = match part.split_once('[') {
            Some((k, rest)) => (k, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        v = if i == 0 {
            doc.get(key)
        } else {
            v.and_then(Value::as_table).and_then(|t| t.get(key))
        };
        if let Some(ix) = index {
            v = v.and_then(Value::as_array).and_then(|a| a.get(ix));
        }
    }
    v.map_or_else(|| "(missing)".to_string(), fmt_value)
}

/// Longest name (scenario, vehicle) in characters.
pub const MAX_NAME_CHARS: usize = 100;

/// Names (scenario, vehicle) label files, plots and directories: non-empty, at most
/// [`MAX_NAME_CHARS`] characters, no control characters (NUL, newline, tab, ...), no
/// leading or trailing blanks.
///
/// # Errors
/// What the name breaks, for the caller's field error.
pub fn check_name(name: &str) -> Result<(), &'static str> {
    if name.trim().is_empty() {
        Err("must be a non-empty name")
    } else if name.chars().count() > MAX_NAME_CHARS {
        Err("must be at most 100 characters")
    } else if name.chars().any(char::is_control) {
        Err("must not contain control characters (NUL, newline, tab, ...)")
    } else if name.trim() != name {
        Err("must not start or end with blanks")
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Doc {
        a: Num,
        sec: Option<Sec>,
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Sec {
        xs: Option<Vec<Num>>,
    }

    #[test]
    fn errors_name_field_value_and_reason() {
        let (d, doc) = parse::<Doc>("a = 3\n[sec]\nxs = [1, 2.5]\n").unwrap();
        assert_eq!(d.a, Num(3.0));
        assert_eq!(d.sec.and_then(|s| s.xs), Some(vec![Num(1.0), Num(2.5)]));
        assert_eq!(shown(&doc, "sec.xs[1]"), "2.5");
        assert_eq!(shown(&doc, "sec.nope"), "(missing)");
        let e = parse::<Doc>("a = \"x\"\n").unwrap_err();
        assert_eq!(
            e,
            TomlInputError::Field {
                field: "a".into(),
                value: "\"x\"".into(),
                reason: "must be a number".into()
            }
        );
        let e = parse::<Doc>("[sec]\nxs = []\n").unwrap_err();
        assert!(
            matches!(e, TomlInputError::Field { ref field, ref value, .. } if field == "a" && value == "(missing)"),
            "{e:?}"
        );
        let e = parse::<Doc>("a = 1\n[sec]\nys = 2\n").unwrap_err();
        assert!(
            matches!(e, TomlInputError::Field { ref field, ref value, ref reason } if field == "sec.ys" && value == "2" && reason.starts_with("unknown field")),
            "{e:?}"
        );
        let e = parse::<Doc>("a = 1\n[sec]\nxs = [1, true]\n").unwrap_err();
        assert!(
            matches!(e, TomlInputError::Field { ref field, ref value, .. } if field == "sec.xs[1]" && value == "true"),
            "{e:?}"
        );
        assert!(matches!(
            parse::<Doc>("a = = 1"),
            Err(TomlInputError::Syntax(_))
        ));
    }
}
