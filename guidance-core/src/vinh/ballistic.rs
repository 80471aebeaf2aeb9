//! Ballistic (Kepler) arc between atmospheric exit and re-entry (thesis sec. 3.5.3, corrected).
//!
//! Eq. 3.81 of the thesis, `r/R = S0^2 cos^2(gamma0) / (1 + sqrt(1 - S0^2 cos^2(gamma0)(2 - S0^2))
//! cos(theta))` with `S0 = V0 / V_c0`, is the conic `r = p / (1 + e cos(nu))` with the true
//! anomaly `nu` written as if it were zero at the exit point. It is not (ERRATA): the exit lies at
//! true anomaly `nu0` with
//!
//! * `p / r0 = S0^2 cos^2(gamma0)`, `e cos(nu0) = p/r0 - 1`,
//!   `e sin(nu0) = sqrt(p/mu) V0 sin(gamma0)`, `e = |(e cos nu0, e sin nu0)|`,
//!
//! so the arc is `r(theta) = p / (1 + e cos(nu0 + theta))` with `theta` the range angle from the
//! exit (planar, non-rotating planet: range angle = change of true anomaly). Re-entry at radius
//! `r1` is at `nu1 = 2 pi - acos((p/r1 - 1)/e)` (descending branch), so the range angle is
//! `nu1 - nu0` (`2 pi - 2 nu0` when `r1 = r0`). The flight time follows from Kepler's equation
//! `M = E - e sin(E)` between the two eccentric anomalies; the state at a given time solves
//! Kepler's equation by safeguarded Newton iteration (bounded).
//!
//! # Domain of validity
//! * Exit flight-path angle `0 < gamma0 < 90 deg` (leaving; vertical flight is a degenerate
//!   conic): [`VinhError::NotAscending`], [`VinhError::FlightPathAngleOutOfDomain`].
//! * Elliptic conic `e < 1`: [`VinhError::EscapeTrajectory`] (this is the failure above about
//!   11 km/s that the thesis reports as complex numbers: the escape speed at 122 km is 11.07 km/s).
//! * Re-entry radius between periapsis and apoapsis: [`VinhError::NoReentry`].
//! * Exact for two-body motion (validated against Cartesian propagation to integration
//!   tolerance, docs/validation/vinh-numerical.md); atmosphere, oblateness and planet rotation are ignored.

use super::error::VinhError;
use super::nondim::{EntryState, Planet};
use super::num::{finite, k, sin_cos};
use crate::scalar::Real;

/// Newton/bisection steps for Kepler's equation: the bracket `[M - e, M + e]` halves at least
/// every other step, so 120 steps reach full `f64` precision; Newton converges in < 10 steps for
/// `e < 0.99`.
pub const KEPLER_MAX_STEPS: u32 = 120;

/// A point on the ballistic arc.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ArcPoint<S> {
    /// Time since the exit point \[s\].
    pub time_s: S,
    /// Range angle from the exit point \[rad\].
    pub range_angle_rad: S,
    /// Distance from the planet centre \[m\].
    pub radius_m: S,
    /// Speed \[m/s\].
    pub speed_m_s: S,
    /// Flight-path angle \[rad\].
    pub flight_path_angle_rad: S,
}

/// Elliptic arc from an exit state to re-entry at a given radius.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BallisticArc<S> {
    mu: S,
    p: S,
    e: S,
    a: S,
    nu0: S,
    nu1: S,
    mean0: S,
    mean1: S,
    n: S,
    reentry: ArcPoint<S>,
}

/// Eccentric anomaly in `[0, 2 pi)` for true anomaly `nu` in `[0, 2 pi)`.
fn ecc_from_true<S: Real>(e: S, nu: S) -> S {
    let (sn, cn) = sin_cos(nu);
    let s = (S::ONE - e * e).sqrt() * sn;
    let c = e + cn;
    let mut ea = s.atan2(c);
    if ea < S::ZERO {
        ea = ea + S::PI + S::PI;
    }
    ea
}

