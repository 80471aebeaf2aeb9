//! The integrated model of the numerical predictor: state, right-hand side of the planar
//! equations of motion, the RK4 step and the step rule (see the parent module), and the
//! parabolic refinement of a sampled peak.

use crate::replan::bank_shape::BankShape;
use crate::replan::path_bound::BarrierPoint;
use crate::replan::{LiftSchedule, PathBound};
use crate::scalar::Real;
use crate::vinh::nondim::{ExpAtmosphere, VehicleParams, aero_accelerations_m_s2};
use crate::vinh::num::{k, sin_cos};

use super::steps::{MAX_STEP_S, PHUGOID_STEP_RAD, SPEED_STEP_FRACTION, VERTICAL_STEP_FRACTION};

/// Integrated state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct Y<S> {
    /// Altitude above the planet radius \[m\].
    pub(super) h: S,
    /// Speed \[m/s\].
    pub(super) v: S,
    /// Flight-path angle \[rad\].
    pub(super) gamma: S,
    /// Range angle flown \[rad\].
    pub(super) theta: S,
}

impl<S: Real> Y<S> {
    /// `self + a d`.
    pub(super) fn axpy(&self, d: &Y<S>, a: S) -> Y<S> {
        Y {
            h: self.h + a * d.h,
            v: self.v + a * d.v,
            gamma: self.gamma + a * d.gamma,
            theta: self.theta + a * d.theta,
        }
    }

    pub(super) fn is_finite(&self) -> bool {
        self.h.is_finite() && self.v.is_finite() && self.gamma.is_finite() && self.theta.is_finite()
    }
}

/// Rates and the aerodynamic quantities they were computed from.
#[derive(Clone, Copy, Debug)]
pub(super) struct Rates<S> {
    pub(super) dy: Y<S>,
    pub(super) rho: S,
    pub(super) drag: S,
    pub(super) lift: S,
    /// The vertical lift fraction flown (the model's, or the path bound's if larger).
    pub(super) f: S,
}

/// The predictor model with the constant lift setting.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct Model<S> {
    pub(super) mu: S,
    pub(super) radius_m: S,
    /// The atmosphere with its reference radius taken from the planet radius (density as a
    /// function of the altitude `h`).
    pub(super) atmosphere_h: ExpAtmosphere<S>,
    pub(super) vehicle: VehicleParams<S>,
    pub(super) sqrt_cd0_k: S,
    pub(super) lambda: S,
    /// `1 + lambda^2`.
    pub(super) one_l2: S,
    pub(super) f: S,
    /// The lift parameter and drag scale against speed (replace `lambda` and the polar's
    /// `1 + lambda^2` when present).
    pub(super) schedule: Option<LiftSchedule<S>>,
    /// The vertical lift fraction is at least this bound's at every state (when present).
    pub(super) bound: Option<PathBound<S>>,
    /// The planet's rotation, latitude and heading held (when present; module docs).
    pub(super) rotation: Option<Rotation<S>>,
    /// The offset \[rad\] of the bank shape the prediction flies (when present: the shape is
    /// passed to [`Model::rates`], not held, so that the solver's copies stay small).
    pub(super) shape_offset: Option<S>,
}

/// The rotating-planet terms of the planar equations with the latitude `phi` and heading `psi`
/// held at their values at the start of the prediction (module docs, "Rotating planet").
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct Rotation<S> {
    /// Coriolis turn rate `2 Omega cos(phi) sin(psi)` \[rad/s\].
    pub(super) coriolis_rad_s: S,
    /// `Omega^2 cos(phi)` \[1/s^2\].
    pub(super) w2_cos_phi: S,
    /// `cos(phi)` \[-\].
    pub(super) cos_phi: S,
    /// `sin(phi) cos(psi)` \[-\].
    pub(super) sin_phi_cos_psi: S,
}

