//! Numerical predictor (FNPEG-style): the predictor model's planar equations of motion
//! integrated from the navigated state, flight-path angle included, with constant lift, to the
//! final speed. The re-planner's [`super::PredictorMode::Numerical`] (and the fall-back of
//! [`super::PredictorMode::Hybrid`] outside the closed forms' validated domain).
//!
//! # Model (the same as the closed forms')
//! Central gravity `g = mu/r^2` ([`Planet`]; its `mu` may be the rotation-corrected effective
//! one of [`super::PredictorModel::effective_planet`]), exponential atmosphere
//! ([`ExpAtmosphere`]), parabolic polar ([`VehicleParams`]) at lift parameter `lambda` with the
//! vertical lift fraction `f = cos(sigma)` ([`LiftControl`]), non-rotating planar flight:
//!
//! ```text
//! dh/dt     = V sin(gamma)                              (h = r - R)
//! dV/dt     = -D/m - g sin(gamma)
//! dgamma/dt = f L/(m V) - (g/V - V/r) cos(gamma)
//! dtheta/dt = V cos(gamma)/r
//! ```
//!
//! # Rotating planet (opt-in, [`NumericalRun::with_rotation`])
//! The 3-DOF entry equations over a planet rotating at `Omega` (Vinh, Busemann & Culp 1980;
//! heading `psi` clockwise from north, latitude `phi`, planet-relative speed) add to the
//! speed and flight-path-angle rates
//!
//! ```text
//! dV/dt     += Omega^2 r cos(phi) (sin(gamma) cos(phi) - cos(gamma) sin(phi) cos(psi))
//! dgamma/dt += 2 Omega cos(phi) sin(psi)
//!              + Omega^2 r cos(phi) (cos(gamma) cos(phi) + sin(gamma) sin(phi) cos(psi)) / V
//! ```
//!
//! (Coriolis, then centrifugal; the Coriolis force is normal to the velocity, so it has no
//! speed term). The planar projection holds `phi` and `psi` at their values at the start of the
//! prediction (a documented first-order assumption: it ignores the heading's turn by the bank
//! reversals and the latitude change along the track, and the rotation's terms in the heading
//! and latitude rates); `r` and `V` are the current ones at every stage. The range-angle rate is
//! unchanged. Use it with the planet's own `mu` (not the effective one), or the rotation counts
//! twice.
//!
//! `D/m`, `L/m`, the Chapman heat flux and the g-load are the closed forms' own definitions
//! (`crate::vinh::nondim`'s `aero_accelerations_m_s2`, `chapman_heat_flux_w_m2`, `g_load_of`;
//! the density is [`ExpAtmosphere`]'s). The altitude `h = r - R` is the integrated variable so
//! that `f32` keeps centimetre resolution on it (a radius of 6.5e6 m has a 0.5 m ulp).
//!
//! # Step rule (classic RK4, step chosen from the state at the start of each step)
//! `dt = min(MAX_STEP_S, VERTICAL_STEP_FRACTION H_s/|V sin gamma|,
//! SPEED_STEP_FRACTION V/(D/m), PHUGOID_STEP_RAD sqrt(H_s/|f L/m|))`:
//! the density changes by at most a factor `exp(0.5)` per step (a skip's pull-up is resolved),
//! the speed by at most 5 % (drag grows as `V^2`), and the phugoid (angular frequency
//! `sqrt(|f L/m|/H_s)`: the lift's restoring force per metre of altitude) turns by at most
//! 0.5 rad per step (about 12 steps per period). The 20 s cap bounds the step on a long glide
//! near circular speed, where all three are loose. Measured accuracy against the same equations
//! integrated with 1/16 of this step: `validate_integration_numerical_predictor_*`
//! (docs/reference/vinh.md, "Numerical predictor").
//!
//! # Terminal condition
//! With [`NumericalRun::with_final_energy`] (the re-planner's, given the terminal interface's
//! energy) the prediction ends at a specific energy `E = V^2/2 - mu/r`, the interface the
//! flights end on. The energy only falls (drag dissipates it; the rotation terms are small),
//! so the first step that ends below it holds the one crossing: that step is redone from its
//! start to the fraction interpolated linearly in energy, refined by Newton steps on the
//! energy (each an RK4 step from the start, `TERMINAL_REFINEMENTS`), and the remainder is
//! closed to first order with the rates at its end. The speed need not fall: a pull-up slows
//! the vehicle through a final speed and the next descent speeds it up again, between two
//! steps (the SRM from 99.5 km, 3,350 m/s, -2.2 deg, f 0.91: the speed-ended prediction takes
//! the later crossing, 20.1 % long; `numerical_predictor_ends_at_the_final_energy_inside_a_step`).
//!
//! Without it the prediction ends at the final speed of [`PredictorConfig`]: the last step,
//! which takes the speed below the final speed, is redone from its start with the step
//! interpolated linearly in speed, and the small remainder is closed with the rates at its end
//! (first order in a residual of a few mm/s), so the prediction ends at the final speed.
//!
//! # Peaks
//! Heat flux and g-load are evaluated at every integration node (from the first stage of the
//! step: no extra right-hand side); an interior maximum is refined by the parabola through it
//! and its two neighbours. [`PeakMode::Limits`] stops as soon as a node value exceeds a limit
//! ([`PeakStatus::LimitExceeded`], range so far); the final status compares the refined peaks.
//! [`PeakMode::RangeOnly`] computes no loads.
//!
//! # Other outputs
//! `skips`: upward crossings of the starting radius, `arcs`: downward crossings after being
//! above it (counted at the nodes); `glide_start_radius_m` and `glide_range_angle_rad` are 0 (no
//! glide phase); `validity` is always [`Validity::InDomain`] (the model is integrated, not
//! approximated).
//!
//! # Cost and resumability
//! One step is one RK4 step (4 right-hand sides: one `exp`, one `sin_cos`, a few divisions),
//! plus a Chapman heat flux (`powf`) and a square root with peaks; the last step about twice
//! that. At most [`MAX_STEPS`] steps. [`NumericalRun`] (`Copy`, a few hundred bytes) holds the
//! integration and is advanced a bounded number of steps at a time
//! ([`NumericalRun::advance`]); [`predict_numerical`] is that run to completion (bit-identical).
//!
//! # Errors (typed, outputs never NaN)
//! Input validation as the closed forms ([`VinhError::NonFiniteInput`], ...),
//! [`VinhError::BelowFinalSpeed`], [`VinhError::GroundImpact`], [`VinhError::StepLimit`],
//! [`VinhError::EscapeTrajectory`] (ascending above escape speed out of the atmosphere),
//! [`VinhError::NonFiniteResult`] (defensive).

