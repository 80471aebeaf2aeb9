//! The fuzz targets and the per-case generator.

mod closed_forms;
mod estimate;
mod guidance;
mod lateral;
mod link;
mod navconv;
mod nodes;

use rand::SeedableRng;
use rand_chacha::ChaCha12Rng;

/// One fuzz target.
#[derive(Clone, Copy, Debug)]
pub enum Target {
    /// Node tables and interpolation.
    Nodes,
    /// Guidance updates with hostile times and states.
    Guidance,
    /// The PIL frame decoder.
    Link,
    /// The navigation interface (Cartesian -> guidance variables).
    Navconv,
    /// The Vinh closed forms through the predictor, and the re-planning solver.
    ClosedForms,
    /// Lateral guidance (bank reversals) with hostile configurations and states.
    Lateral,
    /// Onboard aerodynamic estimation with hostile settings and accelerations.
    Estimate,
}

impl Target {
    /// Every target, in the order they run.
    pub const ALL: [Target; 7] = [
        Target::Nodes,
        Target::Guidance,
        Target::Link,
        Target::Navconv,
        Target::ClosedForms,
        Target::Lateral,
        Target::Estimate,
    ];

    /// The target's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Target::Nodes => "nodes",
            Target::Guidance => "guidance",
            Target::Link => "link",
            Target::Navconv => "navconv",
            Target::ClosedForms => "closed-forms",
            Target::Lateral => "lateral",
            Target::Estimate => "estimate",
        }
    }

    /// The target called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Run one case; `Err` describes a finding.
    pub fn run(self, seed: u64, case: u64) -> Result<(), String> {
        // Each (seed, target, case) has its own stream: a case reproduces on its own.
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        key[8..16].copy_from_slice(&case.to_le_bytes());
        key[16] = self as u8;
        let mut rng = ChaCha12Rng::from_seed(key);
        match self {
            Target::Nodes => nodes::run(&mut rng),
            Target::Guidance => guidance::run(&mut rng),
            Target::Link => link::run(&mut rng),
            Target::Navconv => navconv::run(&mut rng),
            Target::ClosedForms => closed_forms::run(&mut rng),
            Target::Lateral => lateral::run(&mut rng),
            Target::Estimate => estimate::run(&mut rng),
        }
    }
}