impl<S: Real> Rotation<S> {
    /// `Omega` \[rad/s\] at latitude `phi` \[rad\] and heading `psi` \[rad, clockwise from
    /// north\]; `None` if any is non-finite or the rate is zero.
    pub(super) fn new(omega_rad_s: S, phi: S, psi: S) -> Option<Self> {
        if !(omega_rad_s.is_finite() && phi.is_finite() && psi.is_finite())
            || omega_rad_s == S::ZERO
        {
            return None;
        }
        let (sp, cp) = sin_cos(phi);
        let (ss, cs) = sin_cos(psi);
        Some(Self {
            coriolis_rad_s: k::<S>(2.0) * omega_rad_s * cp * ss,
            w2_cos_phi: omega_rad_s * omega_rad_s * cp,
            cos_phi: cp,
            sin_phi_cos_psi: sp * cs,
        })
    }
}

/// `dy` with the rotating-planet terms of `w` added at radius `r` \[m\], speed `v` \[m/s\] and
/// flight-path angle of sine `sg` and cosine `cg` (out of line: the non-rotating path of
/// [`Model::rates`] keeps its code; the sine and cosine are the ones `rates` computed).
#[inline(never)]
fn add_rotation<S: Real>(w: &Rotation<S>, r: S, v: S, (sg, cg): (S, S), dy: &mut Y<S>) {
    let c = w.w2_cos_phi * r;
    dy.v = dy.v + c * (sg * w.cos_phi - cg * w.sin_phi_cos_psi);
    dy.gamma = dy.gamma + w.coriolis_rad_s + c * (cg * w.cos_phi + sg * w.sin_phi_cos_psi) / v;
}

/// `f`, raised to `bound`'s fraction at this state (out of line: the unbounded path of
/// [`Model::rates`] keeps its code). A bound that is not computable leaves `f`.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn bounded_f<S: Real>(
    bound: &PathBound<S>,
    m: &Model<S>,
    f: S,
    r: S,
    v: S,
    (sin_gamma, cos_gamma): (S, S),
    (lambda, one_l2): (S, S),
    (rho, drag, lift): (S, S, S),
) -> S {
    let fb = if bound.is_barrier() {
        let p = BarrierPoint {
            mu_m3_s2: m.mu,
            r,
            v,
            sin_gamma,
            cos_gamma,
            rho,
            scale_height_m: m.atmosphere_h.scale_height_m,
            lift,
            drag,
        };
        bound.barrier_fraction(&p, m.vehicle.nose_radius_m)
    } else {
        let cl = lambda * m.sqrt_cd0_k;
        let cd = m.vehicle.cd0 * one_l2;
        bound.fraction(m.mu, r, v, sin_gamma, cl, cd, &m.vehicle)
    };
    match fb {
        Some(fb) if fb > f => fb,
        _ => f,
    }
}

/// `(lambda, (1 + lambda^2) drag scale)` of `schedule` at speed `v`: the lift parameter and the
/// drag coefficient over `C_D0` (out of line: the constant-lambda path of [`Model::rates`]
/// keeps its code).
#[inline(never)]
fn scheduled<S: Real>(schedule: &LiftSchedule<S>, v: S) -> (S, S) {
    let (l, scale) = schedule.at(v);
    (l, (S::ONE + l * l) * scale)
}