use super::bank_shape::BankShape;
use crate::replan::{LiftSchedule, PathBound};
use crate::scalar::Real;
use crate::vinh::VinhError;
use crate::vinh::nondim::{
    EntryState, ExpAtmosphere, LiftControl, Planet, VehicleParams, chapman_heat_flux_w_m2,
    g_load_of,
};
use crate::vinh::num::k;

mod dynamics;
mod steps;
use crate::vinh::predict::{PeakMode, PeakStatus, Prediction, PredictorConfig};
use crate::vinh::validity::Validity;
use dynamics::{Model, Node, Rates, Rotation, Y, vertex};
pub use steps::{MAX_STEP_S, PHUGOID_STEP_RAD, SPEED_STEP_FRACTION, VERTICAL_STEP_FRACTION};

/// Largest number of integration steps of one prediction.
pub const MAX_STEPS: u16 = 4096;
/// Integration steps per [`super::ReplanSolver::step`] of a numerical prediction: a converged
/// SRM glide re-plan then stays within the per-tick instruction budget of the Cortex-M4F with
/// one solver step per tick (docs/reference/performance.md).
pub const STEPS_PER_SOLVER_STEP: u16 = 64;
/// Drag acceleration below which an ascending state above escape energy is taken as escaping
/// \[m/s^2\].
const ESCAPE_DRAG_M_S2: f64 = 1e-6;

