//! Atmospheric glide, second order (thesis sec. 3.5.2; Vinh, Kim & Greenwood 1993), with the
//! ERRATA corrections.
//!
//! Independent variable `u = V^2 / (g_E r_E)` (`alpha u = exp(-eta v)`), decreasing along the
//! glide. With `s = r_E / H_s` (Vinh's `beta r_E`), the vertical lift-to-drag ratio
//! `E = 2 E* lambda cos(sigma) / (1 + lambda^2)` (ERRATA: the actual L/D, not `E*`) and
//! `k1 = B lambda cos(sigma)`:
//!
//! * first order (equilibrium glide, `phi' = 0`): `y0 = (1 - u)/(k1 u)` (3.66),
//!   `phi0 = 2 (1 - u) / (E sqrt(s) [2/s + u (1 - u)])` (3.68);
//! * second order: `y1 = y0 (1 + A Bx)/(1 + Bx)` (3.69) with `w = 2/(s u (1 - u))`,
//!   `A = w/(1 + w)`, `Bx = 2 w (1 - (1 - w) u) / (E^2 (1 + w)^2)` (3.70-3.72; `Bx` is the
//!   auxiliary `B` of eq. 3.72, ERRATA); `phi1` from the defining relation eq. 3.64,
//!   `eta (1 + lambda^2) u / phi = eta k / y - 1/y'`, evaluated with `y1` and its analytic
//!   derivative `y1'` (eq. 3.73/3.74 is its closed form; the printed eq. 3.74 is compared with
//!   this in the tests, see docs/validation/vinh-numerical.md);
//! * range angle (3.77, ERRATA layout):
//!   `theta = (E/2) { ln[(1-u)/(1-u_E)] + (2/s) ln[u_E (1-u) / ((1-u_E) u)] +
//!   (2/s) \[1/(1-u_E) - 1/(1-u)\] }`;
//! * imposed entry (3.78/3.79, ERRATA sign): `u_E = 1/(1 + k1)`,
//!   `sin(gamma_E) = -2 k1 (1 + k1) / (E [2 (1 + k1)^2 + s k1])`.
//!
//! The glide starts at the reference radius with the imposed speed and flight-path angle; the
//! method does not accept another entry state (thesis sec. 8.1.1).
//!
//! # Domain of validity
//! * `E > 0`, `k1 > 0` (lift up): [`VinhError::GlideNoLift`].
//! * `1 - u_E >= MIN_ONE_MINUS_U_E`: near circular speed the range-angle step
//!   `d theta / d u ~ E/(s (1 - u_E)^2)` blows up and the numerical solution skips instead of
//!   gliding (thesis sec. 8.1.6, HORUS-2B): [`VinhError::GlideNearCircular`].
//! * `u` in `(0, u_E]` with the second-order altitude above the surface:
//!   [`VinhError::GlideSpeedOutOfDomain`].
//! * Measured accuracy of the final range angle against the numerical solution in the same
//!   (simplified) environment: docs/validation/vinh-numerical.md (thesis claim, fig. 8.5: <= 3 % below 110 km).

use super::error::VinhError;
use super::nondim::{
    CHAPMAN_SPEED_EXPONENT, EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams,
    k1_min,
};
use super::num::{brent, finite, k, maximize};
use crate::scalar::Real;

/// Smallest accepted `1 - u_E` (glide entry speed ratio to circular, `u_E = 1/(1 + k1)`).
///
/// Chosen from the measured validation (docs/validation/vinh-numerical.md; measured with the limit lowered): the final
/// range-angle error against the numerical glide grows as `1 - u_E` shrinks (about 2 % at
/// 0.012, 3 % at 0.006, 5-9 % at 0.0015-0.003, 15-50 % at 1e-4 to 4e-4); HORUS-2B at 122 km has
/// `1 - u_E ~ 1e-4` (thesis sec. 8.1.6). 0.01 keeps the measured error below 2.1 %.
pub const MIN_ONE_MINUS_U_E: f64 = 0.01;

