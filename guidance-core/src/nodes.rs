//! Guidance node tables (thesis sec. 3.7, eq. 3.102-3.103, and sec. 4.2.1, eq. 4.7).
//!
//! A node is `{x, alpha, sigma}`: the value `x` of the independent variable and the commanded
//! angle of attack and bank angle there \[rad\]. A [`NodeTable`] holds between 2 and its
//! capacity `N` nodes in *flight order*:
//!
//! * [`Independent::NormalizedEnergy`]: `x` is E-hat \[-\] (see [`crate::energy`]), which falls
//!   during unpowered flight, so `x` must be strictly *decreasing* node to node;
//! * [`Independent::TimeS`]: `x` is mission time \[s\] (the HORUS-2B reference mission of thesis
//!   eq. 2.3 is time-indexed), strictly *increasing*.
//!
//! Construction validates every node: finite values, strictly monotone `x` in flight order, and
//! angles inside the configured [`AngleBounds`] (thesis sec. 4.2.1: alpha 0..45 deg, sigma
//! 0..90 deg). A rejected table names the first offending node by index.
//!
//! Thesis sec. 4.2.1: the first and last nodes represent the initial and the desired final state
//! and are not decision variables; [`NodeTable::with_fixed_ends`] builds a table from fixed end
//! nodes plus free interior nodes, and [`NodeTable::interior`] returns the free ones.
//! (The thesis also restricts the optimiser's interior E-hat to 0.1..0.95; that is a bound of the
//! optimisation problem, not of a valid table, and is not enforced here.)
//!
//! # Capacity
//! The capacity `N` is a const generic, storage is inline (no allocation):
//! `NodeTable<S>` holds at most [`DEFAULT_NODE_CAPACITY`]` = 16` nodes (the thesis uses at most
//! 8; this is what the firmware carries), [`HostNodeTable`] (`N = `[`HOST_NODE_CAPACITY`]`
//! = 256`) takes a profile exported from an optimal-control solver as is. More nodes than `N`
//! is [`NodeTableError::TooManyNodes`]. [`crate::interp::Interpolator`],
//! [`crate::guidance::Guidance`] and the re-planning guidance carry the same `N`.

use crate::scalar::Scalar;
use heapless::Vec;

/// Default node capacity of a [`NodeTable`] (the thesis uses at most 8 nodes): what the
/// firmware carries.
pub const DEFAULT_NODE_CAPACITY: usize = 16;

/// The default capacity under its historical name (equal to [`DEFAULT_NODE_CAPACITY`]).
pub const MAX_NODES: usize = DEFAULT_NODE_CAPACITY;

/// Node capacity for host use ([`HostNodeTable`]): room for a profile exported from an
/// optimal-control solver.
pub const HOST_NODE_CAPACITY: usize = 256;

/// A node table with the host capacity ([`HOST_NODE_CAPACITY`] nodes).
pub type HostNodeTable<S> = NodeTable<S, HOST_NODE_CAPACITY>;

/// Degrees to radians, in `f64` (for the `*_deg` constructors).
const DEG_TO_RAD: f64 = core::f64::consts::PI / 180.0;

/// What the independent variable `x` of a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Independent {
    /// Normalised specific energy E-hat \[-\]; nodes strictly decreasing in flight order.
    NormalizedEnergy,
    /// Mission time since entry interface \[s\]; nodes strictly increasing.
    TimeS,
}

impl Independent {
    /// True if `x` increases in flight order (time), false if it decreases (energy).
    #[must_use]
    pub fn increasing(self) -> bool {
        matches!(self, Independent::TimeS)
    }
}

/// One guidance node (thesis eq. 3.102).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Node<S> {
    /// Independent variable: E-hat \[-\] or time \[s\], see [`Independent`].
    pub x: S,
    /// Commanded angle of attack \[rad\].
    pub alpha_rad: S,
    /// Commanded bank angle \[rad\].
    pub sigma_rad: S,
}