/// The terminal energy of a prediction ([`NumericalRun::with_final_energy`]), held as the
/// energy above standstill on the surface (`E + mu/R`, positive: no cancellation of two
/// large terms at every step in `f32`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct FinalEnergy<S> {
    /// Gravitational parameter the energy is measured with \[m^3/s^2\].
    mu: S,
    /// `mu / R` \[J/kg\].
    mu_over_r: S,
    /// The final energy above surface standstill, `E_f + mu/R` \[J/kg\].
    above_surface: S,
}

impl<S: Real> FinalEnergy<S> {
    /// `E(y) - E_f` \[J/kg\]: positive before the end (planet radius `radius_m` \[m\]).
    fn residual(&self, y: &Y<S>, radius_m: S) -> S {
        // -mu/r + mu/R = mu h / (R r).
        (y.v * y.v).half() + self.mu_over_r * y.h / (radius_m + y.h) - self.above_surface
    }

    /// `d(E - E_f)/dt` \[W/kg\] at `y` with rates `dy`.
    fn rate(&self, y: &Y<S>, dy: &Y<S>, radius_m: S) -> S {
        let r = radius_m + y.h;
        y.v * dy.v + self.mu / (r * r) * dy.h
    }
}

/// Newton refinements of the terminal crossing inside the last step (each one RK4 step from
/// the start of that step), before the first-order closure.
const TERMINAL_REFINEMENTS: u8 = 2;

/// A numerical prediction in progress (module docs): `Copy`, advanced a bounded number of steps
/// at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NumericalRun<S> {
    model: Model<S>,
    final_speed_m_s: S,
    /// The terminal energy (`None`: the prediction ends at `final_speed_m_s`).
    final_energy: Option<FinalEnergy<S>>,
    peaks: PeakMode<S>,
    y: Y<S>,
    h0: S,
    t: S,
    steps: u16,
    q_max: S,
    n_max: S,
    /// The two previous nodes (older first) and how many are valid.
    hist: [Node<S>; 2],
    nodes: u8,
    skips: u8,
    arcs: u8,
    above: bool,
    outcome: Option<Result<Prediction<S>, VinhError>>,
}

impl<S: Real> NumericalRun<S> {
    /// Set up a prediction from `state` with constant `lift` to `config.final_speed_m_s`
    /// (`config.max_skips` is not used), peaks as `peaks` asks.
    ///
    /// # Errors
    /// The input validation errors of the closed forms ([`VinhError::NonFiniteInput`],
    /// [`VinhError::InvalidPlanet`], [`VinhError::InvalidAtmosphere`],
    /// [`VinhError::InvalidVehicle`], [`VinhError::NonPositiveZeroLiftDrag`],
    /// [`VinhError::InvalidLiftControl`], [`VinhError::UnphysicalState`],
    /// [`VinhError::EntrySpeedTooHigh`], [`VinhError::FlightPathAngleOutOfDomain`]),
    /// [`VinhError::InvalidConfig`] for a final speed that is not positive,
    /// [`VinhError::BelowFinalSpeed`] if the state is not faster than the final speed.
    pub fn new(
        planet: &Planet<S>,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
        lift: &LiftControl<S>,
        state: &EntryState<S>,
        config: &PredictorConfig<S>,
        peaks: PeakMode<S>,
    ) -> Result<Self, VinhError> {
        if !config.final_speed_m_s.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if !(config.final_speed_m_s > S::ZERO) {
            return Err(VinhError::InvalidConfig);
        }
        planet.validate()?;
        atmosphere.validate()?;
        vehicle.validate()?;
        lift.validate()?;
        state.validate(planet)?;
        if !(state.speed_m_s > config.final_speed_m_s) {
            return Err(VinhError::BelowFinalSpeed);
        }
        let sqrt_cd0_k = vehicle.cl_max_ld()?;
        let h0 = state.radius_m - planet.radius_m;
        Ok(Self {
            model: Model {
                mu: planet.mu_m3_s2,
                radius_m: planet.radius_m,
                atmosphere_h: ExpAtmosphere {
                    ref_radius_m: atmosphere.ref_radius_m - planet.radius_m,
                    ..*atmosphere
                },
                vehicle: *vehicle,
                sqrt_cd0_k,
                lambda: lift.lambda,
                one_l2: S::ONE + lift.lambda * lift.lambda,
                f: lift.vertical_fraction,
                schedule: None,
                bound: None,
                rotation: None,
                shape_offset: None,
            },
            final_speed_m_s: config.final_speed_m_s,
            final_energy: None,
            peaks,
            y: Y {
                h: h0,
                v: state.speed_m_s,
                gamma: state.flight_path_angle_rad,
                theta: S::ZERO,
            },
            h0,
            t: S::ZERO,
            steps: 0,
            q_max: S::ZERO,
            n_max: S::ZERO,
            hist: [Node {
                t: S::ZERO,
                q: S::ZERO,
                n: S::ZERO,
            }; 2],
            nodes: 0,
            skips: 0,
            arcs: 0,
            above: state.flight_path_angle_rad > S::ZERO,
            outcome: None,
        })
    }

