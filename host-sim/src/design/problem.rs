//! The re-entry guidance problem (thesis sec. 4.2): a decision is a node table (see
//! [`Encoding`]); its evaluation flies the closed loop (guidance-core's `Guidance` at its 2 s
//! clock in the numerical simulator; or, after [`ReentryProblem::with_simulator`] with
//! [`Simulator::Analytical`], the analytical simulator's node-guided glide) and returns, from
//! the flight's [`Summary`] either way,
//!
//! * objectives (minimised): `f_r = -theta / pi` (eq. 9.1; `theta` the flown range angle, the
//!   integrated angle travelled over the planet, which like the thesis' can exceed pi, whereas
//!   the great-circle angle between entry and end points saturates at pi) and
//!   `f_Q = Q / Q_scale` (heat load, `Q_scale` = [`Objectives::heat_load_scale_j_m2`]);
//!   optionally the number of skips as a third objective. With a target range
//!   ([`Objectives::target_range_deg`]) the first objective is the miss distance instead,
//!   `f_r = |theta - theta_target| / pi` (flown range angle against the target, as a
//!   fraction of pi like eq. 9.1; times the planet radius it is the miss in metres along the
//!   track);
//! * constraints (`g <= 0` feasible): `q_max / q_lim - 1`, `n_max / n_lim - 1`,
//!   `ndot_max / ndot_lim - 1` (eq. 4.9-4.11 as continuous functions with the same zero
//!   crossing), optionally `skips - max_skips`.
//!
//! A flight that the simulator rejects or that does not end on its termination condition
//! (it reaches the time limit, e.g. skipping out of the atmosphere) is a failed evaluation
//! ([`Evaluation::failure`]): the run goes on and the individual loses every comparison.

use serde::{Deserialize, Serialize};

use super::analytical::{AnalyticalModel, Simulator};
use super::{DesignError, Encoding};
use crate::optim::{Bounds, EvalError, Evaluation, Problem, RealProblem};
use crate::scenario::{Scenario, fly};
use crate::sim::{Summary, TerminationReason};

/// The thesis' trajectory constraints (sec. 4.2.3), SI.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    /// Maximum stagnation heat flux \[kW/m^2\] (thesis: 500).
    pub heat_flux_kw_m2: f64,
    /// Maximum g-load \[-\] (thesis: 3).
    pub g_load: f64,
    /// Maximum g-load rate \[1/s\] (thesis: 0.5).
    pub g_load_rate_per_s: f64,
    /// Maximum number of skips (atmosphere exits followed by re-entry); `None`: not a
    /// constraint.
    pub max_skips: Option<u32>,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            heat_flux_kw_m2: 500.0,
            g_load: 3.0,
            g_load_rate_per_s: 0.5,
            max_skips: None,
        }
    }
}

/// Objective settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Objectives {
    /// Heat load divided by this in the objective \[J/m^2\] (default 1e9: GJ/m^2).
    pub heat_load_scale_j_m2: f64,
    /// The number of skips as a third objective.
    pub skips: bool,
    /// Target flown range angle \[deg\]: when set, the first objective is the miss distance
    /// `|theta - target| / pi` instead of `-theta / pi` (issue 11 item 2); `None`: the
    /// thesis' maximal range. In (0, 720] deg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_range_deg: Option<f64>,
}

impl Objectives {
    /// The objectives' axis labels, in order: the range objective (the miss of
    /// `target_range_deg` when it is set), the heat load, and the skips when counted.
    #[must_use]
    pub fn labels(&self) -> Vec<String> {
        let mut l = vec![
            match self.target_range_deg {
                Some(_) => "f_r = |theta - theta_target|/pi [-]".to_string(),
                None => "f_r = -theta/pi [-]".to_string(),
            },
            "f_Q = heat load [scaled]".to_string(),
        ];
        if self.skips {
            l.push("skips [-]".to_string());
        }
        l
    }
}

