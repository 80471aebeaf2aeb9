//! Checks of a restored (deserialised) algorithm state against itself and the problem
//! ([`crate::optim::Algorithm::validate`]): a checkpoint that was tampered with or corrupted
//! gives a [`StateError`] naming the field, never a panic (an index out of range) or a run that
//! never ends (a population of 0, a batch counter of a million).

use std::fmt::Display;

use super::algorithm::Batch;
use super::archive::ParetoArchive;
pub use super::error::StateError;
use super::population::Individual;
use super::problem::Bounds;

/// A [`StateError`] for `field`.
pub fn bad(field: impl Into<String>, value: impl Display, reason: impl Into<String>) -> StateError {
    let mut value = value.to_string();
    if value.len() > 80 {
        value.truncate(77);
        value.push_str("...");
    }
    StateError {
        field: field.into(),
        value,
        reason: reason.into(),
    }
}

/// `got == want` for a length or count.
///
/// # Errors
/// [`StateError`] naming `field`.
pub fn count(field: &str, got: usize, want: usize) -> Result<(), StateError> {
    if got == want {
        Ok(())
    } else {
        Err(bad(field, got, format!("must be {want}")))
    }
}

/// A real decision: the problem's dimension, finite, within its bounds.
///
/// # Errors
/// [`StateError`] naming `field`.
pub fn real_decision(field: &str, x: &[f64], bounds: &Bounds) -> Result<(), StateError> {
    count(&format!("{field}.len()"), x.len(), bounds.dim())?;
    for (j, (&v, (&lo, &hi))) in x
        .iter()
        .zip(bounds.lower().iter().zip(bounds.upper()))
        .enumerate()
    {
        if !(lo..=hi).contains(&v) {
            return Err(bad(
                format!("{field}[{j}]"),
                v,
                format!("must be within the bounds [{lo}, {hi}]"),
            ));
        }
    }
    Ok(())
}

/// Finite values (the optimisers store a failed evaluation's values as `f64::MAX`).
///
/// # Errors
/// [`StateError`] naming the first non-finite value.
pub fn finite(field: &str, v: &[f64]) -> Result<(), StateError> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(j) => Err(bad(format!("{field}[{j}]"), v[j], "must be finite")),
        None => Ok(()),
    }
}

/// One evaluated individual: `m` objectives and `c` constraints, finite, a violation that is
/// the sum of the constraints' positive parts (or `f64::MAX`: failed), and its decision checked
/// by `decision`.
///
/// # Errors
/// [`StateError`] naming the field.
pub fn individual<D>(
    field: &str,
    ind: &Individual<D>,
    m: usize,
    c: usize,
    decision: &dyn Fn(&str, &D) -> Result<(), StateError>,
) -> Result<(), StateError> {
    decision(&format!("{field}.decision"), &ind.decision)?;
    values(
        field,
        &ind.objectives,
        &ind.constraints,
        ind.violation,
        m,
        c,
    )
}

fn values(field: &str, f: &[f64], g: &[f64], v: f64, m: usize, c: usize) -> Result<(), StateError> {
    count(&format!("{field}.objectives.len()"), f.len(), m)?;
    count(&format!("{field}.constraints.len()"), g.len(), c)?;
    finite(&format!("{field}.objectives"), f)?;
    finite(&format!("{field}.constraints"), g)?;
    let failed = v == f64::MAX;
    let sum: f64 = g.iter().map(|&x| x.max(0.0)).sum();
    if !(failed || (v.is_finite() && v >= 0.0 && (v - sum).abs() <= 1e-9 * sum.max(1.0))) {
        return Err(bad(
            format!("{field}.violation"),
            v,
            format!("must be the sum of the positive constraint values ({sum}) or f64::MAX"),
        ));
    }
    Ok(())
}

/// A population: each individual as in [`individual`].
///
/// # Errors
/// [`StateError`] naming the field.
pub fn individuals<D>(
    field: &str,
    pop: &[Individual<D>],
    m: usize,
    c: usize,
    decision: &dyn Fn(&str, &D) -> Result<(), StateError>,
) -> Result<(), StateError> {
    for (i, ind) in pop.iter().enumerate() {
        individual(&format!("{field}[{i}]"), ind, m, c, decision)?;
    }
    Ok(())
}

impl<D> Batch<D> {
    /// Check a restored batch: one told slot per decision, `remaining` the untold ones,
    /// every decision checked by `decision`, every told value as in [`individual`].
    ///
    /// # Errors
    /// [`StateError`] naming the field.
    pub fn validate(
        &self,
        field: &str,
        m: usize,
        c: usize,
        decision: &dyn Fn(&str, &D) -> Result<(), StateError>,
    ) -> Result<(), StateError> {
        let (d, told) = (self.decisions(), self.told_slots());
        count(&format!("{field}.told.len()"), told.len(), d.len())?;
        let untold = told.iter().filter(|t| t.is_none()).count();
        count(&format!("{field}.remaining"), self.remaining(), untold)?;
        for (i, x) in d.iter().enumerate() {
            decision(&format!("{field}.decisions[{i}]"), x)?;
        }
        for (i, t) in told.iter().enumerate() {
            if let Some(t) = t {
                let f = format!("{field}.told[{i}]");
                values(&f, &t.objectives, &t.constraints, t.violation, m, c)?;
            }
        }
        Ok(())
    }
}

impl<D: Clone> ParetoArchive<D> {
    /// Check a restored archive: the configured capacity, at most that many members, each
    /// feasible and valid, sorted by objectives.
    ///
    /// # Errors
    /// [`StateError`] naming the field.
    pub fn validate(
        &self,
        field: &str,
        capacity: Option<usize>,
        m: usize,
        c: usize,
        decision: &dyn Fn(&str, &D) -> Result<(), StateError>,
    ) -> Result<(), StateError> {
        let Some(cap) = capacity else {
            return Err(bad(field, "present", "the configuration has no archive"));
        };
        count(&format!("{field}.capacity"), self.capacity(), cap)?;
        let members = self.members();
        if members.len() > cap {
            return Err(bad(
                format!("{field}.members.len()"),
                members.len(),
                format!("must be at most the capacity {cap}"),
            ));
        }
        individuals(&format!("{field}.members"), members, m, c, decision)?;
        for (i, w) in members.windows(2).enumerate() {
            let order = w[0]
                .objectives
                .iter()
                .zip(&w[1].objectives)
                .map(|(a, b)| a.total_cmp(b))
                .find(|o| o.is_ne());
            if order != Some(std::cmp::Ordering::Less) {
                return Err(bad(
                    format!("{field}.members[{}]", i + 1),
                    format!("{:?}", w[1].objectives),
                    "members must be distinct and sorted by objectives",
                ));
            }
        }
        if let Some(i) = members.iter().position(|x| x.violation != 0.0) {
            return Err(bad(
                format!("{field}.members[{i}].violation"),
                members[i].violation,
                "archive members are feasible (0)",
            ));
        }
        Ok(())
    }
}

/// Indices below `n`.
///
/// # Errors
/// [`StateError`] naming the first index out of range.
pub fn indices(field: &str, v: &[usize], n: usize) -> Result<(), StateError> {
    match v.iter().position(|&i| i >= n) {
        Some(j) => Err(bad(
            format!("{field}[{j}]"),
            v[j],
            format!("must be below {n}"),
        )),
        None => Ok(()),
    }
}