impl<S: Scalar> Node<S> {
    /// Node from `x` (E-hat \[-\] or time \[s\]) and angles in degrees (converted to radians).
    /// `None` if a value is non-finite or does not fit `S` (bounds are checked later, by
    /// [`NodeTable::new`]).
    #[must_use]
    pub fn from_deg(x: f64, alpha_deg: f64, sigma_deg: f64) -> Option<Self> {
        Some(Self {
            x: S::from_f64_checked(x)?,
            alpha_rad: S::from_f64_checked(alpha_deg * DEG_TO_RAD)?,
            sigma_rad: S::from_f64_checked(sigma_deg * DEG_TO_RAD)?,
        })
    }
}

/// Allowed ranges of the commanded angles \[rad\], inclusive.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AngleBounds<S> {
    /// Smallest angle of attack \[rad\].
    pub alpha_min_rad: S,
    /// Largest angle of attack \[rad\].
    pub alpha_max_rad: S,
    /// Smallest bank angle \[rad\].
    pub sigma_min_rad: S,
    /// Largest bank angle \[rad\].
    pub sigma_max_rad: S,
}

impl<S: Scalar> AngleBounds<S> {
    /// Thesis sec. 4.2.1 bounds: alpha 0..45 deg, sigma 0..90 deg (in radians).
    #[must_use]
    pub fn thesis_default() -> Self {
        Self {
            alpha_min_rad: S::ZERO,
            alpha_max_rad: S::from_f64(45.0 * DEG_TO_RAD),
            sigma_min_rad: S::ZERO,
            sigma_max_rad: S::from_f64(90.0 * DEG_TO_RAD),
        }
    }

    /// Bounds from degrees (converted to radians and validated).
    ///
    /// # Errors
    /// [`NodeTableError::InvalidBounds`] for non-finite values, values that do not fit `S`,
    /// or `min > max`.
    pub fn from_deg(
        alpha_min_deg: f64,
        alpha_max_deg: f64,
        sigma_min_deg: f64,
        sigma_max_deg: f64,
    ) -> Result<Self, NodeTableError> {
        let c = |v: f64| S::from_f64_checked(v * DEG_TO_RAD).ok_or(NodeTableError::InvalidBounds);
        let b = Self {
            alpha_min_rad: c(alpha_min_deg)?,
            alpha_max_rad: c(alpha_max_deg)?,
            sigma_min_rad: c(sigma_min_deg)?,
            sigma_max_rad: c(sigma_max_deg)?,
        };
        b.validate()?;
        Ok(b)
    }

    /// Check that all four bounds are finite and `min <= max` for both angles.
    ///
    /// # Errors
    /// [`NodeTableError::InvalidBounds`] otherwise.
    pub fn validate(&self) -> Result<(), NodeTableError> {
        let all = [
            self.alpha_min_rad,
            self.alpha_max_rad,
            self.sigma_min_rad,
            self.sigma_max_rad,
        ];
        // Finite first, so the comparisons below see no NaN.
        if all.iter().any(|v| !v.is_finite())
            || self.alpha_min_rad > self.alpha_max_rad
            || self.sigma_min_rad > self.sigma_max_rad
        {
            return Err(NodeTableError::InvalidBounds);
        }
        Ok(())
    }

    /// True if `alpha_rad` lies in `\[alpha_min_rad, alpha_max_rad\]` (false for NaN).
    #[must_use]
    pub fn alpha_ok(&self, alpha_rad: S) -> bool {
        alpha_rad >= self.alpha_min_rad && alpha_rad <= self.alpha_max_rad
    }

    /// True if `sigma_rad` lies in `\[sigma_min_rad, sigma_max_rad\]` (false for NaN).
    #[must_use]
    pub fn sigma_ok(&self, sigma_rad: S) -> bool {
        sigma_rad >= self.sigma_min_rad && sigma_rad <= self.sigma_max_rad
    }