    /// This prediction with the lift parameter following `schedule` against the speed instead
    /// of the constant `lift.lambda` (an angle-of-attack profile that changes along the
    /// flight). An invalid schedule ([`LiftSchedule::is_valid`]) is ignored.
    #[must_use]
    pub fn with_lift_schedule(mut self, schedule: LiftSchedule<S>) -> Self {
        if schedule.is_valid() {
            self.model.schedule = Some(schedule);
        }
        self
    }

    /// This prediction with the vertical lift fraction raised, at every state, to `bound`'s
    /// ([`PathBound`]: the limits flown as a bank bound, as the guidance does with
    /// [`crate::replan::ReplanningGuidance::with_path_bound`]). An invalid bound is ignored.
    #[must_use]
    pub fn with_path_bound(mut self, bound: PathBound<S>) -> Self {
        if bound.is_valid() {
            self.model.bound = Some(bound);
        }
        self
    }

    /// This prediction flying `shape` ([`BankShape`]) instead of the constant vertical
    /// fraction: its offset set so that the bank at the start is the one of `lift` given to
    /// [`NumericalRun::new`]. The shape itself is not held: advance the run with
    /// [`NumericalRun::advance_shaped`] and the same shape (with [`NumericalRun::advance`] it
    /// flies the constant fraction). A start whose E-hat is not computable leaves the constant
    /// fraction.
    #[must_use]
    pub fn with_bank_shape(mut self, shape: &BankShape<S>) -> Self {
        self.set_bank_shape(shape);
        self
    }

    /// [`NumericalRun::with_bank_shape`] in place (no copy of the run).
    pub fn set_bank_shape(&mut self, shape: &BankShape<S>) {
        let r = self.model.radius_m + self.y.h;
        if let Some(e) = shape.normalized_energy(r, self.y.v) {
            let offset = shape.offset_for(e, self.model.f);
            self.model.shape_offset = offset.is_finite().then_some(offset);
        }
    }

    /// This prediction on a planet rotating at `omega_rad_s` \[rad/s\], with the latitude
    /// `latitude_rad` \[rad\] and heading `heading_rad` \[rad, clockwise from north\] held
    /// (module docs, "Rotating planet"): the Coriolis and centrifugal terms at the current
    /// speed and radius of every step. Give it the planet without a rotation correction of its
    /// `mu`. A zero or non-finite input leaves the prediction non-rotating (bit-identical).
    #[must_use]
    pub fn with_rotation(mut self, omega_rad_s: S, latitude_rad: S, heading_rad: S) -> Self {
        self.model.rotation = Rotation::new(omega_rad_s, latitude_rad, heading_rad);
        self
    }

