//! MOEA/D's restored-state check ([`crate::optim::Algorithm::validate`]).

use super::{MoeadVariation, MoeadWith};
use crate::optim::StateError;
use crate::optim::problem::Problem;
use crate::optim::restore::{bad, count, finite, indices, individuals};

impl<D: Clone, V> MoeadWith<D, V> {
    /// Check every field of a restored state against itself and `problem`.
    pub(super) fn validate_state<P>(&self, problem: &P) -> Result<(), StateError>
    where
        P: Problem<Decision = D>,
        V: MoeadVariation<P>,
    {
        let (m, c) = (problem.objectives(), problem.constraints());
        self.config
            .check(m)
            .map_err(|e| bad("config", "(restored)", e.to_string()))?;
        self.variation
            .check(problem, &self.config)
            .map_err(|e| bad("variation", "(restored)", e.to_string()))?;
        let n = self.config.population;
        let dec = |f: &str, d: &D| self.variation.check_decision(problem, f, d);
        let started = self.initialised || self.batch.is_open() || !self.weights.is_empty();
        if !started {
            count("generation", self.generation as usize, 0)?;
            return Ok(());
        }
        count("weights.len()", self.weights.len(), n)?;
        for (i, w) in self.weights.iter().enumerate() {
            count(&format!("weights[{i}].len()"), w.len(), m)?;
            finite(&format!("weights[{i}]"), w)?;
            if let Some(j) = w.iter().position(|&x| x < 0.0) {
                return Err(bad(format!("weights[{i}][{j}]"), w[j], "must be >= 0"));
            }
        }
        count("neighbourhoods.len()", self.neighbourhoods.len(), n)?;
        for (i, h) in self.neighbourhoods.iter().enumerate() {
            let f = format!("neighbourhoods[{i}]");
            count(&format!("{f}.len()"), h.len(), self.config.neighbours)?;
            indices(&f, h, n)?;
        }
        count("ideal.len()", self.ideal.len(), m)?;
        if let Some(j) = self.ideal.iter().position(|x| x.is_nan()) {
            return Err(bad(format!("ideal[{j}]"), "NaN", "must be a number"));
        }
        self.batch.validate("batch", m, c, &dec)?;
        if let Some(a) = &self.archive {
            a.validate("archive", self.config.archive, m, c, &dec)?;
        } else if self.config.archive.is_some() {
            return Err(bad("archive", "absent", "the configuration has an archive"));
        }
        if !self.initialised {
            count("population.len()", self.population.len(), 0)?;
            count("generation", self.generation as usize, 0)?;
            if self.batch.is_open() {
                count("batch.decisions.len()", self.batch.decisions().len(), n)?;
            }
            return Ok(());
        }
        count("population.len()", self.population.len(), n)?;
        individuals("population", &self.population, m, c, &dec)?;
        if self.order.is_empty() || self.order.len() > n {
            return Err(bad(
                "order.len()",
                self.order.len(),
                format!("must be in [1, {n}]"),
            ));
        }
        indices("order", &self.order, n)?;
        if self.cursor >= self.order.len() {
            return Err(bad(
                "cursor",
                self.cursor,
                format!("must be below order.len() = {}", self.order.len()),
            ));
        }
        if self.batch.is_open() {
            let b = self.batch.decisions().len();
            if b > self.config.batch_size || self.cursor + b > self.order.len() {
                return Err(bad(
                    "batch.decisions.len()",
                    b,
                    "must be at most batch_size and the subproblems left in the generation",
                ));
            }
            count("origins.len()", self.origins.len(), b)?;
            for (k, o) in self.origins.iter().enumerate() {
                if o.subproblem != self.order[self.cursor + k] {
                    return Err(bad(
                        format!("origins[{k}].subproblem"),
                        o.subproblem,
                        format!(
                            "must be order[cursor + {k}] = {}",
                            self.order[self.cursor + k]
                        ),
                    ));
                }
            }
        }
        match (&self.config.resource_allocation, &self.dra) {
            (Some(_), Some(d)) => d.validate(n, m)?,
            (None, None) => {}
            (Some(_), None) => return Err(bad("dra", "absent", "resource allocation is on")),
            (None, Some(_)) => return Err(bad("dra", "present", "resource allocation is off")),
        }
        Ok(())
    }
}
