//! Atmospheric skip, second order (thesis sec. 3.5.1; Vinh, Kim & Greenwood 1993), with the
//! ERRATA corrections.
//!
//! # What is computed
//! * First-order deepest point `x1f`: root of `phi^2 = c^2 - 2 k1 (e^x - 1) - 2 (1 - alpha) x`
//!   (eq. 3.39, ERRATA `(1 - alpha)`), by bracketing on `[0, x_surface]`.
//! * Second-order deepest point `x1`: first root of eq. 3.50,
//!   `phi^2 = c^2 - 2 k1 (e^x - 1) - 2 (1 - alpha) x + 2 eta alpha I(x)`, where `I` (eq. 3.51) is
//!   evaluated on the descending leg of the first-order solution. Beyond `x1f` the first-order
//!   `tau(x)` is complex; Vinh's remedy (low L/D, where `x1 > x1f`) freezes `x = x1f` inside
//!   `2 eta alpha I(x)`, which is applied here. With [`SkipOptions::deepest_point_refinements`]
//!   `> 0` the quadratic is rebuilt at the new `x1` and the root found again (the thesis'
//!   "iterating on the estimated deepest value"), a bounded number of times.
//! * `a1, a2, a3` (eq. 3.45-3.47, written with `(e^x - 1 - x)/x^2` to avoid cancellation) at
//!   `x1`; `x(tau) = -a2/(2 a1) - sqrt(a2^2 - 4 a1 a3)/(2 a1) sin(sqrt(-a1) tau - beta)`,
//!   `sin(beta) = a2 / sqrt(a2^2 - 4 a1 a3)` (eq. 3.43/3.44 as corrected in ERRATA), evaluated in
//!   an identical form about the deepest point that stays accurate in `f32` when `a1 -> 0`
//!   (shallow skips); the approximate `phi_a = dx/dtau` is the derivative of that sinusoid.
//! * `I1, I2` (eq. 3.52/3.53), `I` (3.51), `J` (3.55), `phi` from eq. 3.50 with its sign per
//!   leg (ERRATA: `phi > 0` descending, `phi < 0` ascending), `v` (3.54).
//! * Drag, lift, g-load and Chapman heat flux (eq. 3.56-3.58), radius, speed and flight-path
//!   angle (eq. 3.59-3.61), and the exit where `x(tau)` returns to 0 at
//!   `tau_exit = (pi + 2 beta)/sqrt(-a1)`, twice the range angle of the deepest point.
//!
//! # Domain of validity (each limit is a [`VinhError`], checked before it could bite)
//! * Reference state descending (`gamma_E < 0`): [`VinhError::NotDescending`].
//! * `|k1|` above `64 EPSILON` of the float type: [`VinhError::VerticalLiftTooSmall`] (the
//!   closed forms divide by `k1`).
//! * A real deepest point above the surface: [`VinhError::NoDeepestPoint`].
//! * `a1 < 0`: [`VinhError::NotOscillatory`].
//! * `|eta v| <= MAX_ETA_V` along the skip, where `exp(eta v) ~ 1 + eta v` holds:
//!   [`VinhError::SpeedExpansionInvalid`]. Entry speeds above
//!   [`super::nondim::MAX_ENTRY_SPEED_M_S`] (thesis: complex numbers above 11 km/s) are
//!   rejected by the set-up.
//! * Eq. 3.50 and the quadratic fit are two different approximations of `phi^2`; near the
//!   deepest point 3.50 may dip slightly below zero. Values above `-PHI2_TOLERANCE c^2` are
//!   taken as 0 (the deepest point); below that the point is "beyond the deepest point" and
//!   [`VinhError::BeyondDeepestPoint`] is returned, never a complex or NaN `phi`.
//! * The solution is planar and non-rotating, with an exponential atmosphere and inverse-square
//!   gravity; `cos(gamma) ~ 1` and `h ~ 0` are assumed (eq. 3.33-3.35), so accuracy degrades for
//!   steep entries and deep dives (see docs/validation/vinh-numerical.md for the measured errors).

use super::error::VinhError;
use super::nondim::{NonDim, k1_min};
use super::num::{
    asin_unit, brent, brent_max, expm1mx_over_x2, finite, first_root, first_root_from, k, maximize,
    parabolic_max, sin_cos_reduced,
};
use crate::scalar::Real;

/// Largest accepted `|eta v|` along the skip: the speed-ratio range `V/V_E` in
/// `[exp(-0.35), exp(0.35)] = [0.70, 1.42]` over which `exp(eta v) ~ 1 + eta v` (error
/// `(eta v)^2/2 <= 25 %` of the gravity term) is used; the measured exit errors grow with
/// `eta v` (docs/validation/vinh-numerical.md).
pub const MAX_ETA_V: f64 = 0.7;

/// Relative tolerance (times `c^2`) for a negative second-order `phi^2` near the deepest point.
pub const PHI2_TOLERANCE: f64 = 0.05;

/// Options of the skip solution (default: the thesis' single pass).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SkipOptions {
    /// Number of extra passes re-fitting the quadratic at the new second-order `x1` and
    /// re-solving eq. 3.50 (0 = the thesis' single pass with Vinh's freeze). At most 8 are used.
    pub deepest_point_refinements: u8,
}