    /// Clamp an angle of attack \[rad\] into the bounds; NaN maps to `alpha_min_rad`.
    #[must_use]
    pub fn clamp_alpha(&self, alpha_rad: S) -> S {
        clamp_finite(alpha_rad, self.alpha_min_rad, self.alpha_max_rad)
    }

    /// Clamp a bank angle \[rad\] into the bounds; NaN maps to `sigma_min_rad`.
    #[must_use]
    pub fn clamp_sigma(&self, sigma_rad: S) -> S {
        clamp_finite(sigma_rad, self.sigma_min_rad, self.sigma_max_rad)
    }
}

/// Clamp into `\[lo, hi\]` (valid bounds assumed); NaN gives `lo`, so the result is always
/// inside the bounds.
fn clamp_finite<S: Scalar>(v: S, lo: S, hi: S) -> S {
    if v.is_finite() {
        v.clamp(lo, hi)
    } else if v > S::ZERO {
        hi
    } else {
        lo
    }
}

/// Why a node table (or a change to one) was rejected. Indices are node indices in flight
/// order (saturated at 65535).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum NodeTableError {
    /// Fewer than two nodes.
    TooFewNodes,
    /// More nodes than the table's capacity `N` (or a capacity below 2).
    TooManyNodes,
    /// A value of node `index` is NaN or infinite.
    NonFinite {
        /// Offending node.
        index: u16,
    },
    /// Node `index` does not strictly continue the flight-order monotonicity of `x`
    /// (time increasing, E-hat decreasing) relative to node `index - 1`.
    NotMonotone {
        /// Offending node.
        index: u16,
    },
    /// The angle of attack of node `index` lies outside the bounds.
    AlphaOutOfBounds {
        /// Offending node.
        index: u16,
    },
    /// The bank angle of node `index` lies outside the bounds.
    SigmaOutOfBounds {
        /// Offending node.
        index: u16,
    },
    /// The bounds are non-finite or have `min > max`.
    InvalidBounds,
    /// A node index passed to a setter does not exist.
    IndexOutOfRange {
        /// Requested index.
        index: u16,
    },
}

fn idx(i: usize) -> u16 {
    u16::try_from(i).unwrap_or(u16::MAX)
}

/// A validated guidance table (thesis eq. 3.103 / 4.7), nodes in flight order; at most `N`
/// nodes (see "Capacity" in the module docs).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NodeTable<S, const N: usize = DEFAULT_NODE_CAPACITY> {
    independent: Independent,
    nodes: Vec<Node<S>, N>,
    bounds: AngleBounds<S>,
}

impl<S: Scalar, const N: usize> NodeTable<S, N> {
    /// Build and validate a table. Nodes in flight order: time strictly increasing, normalised
    /// energy strictly decreasing. Angles in radians.
    ///
    /// # Errors
    /// [`NodeTableError`]: too few nodes or more than `N`, invalid bounds, or the first offending node
    /// (non-finite, not monotone, angle out of bounds), checked node by node in order.
    pub fn new(
        independent: Independent,
        nodes: &[Node<S>],
        bounds: AngleBounds<S>,
    ) -> Result<Self, NodeTableError> {
        if nodes.len() < 2 {
            return Err(NodeTableError::TooFewNodes);
        }
        bounds.validate()?;
        let mut stored: Vec<Node<S>, N> = Vec::new();
        let mut prev: Option<S> = None;
        for (i, n) in nodes.iter().enumerate() {
            check_node(n, i, prev, independent, &bounds)?;
            prev = Some(n.x);
            stored.push(*n).map_err(|_| NodeTableError::TooManyNodes)?;
        }
        Ok(Self {
            independent,
            nodes: stored,
            bounds,
        })
    }

