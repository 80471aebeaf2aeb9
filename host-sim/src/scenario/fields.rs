//! The context every section reader of the scenario resolver shares ([`Fields`]: the file
//! named in errors, the range check of a number), in a leaf module so that `resolve`, its
//! per-section helpers (`resolve_environment`, `resolve_guidance`, `resolve_layers`) and
//! `required` import it rather than each other.

use super::ScenarioError;
use super::file::Num;
use crate::num_fmt::compact;

/// Names the file in errors and range-checks numbers.
pub(super) struct Fields<'a> {
    pub(super) file: &'a str,
}

impl Fields<'_> {
    /// The error naming this file, `field`, `value` and `reason`.
    pub(super) fn err(&self, field: &str, value: &str, reason: &str) -> ScenarioError {
        ScenarioError::Field {
            file: self.file.to_string(),
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.to_string(),
        }
    }

    /// A number of field `field` that must be finite and satisfy `ok`.
    pub(super) fn checked(
        &self,
        field: &str,
        v: Option<Num>,
        ok: impl Fn(f64) -> bool,
        reason: &str,
    ) -> Result<Option<f64>, ScenarioError> {
        match v {
            None => Ok(None),
            Some(Num(x)) if !x.is_finite() => Err(self.err(field, &compact(x), "must be finite")),
            Some(Num(x)) if !ok(x) => Err(self.err(field, &compact(x), reason)),
            Some(Num(x)) => Ok(Some(x)),
        }
    }
}
