//! Decision vector <-> guidance node table (thesis sec. 4.2.1, eq. 4.7): the first and last
//! nodes are fixed (entry and final state), the nodes in between are free, each with its
//! normalised energy, angle of attack (unless the vehicle is steered by bank only) and bank
//! angle; optionally the entry altitude is one more variable.
//!
//! Layout of a decision vector `x` (degrees and km only here, at the edge of the optimiser;
//! the node table is SI and radians):
//! `[E_1, alpha_1_deg, sigma_1_deg, ..., E_k, alpha_k_deg, sigma_k_deg, (h_entry_km)]`,
//! without the `alpha` genes for a bank-only vehicle. The free nodes are put in flight order
//! (decreasing energy) by a stable sort; a node whose energy equals an earlier one's is
//! dropped (the core needs strictly monotonic nodes), so every decision maps to a valid table.

use serde::{Deserialize, Serialize};

use super::DesignError;
use crate::optim::Bounds;

/// A fixed node in file units: normalised energy \[-\], angle of attack \[deg\], bank \[deg\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FixedNode {
    /// Normalised energy E-hat \[-\].
    pub energy: f64,
    /// Angle of attack \[deg\].
    pub alpha_deg: f64,
    /// Bank angle \[deg\].
    pub sigma_deg: f64,
}

impl FixedNode {
    fn to_rad(self) -> [f64; 3] {
        [
            self.energy,
            self.alpha_deg.to_radians(),
            self.sigma_deg.to_radians(),
        ]
    }
}

/// How decisions map to node tables (file units: degrees, km).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Encoding {
    /// Nodes in the table, fixed end nodes included (thesis: 8). At least 3.
    pub nodes: usize,
    /// The fixed first node (entry).
    pub first: FixedNode,
    /// The fixed last node (final state).
    pub last: FixedNode,
    /// Bounds of a free node's normalised energy \[-\] (thesis: 0.1 to 0.95).
    pub energy: [f64; 2],
    /// Bounds of a free node's angle of attack \[deg\] (thesis: 0 to 45).
    pub alpha_deg: [f64; 2],
    /// Bounds of a free node's bank angle \[deg\] (thesis: 0 to 90).
    pub sigma_deg: [f64; 2],
    /// The angle of attack is a decision variable (false for a bank-only vehicle such as the
    /// SRM capsule, which then flies the first node's angle of attack throughout).
    pub free_alpha: bool,
    /// Entry altitude bounds \[km\] when it is a decision variable (thesis: 50 to 110);
    /// `None` keeps the base scenario's entry altitude.
    pub entry_altitude_km: Option<[f64; 2]>,
}

impl Encoding {
    /// Genes per free node.
    #[must_use]
    pub fn genes_per_node(&self) -> usize {
        if self.free_alpha { 3 } else { 2 }
    }

    /// Free nodes (the table's nodes less the two fixed ones).
    #[must_use]
    pub fn free_nodes(&self) -> usize {
        self.nodes.saturating_sub(2)
    }