/// Which leg of the skip a depth belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Leg {
    /// Before the deepest point (`gamma < 0`, `phi > 0`).
    Descending,
    /// After the deepest point (`gamma > 0`, `phi < 0`).
    Ascending,
}

/// One point of the skip, dimensional and non-dimensional.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SkipPoint<S> {
    /// Non-dimensional range angle `tau` \[-\].
    pub tau: S,
    /// Range angle from the reference point `theta` \[rad\].
    pub range_angle_rad: S,
    /// Depth `x = (r_E - r)/H_s` \[-\].
    pub x: S,
    /// `phi = -sqrt(r_E/H_s) sin(gamma)` \[-\].
    pub phi: S,
    /// `eta v = ln(V_E^2 / V^2)` \[-\].
    pub eta_v: S,
    /// Distance from the planet centre \[m\].
    pub radius_m: S,
    /// Speed \[m/s\].
    pub speed_m_s: S,
    /// Flight-path angle \[rad\].
    pub flight_path_angle_rad: S,
    /// Chapman stagnation heat flux \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// Drag acceleration \[m/s^2\].
    pub drag_acc_m_s2: S,
    /// Total-lift acceleration \[m/s^2\].
    pub lift_acc_m_s2: S,
    /// g-load `sqrt(L^2 + D^2)/(m g0)` \[-\].
    pub g_load: S,
}

impl<S: Real> SkipPoint<S> {
    #[inline(always)]
    fn check(self) -> Result<Self, VinhError> {
        let all = [
            self.tau,
            self.range_angle_rad,
            self.x,
            self.phi,
            self.eta_v,
            self.radius_m,
            self.speed_m_s,
            self.flight_path_angle_rad,
            self.heat_flux_w_m2,
            self.drag_acc_m_s2,
            self.lift_acc_m_s2,
            self.g_load,
        ];
        if all.iter().all(|v| v.is_finite()) {
            Ok(self)
        } else {
            Err(VinhError::NonFiniteResult)
        }
    }
}

/// Quadratic fit `phi_a^2 = a1 x^2 + a2 x + a3` and its sinusoidal `x(tau)`.
///
/// Evaluated in a form that stays well conditioned when `a1 -> 0-` (shallow skips, where
/// `phi^2` is nearly linear in `x` and the centre `-a2/(2 a1)` and amplitude of eq. 3.43 grow
/// without bound): with `omega = sqrt(-a1)`, `sd = sqrt(a2^2 - 4 a1 a3)`,
/// `tau_b = atan2(2 omega c, -a2) / omega` (= `(beta + pi/2)/omega`, eq. 3.44) and
/// `Delta = tau - tau_b`, eq. 3.43 is identically
/// `x = x1 - sd (sin(omega Delta / 2) / omega)^2`, `phi_a = dx/dtau = -sd sin(omega Delta)/(2 omega)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Quad<S> {
    a1: S,
    a2: S,
    a3: S,
    x1: S,
    omega: S,
    sd: S,
    tau_bottom: S,
    tau_exit: S,
}

impl<S: Real> Quad<S> {
    /// Eq. 3.45-3.47 at deepest point `x1 > 0`, `c > 0`.
    #[inline(always)]
    fn new(c: S, k1: S, oma: S, x1: S) -> Result<Self, VinhError> {
        if !(x1 > S::ZERO) {
            return Err(VinhError::NoDeepestPoint);
        }
        let c2 = c * c;
        let three: S = k(3.0);
        let g = expm1mx_over_x2(x1);
        let a1 = three / x1 * (k::<S>(2.0) * oma - c2 / x1 + k::<S>(4.0) * k1 * g);
        let a2 = k::<S>(-6.0) * oma + k::<S>(2.0) * c2 / x1 - k::<S>(12.0) * k1 * g;
        let a3 = c2;
        finite(a1)?;
        finite(a2)?;
        if !(a1 < S::ZERO) {
            return Err(VinhError::NotOscillatory);
        }
        let disc = a2 * a2 - k::<S>(4.0) * a1 * a3;
        if !(disc > S::ZERO) {
            return Err(VinhError::NotOscillatory);
        }
        let sd = disc.sqrt_fast();
        let omega = (-a1).sqrt_fast();
        if !(omega > S::ZERO) {
            return Err(VinhError::NotOscillatory);
        }
        // Positive root of the quadratic without cancellation.
        let x1q = if a2 < S::ZERO {
            k::<S>(2.0) * a3 / (sd - a2)
        } else {
            (a2 + sd) / (k::<S>(-2.0) * a1)
        };
        let tau_bottom = (k::<S>(2.0) * omega * c).atan2(-a2) / omega;
        Ok(Self {
            a1,
            a2,
            a3,
            x1: finite(x1q)?,
            omega,
            sd,
            tau_bottom: finite(tau_bottom)?,
            tau_exit: finite(tau_bottom + tau_bottom)?,
        })
    }

    fn x(&self, tau: S) -> S {
        self.x_phi_a(tau).0
    }

