//! Typed field reader of TOML tables: every error names the file, the field and the value.

use toml::{Table, Value};

use super::CliError;

/// A TOML value as written in error messages (strings quoted).
pub(super) fn fmt_value(v: &Value) -> String {
    match v {
        Value::String(s) => format!("{s:?}"),
        other => other.to_string(),
    }
}

/// Dotted field name of `key` in section `prefix` (`""`: top level).
fn field_name(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// Reads typed fields out of a TOML table, naming file, field and value on errors.
pub(super) struct Fields<'a> {
    pub(super) file: &'a str,
}

impl Fields<'_> {
    /// The error naming this file, `field`, `value` and `reason`.
    pub(super) fn err(&self, field: &str, value: &str, reason: &str) -> CliError {
        CliError::Scenario(format!(
            "{}: field `{field}` = {value}: {reason}",
            self.file
        ))
    }

    /// Reject keys of `t` (section `prefix`) that are not in `allowed`.
    pub(super) fn reject_unknown(
        &self,
        t: &Table,
        prefix: &str,
        allowed: &[&str],
    ) -> Result<(), CliError> {
        for (k, v) in t {
            if !allowed.contains(&k.as_str()) {
                return Err(self.err(
                    &field_name(prefix, k),
                    &fmt_value(v),
                    &format!("unknown field (expected one of: {})", allowed.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// Top-level section `key`, if present.
    pub(super) fn table<'t>(&self, t: &'t Table, key: &str) -> Result<Option<&'t Table>, CliError> {
        match t.get(key) {
            None => Ok(None),
            Some(Value::Table(tt)) => Ok(Some(tt)),
            Some(v) => Err(self.err(key, &fmt_value(v), "must be a table ([section])")),
        }
    }

    /// Finite number `key` of section `prefix`, if present.
    pub(super) fn num(&self, t: &Table, prefix: &str, key: &str) -> Result<Option<f64>, CliError> {
        let field = field_name(prefix, key);
        match t.get(key) {
            None => Ok(None),
            Some(Value::Float(f)) if f.is_finite() => Ok(Some(*f)),
            Some(Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(v @ Value::Float(_)) => Err(self.err(&field, &fmt_value(v), "must be finite")),
            Some(v) => Err(self.err(&field, &fmt_value(v), "must be a number")),
        }
    }

    /// String `key` of section `prefix`, if present.
    pub(super) fn string(
        &self,
        t: &Table,
        prefix: &str,
        key: &str,
    ) -> Result<Option<String>, CliError> {
        let field = field_name(prefix, key);
        match t.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(v) => Err(self.err(&field, &fmt_value(v), "must be a string")),
        }
    }

    /// Boolean `key` of section `prefix`, if present.
    pub(super) fn boolean(
        &self,
        t: &Table,
        prefix: &str,
        key: &str,
    ) -> Result<Option<bool>, CliError> {
        match t.get(key) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(v) => Err(self.err(
                &field_name(prefix, key),
                &fmt_value(v),
                "must be true or false",
            )),
        }
    }

    /// A number that must satisfy `ok`.
    pub(super) fn checked(
        &self,
        t: &Table,
        prefix: &str,
        key: &str,
        ok: impl Fn(f64) -> bool,
        reason: &str,
    ) -> Result<Option<f64>, CliError> {
        let v = self.num(t, prefix, key)?;
        if let Some(x) = v
            && !ok(x)
        {
            return Err(self.err(&field_name(prefix, key), &x.to_string(), reason));
        }
        Ok(v)
    }
}