impl<S: Real> BallisticArc<S> {
    /// Arc from `exit` (radius \[m\], speed \[m/s\], flight-path angle \[rad\] > 0) to the descending
    /// crossing of `reentry_radius_m` \[m\].
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::InvalidPlanet`], [`VinhError::UnphysicalState`]
    /// (radius not above the surface, speed not positive), [`VinhError::NotAscending`],
    /// [`VinhError::FlightPathAngleOutOfDomain`] (`gamma0 >= 90 deg`, degenerate conic),
    /// [`VinhError::EscapeTrajectory`], [`VinhError::NoReentry`], [`VinhError::NonFiniteResult`].
    pub fn new(
        planet: &Planet<S>,
        exit: &EntryState<S>,
        reentry_radius_m: S,
    ) -> Result<Self, VinhError> {
        planet.validate()?;
        if !(exit.radius_m.is_finite()
            && exit.speed_m_s.is_finite()
            && exit.flight_path_angle_rad.is_finite()
            && reentry_radius_m.is_finite())
        {
            return Err(VinhError::NonFiniteInput);
        }
        if exit.radius_m <= planet.radius_m
            || reentry_radius_m <= planet.radius_m
            || exit.speed_m_s <= S::ZERO
        {
            return Err(VinhError::UnphysicalState);
        }
        let g0 = exit.flight_path_angle_rad;
        if !(g0 > S::ZERO) {
            return Err(VinhError::NotAscending);
        }
        // Vertical flight is a degenerate (rectilinear, e = 1) conic with zero range.
        if g0 >= S::PI.half() {
            return Err(VinhError::FlightPathAngleOutOfDomain);
        }
        let mu = planet.mu_m3_s2;
        let r0 = exit.radius_m;
        let v0 = exit.speed_m_s;
        // S0^2 = V0^2 r0 / mu; p/r0 = S0^2 cos^2(gamma0).
        let s02 = finite(v0 * v0 * r0 / mu)?;
        let (sg, cg) = sin_cos(g0);
        let p_r0 = s02 * cg * cg;
        let p = finite(p_r0 * r0)?;
        let ec = p_r0 - S::ONE;
        // sqrt(p/mu) V0 sin(gamma0) = sqrt(p_r0 * S0^2) sin(gamma0) = S0^2 cos sin.
        let es = s02 * cg * sg;
        let e = finite((ec * ec + es * es).sqrt())?;
        if e >= S::ONE {
            return Err(VinhError::EscapeTrajectory);
        }
        if !(e > S::ZERO) {
            return Err(VinhError::NotAscending);
        }
        let nu0 = es.atan2(ec);
        let c1 = (p / reentry_radius_m - S::ONE) / e;
        // |c1| > 1: the conic never reaches r1 (apoapsis below it, or periapsis above it).
        if !(c1.abs() <= S::ONE) {
            return Err(VinhError::NoReentry);
        }
        let nu1 = S::PI + S::PI - c1.acos();
        let a = finite(p / (S::ONE - e * e))?;
        let n = finite((mu / (a * a * a)).sqrt_raw())?;
        let ecc0 = ecc_from_true(e, nu0);
        let ecc1 = ecc_from_true(e, nu1);
        let mean0 = ecc0 - e * sin_cos(ecc0).0;
        let mean1 = ecc1 - e * sin_cos(ecc1).0;
        let t1 = finite((mean1 - mean0) / n)?;
        // A flight-path angle too small to resolve at apoapsis gives a zero-length arc.
        if !(nu1 > nu0 && t1 > S::ZERO) {
            return Err(VinhError::NotAscending);
        }
        let mut arc = Self {
            mu,
            p,
            e,
            a,
            nu0,
            nu1,
            mean0,
            mean1,
            n,
            reentry: ArcPoint {
                time_s: t1,
                range_angle_rad: S::ZERO,
                radius_m: reentry_radius_m,
                speed_m_s: S::ZERO,
                flight_path_angle_rad: S::ZERO,
            },
        };
        arc.reentry = arc.point_at_true_anomaly(nu1, t1)?;
        arc.reentry.radius_m = reentry_radius_m;
        Ok(arc)
    }

    fn point_at_true_anomaly(&self, nu: S, time_s: S) -> Result<ArcPoint<S>, VinhError> {
        let e = self.e;
        let (sn, cn) = sin_cos(nu);
        let den = S::ONE + e * cn;
        let r = finite(self.p / den)?;
        let v2 = self.mu * (k::<S>(2.0) / r - S::ONE / self.a);
        let speed = finite(v2.sqrt())?;
        let fpa = (e * sn).atan2(den);
        Ok(ArcPoint {
            time_s: finite(time_s)?,
            range_angle_rad: finite(nu - self.nu0)?,
            radius_m: r,
            speed_m_s: speed,
            flight_path_angle_rad: finite(fpa)?,
        })
    }

    /// Range angle from exit to re-entry \[rad\].
    #[must_use]
    pub fn range_angle_rad(&self) -> S {
        self.nu1 - self.nu0
    }

    /// Flight time from exit to re-entry \[s\].
    #[must_use]
    pub fn flight_time_s(&self) -> S {
        self.reentry.time_s
    }

    /// State at re-entry.
    #[must_use]
    pub fn reentry(&self) -> ArcPoint<S> {
        self.reentry
    }

    /// Eccentricity `e` \[-\].
    #[must_use]
    pub fn eccentricity(&self) -> S {
        self.e
    }

    /// Semi-latus rectum `p` \[m\].
    #[must_use]
    pub fn semi_latus_rectum_m(&self) -> S {
        self.p
    }

    /// True anomaly at the exit point `nu0` \[rad\] (not zero in general, ERRATA on eq. 3.81).
    #[must_use]
    pub fn exit_true_anomaly_rad(&self) -> S {
        self.nu0
    }

    /// Apoapsis radius `p / (1 - e)` \[m\].
    #[must_use]
    pub fn apoapsis_radius_m(&self) -> S {
        self.p / (S::ONE - self.e)
    }

    /// Radius \[m\] at range angle `theta` \[rad\] from the exit: `p / (1 + e cos(nu0 + theta))`
    /// (eq. 3.81 with the exit phase).
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::OutsideArc`] outside `[0, nu1 - nu0]`.
    pub fn radius_at_range_angle(&self, range_angle_rad: S) -> Result<S, VinhError> {
        if !range_angle_rad.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if range_angle_rad < S::ZERO || range_angle_rad > self.range_angle_rad() {
            return Err(VinhError::OutsideArc);
        }
        finite(self.p / (S::ONE + self.e * (self.nu0 + range_angle_rad).cos()))
    }

    /// State at time `time_s` \[s\] after the exit, by Kepler's equation.
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`], [`VinhError::OutsideArc`] outside `[0, flight time]`,
    /// [`VinhError::NonFiniteResult`].
    pub fn state_at_time(&self, time_s: S) -> Result<ArcPoint<S>, VinhError> {
        if !time_s.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        if time_s < S::ZERO || time_s > self.reentry.time_s {
            return Err(VinhError::OutsideArc);
        }
        let e = self.e;
        let m = (self.mean0 + self.n * time_s).clamp(self.mean0, self.mean1);
        // Solve E - e sin E = m on the bracket [m - e, m + e] (E - m = e sin E).
        let mut lo = m - e;
        let mut hi = m + e;
        let mut ea = if e < k(0.8) { m + e * m.sin() } else { m };
        ea = ea.clamp(lo, hi);
        let tol = k::<S>(4.0) * S::EPSILON * (S::ONE + m.abs());
        let mut i = 0;
        while i < KEPLER_MAX_STEPS {
            let f = ea - e * ea.sin() - m;
            if f == S::ZERO {
                break;
            }
            if f > S::ZERO {
                hi = ea;
            } else {
                lo = ea;
            }
            let d = S::ONE - e * ea.cos();
            let newton = ea - f / d;
            let next = if newton > lo && newton < hi {
                newton
            } else {
                (lo + hi).half()
            };
            if (next - ea).abs() <= tol || hi - lo <= tol {
                ea = next;
                break;
            }
            ea = next;
            i += 1;
        }
        // True anomaly continuous with E (both increase together).
        let half = ea.half();
        let nu_half = ((S::ONE + e).sqrt() * half.sin()).atan2((S::ONE - e).sqrt() * half.cos());
        let mut nu = nu_half + nu_half;
        // Unwrap E to the same revolution as nu: nu - E is small compared with pi for the same revolution.
        let two_pi = S::PI + S::PI;
        if nu - ea > S::PI {
            nu = nu - two_pi;
        } else if ea - nu > S::PI {
            nu = nu + two_pi;
        }
        self.point_at_true_anomaly(nu, time_s)
    }
}