    /// `(x, phi_a)` at `tau` from one sine and cosine of `theta = omega (tau - tau_b)/2`
    /// (`|theta| <= pi/2` on the skip; `sin(2 theta) = 2 sin(theta) cos(theta)`), by the
    /// single-precision kernels of [`super::num::sin_cos_reduced`] in `f32`.
    #[inline(always)]
    fn x_phi_a(&self, tau: S) -> (S, S) {
        let (sn, cs) = sin_cos_reduced((self.omega * (tau - self.tau_bottom)).half());
        let h = sn / self.omega;
        (
            self.x1 - self.sd * h * h,
            -self.sd * (sn + sn) * cs / (k::<S>(2.0) * self.omega),
        )
    }

    fn phi_a(&self, tau: S) -> S {
        self.x_phi_a(tau).1
    }

    /// `(tau, phi_a)` at depth `x` in `[0, x1]` on a leg.
    #[inline(always)]
    fn at_depth(&self, x: S, leg: Leg) -> (S, S) {
        let depth = (self.x1 - x).max(S::ZERO);
        let arg = (self.omega * (depth / self.sd).sqrt_fast()).min(S::ONE);
        let half = k::<S>(2.0) / self.omega * asin_unit(arg);
        // phi_a = -sd sin(omega Delta)/(2 omega) with sin(omega half/2) = arg (no second sine).
        let pa = self.sd * arg * (S::ONE - arg * arg).max(S::ZERO).sqrt_fast() / self.omega;
        match leg {
            Leg::Descending => {
                let tau = self.tau_bottom - half;
                if tau >= S::ZERO {
                    (tau, pa)
                } else {
                    (S::ZERO, self.phi_a(S::ZERO))
                }
            }
            Leg::Ascending => {
                let tau = self.tau_bottom + half;
                if tau <= self.tau_exit {
                    (tau, -pa)
                } else {
                    (self.tau_exit, self.phi_a(self.tau_exit))
                }
            }
        }
    }
}

/// First-order deepest point: root of `f1 = c^2 - 2 k1 (e^x - 1) - 2 (1 - alpha) x` on
/// `(0, x_surf]` (`f1(0) = c^2 > 0`). With upward lift (`k1 > 0`) `f1` is concave, so it has
/// exactly one positive root; it is bracketed by `x_g = ln(1 + c^2/(2 k1))` (where the lift
/// term alone cancels `c^2`: an upper bound for `alpha <= 1`, a lower bound above circular
/// speed) and solved by Newton's method with the exact derivative ([`lift_root`]) to the
/// working precision. With downward lift (`k1 < 0`, convex, zero or two roots) the first sign
/// change of a 64-point scan, as in the thesis set-up.
fn first_order_root<S: Real, F: FnMut(S) -> Result<S, VinhError>>(
    mut f1: F,
    c2: S,
    k1: S,
    oma: S,
    x_surf: S,
) -> Result<S, VinhError> {
    if !(k1 > S::ZERO) {
        return first_root(f1, S::ZERO, x_surf, c2)?.ok_or(VinhError::NoDeepestPoint);
    }
    let f_surf = f1(x_surf)?;
    if f_surf > S::ZERO {
        return Err(VinhError::NoDeepestPoint);
    }
    let x_g = finite((S::ONE + c2 / (k::<S>(2.0) * k1)).ln())?;
    let (a, b) = if x_g < x_surf && x_g > S::ZERO {
        if f1(x_g)? > S::ZERO {
            (x_g, x_surf)
        } else {
            (S::ZERO, x_g)
        }
    } else {
        (S::ZERO, x_surf)
    };
    lift_root(c2, k1, oma, S::ZERO, a, b)
}

/// Largest number of Newton steps of [`lift_root`].
const MAX_NEWTON_STEPS: u32 = 64;

/// Root of `g(x) = c^2 - 2 k1 (e^x - 1) - 2 (1 - alpha) x + offset` on a bracket `[lo, hi]`
/// with `g(lo) > 0 >= g(hi)`, `k1 > 0` (`g` concave and decreasing past its maximum: one root),
/// by Newton's method with the exact derivative `-2 k1 e^x - 2 (1 - alpha)` (one exponential
/// per step for both), kept in the bracket by bisection; stops at the working precision
/// (`2 EPSILON |x|`). The first-order deepest point is `offset = 0`; beyond the first-order
/// point the second-order `phi^2` with Vinh's freeze is this `g` with `offset = 2 eta alpha I`
/// frozen.
fn lift_root<S: Real>(c2: S, k1: S, oma: S, offset: S, lo: S, hi: S) -> Result<S, VinhError> {
    let two: S = k(2.0);
    let (mut lo, mut hi) = (lo, hi);
    let mut x = lo;
    let mut n = 0_u32;
    while n < MAX_NEWTON_STEPS {
        let e = x.exp();
        let g = finite(c2 - two * k1 * (e - S::ONE) - two * oma * x + offset)?;
        let dg = -two * (k1 * e + oma);
        if g == S::ZERO {
            return Ok(x);
        }
        if g > S::ZERO {
            lo = x;
        } else {
            hi = x;
        }
        let mut xn = x - g / dg;
        if !(xn > lo && xn < hi) {
            xn = (lo + hi).half();
        }
        if !((xn - x).abs() > two * S::EPSILON * x.abs()) || !(hi - lo > two * S::EPSILON * hi) {
            return Ok(xn);
        }
        x = xn;
        n += 1;
    }
    Ok(x)
}