/// One point of the glide.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GlidePoint<S> {
    /// `u = V^2 / (g_E r_E)` \[-\].
    pub u: S,
    /// Speed \[m/s\].
    pub speed_m_s: S,
    /// Range angle from the glide start \[rad\] (eq. 3.77).
    pub range_angle_rad: S,
    /// Second-order density ratio `y1 = rho / rho_E` \[-\].
    pub density_ratio: S,
    /// Distance from the planet centre, `r_E - H_s ln(y1)` \[m\].
    pub radius_m: S,
    /// Second-order `phi1` \[-\].
    pub phi: S,
    /// Flight-path angle `asin(-phi1 / sqrt(s))` \[rad\].
    pub flight_path_angle_rad: S,
    /// Chapman heat flux \[W/m^2\].
    pub heat_flux_w_m2: S,
    /// Drag acceleration \[m/s^2\].
    pub drag_acc_m_s2: S,
    /// Total-lift acceleration \[m/s^2\].
    pub lift_acc_m_s2: S,
    /// g-load \[-\].
    pub g_load: S,
}

impl<S: Real> GlidePoint<S> {
    fn check(self) -> Result<Self, VinhError> {
        let all = [
            self.u,
            self.speed_m_s,
            self.range_angle_rad,
            self.density_ratio,
            self.radius_m,
            self.phi,
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

/// Second-order glide from the imposed entry state at a reference radius.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GlideSolution<S> {
    nd: NonDim<S>,
    u_e: S,
    e: S,
    k1: S,
    s: S,
}

/// `y1`, `y1'` (derivative with respect to `u`) at `u`.
struct Y1<S> {
    y: S,
    dy: S,
}

impl<S: Real> GlideSolution<S> {
    /// Glide starting at `reference_radius_m` \[m\] with lift setting `lift`; the entry speed and
    /// flight-path angle are imposed by eq. 3.78/3.79.
    ///
    /// # Errors
    /// Set-up errors of [`NonDim::new`], [`VinhError::GlideNoLift`],
    /// [`VinhError::VerticalLiftTooSmall`], [`VinhError::GlideNearCircular`],
    /// [`VinhError::FlightPathAngleOutOfDomain`], [`VinhError::NonFiniteResult`].
    pub fn new(
        planet: &Planet<S>,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
        lift: &LiftControl<S>,
        reference_radius_m: S,
    ) -> Result<Self, VinhError> {
        planet.validate()?;
        if !reference_radius_m.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if reference_radius_m <= planet.radius_m {
            return Err(VinhError::UnphysicalState);
        }
        // Set-up at circular speed first: k1, E and s do not depend on the speed.
        let vc = finite((planet.mu_m3_s2 / reference_radius_m).sqrt_raw())?;
        let probe = EntryState {
            radius_m: reference_radius_m,
            speed_m_s: vc.min(k(super::nondim::MAX_ENTRY_SPEED_M_S)),
            flight_path_angle_rad: S::ZERO,
        };
        let nd0 = NonDim::new(planet, atmosphere, vehicle, lift, &probe)?;
        let c = nd0.c;
        if !(c.k1 > S::ZERO && c.e_vertical > S::ZERO) {
            return Err(VinhError::GlideNoLift);
        }
        if c.k1 < k1_min::<S>() {
            return Err(VinhError::VerticalLiftTooSmall);
        }
        let u_e = S::ONE / (S::ONE + c.k1);
        if S::ONE - u_e < k(MIN_ONE_MINUS_U_E) {
            return Err(VinhError::GlideNearCircular);
        }
        let two: S = k(2.0);
        let opk = S::ONE + c.k1;
        let sin_g = -two * c.k1 * opk / (c.e_vertical * (two * opk * opk + c.s * c.k1));
        if !(sin_g.abs() < S::ONE) {
            return Err(VinhError::FlightPathAngleOutOfDomain);
        }
        let entry = EntryState {
            radius_m: reference_radius_m,
            speed_m_s: finite((u_e * nd0.g_e * reference_radius_m).sqrt_raw())?,
            flight_path_angle_rad: finite(sin_g.asin())?,
        };
        let nd = NonDim::new(planet, atmosphere, vehicle, lift, &entry)?;
        Ok(Self {
            nd,
            u_e,
            e: c.e_vertical,
            k1: c.k1,
            s: c.s,
        })
    }

    /// Entry state imposed by the method (eq. 3.78/3.79).
    #[must_use]
    pub fn imposed_entry(&self) -> EntryState<S> {
        self.nd.entry
    }

    /// `u_E = 1/(1 + k1)` \[-\].
    #[must_use]
    pub fn u_entry(&self) -> S {
        self.u_e
    }

    /// The set-up at the imposed entry state.
    #[must_use]
    pub fn nondim(&self) -> &NonDim<S> {
        &self.nd
    }

    /// `u` \[-\] of speed `speed_m_s` \[m/s\].
    #[must_use]
    pub fn u_from_speed(&self, speed_m_s: S) -> S {
        speed_m_s * speed_m_s / (self.nd.g_e * self.nd.entry.radius_m)
    }

    fn y1(&self, u: S) -> Y1<S> {
        let one = S::ONE;
        let two: S = k(2.0);
        let (k1, s, e2) = (self.k1, self.s, self.e * self.e);
        let omu = one - u;
        let y0 = omu / (k1 * u);
        let dy0 = -one / (k1 * u * u);
        let w = two / (s * u * omu);
        let dw = -w * (one - two * u) / (u * omu);
        let opw = one + w;
        let a = w / opw;
        let da = dw / (opw * opw);
        let n = one - (one - w) * u;
        let dn = -one + w + dw * u;
        let bx = two * w * n / (e2 * opw * opw);
        let dbx =
            two / e2 * ((dw * n + w * dn) / (opw * opw) - two * w * n * dw / (opw * opw * opw));
        let f = (one + a * bx) / (one + bx);
        let df =
            ((da * bx + a * dbx) * (one + bx) - (one + a * bx) * dbx) / ((one + bx) * (one + bx));
        Y1 {
            y: y0 * f,
            dy: dy0 * f + y0 * df,
        }
    }

    /// First-order density ratio `y0 = (1 - u)/(k1 u)` (eq. 3.66).
    #[must_use]
    pub fn y0(&self, u: S) -> S {
        (S::ONE - u) / (self.k1 * u)
    }

    /// Range angle \[rad\] from the glide start to `u` (eq. 3.77, ERRATA layout).
    fn theta(&self, u: S) -> S {
        let one = S::ONE;
        let two: S = k(2.0);
        let ue = self.u_e;
        let t1 = ((one - u) / (one - ue)).ln();
        let t2 = (ue * (one - u) / ((one - ue) * u)).ln();
        let t3 = one / (one - ue) - one / (one - u);
        self.e.half() * (t1 + two / self.s * (t2 + t3))
    }

    /// Glide point at `u` in `(0, u_E]`.
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::GlideSpeedOutOfDomain`],
    /// [`VinhError::FlightPathAngleOutOfDomain`], [`VinhError::NonFiniteResult`].
    pub fn point_at_u(&self, u: S) -> Result<GlidePoint<S>, VinhError> {
        if !u.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if !(u > S::ZERO) || u > self.u_e {
            return Err(VinhError::GlideSpeedOutOfDomain);
        }
        let nd = &self.nd;
        let c = nd.c;
        let y = self.y1(u);
        if !(y.y > S::ZERO && y.dy < S::ZERO) {
            return Err(VinhError::GlideSpeedOutOfDomain);
        }
        let x = finite(y.y.ln())?;
        if x > nd.surface_x() {
            return Err(VinhError::GlideSpeedOutOfDomain);
        }
        // Eq. 3.64: eta (1 + lambda^2) u / phi = eta k / y - 1/y', with
        // eta (1 + lambda^2) = 2 k1 / (E sqrt(s)) and eta k = 2/s.
        let two: S = k(2.0);
        let den = two / (c.s * y.y) - S::ONE / y.dy;
        let phi = finite(two * self.k1 * u / (self.e * c.sqrt_s) / den)?;
        let eta_v = finite((self.u_e / u).ln())?;
        GlidePoint {
            u,
            speed_m_s: nd.speed_from_eta_v(eta_v),
            range_angle_rad: finite(self.theta(u))?,
            density_ratio: y.y,
            radius_m: nd.radius_from_x(x),
            phi,
            flight_path_angle_rad: nd.fpa_from_phi(phi)?,
            heat_flux_w_m2: nd.heat_flux_w_m2(x, eta_v),
            drag_acc_m_s2: nd.drag_acc_m_s2(x, eta_v),
            lift_acc_m_s2: nd.lift_acc_m_s2(x, eta_v),
            g_load: nd.g_load(x, eta_v),
        }
        .check()
    }

    /// Glide point at speed `speed_m_s` \[m/s\] (at most the imposed entry speed).
    ///
    /// # Errors
    /// As [`GlideSolution::point_at_u`].
    pub fn point_at_speed(&self, speed_m_s: S) -> Result<GlidePoint<S>, VinhError> {
        if !speed_m_s.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        let u = if speed_m_s >= self.nd.entry.speed_m_s {
            if speed_m_s > self.nd.entry.speed_m_s {
                return Err(VinhError::GlideSpeedOutOfDomain);
            }
            self.u_e
        } else {
            self.u_from_speed(speed_m_s)
        };
        self.point_at_u(u)
    }

    /// Maximum of a log-score between the final speed and the glide start, located from its
    /// analytic derivative `deriv(u, y1, y1')` (the closed form's own derivative): Brent's
    /// method on the derivative when it falls through zero on `[u_f, u_E]`, else the better
    /// end; a derivative rising through zero (a minimum inside) falls back to the dense scan
    /// and golden-section search of `score`.
    fn peak_by<D: Fn(S, S, S) -> S, F: Fn(&GlidePoint<S>) -> S>(
        &self,
        final_speed_m_s: S,
        deriv: D,
        score: F,
    ) -> Result<GlidePoint<S>, VinhError> {
        let end = self.point_at_speed(final_speed_m_s)?;
        let (lo, hi) = (end.u, self.u_e);
        let d = |u: S| -> Result<S, VinhError> {
            let y = self.y1(u);
            finite(deriv(u, y.y, y.dy))
        };
        if !(hi > lo) {
            return Ok(end);
        }
        let (d_lo, d_hi) = (d(lo)?, d(hi)?);
        if d_lo > S::ZERO && d_hi < S::ZERO {
            let tol = S::EPSILON.sqrt_raw() * (hi - lo);
            let u = brent(d, lo, hi, d_lo, d_hi, tol)?;
            return self.point_at_u(u.clamp(lo, hi));
        }
        if d_lo < S::ZERO && d_hi > S::ZERO {
            let (u, _) = maximize(|u| self.point_at_u(u).map(|p| score(&p)), lo, hi)?;
            return self.point_at_u(u);
        }
        let start = self.point_at_u(hi)?;
        Ok(if score(&start) > score(&end) {
            start
        } else {
            end
        })
    }

    /// Peak Chapman heat flux between the glide start and `final_speed_m_s` \[m/s\].
    ///
    /// # Errors
    /// As [`GlideSolution::point_at_u`] for the final speed.
    pub fn peak_heat_flux(&self, final_speed_m_s: S) -> Result<GlidePoint<S>, VinhError> {
        let m2: S = k(CHAPMAN_SPEED_EXPONENT / 2.0);
        let ue = self.u_e;
        self.peak_by(
            final_speed_m_s,
            |u, y, dy| dy / (y + y) + m2 / u,
            |p| p.density_ratio.ln().half() - m2 * (ue / p.u).ln(),
        )
    }

    /// Peak g-load between the glide start and `final_speed_m_s` \[m/s\].
    ///
    /// # Errors
    /// As [`GlideSolution::point_at_u`] for the final speed.
    pub fn peak_g_load(&self, final_speed_m_s: S) -> Result<GlidePoint<S>, VinhError> {
        let ue = self.u_e;
        self.peak_by(
            final_speed_m_s,
            |u, y, dy| dy / y + S::ONE / u,
            |p| p.density_ratio.ln() + p.u.ln() - ue.ln(),
        )
    }
}