    /// This prediction ending at the specific energy `final_energy_j_kg` \[J/kg\]
    /// (`E = V^2/2 - mu/r`, measured with `mu_m3_s2` \[m^3/s^2\]: the planet's own, also when
    /// the dynamics fly a rotation-corrected effective `mu`) instead of at the final speed of
    /// [`NumericalRun::new`]: the interface the flights end on. The energy falls monotonically
    /// (drag only dissipates it) where the speed need not (a pull-up or a dive changes the speed
    /// both ways), so the first step that ends below it holds the one crossing, located inside
    /// that step (module docs). A non-finite or non-positive `mu_m3_s2`, or a non-finite
    /// energy, leaves the prediction unchanged (ending at the final speed); a state not above
    /// the final energy makes the outcome [`VinhError::BelowFinalSpeed`] without a step.
    #[must_use]
    pub fn with_final_energy(mut self, mu_m3_s2: S, final_energy_j_kg: S) -> Self {
        let r = self.model.radius_m;
        let mu_over_r = mu_m3_s2 / r;
        let above_surface = final_energy_j_kg + mu_over_r;
        if !(mu_m3_s2.is_finite()
            && mu_m3_s2 > S::ZERO
            && final_energy_j_kg.is_finite()
            && above_surface.is_finite())
        {
            return self;
        }
        let e = FinalEnergy {
            mu: mu_m3_s2,
            mu_over_r,
            above_surface,
        };
        if !(e.residual(&self.y, r) > S::ZERO) && self.steps == 0 {
            self.outcome = Some(Err(VinhError::BelowFinalSpeed));
        }
        self.final_energy = Some(e);
        self
    }

    /// Integration steps taken so far (at most [`MAX_STEPS`]).
    #[must_use]
    pub fn steps(&self) -> u16 {
        self.steps
    }

    /// The outcome, once the prediction is finished.
    #[must_use]
    pub fn outcome(&self) -> Option<Result<Prediction<S>, VinhError>> {
        self.outcome
    }

    /// Take at most `max_steps` integration steps; the outcome once finished (then further
    /// calls take no step and return it again).
    pub fn advance(&mut self, max_steps: u16) -> Option<Result<Prediction<S>, VinhError>> {
        self.advance_shaped(max_steps, None)
    }

    /// [`NumericalRun::advance`] flying `shape` (the one given to
    /// [`NumericalRun::with_bank_shape`]; `None`: the constant fraction).
    pub fn advance_shaped(
        &mut self,
        max_steps: u16,
        shape: Option<&BankShape<S>>,
    ) -> Option<Result<Prediction<S>, VinhError>> {
        let mut n = 0_u16;
        while n < max_steps && self.outcome.is_none() {
            self.outcome = self.step_once(shape);
            n += 1;
        }
        self.outcome
    }

    /// Heat flux and g-load at a node (not computed in [`PeakMode::RangeOnly`]); whether a
    /// node value exceeds a limit of [`PeakMode::Limits`].
    fn record_node(&mut self, t: S, rho: S, v: S, drag: S, lift: S) -> bool {
        if self.peaks == PeakMode::RangeOnly {
            return false;
        }
        let q = chapman_heat_flux_w_m2(self.model.vehicle.nose_radius_m, rho, v);
        let n = g_load_of(drag, lift);
        let [a, b] = self.hist;
        if self.nodes >= 2 {
            self.q_max = self.q_max.max(vertex(a.t, a.q, b.t, b.q, t, q));
            self.n_max = self.n_max.max(vertex(a.t, a.n, b.t, b.n, t, n));
        }
        self.q_max = self.q_max.max(q);
        self.n_max = self.n_max.max(n);
        self.hist = [b, Node { t, q, n }];
        self.nodes = self.nodes.saturating_add(1);
        match self.peaks {
            PeakMode::Limits(l) => q > l.heat_flux_w_m2 || n > l.g_load,
            _ => false,
        }
    }

    /// The prediction with range angle `theta` \[rad\] and peak status `status`.
    fn prediction(&self, theta: S, status: PeakStatus) -> Result<Prediction<S>, VinhError> {
        let range = theta * self.model.radius_m;
        let (q, n) = if status == PeakStatus::NotComputed {
            (S::ZERO, S::ZERO)
        } else {
            (self.q_max, self.n_max)
        };
        if !(theta.is_finite() && range.is_finite() && q.is_finite() && n.is_finite()) {
            return Err(VinhError::NonFiniteResult);
        }
        Ok(Prediction {
            range_angle_rad: theta,
            range_m: range,
            peak_heat_flux_w_m2: q,
            peak_g_load: n,
            skips: self.skips,
            arcs: self.arcs,
            glide_start_radius_m: S::ZERO,
            glide_range_angle_rad: S::ZERO,
            peak_status: status,
            validity: Validity::InDomain,
        })
    }

