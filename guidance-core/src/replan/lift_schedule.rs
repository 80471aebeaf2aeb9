//! [`LiftSchedule`]: the aerodynamics of the numerical predictor as a function of speed, for a
//! vehicle whose stored angle-of-attack profile changes along the flight (HORUS-2B: 40 deg down
//! to 4.2 km/s, then a ramp to 11.5 deg at the interface) and whose coefficients change with
//! the Mach number (below Mach 10 HORUS-2B's `C_L`, `C_D` at a given angle of attack depart
//! from the Mach-20 polar of the model). Each speed node carries the lift parameter `lambda =
//! C_L / C_L*` and a drag scale `C_D / (C_D0 (1 + lambda^2))` relative to the model's parabolic
//! polar; both are linear in speed between nodes. The closed forms keep the solver's constant
//! [`super::ReplanConfig::lambda`] and the polar.

use crate::scalar::Real;

/// Most speed nodes of a [`LiftSchedule`].
pub const SCHEDULE_NODES: usize = 12;

/// One speed node of a [`LiftSchedule`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScheduleNode<S> {
    /// Speed \[m/s\].
    pub speed_m_s: S,
    /// Lift parameter `lambda = C_L / C_L*` \[-\] (`C_L* = sqrt(C_D0/K)` of the model polar):
    /// the lift acceleration is `q S/m C_L* lambda` (`q` the dynamic pressure, `S/m` the
    /// reference area over the mass).
    pub lambda: S,
    /// Drag scale `C_D / (C_D0 (1 + lambda^2))` \[-\]: the drag coefficient over the model
    /// polar's at this `lambda` (1: the polar).
    pub drag_scale: S,
}

/// Lift parameter and drag scale against speed: `len` nodes of `nodes` in strictly decreasing
/// speed (the order flown); the first node's values at and above its speed, the last node's at
/// and below its speed, linear in speed between neighbouring nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LiftSchedule<S> {
    /// The nodes; only the first `len` are used.
    pub nodes: [ScheduleNode<S>; SCHEDULE_NODES],
    /// Number of nodes used (`2..=SCHEDULE_NODES` for a valid schedule).
    pub len: usize,
}

/// Why [`LiftSchedule::from_nodes`] refused its nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LiftScheduleError {
    /// Fewer than 2 or more than [`SCHEDULE_NODES`] nodes.
    NodeCount,
    /// A non-finite value, a negative speed or lift parameter, a non-positive drag scale, or
    /// speeds not strictly decreasing.
    InvalidNode,
}

impl<S: Real> LiftSchedule<S> {
    /// Two nodes with the polar's drag (drag scale 1): `lambda_high` at and above
    /// `speed_high_m_s` \[m/s\], linear in speed down to `lambda_low` at `speed_low_m_s`
    /// \[m/s\], `lambda_low` below. Not checked ([`Self::is_valid`]).
    #[must_use]
    pub fn linear(speed_high_m_s: S, lambda_high: S, speed_low_m_s: S, lambda_low: S) -> Self {
        let node = |speed_m_s, lambda| ScheduleNode {
            speed_m_s,
            lambda,
            drag_scale: S::ONE,
        };
        let low = node(speed_low_m_s, lambda_low);
        let mut nodes = [low; SCHEDULE_NODES];
        if let Some(first) = nodes.first_mut() {
            *first = node(speed_high_m_s, lambda_high);
        }
        Self { nodes, len: 2 }
    }

    /// The schedule of `nodes` (strictly decreasing speed).
    ///
    /// # Errors
    /// [`LiftScheduleError`] if the count or a node is not valid ([`Self::is_valid`]).
    pub fn from_nodes(nodes: &[ScheduleNode<S>]) -> Result<Self, LiftScheduleError> {
        let (Some(last), true) = (nodes.last(), (2..=SCHEDULE_NODES).contains(&nodes.len())) else {
            return Err(LiftScheduleError::NodeCount);
        };
        let mut out = Self {
            nodes: [*last; SCHEDULE_NODES],
            len: nodes.len(),
        };
        for (o, n) in out.nodes.iter_mut().zip(nodes) {
            *o = *n;
        }
        if out.is_valid() {
            Ok(out)
        } else {
            Err(LiftScheduleError::InvalidNode)
        }
    }

    /// The nodes in use (all of them if `len` is out of range).
    #[must_use]
    pub fn used(&self) -> &[ScheduleNode<S>] {
        self.nodes.get(..self.len).unwrap_or(&self.nodes)
    }

    /// Whether the schedule is usable: `2 <= len <= SCHEDULE_NODES`, every value finite,
    /// speeds non-negative and strictly decreasing, lift parameters non-negative, drag scales
    /// positive.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let n = self.used();
        (2..=SCHEDULE_NODES).contains(&self.len)
            && n.iter().all(|v| {
                v.speed_m_s.is_finite()
                    && v.lambda.is_finite()
                    && v.drag_scale.is_finite()
                    && v.speed_m_s >= S::ZERO
                    && v.lambda >= S::ZERO
                    && v.drag_scale > S::ZERO
            })
            && n.windows(2).all(|w| match w {
                [a, b] => a.speed_m_s > b.speed_m_s,
                _ => false,
            })
    }

    /// `(lambda, drag scale)` at speed `speed_m_s` \[m/s\] (both \[-\]); each between the
    /// values of the two nodes around the speed (a NaN speed gives the last node's).
    #[must_use]
    pub fn at(&self, speed_m_s: S) -> (S, S) {
        let n = self.used();
        // The segment whose lower node is at or below the speed, else the last one (NaN).
        let seg = n
            .windows(2)
            .find(|w| matches!(w, [_, lo] if speed_m_s >= lo.speed_m_s))
            .or_else(|| n.windows(2).last());
        let Some([hi, lo]) = seg else {
            return match n.last() {
                Some(l) => (l.lambda, l.drag_scale),
                None => (S::ZERO, S::ONE),
            };
        };
        let span = hi.speed_m_s - lo.speed_m_s;
        let w = (speed_m_s - lo.speed_m_s) / span;
        // NaN (a NaN speed or an invalid schedule) -> 0: the lower node.
        let w = if w.is_finite() || w > S::ZERO {
            w.clamp(S::ZERO, S::ONE)
        } else {
            S::ZERO
        };
        // Clamped: rounding must not carry the interpolation past an end.
        let lerp = |lo: S, hi: S| (lo + w * (hi - lo)).clamp(lo.min(hi), lo.max(hi));
        (
            lerp(lo.lambda, hi.lambda),
            lerp(lo.drag_scale, hi.drag_scale),
        )
    }

    /// The lift parameter at speed `speed_m_s` \[m/s\] \[-\] ([`Self::at`]).
    #[must_use]
    pub fn lambda_at(&self, speed_m_s: S) -> S {
        self.at(speed_m_s).0
    }

    /// The drag scale at speed `speed_m_s` \[m/s\] \[-\] ([`Self::at`]).
    #[must_use]
    pub fn drag_scale_at(&self, speed_m_s: S) -> S {
        self.at(speed_m_s).1
    }
}
