//! The design problem as a file (`[problem]` of an optimisation TOML): base case, encoding,
//! limits and objectives, with the thesis' presets for HORUS-2B and the SRM capsule.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{DesignError, Encoding, FixedNode, Limits, Objectives, ReentryProblem, Simulator};
use crate::scenario::{Scenario, read_scenario};

/// Names of the built-in base cases.
pub const PRESETS: [&str; 5] = [
    "horus-2b",
    "srm",
    "srm-altitude",
    "srm-analytical",
    "srm-analytical-altitude",
];

/// A design problem in file units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignConfig {
    /// Base case: a preset name (`horus-2b`, `srm`, `srm-altitude`, `srm-analytical`,
    /// `srm-analytical-altitude`) or a scenario file (its vehicle, environment, entry state,
    /// guidance settings and termination; its nodes are replaced).
    pub base: String,
    /// The simulator that evaluates (`numerical`, the default, or `analytical`: the glide
    /// closed form flown segment by segment, [`crate::analytic::guided_glide`]).
    #[serde(default, skip_serializing_if = "Simulator::is_numerical")]
    pub simulator: Simulator,
    /// Decision encoding.
    pub encoding: Encoding,
    /// Constraints.
    #[serde(default)]
    pub limits: Limits,
    /// Objectives.
    #[serde(default)]
    pub objectives: Objectives,
}

impl DesignConfig {
    /// A preset: `horus-2b` (8 nodes, alpha and bank free, entry of thesis table 2.1; first
    /// node the reference initial attitude 40 deg / 0 deg, last node 0 deg / 0 deg at E-hat
    /// = 0, the thesis' sea-level standstill terminal node of sec. 9.3.3),
    /// `srm` (8 nodes, bank only, 100 km entry of thesis sec. 9.2), `srm-altitude` (the same
    /// with the entry altitude a variable in 50 to 110 km), `srm-analytical` and
    /// `srm-analytical-altitude` (the same two on the analytical simulator, thesis sec. 9.2:
    /// the entry speed and flight-path angle imposed by the glide closed form).
    ///
    /// # Errors
    /// [`DesignError::UnknownPreset`].
    pub fn preset(name: &str) -> Result<Self, DesignError> {
        let thesis = |first: FixedNode, last: FixedNode, free_alpha| Encoding {
            nodes: 8,
            first,
            last,
            energy: [0.1, 0.95],
            alpha_deg: [0.0, 45.0],
            sigma_deg: [0.0, 90.0],
            free_alpha,
            entry_altitude_km: None,
        };
        let node = |energy, alpha_deg, sigma_deg| FixedNode {
            energy,
            alpha_deg,
            sigma_deg,
        };
        let encoding = match name {
            "horus-2b" => thesis(node(1.0, 40.0, 0.0), node(0.0, 0.0, 0.0), true),
            "srm" | "srm-analytical" => thesis(node(1.0, 0.0, 0.0), node(0.0, 0.0, 0.0), false),
            "srm-altitude" | "srm-analytical-altitude" => Encoding {
                entry_altitude_km: Some([50.0, 110.0]),
                ..thesis(node(1.0, 0.0, 0.0), node(0.0, 0.0, 0.0), false)
            },
            _ => {
                return Err(DesignError::UnknownPreset {
                    name: name.to_string(),
                });
            }
        };
        let simulator = if name.starts_with("srm-analytical") {
            Simulator::Analytical
        } else {
            Simulator::Numerical
        };
        Ok(Self {
            base: name.to_string(),
            simulator,
            encoding,
            limits: Limits::default(),
            objectives: Objectives::default(),
        })
    }

    /// This configuration with a scenario-file `base` made absolute (a relative one resolved
    /// against `dir`), so a run directory's config.toml finds its base from any working
    /// directory (a resumed run, a run resumed by another front end). A built-in base
    /// ([`PRESETS`]) is kept.
    #[must_use]
    pub fn anchored(&self, dir: &Path) -> Self {
        let mut c = self.clone();
        if !PRESETS.contains(&c.base.as_str())
            && let Ok(p) = std::path::absolute(dir.join(&c.base))
        {
            c.base = p.display().to_string();
        }
        c
    }

    /// The base scenario: a preset's, or the scenario file `base` (relative to `dir`), flying
    /// its stored profile alone (its guidance layers off: the design problems shape the
    /// stored profile).
    ///
    /// # Errors
    /// [`DesignError::Scenario`] when the file cannot be read.
    pub fn base_scenario(&self, dir: &Path) -> Result<Scenario, DesignError> {
        let mut sc = self.stack_scenario(dir)?;
        sc.layers = None;
        Ok(sc)
    }

    /// The base scenario with its guidance layers as given (the stack a robust problem flies;
    /// [`super::RobustProblem`]): the scenario file's, or for a preset its built-in mission's
    /// (`horus-2b`: `horus-2b-reference`'s layers; the SRM presets: `srm-glide`'s).
    ///
    /// # Errors
    /// [`DesignError::Scenario`] when the file cannot be read.
    pub fn stack_scenario(&self, dir: &Path) -> Result<Scenario, DesignError> {
        let d = std::f64::consts::PI / 180.0;
        match self.base.as_str() {
            "horus-2b" => {
                let mut sc = Scenario {
                    name: "horus-2b-design".into(),
                    ..Scenario::default()
                };
                // The reference mission's 2500 s limit cuts long-range profiles (a flight
                // reaching it is a failed evaluation): allow 5000 s.
                sc.termination.max_time_s = 5000.0;
                sc.guidance.independent = guidance_core::nodes::Independent::NormalizedEnergy;
                sc.guidance.interpolation = crate::scenario::InterpolationKind::Linear;
                sc.guidance.initial = guidance_core::guidance::Command {
                    alpha_rad: self.encoding.first.alpha_deg * d,
                    sigma_rad: self.encoding.first.sigma_deg * d,
                };
                Ok(sc)
            }
            "srm" | "srm-altitude" | "srm-analytical" | "srm-analytical-altitude" => {
                let mut sc = Scenario::srm_glide();
                sc.name = "srm-design".into();
                Ok(sc)
            }
            file => Ok(read_scenario(&dir.join(file))?),
        }
    }

    /// Build the problem (`dir` resolves a scenario-file base).
    ///
    /// # Errors
    /// [`DesignError`] naming the field.
    pub fn problem(&self, dir: &Path) -> Result<ReentryProblem, DesignError> {
        let base = self.base_scenario(dir)?;
        ReentryProblem::new(
            base,
            self.encoding.clone(),
            self.limits,
            self.objectives,
            &self.base,
        )?
        .with_simulator(self.simulator)
    }
}