    /// One integration step; the outcome if the prediction ends.
    fn step_once(
        &mut self,
        shape: Option<&BankShape<S>>,
    ) -> Option<Result<Prediction<S>, VinhError>> {
        if self.steps >= MAX_STEPS {
            return Some(Err(VinhError::StepLimit));
        }
        self.steps += 1;
        let y0 = self.y;
        // Borrowed, not copied: the model carries the schedule (up to 12 nodes).
        let rt = self.model.rates(&y0, shape);
        if !(rt.dy.is_finite() && rt.rho.is_finite() && rt.drag.is_finite()) {
            return Some(Err(VinhError::NonFiniteResult));
        }
        if !(y0.h > S::ZERO) {
            return Some(Err(VinhError::GroundImpact));
        }
        if self.record_node(self.t, rt.rho, y0.v, rt.drag, rt.lift) {
            return Some(self.prediction(y0.theta, PeakStatus::LimitExceeded));
        }
        // Skips and arcs: crossings of the starting radius.
        let above = y0.h > self.h0;
        if above && !self.above {
            self.skips = self.skips.saturating_add(1);
        } else if !above && self.above {
            self.arcs = self.arcs.saturating_add(1);
        }
        self.above = above;
        // Escape: ascending with positive energy out of the atmosphere.
        let m = &self.model;
        let r0 = m.radius_m + y0.h;
        if y0.gamma > S::ZERO
            && y0.v * y0.v > k::<S>(2.0) * m.mu / r0
            && rt.drag < k(ESCAPE_DRAG_M_S2)
        {
            return Some(Err(VinhError::EscapeTrajectory));
        }
        let dt = m.step_size(&y0, &rt);
        let y1 = m.rk4(&y0, &rt.dy, dt, shape);
        if !y1.is_finite() {
            return Some(Err(VinhError::NonFiniteResult));
        }
        if let Some(e) = self.final_energy {
            let r = m.radius_m;
            let g1 = e.residual(&y1, r);
            if !(g1 > S::ZERO) {
                return Some(self.finish_energy(&e, &y0, &rt, dt, g1, shape));
            }
        } else if y1.v <= self.final_speed_m_s {
            return Some(self.finish(&y0, &rt, dt, &y1, shape));
        }
        if !(y1.h > S::ZERO) {
            return Some(Err(VinhError::GroundImpact));
        }
        self.y = y1;
        self.t = self.t + dt;
        None
    }

    /// The step `dt` from `y0` (rates `rt`) ended `g1 <= 0` \[J/kg\] past the final energy
    /// `e`: the crossing inside the step, from the linear interpolation of the energy over the
    /// step refined by [`TERMINAL_REFINEMENTS`] Newton steps (each an RK4 step from `y0`), the
    /// small remainder closed to first order with the rates at its end.
    fn finish_energy(
        &mut self,
        e: &FinalEnergy<S>,
        y0: &Y<S>,
        rt: &Rates<S>,
        dt: S,
        g1: S,
        shape: Option<&BankShape<S>>,
    ) -> Result<Prediction<S>, VinhError> {
        let m = &self.model;
        let r = m.radius_m;
        let g0 = e.residual(y0, r);
        // g0 > 0 >= g1, so the fraction is in [0, 1].
        let frac = (g0 / (g0 - g1)).clamp(S::ZERO, S::ONE);
        let mut dt1 = dt * frac;
        let mut y2 = m.rk4(y0, &rt.dy, dt1, shape);
        let mut r2 = m.rates(&y2, shape);
        let mut dtc;
        let mut i = 0_u8;
        loop {
            let rate = e.rate(&y2, &r2.dy, r);
            let c = -e.residual(&y2, r) / rate;
            dtc = if c.is_finite() && (dt1 + c) >= S::ZERO && (dt1 + c) <= dt {
                c
            } else {
                S::ZERO
            };
            if i >= TERMINAL_REFINEMENTS || dtc == S::ZERO {
                break;
            }
            i += 1;
            dt1 = dt1 + dtc;
            y2 = m.rk4(y0, &rt.dy, dt1, shape);
            r2 = m.rates(&y2, shape);
        }
        let yf = Y {
            h: y2.h + r2.dy.h * dtc,
            v: y2.v + r2.dy.v * dtc,
            gamma: y2.gamma + r2.dy.gamma * dtc,
            theta: y2.theta + r2.dy.theta * dtc,
        };
        let t_end = self.t + (dt1 + dtc);
        self.end_at(&yf, &r2, t_end, shape)
    }