impl Default for Objectives {
    fn default() -> Self {
        Self {
            heat_load_scale_j_m2: 1e9,
            skips: false,
            target_range_deg: None,
        }
    }
}

/// A re-entry guidance design problem: base scenario (vehicle, environment, entry state,
/// guidance settings, termination), encoding, constraints and objectives.
#[derive(Clone, Debug)]
pub struct ReentryProblem {
    base: Scenario,
    encoding: Encoding,
    limits: Limits,
    objectives: Objectives,
    bounds: Bounds,
    file: String,
    /// The analytical simulator's model when the problem is analytical
    /// ([`ReentryProblem::with_simulator`]); `None`: the numerical closed loop.
    analytical: Option<AnalyticalModel>,
}

impl ReentryProblem {
    /// A problem on `base` (its guidance nodes are replaced by each decision's; its
    /// independent variable must be the normalised energy). `file` names the base in errors.
    ///
    /// # Errors
    /// [`DesignError`] for bad settings, naming the field.
    pub fn new(
        base: Scenario,
        encoding: Encoding,
        limits: Limits,
        objectives: Objectives,
        file: &str,
    ) -> Result<Self, DesignError> {
        encoding.validate()?;
        if base.guidance.independent != guidance_core::nodes::Independent::NormalizedEnergy {
            return Err(DesignError::Setting {
                field: "base.guidance.independent",
                value: format!("{:?}", base.guidance.independent),
                reason: "the design nodes are energy nodes: use normalized_energy",
            });
        }
        let checks = [
            ("limits.heat_flux_kw_m2", limits.heat_flux_kw_m2),
            ("limits.g_load", limits.g_load),
            ("limits.g_load_rate_per_s", limits.g_load_rate_per_s),
            (
                "objectives.heat_load_scale_j_m2",
                objectives.heat_load_scale_j_m2,
            ),
        ];
        for (field, v) in checks {
            if !(v.is_finite() && v > 0.0) {
                return Err(DesignError::Setting {
                    field,
                    value: v.to_string(),
                    reason: "use a finite positive value",
                });
            }
        }
        if let Some(t) = objectives.target_range_deg
            && !(t.is_finite() && t > 0.0 && t <= 720.0)
        {
            return Err(DesignError::Setting {
                field: "objectives.target_range_deg",
                value: t.to_string(),
                reason: "use a flown range angle in (0, 720] deg",
            });
        }
        // The base must load and build its guidance (vehicle files, bounds).
        base.load_vehicle().map_err(DesignError::Scenario)?;
        let bounds = encoding.bounds()?;
        Ok(Self {
            base,
            encoding,
            limits,
            objectives,
            bounds,
            file: file.to_string(),
            analytical: None,
        })
    }

    /// The problem evaluated by `simulator` (default: numerical). The objectives and
    /// constraints are the same functions of the flight's summary
    /// ([`ReentryProblem::evaluation_of`]) for both.
    ///
    /// # Errors
    /// [`DesignError`] when the base cannot be flown analytically (see
    /// [`AnalyticalModel::of`]), naming the field.
    pub fn with_simulator(mut self, simulator: Simulator) -> Result<Self, DesignError> {
        self.analytical = match simulator {
            Simulator::Numerical => None,
            Simulator::Analytical => Some(AnalyticalModel::of(&self.base)?),
        };
        Ok(self)
    }

    /// Which simulator evaluates the problem.
    #[must_use]
    pub fn simulator(&self) -> Simulator {
        if self.analytical.is_some() {
            Simulator::Analytical
        } else {
            Simulator::Numerical
        }
    }

    /// The analytical simulator's model, for an analytical problem.
    #[must_use]
    pub fn analytical(&self) -> Option<&AnalyticalModel> {
        self.analytical.as_ref()
    }

    /// The encoding.
    #[must_use]
    pub fn encoding(&self) -> &Encoding {
        &self.encoding
    }

    /// The base scenario.
    #[must_use]
    pub fn base(&self) -> &Scenario {
        &self.base
    }