/// Scan intervals of the peak searches ([`SkipSolution::peaks`]).
pub const PEAK_SCAN_INTERVALS: u32 = 8;

/// Second-order skip solution from a descending reference state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SkipSolution<S> {
    nd: NonDim<S>,
    q: Quad<S>,
    x1_first: S,
    remedy_used: bool,
    exit: SkipPoint<S>,
}

/// Log-loads at one range angle with the state they came from ([`SkipSolution::peaks`]).
#[derive(Clone, Copy)]
struct LoadSample<S> {
    /// `x/2 - (m/2) eta v` (log heat flux up to a constant).
    heat: S,
    /// `x - eta v` (log g-load up to a constant).
    load: S,
    /// `(x, phi, eta v)`.
    state: (S, S, S),
}

/// Terms of eq. 3.50/3.54 at one point.
struct Terms<S> {
    phi2: S,
    i: S,
    j: S,
}

impl<S: Real> SkipSolution<S> {
    /// Solve the skip with default options.
    ///
    /// # Errors
    /// See [`SkipSolution::with_options`].
    pub fn new(nd: &NonDim<S>) -> Result<Self, VinhError> {
        Self::with_options(nd, SkipOptions::default())
    }

    /// Solve the skip from the reference state of `nd`.
    ///
    /// Cost: two bracketed roots, each solved by Brent's method to the working precision
    /// (typically 6-10 evaluations in `f32`; at most 64 scan points + 128 evaluations), plus
    /// the second root again per refinement pass. The first-order root (upward lift) is
    /// bracketed by `x_g = ln(1 + c^2/(2 k1))`, the second-order root by the first sign change
    /// on a grid of step `x1f/2` (the roots lie close together); with downward lift both use
    /// the 64-interval scan of the thesis set-up.
    ///
    /// # Errors
    /// [`VinhError::NotDescending`], [`VinhError::VerticalLiftTooSmall`],
    /// [`VinhError::NoDeepestPoint`], [`VinhError::NotOscillatory`],
    /// [`VinhError::NoAtmosphericExit`] (`phi^2 < 0` where `x` returns to 0: captured), [`VinhError::SpeedExpansionInvalid`],
    /// [`VinhError::FlightPathAngleOutOfDomain`], [`VinhError::NonFiniteResult`].
    pub fn with_options(nd: &NonDim<S>, options: SkipOptions) -> Result<Self, VinhError> {
        let c = nd.c;
        if !(c.c > S::ZERO) {
            return Err(VinhError::NotDescending);
        }
        if c.k1.abs() < k1_min::<S>() {
            return Err(VinhError::VerticalLiftTooSmall);
        }
        let c2 = c.c * c.c;
        let oma = S::ONE - c.alpha;
        let two: S = k(2.0);
        let x_surf = nd.surface_x();
        let f1 = |x: S| -> Result<S, VinhError> {
            finite(c2 - two * c.k1 * (x.exp() - S::ONE) - two * oma * x)
        };
        let x1_first = first_order_root(f1, c2, c.k1, oma, x_surf)?;
        let mut q = Quad::new(c.c, c.k1, oma, x1_first)?;
        let mut remedy_used = false;
        let passes = 1 + options.deepest_point_refinements.min(8);
        let mut pass = 0;
        while pass < passes {
            let q_fit = q;
            let mut froze = false;
            let f2 = |x: S| -> Result<S, VinhError> {
                let x_eff = if x > q_fit.x1 {
                    froze = true;
                    q_fit.x1
                } else {
                    x
                };
                let (tau, phi_a) = q_fit.at_depth(x_eff, Leg::Descending);
                let i = Self::terms_raw(nd, &q_fit, tau, x_eff, phi_a).i;
                finite(
                    c2 - two * c.k1 * (x.exp() - S::ONE) - two * oma * x
                        + two * c.eta * c.alpha * i,
                )
            };
            // Upward lift: next to the fit's deepest point (`second_order_root`). With downward
            // lift the first-order phi^2 is convex and may have two roots: the original fine
            // scan, then Brent.
            let x1 = if c.k1 > S::ZERO {
                Self::second_order_root(nd, &q_fit, f2, x_surf)?
            } else {
                first_root(f2, S::ZERO, x_surf, c2)?.ok_or(VinhError::NoDeepestPoint)?
            };
            if pass == 0 {
                remedy_used = froze && x1 > q_fit.x1;
            }
            q = Quad::new(c.c, c.k1, oma, x1)?;
            pass += 1;
        }
        // Built in the return value and completed in place (a `Self` is ~220 bytes: every move
        // is a `memcpy`, ~800 instructions on the Cortex-M4F at the firmware's opt-level "s").
        let mut out = Ok(Self {
            nd: *nd,
            q,
            x1_first,
            remedy_used,
            exit: SkipPoint {
                tau: S::ZERO,
                range_angle_rad: S::ZERO,
                x: S::ZERO,
                phi: S::ZERO,
                eta_v: S::ZERO,
                radius_m: S::ZERO,
                speed_m_s: S::ZERO,
                flight_path_angle_rad: S::ZERO,
                heat_flux_w_m2: S::ZERO,
                drag_acc_m_s2: S::ZERO,
                lift_acc_m_s2: S::ZERO,
                g_load: S::ZERO,
            },
        });
        if let Ok(sol) = &mut out {
            // A negative phi^2 at the return to x = 0 means the vehicle cannot climb back to
            // the reference radius: no exit (captured).
            match sol.point_at_tau(q.tau_exit) {
                Ok(p) => sol.exit = p,
                Err(VinhError::BeyondDeepestPoint) => return Err(VinhError::NoAtmosphericExit),
                Err(e) => return Err(e),
            }
        }
        out
    }