impl<S: Real> Model<S> {
    #[inline(always)]
    pub(super) fn rates(&self, y: &Y<S>, shape: Option<&BankShape<S>>) -> Rates<S> {
        let r = self.radius_m + y.h;
        let rho = self.atmosphere_h.density_unchecked(y.h);
        let (lambda, one_l2) = match &self.schedule {
            None => (self.lambda, self.one_l2),
            Some(s) => scheduled(s, y.v),
        };
        let (drag, lift) =
            aero_accelerations_m_s2(&self.vehicle, self.sqrt_cd0_k, lambda, one_l2, rho, y.v);
        let g = self.mu / (r * r);
        let (sg, cg) = sin_cos(y.gamma);
        let f = match (shape, self.shape_offset) {
            (Some(s), Some(offset)) => s.fraction(r, y.v, offset).unwrap_or(self.f),
            _ => self.f,
        };
        let f = match &self.bound {
            None => f,
            Some(b) => bounded_f(
                b,
                self,
                f,
                r,
                y.v,
                (sg, cg),
                (lambda, one_l2),
                (rho, drag, lift),
            ),
        };
        let v_r = y.v / r;
        let mut dy = Y {
            h: y.v * sg,
            v: -drag - g * sg,
            gamma: f * lift / y.v - (g / y.v - v_r) * cg,
            theta: v_r * cg,
        };
        if let Some(w) = &self.rotation {
            add_rotation(w, r, y.v, (sg, cg), &mut dy);
        }
        Rates {
            dy,
            rho,
            drag,
            lift,
            f,
        }
    }

    /// One classic RK4 step of `dt` from `y` with first stage `k1`.
    pub(super) fn rk4(&self, y: &Y<S>, k1: &Y<S>, dt: S, shape: Option<&BankShape<S>>) -> Y<S> {
        let half = dt.half();
        let k2 = self.rates(&y.axpy(k1, half), shape).dy;
        let k3 = self.rates(&y.axpy(&k2, half), shape).dy;
        let k4 = self.rates(&y.axpy(&k3, dt), shape).dy;
        let two: S = k(2.0);
        let sum = Y {
            h: k1.h + two * (k2.h + k3.h) + k4.h,
            v: k1.v + two * (k2.v + k3.v) + k4.v,
            gamma: k1.gamma + two * (k2.gamma + k3.gamma) + k4.gamma,
            theta: k1.theta + two * (k2.theta + k3.theta) + k4.theta,
        };
        y.axpy(&sum, dt / k(6.0))
    }

    /// The step rule (module docs) at a state with rates `rt`.
    pub(super) fn step_size(&self, y: &Y<S>, rt: &Rates<S>) -> S {
        let h_s = self.atmosphere_h.scale_height_m;
        let mut dt: S = k(MAX_STEP_S);
        let vz = rt.dy.h.abs();
        let dh_max = k::<S>(VERTICAL_STEP_FRACTION) * h_s;
        if vz * dt > dh_max {
            dt = dh_max / vz;
        }
        let dv_max = k::<S>(SPEED_STEP_FRACTION) * y.v;
        if rt.drag * dt > dv_max {
            dt = dv_max / rt.drag;
        }
        let fl = (rt.f * rt.lift).abs();
        let phase: S = k(PHUGOID_STEP_RAD);
        if fl * dt * dt > phase * phase * h_s {
            dt = phase * (h_s / fl).sqrt_fast();
        }
        dt
    }
}

/// A node of the peak history: time \[s\], heat flux \[W/m^2\], g-load \[-\].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(super) struct Node<S> {
    pub(super) t: S,
    pub(super) q: S,
    pub(super) n: S,
}

/// Value at the vertex of the parabola through `(t0, y0)`, `(t1, y1)`, `(t2, y2)` when `y1` is
/// an interior maximum and the vertex lies between `t0` and `t2`; else `y1`.
pub(super) fn vertex<S: Real>(t0: S, y0: S, t1: S, y1: S, t2: S, y2: S) -> S {
    let (h1, h2) = (t1 - t0, t2 - t1);
    if !(y1 >= y0 && y1 >= y2 && h1 > S::ZERO && h2 > S::ZERO) {
        return y1;
    }
    let d1 = (y1 - y0) / h1;
    let d2 = (y2 - y1) / h2;
    let a = (d2 - d1) / (h1 + h2);
    if !(a < S::ZERO) {
        return y1;
    }
    let s = d1 + a * h1;
    let off = -s / (k::<S>(2.0) * a);
    let peak = y1 - s * s / (k::<S>(4.0) * a);
    if off >= -h1 && off <= h2 && peak.is_finite() {
        peak
    } else {
        y1
    }
}