    /// Build a table from the fixed first node (initial state), the free interior nodes (the
    /// decision variables of thesis sec. 4.2.1) and the fixed last node (desired final state).
    /// Validation as for [`NodeTable::new`]; indices in errors count the first node as 0.
    ///
    /// # Errors
    /// As [`NodeTable::new`]; [`NodeTableError::TooManyNodes`] if `interior.len() + 2 > N`.
    pub fn with_fixed_ends(
        independent: Independent,
        first: Node<S>,
        interior: &[Node<S>],
        last: Node<S>,
        bounds: AngleBounds<S>,
    ) -> Result<Self, NodeTableError> {
        let mut all: Vec<Node<S>, N> = Vec::new();
        all.push(first).map_err(|_| NodeTableError::TooManyNodes)?;
        for n in interior {
            all.push(*n).map_err(|_| NodeTableError::TooManyNodes)?;
        }
        all.push(last).map_err(|_| NodeTableError::TooManyNodes)?;
        Self::new(independent, &all, bounds)
    }

    /// Build a table from `(x, alpha_deg, sigma_deg)` rows (x: E-hat \[-\] or time \[s\]; angles
    /// in degrees, converted to radians). Validation as for [`NodeTable::new`].
    ///
    /// # Errors
    /// As [`NodeTable::new`]; [`NodeTableError::NonFinite`] also for a value that does not fit
    /// `S`.
    pub fn from_deg(
        independent: Independent,
        rows: &[(f64, f64, f64)],
        bounds: AngleBounds<S>,
    ) -> Result<Self, NodeTableError> {
        let mut nodes: Vec<Node<S>, N> = Vec::new();
        for (i, &(x, a, s)) in rows.iter().enumerate() {
            let n = Node::from_deg(x, a, s).ok_or(NodeTableError::NonFinite { index: idx(i) })?;
            nodes.push(n).map_err(|_| NodeTableError::TooManyNodes)?;
        }
        Self::new(independent, &nodes, bounds)
    }

    /// The same nodes, independent variable and bounds in a table of capacity `M`.
    ///
    /// # Errors
    /// [`NodeTableError::TooManyNodes`] if the nodes do not fit `M`.
    pub fn to_capacity<const M: usize>(&self) -> Result<NodeTable<S, M>, NodeTableError> {
        NodeTable::new(self.independent, &self.nodes, self.bounds)
    }

    /// All nodes in flight order.
    #[must_use]
    pub fn nodes(&self) -> &[Node<S>] {
        &self.nodes
    }

    /// The free interior nodes (all but the first and last; thesis sec. 4.2.1).
    #[must_use]
    pub fn interior(&self) -> &[Node<S>] {
        match self.nodes.split_first() {
            Some((_, rest)) => match rest.split_last() {
                Some((_, mid)) => mid,
                None => &[],
            },
            None => &[],
        }
    }

    /// What `x` means.
    #[must_use]
    pub fn independent(&self) -> Independent {
        self.independent
    }

    /// The angle bounds the table was validated against.
    #[must_use]
    pub fn bounds(&self) -> AngleBounds<S> {
        self.bounds
    }

    /// Number of nodes (2..=`N`).
    #[must_use]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false (a valid table has at least two nodes); provided for API hygiene.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Change the bank angle of node `index` \[rad\] (onboard re-planning). The table is
    /// unchanged on error.
    ///
    /// # Errors
    /// [`NodeTableError::IndexOutOfRange`], [`NodeTableError::NonFinite`] or
    /// [`NodeTableError::SigmaOutOfBounds`].
    pub fn set_sigma(&mut self, index: usize, sigma_rad: S) -> Result<(), NodeTableError> {
        let bounds = self.bounds;
        let node = self
            .nodes
            .get_mut(index)
            .ok_or(NodeTableError::IndexOutOfRange { index: idx(index) })?;
        if !sigma_rad.is_finite() {
            return Err(NodeTableError::NonFinite { index: idx(index) });
        }
        if !bounds.sigma_ok(sigma_rad) {
            return Err(NodeTableError::SigmaOutOfBounds { index: idx(index) });
        }
        node.sigma_rad = sigma_rad;
        Ok(())
    }