    /// The prediction ends at `yf` at time `t_end` \[s\] (`r2` the rates the closure used):
    /// checks, the last node, the status.
    fn end_at(
        &mut self,
        yf: &Y<S>,
        r2: &Rates<S>,
        t_end: S,
        shape: Option<&BankShape<S>>,
    ) -> Result<Prediction<S>, VinhError> {
        if !(yf.is_finite() && r2.dy.is_finite()) {
            return Err(VinhError::NonFiniteResult);
        }
        if !(yf.h > S::ZERO) {
            return Err(VinhError::GroundImpact);
        }
        let m = &self.model;
        self.y = *yf;
        self.t = t_end;
        if self.peaks == PeakMode::RangeOnly {
            return self.prediction(yf.theta, PeakStatus::NotComputed);
        }
        let rf = m.rates(yf, shape);
        if self.record_node(self.t, rf.rho, yf.v, rf.drag, rf.lift) {
            return self.prediction(yf.theta, PeakStatus::LimitExceeded);
        }
        let status = match self.peaks {
            PeakMode::Limits(l) if self.q_max > l.heat_flux_w_m2 || self.n_max > l.g_load => {
                PeakStatus::LimitExceeded
            }
            _ => PeakStatus::Computed,
        };
        self.prediction(yf.theta, status)
    }

    /// The step `dt` from `y0` (rates `rt`) to `y1` crossed the final speed: redo it to the
    /// interpolated crossing, close the remainder to first order, record the last node.
    fn finish(
        &mut self,
        y0: &Y<S>,
        rt: &Rates<S>,
        dt: S,
        y1: &Y<S>,
        shape: Option<&BankShape<S>>,
    ) -> Result<Prediction<S>, VinhError> {
        let m = &self.model;
        let vf = self.final_speed_m_s;
        // y0.v > vf >= y1.v, so the fraction is in (0, 1].
        let frac = ((y0.v - vf) / (y0.v - y1.v)).clamp(S::ZERO, S::ONE);
        let dt1 = dt * frac;
        let y2 = m.rk4(y0, &rt.dy, dt1, shape);
        let r2 = m.rates(&y2, shape);
        let mut dtc = (vf - y2.v) / r2.dy.v;
        if !(dtc.is_finite() && dtc.abs() <= dt1) {
            dtc = S::ZERO;
        }
        let yf = Y {
            h: y2.h + r2.dy.h * dtc,
            v: vf,
            gamma: y2.gamma + r2.dy.gamma * dtc,
            theta: y2.theta + r2.dy.theta * dtc,
        };
        let t_end = self.t + dt1 + dtc;
        self.end_at(&yf, &r2, t_end, shape)
    }
}

/// Numerical prediction ([`NumericalRun`] run to completion; module docs).
///
/// # Errors
/// As [`NumericalRun::new`], and [`VinhError::GroundImpact`], [`VinhError::StepLimit`],
/// [`VinhError::EscapeTrajectory`], [`VinhError::NonFiniteResult`].
pub fn predict_numerical<S: Real>(
    planet: &Planet<S>,
    atmosphere: &ExpAtmosphere<S>,
    vehicle: &VehicleParams<S>,
    lift: &LiftControl<S>,
    state: &EntryState<S>,
    config: &PredictorConfig<S>,
    peaks: PeakMode<S>,
) -> Result<Prediction<S>, VinhError> {
    let mut run = NumericalRun::new(planet, atmosphere, vehicle, lift, state, config, peaks)?;
    // MAX_STEPS steps and one more that reports the step limit.
    match run.advance(MAX_STEPS.saturating_add(1)) {
        Some(r) => r,
        None => Err(VinhError::StepLimit),
    }
}