    /// Number of decision variables.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.free_nodes() * self.genes_per_node() + usize::from(self.entry_altitude_km.is_some())
    }

    /// Check the settings; the error names the field and what to change.
    ///
    /// # Errors
    /// [`DesignError::Setting`].
    pub fn validate(&self) -> Result<(), DesignError> {
        let bad = |field: &'static str, value: String, reason: &'static str| {
            Err(DesignError::Setting {
                field,
                value,
                reason,
            })
        };
        if self.nodes < 3 {
            return bad(
                "encoding.nodes",
                self.nodes.to_string(),
                "use at least 3 (two fixed end nodes and one free node)",
            );
        }
        if self.nodes > 256 {
            return bad(
                "encoding.nodes",
                self.nodes.to_string(),
                "use at most 256 (the host node capacity)",
            );
        }
        let pairs: [(&'static str, [f64; 2]); 3] = [
            ("encoding.energy", self.energy),
            ("encoding.alpha_deg", self.alpha_deg),
            ("encoding.sigma_deg", self.sigma_deg),
        ];
        for (field, [lo, hi]) in pairs {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return bad(
                    field,
                    format!("[{lo}, {hi}]"),
                    "use finite bounds with lower < upper",
                );
            }
        }
        for (field, n) in [("encoding.first", self.first), ("encoding.last", self.last)] {
            let ok = n.energy.is_finite()
                && (0.0..=45.0).contains(&n.alpha_deg)
                && n.sigma_deg > -180.0
                && n.sigma_deg <= 180.0;
            if !ok {
                return bad(
                    field,
                    format!(
                        "{{ energy = {}, alpha_deg = {}, sigma_deg = {} }}",
                        n.energy, n.alpha_deg, n.sigma_deg
                    ),
                    "use a finite energy, alpha_deg in [0, 45] and sigma_deg in (-180, 180]",
                );
            }
        }
        let [e0, e1] = self.energy;
        if !(self.last.energy < e0 && e1 < self.first.energy) {
            return bad(
                "encoding.energy",
                format!("[{e0}, {e1}]"),
                "free node energies must lie strictly between the last and first nodes' energies",
            );
        }
        if let Some([lo, hi]) = self.entry_altitude_km
            && !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi)
        {
            return bad(
                "encoding.entry_altitude_km",
                format!("[{lo}, {hi}]"),
                "use finite positive bounds with lower < upper",
            );
        }
        Ok(())
    }

    /// The box bounds of the decision vector.
    ///
    /// # Errors
    /// [`DesignError::Bounds`] if the bounds are invalid (see [`Encoding::validate`]).
    pub fn bounds(&self) -> Result<Bounds, DesignError> {
        let (lo, hi) = self.bounds_of(self.free_nodes());
        Ok(Bounds::new(lo, hi)?)
    }

    /// The genes' bounds of one free node: `[E-hat, alpha_deg, sigma_deg]` or
    /// `[E-hat, sigma_deg]` (lower, upper).
    #[must_use]
    pub fn node_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let mut lo = vec![self.energy[0]];
        let mut hi = vec![self.energy[1]];
        if self.free_alpha {
            lo.push(self.alpha_deg[0]);
            hi.push(self.alpha_deg[1]);
        }
        lo.push(self.sigma_deg[0]);
        hi.push(self.sigma_deg[1]);
        (lo, hi)
    }

    /// The bounds (lower, upper) of `free_nodes` free nodes' genes, then the entry altitude
    /// \[km\] when it is a variable: the decision vector of [`Encoding::bounds`] for any node
    /// count (the padded encoding of [`super::VariableReentry`] uses its largest).
    #[must_use]
    pub fn bounds_of(&self, free_nodes: usize) -> (Vec<f64>, Vec<f64>) {
        let (node_lo, node_hi) = self.node_bounds();
        let mut lo = node_lo.repeat(free_nodes);
        let mut hi = node_hi.repeat(free_nodes);
        if let Some([a, b]) = self.entry_altitude_km {
            lo.push(a);
            hi.push(b);
        }
        (lo, hi)
    }

    /// The node table `[E-hat, alpha_rad, sigma_rad]` (flight order, fixed end nodes
    /// included) and the entry altitude \[m\] if it is a variable, of the free genes `genes`
    /// (`genes_per_node()` per node, any number of nodes: a variable-length individual
    /// passes its own) and `altitude_km`.
    #[must_use]
    pub fn table_of(&self, genes: &[f64]) -> Vec<[f64; 3]> {
        let g = self.genes_per_node();
        let mut free: Vec<[f64; 3]> = genes
            .chunks_exact(g)
            .map(|c| {
                let (alpha_deg, sigma_deg) = if self.free_alpha {
                    (c[1], c[2])
                } else {
                    (self.first.alpha_deg, c[1])
                };
                [c[0], alpha_deg.to_radians(), sigma_deg.to_radians()]
            })
            .collect();
        free.sort_by(|a, b| b[0].total_cmp(&a[0]));
        free.dedup_by(|b, a| a[0] == b[0]);
        let mut table = Vec::with_capacity(free.len() + 2);
        table.push(self.first.to_rad());
        table.extend(free);
        table.push(self.last.to_rad());
        table
    }

    /// Split a fixed-length decision into the node table and the entry altitude \[m\].
    ///
    /// # Errors
    /// [`DesignError::Dimension`] for a decision of the wrong length.
    pub fn decode(&self, x: &[f64]) -> Result<(Vec<[f64; 3]>, Option<f64>), DesignError> {
        if x.len() != self.dim() {
            return Err(DesignError::Dimension {
                expected: self.dim(),
                got: x.len(),
            });
        }
        let n = self.free_nodes() * self.genes_per_node();
        let altitude_m = self.entry_altitude_km.map(|_| x[n] * 1e3);
        Ok((self.table_of(&x[..n]), altitude_m))
    }
}