    /// Second-order deepest point with upward lift (`k1 > 0`): the first root of eq. 3.50
    /// (`f2`, with Vinh's freeze beyond the fit's `x1`), found next to the fit's deepest point
    /// `x_b` (the roots of the first- and second-order `phi^2` lie close together):
    /// * `f2(x_b) > 0`: the root lies beyond `x_b`, where the freeze makes `f2` the first-order
    ///   `phi^2` plus the constant `2 eta alpha I(x_b)`: Newton on that ([`lift_root`], one
    ///   exponential per step, no `I`);
    /// * else the root lies below: one Newton step from `x_b` (slope of the first-order
    ///   `phi^2`) overshot twice gives the other end of a bracket, solved by Brent; if that end is
    ///   not positive or lies below `x_b/2`, the first sign change on the grid of step `x_b/2`
    ///   from 0 (the thesis set-up's scan, coarse), then Brent.
    fn second_order_root<F: FnMut(S) -> Result<S, VinhError>>(
        nd: &NonDim<S>,
        q_fit: &Quad<S>,
        mut f2: F,
        x_surf: S,
    ) -> Result<S, VinhError> {
        let c = nd.c;
        let two: S = k(2.0);
        let c2 = c.c * c.c;
        let oma = S::ONE - c.alpha;
        let x_b = q_fit.x1;
        if !(x_b > S::ZERO && x_b < x_surf) {
            return first_root_from(f2, S::ZERO, x_surf, c2, x_b.half())?
                .ok_or(VinhError::NoDeepestPoint);
        }
        let f_b = f2(x_b)?;
        if f_b > S::ZERO {
            let e_b = x_b.exp();
            let offset = f_b - (c2 - two * c.k1 * (e_b - S::ONE) - two * oma * x_b);
            let f_surf = f2(x_surf)?;
            if f_surf > S::ZERO {
                return Err(VinhError::NoDeepestPoint);
            }
            return lift_root(c2, c.k1, oma, offset, x_b, x_surf);
        }
        if f_b == S::ZERO {
            return Ok(x_b);
        }
        let slope = -two * (c.k1 * x_b.exp() + oma);
        let x_lo = x_b - two * (f_b / slope).abs();
        if x_lo.is_finite() && x_lo > x_b.half() {
            let f_lo = f2(x_lo)?;
            if f_lo > S::ZERO {
                return brent(f2, x_lo, x_b, f_lo, f_b, S::ZERO);
            }
        }
        first_root_from(f2, S::ZERO, x_b, c2, x_b.half())?.ok_or(VinhError::NoDeepestPoint)
    }

    /// `I`, `J` and `phi^2` at `(tau, x, phi_a)` on fit `q` (eq. 3.50-3.53, 3.55).
    #[inline(always)]
    fn terms_raw(nd: &NonDim<S>, q: &Quad<S>, tau: S, x: S, phi_a: S) -> Terms<S> {
        let c = nd.c;
        let two: S = k(2.0);
        let l = S::ONE + c.lambda * c.lambda;
        let oma = S::ONE - c.alpha;
        let l_k1 = l / c.k1;
        let ka = c.k * c.alpha;
        let cm = c.c - phi_a;
        let i2 = -cm / q.a1 - q.a2 * tau / (two * q.a1);
        let i1 = phi_a * x / two - q.a2 / (k::<S>(4.0) * q.a1) * cm
            + (k::<S>(4.0) * q.a1 * q.a3 - q.a2 * q.a2) / (k::<S>(8.0) * q.a1) * tau;
        let i = l_k1 * (c.c * x - i1) - ka * x * x / two - oma * l_k1 * (tau * x - i2);
        let j = l_k1 * (c.c * tau - x) - oma * l_k1 * tau * tau / two - ka * i2;
        let phi2 =
            c.c * c.c - two * c.k1 * (x.exp() - S::ONE) - two * oma * x + two * c.eta * c.alpha * i;
        Terms { phi2, i, j }
    }

    /// Second-order `phi` (sign of `leg`), `eta v` and the terms at `(tau, x, phi_a)`.
    #[inline(always)]
    fn phi_eta_v(&self, tau: S, x: S, phi_a: S, leg: Leg) -> Result<(S, S, Terms<S>), VinhError> {
        let nd = &self.nd;
        let c = nd.c;
        let t = Self::terms_raw(nd, &self.q, tau, x, phi_a);
        let phi2 = finite(t.phi2)?;
        let tol = k::<S>(PHI2_TOLERANCE) * c.c * c.c;
        if phi2 < -tol {
            return Err(VinhError::BeyondDeepestPoint);
        }
        let mag = phi2.max(S::ZERO).sqrt_fast();
        let phi = match leg {
            Leg::Descending => mag,
            Leg::Ascending => -mag,
        };
        let l = S::ONE + c.lambda * c.lambda;
        let l_k1 = l / c.k1;
        let oma = S::ONE - c.alpha;
        let v =
            l_k1 * (c.c - phi) - c.k * c.alpha * x - oma * l_k1 * tau - c.eta * c.k * c.alpha * t.i
                + c.eta * c.alpha * l_k1 * t.j;
        let eta_v = finite(c.eta * v)?;
        if eta_v.abs() > k(MAX_ETA_V) {
            return Err(VinhError::SpeedExpansionInvalid);
        }
        Ok((phi, eta_v, t))
    }