    /// Change the angle of attack of node `index` \[rad\]. The table is unchanged on error.
    ///
    /// # Errors
    /// [`NodeTableError::IndexOutOfRange`], [`NodeTableError::NonFinite`] or
    /// [`NodeTableError::AlphaOutOfBounds`].
    pub fn set_alpha(&mut self, index: usize, alpha_rad: S) -> Result<(), NodeTableError> {
        let bounds = self.bounds;
        let node = self
            .nodes
            .get_mut(index)
            .ok_or(NodeTableError::IndexOutOfRange { index: idx(index) })?;
        if !alpha_rad.is_finite() {
            return Err(NodeTableError::NonFinite { index: idx(index) });
        }
        if !bounds.alpha_ok(alpha_rad) {
            return Err(NodeTableError::AlphaOutOfBounds { index: idx(index) });
        }
        node.alpha_rad = alpha_rad;
        Ok(())
    }
}

/// Validate node `i` given the previous node's `x`.
fn check_node<S: Scalar>(
    n: &Node<S>,
    i: usize,
    prev: Option<S>,
    independent: Independent,
    bounds: &AngleBounds<S>,
) -> Result<(), NodeTableError> {
    let index = idx(i);
    if !(n.x.is_finite() && n.alpha_rad.is_finite() && n.sigma_rad.is_finite()) {
        return Err(NodeTableError::NonFinite { index });
    }
    if let Some(p) = prev {
        let ok = if independent.increasing() {
            n.x > p
        } else {
            n.x < p
        };
        if !ok {
            return Err(NodeTableError::NotMonotone { index });
        }
    }
    if !bounds.alpha_ok(n.alpha_rad) {
        return Err(NodeTableError::AlphaOutOfBounds { index });
    }
    if !bounds.sigma_ok(n.sigma_rad) {
        return Err(NodeTableError::SigmaOutOfBounds { index });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    fn n(x: f64, a: f64, s: f64) -> Node<f64> {
        Node {
            x,
            alpha_rad: a.to_radians(),
            sigma_rad: s.to_radians(),
        }
    }

    #[test]
    fn rows_build_in_all_types_and_change_capacity() {
        let rows = [(0.0, 40.0, 0.0), (264.0, 40.0, 0.0), (1319.0, 11.5, 54.0)];
        let b = AngleBounds::thesis_default();
        let ti = Independent::TimeS;
        assert_eq!(NodeTable::<f64>::from_deg(ti, &rows, b).unwrap().len(), 3);
        let b32 = AngleBounds::thesis_default();
        assert_eq!(NodeTable::<f32>::from_deg(ti, &rows, b32).unwrap().len(), 3);
        let t = NodeTable::<Fixed>::from_deg(ti, &rows, AngleBounds::thesis_default()).unwrap();
        assert_eq!(t.interior().len(), 1);
        assert_eq!(t.nodes()[2].x, Fixed::from_f64(1319.0));
        let wide: NodeTable<Fixed, 64> = t.to_capacity().unwrap();
        assert_eq!(wide.nodes(), t.nodes());
        assert_eq!(
            t.to_capacity::<2>().unwrap_err(),
            NodeTableError::TooManyNodes
        );
    }

    #[test]
    fn rejects_with_index() {
        let b = AngleBounds::thesis_default();
        let e = Independent::NormalizedEnergy;
        assert_eq!(
            NodeTable::<f64>::new(e, &[n(1.0, 1.0, 1.0)], b),
            Err(NodeTableError::TooFewNodes)
        );
        assert_eq!(
            NodeTable::<f64>::new(
                e,
                &[n(1.0, 1.0, 1.0), n(0.5, 1.0, 1.0), n(0.5, 1.0, 1.0)],
                b
            ),
            Err(NodeTableError::NotMonotone { index: 2 })
        );
        // Energy must decrease; time must increase.
        assert_eq!(
            NodeTable::<f64>::new(Independent::TimeS, &[n(1.0, 1.0, 1.0), n(0.5, 1.0, 1.0)], b),
            Err(NodeTableError::NotMonotone { index: 1 })
        );
        assert_eq!(
            NodeTable::<f64>::new(e, &[n(1.0, 1.0, 1.0), n(0.5, 46.0, 1.0)], b),
            Err(NodeTableError::AlphaOutOfBounds { index: 1 })
        );
        assert_eq!(
            NodeTable::<f64>::new(e, &[n(1.0, 1.0, -0.1), n(0.5, 4.0, 1.0)], b),
            Err(NodeTableError::SigmaOutOfBounds { index: 0 })
        );
        assert_eq!(
            NodeTable::<f64>::new(e, &[n(1.0, 1.0, 1.0), n(f64::NAN, 4.0, 1.0)], b),
            Err(NodeTableError::NonFinite { index: 1 })
        );
        assert!(Node::<f64>::from_deg(f64::NAN, 1.0, 1.0).is_none());
        assert!(Node::<Fixed>::from_deg(1e12, 1.0, 1.0).is_none());
        assert_eq!(
            NodeTable::<f64>::from_deg(e, &[(1.0, 1.0, 1.0), (0.5, f64::INFINITY, 1.0)], b),
            Err(NodeTableError::NonFinite { index: 1 })
        );
        assert!(AngleBounds::<f64>::from_deg(0.0, 45.0, 0.0, f64::NAN).is_err());
        assert!(AngleBounds::<f64>::from_deg(10.0, 5.0, 0.0, 90.0).is_err());
        let mut bad = b;
        bad.alpha_max_rad = f64::NAN;
        assert_eq!(
            NodeTable::<f64>::new(e, &[n(1.0, 1.0, 1.0), n(0.5, 4.0, 1.0)], bad),
            Err(NodeTableError::InvalidBounds)
        );
        let many = [n(1.0, 1.0, 1.0); MAX_NODES + 1];
        let many: [Node<f64>; MAX_NODES + 1] = core::array::from_fn(|i| Node {
            x: 1.0 - 0.01 * i as f64,
            ..many[i]
        });
        assert_eq!(
            NodeTable::<f64>::new(e, &many, b),
            Err(NodeTableError::TooManyNodes)
        );
        assert!(NodeTable::<f64>::new(e, &many[..MAX_NODES], b).is_ok());
    }

    #[test]
    fn fixed_ends_and_setters() {
        let b = AngleBounds::thesis_default();
        let t = NodeTable::<f64>::with_fixed_ends(
            Independent::NormalizedEnergy,
            n(1.0, 40.0, 0.0),
            &[n(0.8, 30.0, 50.0), n(0.4, 20.0, 60.0)],
            n(0.05, 11.5, 54.0),
            b,
        )
        .unwrap();
        assert_eq!(t.len(), 4);
        assert_eq!(t.interior(), &[n(0.8, 30.0, 50.0), n(0.4, 20.0, 60.0)]);
        let mut t2 = t.clone();
        t2.set_sigma(1, 0.5).unwrap();
        assert_eq!(t2.nodes()[1].sigma_rad, 0.5);
        assert_eq!(
            t2.set_sigma(9, 0.5),
            Err(NodeTableError::IndexOutOfRange { index: 9 })
        );
        assert_eq!(
            t2.set_sigma(1, 2.0),
            Err(NodeTableError::SigmaOutOfBounds { index: 1 })
        );
        assert_eq!(
            t2.set_alpha(1, f64::NAN),
            Err(NodeTableError::NonFinite { index: 1 })
        );
        assert_eq!(t2.nodes()[1].sigma_rad, 0.5);
        // Interior node out of order is reported with its index in the full table.
        let e = NodeTable::<f64>::with_fixed_ends(
            Independent::NormalizedEnergy,
            n(1.0, 40.0, 0.0),
            &[n(0.8, 30.0, 50.0), n(0.9, 20.0, 60.0)],
            n(0.05, 11.5, 54.0),
            b,
        );
        assert_eq!(e, Err(NodeTableError::NotMonotone { index: 2 }));
    }
}