    /// The limits.
    #[must_use]
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// The objective settings.
    #[must_use]
    pub fn objective_settings(&self) -> &Objectives {
        &self.objectives
    }

    /// The scenario that a node table and entry altitude \[m\] fly: the base with its nodes
    /// (and entry radius) replaced.
    #[must_use]
    pub fn scenario_of_table(&self, table: Vec<[f64; 3]>, altitude_m: Option<f64>) -> Scenario {
        let mut sc = self.base.clone();
        sc.guidance.nodes = table;
        if let Some(h) = altitude_m {
            sc.entry.radius_m = sc.environment.planet.radius_m + h;
        }
        sc
    }

    /// The scenario a fixed-length decision flies.
    ///
    /// # Errors
    /// [`DesignError::Dimension`].
    pub fn scenario_of(&self, x: &[f64]) -> Result<Scenario, DesignError> {
        let (table, h) = self.encoding.decode(x)?;
        Ok(self.scenario_of_table(table, h))
    }

    /// Objectives and constraints of a flight's summary.
    #[must_use]
    pub fn evaluation_of(&self, s: &Summary) -> Evaluation {
        let finished = !matches!(
            s.termination,
            TerminationReason::MaxTime | TerminationReason::Ground
        );
        if !finished {
            return Evaluation::failure(self.objectives(), self.constraints());
        }
        let pi = std::f64::consts::PI;
        let f_r = match self.objectives.target_range_deg {
            Some(t) => (s.flown_range_angle_rad - t.to_radians()).abs() / pi,
            None => -s.flown_range_angle_rad / pi,
        };
        let mut f = vec![f_r, s.heat_load_j_m2 / self.objectives.heat_load_scale_j_m2];
        if self.objectives.skips {
            f.push(f64::from(s.skips));
        }
        let l = &self.limits;
        let mut g = vec![
            s.peak_heat_flux_w_m2.value / (l.heat_flux_kw_m2 * 1e3) - 1.0,
            s.peak_g_load.value / l.g_load - 1.0,
            s.peak_g_load_rate_per_s.value / l.g_load_rate_per_s - 1.0,
        ];
        if let Some(m) = l.max_skips {
            g.push(f64::from(s.skips) - f64::from(m));
        }
        Evaluation::with_constraints(f, g)
    }

    /// Fly a scenario of this problem with the problem's simulator and evaluate it (a failed
    /// flight, or an analytical one outside the closed form's domain, is a failed evaluation,
    /// not an error).
    #[must_use]
    pub fn evaluate_scenario(&self, sc: &Scenario) -> Evaluation {
        let summary = match &self.analytical {
            Some(model) => model.fly(sc).ok().map(|run| run.result.summary),
            None => fly(sc, &self.file, &mut |_| {})
                .ok()
                .map(|flight| flight.result.summary),
        };
        match summary {
            Some(s) => self.evaluation_of(&s),
            None => Evaluation::failure(self.objectives(), self.constraints()),
        }
    }
}

impl ReentryProblem {
    /// [`ReentryProblem::evaluate_scenario`] as an optimiser's evaluation: a flight during
    /// which a stop was requested (Ctrl-C: the simulation ends `Interrupted`) is no result.
    ///
    /// # Errors
    /// [`EvalError::Interrupted`] when a stop was requested.
    pub fn try_evaluate_scenario(&self, sc: &Scenario) -> Result<Evaluation, EvalError> {
        let e = self.evaluate_scenario(sc);
        if crate::sim::stop_requested() {
            return Err(EvalError::Interrupted);
        }
        Ok(e)
    }
}

impl Problem for ReentryProblem {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        2 + usize::from(self.objectives.skips)
    }

    fn constraints(&self) -> usize {
        3 + usize::from(self.limits.max_skips.is_some())
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        self.bounds.check_dim(x)?;
        let sc = self
            .scenario_of(x)
            .map_err(|e| EvalError::Failed(Box::new(e)))?;
        self.try_evaluate_scenario(&sc)
    }
}

impl RealProblem for ReentryProblem {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }
}