    /// Second-order point at `(tau, x, phi_a)` with the `phi` sign of `leg`.
    #[inline(always)]
    fn point(&self, tau: S, x: S, phi_a: S, leg: Leg) -> Result<SkipPoint<S>, VinhError> {
        let (phi, eta_v, _) = self.phi_eta_v(tau, x, phi_a, leg)?;
        self.point_from(tau, x, phi, eta_v)
    }

    /// The dimensional point of a second-order state `(tau, x, phi, eta v)`.
    #[inline(always)]
    fn point_from(&self, tau: S, x: S, phi: S, eta_v: S) -> Result<SkipPoint<S>, VinhError> {
        let nd = &self.nd;
        let gamma = nd.fpa_from_phi(phi)?;
        // One exponential for drag, lift and g-load (all scale with e^(x - eta v)).
        let (drag, lift, g_load) = nd.aero_loads(x, eta_v);
        SkipPoint {
            tau,
            range_angle_rad: nd.range_angle_from_tau(tau),
            x,
            phi,
            eta_v,
            radius_m: nd.radius_from_x(x),
            speed_m_s: nd.speed_from_eta_v(eta_v),
            flight_path_angle_rad: gamma,
            heat_flux_w_m2: nd.heat_flux_w_m2(x, eta_v),
            drag_acc_m_s2: drag,
            lift_acc_m_s2: lift,
            g_load,
        }
        .check()
    }

    /// `(x, phi_a, leg)` of the closed form at `tau` in `[0, tau_exit]`.
    #[inline(always)]
    fn depth_at_tau(&self, tau: S) -> (S, S, Leg) {
        let (x, phi_a) = if tau == self.q.tau_exit {
            (S::ZERO, self.q.phi_a(tau))
        } else if tau == S::ZERO {
            (S::ZERO, self.nd.c.c)
        } else {
            let (x, phi_a) = self.q.x_phi_a(tau);
            (x.max(S::ZERO), phi_a)
        };
        let leg = if tau <= self.q.tau_bottom {
            Leg::Descending
        } else {
            Leg::Ascending
        };
        (x, phi_a, leg)
    }

    /// Log heat flux and log g-load (up to constants) at `tau`: `x/2 - (m/2) eta v` and
    /// `x - eta v` (see [`SkipSolution::peaks`]); no dimensional point is built.
    #[inline(always)]
    fn log_loads(&self, tau: S) -> Result<LoadSample<S>, VinhError> {
        let (x, phi_a, leg) = self.depth_at_tau(tau);
        let (phi, eta_v, _) = self.phi_eta_v(tau, x, phi_a, leg)?;
        let m2: S = k(super::nondim::CHAPMAN_SPEED_EXPONENT / 2.0);
        Ok(LoadSample {
            heat: x.half() - m2 * eta_v,
            load: x - eta_v,
            state: (x, phi, eta_v),
        })
    }

