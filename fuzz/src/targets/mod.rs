//! The fuzz targets and the per-case generator.

mod closed_forms;
mod guidance;
mod link;
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
    /// The Vinh closed forms through the predictor, and the re-planning solver.
    ClosedForms,
}

impl Target {
    /// Every target, in the order they run.
    pub const ALL: [Target; 4] = [
        Target::Nodes,
        Target::Guidance,
        Target::Link,
        Target::ClosedForms,
    ];

    /// The target's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Target::Nodes => "nodes",
            Target::Guidance => "guidance",
            Target::Link => "link",
            Target::ClosedForms => "closed-forms",
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
            Target::ClosedForms => closed_forms::run(&mut rng),
        }
    }
}