    /// State at non-dimensional range angle `tau` in `[0, tau_exit]`.
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::OutsideSkip`] outside `[0, tau_exit]`, and the
    /// point errors ([`VinhError::BeyondDeepestPoint`], [`VinhError::SpeedExpansionInvalid`],
    /// [`VinhError::FlightPathAngleOutOfDomain`], [`VinhError::NonFiniteResult`]).
    #[inline(always)]
    pub fn point_at_tau(&self, tau: S) -> Result<SkipPoint<S>, VinhError> {
        if !tau.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if tau < S::ZERO || tau > self.q.tau_exit {
            return Err(VinhError::OutsideSkip);
        }
        let (x, phi_a, leg) = self.depth_at_tau(tau);
        self.point(tau, x, phi_a, leg)
    }

    /// State at range angle `theta` \[rad\] from the reference point.
    ///
    /// # Errors
    /// As [`SkipSolution::point_at_tau`].
    pub fn point_at_range_angle(&self, range_angle_rad: S) -> Result<SkipPoint<S>, VinhError> {
        if !range_angle_rad.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        self.point_at_tau(range_angle_rad * self.nd.c.sqrt_s)
    }

    /// State at depth `x` in `[0, x1]` on `leg`.
    ///
    /// # Errors
    /// [`VinhError::BeyondDeepestPoint`] for `x > x1` (where `phi` would be complex),
    /// [`VinhError::OutsideSkip`] for `x < 0`, and the point errors.
    pub fn point_at_depth(&self, x: S, leg: Leg) -> Result<SkipPoint<S>, VinhError> {
        if !x.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if x > self.q.x1 {
            return Err(VinhError::BeyondDeepestPoint);
        }
        if x < S::ZERO {
            return Err(VinhError::OutsideSkip);
        }
        let (tau, phi_a) = self.q.at_depth(x, leg);
        self.point(tau.clamp(S::ZERO, self.q.tau_exit), x, phi_a, leg)
    }

    /// State at the deepest point (`tau_bottom`, `x = x1`).
    ///
    /// # Errors
    /// The point errors.
    pub fn deepest_point(&self) -> Result<SkipPoint<S>, VinhError> {
        self.point(self.q.tau_bottom, self.q.x1, S::ZERO, Leg::Descending)
    }

    /// Raw second-order `phi^2` of eq. 3.50 at `tau` in `[0, tau_exit]` (before the sign and the
    /// tolerance of the deepest point are applied); a diagnostic of the fit consistency.
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::OutsideSkip`], [`VinhError::NonFiniteResult`].
    pub fn phi_squared_at_tau(&self, tau: S) -> Result<S, VinhError> {
        if !tau.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if tau < S::ZERO || tau > self.q.tau_exit {
            return Err(VinhError::OutsideSkip);
        }
        let x = self.q.x(tau).max(S::ZERO);
        finite(Self::terms_raw(&self.nd, &self.q, tau, x, self.q.phi_a(tau)).phi2)
    }

    /// Exit state, where `x` returns to 0 (the reference radius) on the ascending leg.
    #[must_use]
    pub fn exit(&self) -> SkipPoint<S> {
        self.exit
    }

    /// Second-order deepest depth `x1` \[-\].
    #[must_use]
    pub fn x1(&self) -> S {
        self.q.x1
    }

    /// First-order deepest depth `x1` (root of eq. 3.39) \[-\].
    #[must_use]
    pub fn x1_first_order(&self) -> S {
        self.x1_first
    }

    /// Whether Vinh's low-L/D remedy (freezing `x = x1f` in `2 eta alpha I`) decided the
    /// second-order root.
    #[must_use]
    pub fn low_ld_remedy_used(&self) -> bool {
        self.remedy_used
    }

    /// `(a1, a2, a3)` of the quadratic fit at `x1` (eq. 3.45-3.47).
    #[must_use]
    pub fn fit_coefficients(&self) -> (S, S, S) {
        (self.q.a1, self.q.a2, self.q.a3)
    }

    /// Non-dimensional range angle of the deepest point \[-\].
    #[must_use]
    pub fn tau_bottom(&self) -> S {
        self.q.tau_bottom
    }

    /// Non-dimensional range angle of the exit \[-\].
    #[must_use]
    pub fn tau_exit(&self) -> S {
        self.q.tau_exit
    }

    /// The set-up this solution was built from.
    #[must_use]
    pub fn nondim(&self) -> &NonDim<S> {
        &self.nd
    }

    /// Peak Chapman heat flux and peak g-load over the skip: `(heat-flux peak, g-load peak)`.
    ///
    /// Both log-loads (`x/2 - (m/2) eta v`, `x - eta v`: no exponentials, no dimensional point)
    /// are sampled on one shared grid of [`PEAK_SCAN_INTERVALS`] intervals over the skip, from
    /// the three nodes around the deepest point (the middle node) outwards: a node is added
    /// while the best sample of either load is at an edge of the sampled window, so the window
    /// ends with each best sample between two lower ones (or at an end of the skip), which is
    /// the best node of the whole grid whenever the samples rise to one peak and fall after it.
    /// (Both peaks lie near the deepest point: heat flux on the descending leg, g-load next to
    /// the bottom; typically 3-4 nodes.) Each maximum is then refined by successive parabolic
    /// interpolation from its node and the two neighbours (`vinh::num::parabolic_max`) until
    /// the parabola predicts less than a few ulp of gain; the dimensional point is built from
    /// the state of the best sample (no recomputation).
    ///
    /// Why not a root of the analytic derivative: the closed-form `phi` changes sign at the
    /// deepest point while eq. 3.50's `phi^2` is not exactly zero there, so `v` (eq. 3.54) and
    /// the loads jump at `tau_bottom`, and `dphi/dtau = (dphi^2/dtau)/(2 phi)` swings through
    /// large values next to it; the derivative then has spurious sign changes near the bottom,
    /// where the g-load peak lies (measured during development: peaks 0.4 % low).
    ///
    /// Cost: 3 to `PEAK_SCAN_INTERVALS + 1` log-load evaluations, two parabolic searches
    /// (typically 2-3 evaluations each in `f32`) and two points; at an end of the skip Brent's
    /// search from that end.
    ///
    /// # Errors
    /// The point errors.
    pub fn peaks(&self) -> Result<(SkipPoint<S>, SkipPoint<S>), VinhError> {
        const N: usize = PEAK_SCAN_INTERVALS as usize;
        let te = self.q.tau_exit;
        // Grid step te/8 (a power of two: every node, the middle tau_bottom included, is exact);
        // nodes from an integer in `S` arithmetic (no f64 conversion: soft float on an M4F).
        let step = te / S::from_u32(PEAK_SCAN_INTERVALS);
        let tau_at = |i: usize| -> S {
            match u32::try_from(i) {
                Ok(j) if j < PEAK_SCAN_INTERVALS => step * S::from_u32(j),
                _ => te,
            }
        };
        let mut grid: [Option<LoadSample<S>>; N + 1] = [None; N + 1];
        let (mut lo, mut hi) = (N / 2 - 1, N / 2 + 1);
        for i in lo..=hi {
            if let Some(g) = grid.get_mut(i) {
                *g = Some(self.log_loads(tau_at(i))?);
            }
        }
        let best = |grid: &[Option<LoadSample<S>>], heat: bool| -> Option<(usize, LoadSample<S>)> {
            let mut out: Option<(usize, LoadSample<S>)> = None;
            for (i, g) in grid.iter().enumerate() {
                if let Some(s) = g {
                    let v = if heat { s.heat } else { s.load };
                    let better = out.is_none_or(|(_, b)| v > if heat { b.heat } else { b.load });
                    if better {
                        out = Some((i, *s));
                    }
                }
            }
            out
        };
        // Widen the window while a best sample sits on an inner edge (at most N + 1 nodes).
        loop {
            let (Some((ih, _)), Some((il, _))) = (best(&grid, true), best(&grid, false)) else {
                return Err(VinhError::NonFiniteResult);
            };
            let next = if (ih == lo || il == lo) && lo > 0 {
                lo -= 1;
                lo
            } else if (ih == hi || il == hi) && hi < N {
                hi += 1;
                hi
            } else {
                break;
            };
            if let Some(g) = grid.get_mut(next) {
                *g = Some(self.log_loads(tau_at(next))?);
            }
        }
        // Value tolerance of the refinement: a few ulp of the log-load (the peak value, not its
        // location, is wanted), at least EPSILON.
        let tol_f = |v: S| k::<S>(4.0) * S::EPSILON * v.abs().max(S::ONE);
        let refine = |heat: bool| -> Result<SkipPoint<S>, VinhError> {
            let value = |s: &LoadSample<S>| if heat { s.heat } else { s.load };
            let Some((i, s)) = best(&grid, heat) else {
                return Err(VinhError::NonFiniteResult);
            };
            let eval = |t: S| -> Result<(S, (S, S, S)), VinhError> {
                let s = self.log_loads(t)?;
                Ok((value(&s), s.state))
            };
            let at = |j: usize| {
                grid.get(j)
                    .copied()
                    .flatten()
                    .map(|s| (tau_at(j), value(&s)))
            };
            let left = i.checked_sub(1).and_then(at);
            let right = at(i + 1);
            match (left, right) {
                (Some(l), Some(r)) => {
                    let (t, _, (x, phi, eta_v)) = parabolic_max(
                        eval,
                        l,
                        (tau_at(i), value(&s), s.state),
                        r,
                        tol_f(value(&s)),
                    )?;
                    self.point_from(t, x, phi, eta_v)
                }
                // The best sample is an end of the skip: Brent from it on its interval.
                _ => {
                    let (a, b) = if i == 0 {
                        (S::ZERO, tau_at(1))
                    } else {
                        (tau_at(N - 1), te)
                    };
                    let (t, _) = brent_max(
                        |t| eval(t).map(|(v, _)| v),
                        a,
                        b,
                        tau_at(i),
                        value(&s),
                        S::EPSILON * te,
                    )?;
                    self.point_at_tau(t.clamp(S::ZERO, te))
                }
            }
        };
        Ok((refine(true)?, refine(false)?))
    }

    /// Peak Chapman heat flux over the skip (see [`SkipSolution::peaks`]).
    ///
    /// # Errors
    /// The point errors.
    pub fn peak_heat_flux(&self) -> Result<SkipPoint<S>, VinhError> {
        self.peaks().map(|(h, _)| h)
    }

    /// Peak g-load over the skip (see [`SkipSolution::peaks`]).
    ///
    /// # Errors
    /// The point errors.
    pub fn peak_g_load(&self) -> Result<SkipPoint<S>, VinhError> {
        self.peaks().map(|(_, l)| l)
    }

    /// Peak heat flux by a dense scan (48 intervals) and a golden-section search (62
    /// evaluations): the reference the derivative-based [`SkipSolution::peaks`] is tested
    /// against, and its fall-back.
    ///
    /// # Errors
    /// The point errors.
    pub fn peak_heat_flux_dense(&self) -> Result<SkipPoint<S>, VinhError> {
        let m2: S = k(super::nondim::CHAPMAN_SPEED_EXPONENT / 2.0);
        let (tau, _) = maximize(
            |t| {
                let p = self.point_at_tau(t)?;
                Ok(p.x.half() - m2 * p.eta_v)
            },
            S::ZERO,
            self.q.tau_exit,
        )?;
        self.point_at_tau(tau)
    }

    /// Peak g-load by a dense scan and golden-section search (see
    /// [`SkipSolution::peak_heat_flux_dense`]).
    ///
    /// # Errors
    /// The point errors.
    pub fn peak_g_load_dense(&self) -> Result<SkipPoint<S>, VinhError> {
        let (tau, _) = maximize(
            |t| {
                let p = self.point_at_tau(t)?;
                Ok(p.x - p.eta_v)
            },
            S::ZERO,
            self.q.tau_exit,
        )?;
        self.point_at_tau(tau)
    }
}
