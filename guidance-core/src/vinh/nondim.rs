//! Non-dimensional set-up of Vinh, Kim & Greenwood (1993), thesis eq. 3.16-3.28 and 3.32.
//!
//! From a vehicle ([`VehicleParams`]), a lift setting ([`LiftControl`]), an exponential
//! atmosphere ([`ExpAtmosphere`]), a central-gravity planet ([`Planet`]) and a reference
//! ("entry") state ([`EntryState`]) it builds the constants
//!
//! | symbol | definition | eq. |
//! |---|---|---|
//! | `E*` | `1 / (2 sqrt(K C_D0))`, maximum L/D | 3.18 |
//! | `B` | `rho_E S r_E / (2 m) sqrt(C_D0 / K)` | 3.20 |
//! | `lambda` | `C_L / sqrt(C_D0 / K)` (total lift; 1 at maximum L/D) | 3.21 |
//! | `s` | `r_E / H_s` (Vinh's `beta r_E`, ERRATA) | |
//! | `eta` | `B / (E* sqrt(s)) = rho_E S C_D0 sqrt(H_s r_E) / m` | 3.25 |
//! | `k` | `2 E* / (sqrt(s) B) = 2 / (eta s)` | 3.27 |
//! | `alpha` | `g_E r_E / V_E^2` | 3.28 |
//! | `k1` | `B lambda cos(sigma)` (vertical lift; `cos(sigma) = 1` in the thesis) | 3.32 |
//! | `c` | `phi_E = -sqrt(s) sin(gamma_E)` | |
//!
//! and the variables `tau = sqrt(s) theta` (3.22), `x = ln y = (r_E - r)/H_s` (3.23, 3.40 per
//! ERRATA), `v = ln(V_E^2/V^2)/eta` (3.24; positive and growing as the vehicle slows, ERRATA),
//! `phi = -sqrt(s) sin(gamma)` (3.26). Gravity is central, `g = g_E (r_E/r)^2`; the atmosphere is
//! `rho = rho_0 exp(-(r - r_0)/H_s)`; the planet does not rotate.
//!
//! Bank angle: the thesis (planar, `sigma = 0`) uses one `lambda`. Here drag and the g-load use
//! the total `lambda` (`C_D = C_D0 (1 + lambda^2)`), and the `phi` equation uses the vertical part
//! `k1 = B lambda cos(sigma)`: this is the exact planar projection of a banked flight, which the
//! re-planner uses. With `cos(sigma) = 1` it is the thesis' set-up.
//!
//! Domain of validity: finite positive vehicle constants, `C_D0 > 0` (else `E*` and `B` are not
//! real: [`VinhError::NonPositiveZeroLiftDrag`]), reference radius above the surface, speed in
//! `(0, MAX_ENTRY_SPEED_M_S]`, `|gamma_E| < 90 deg`.

use super::error::VinhError;
use super::num::{asin_signed, finite, k, sin_cos};
use crate::scalar::Real;

/// Chapman heat-flux constant `c*` (thesis eq. 2.2) \[W/m^2 with the nose radius in m\].
pub const CHAPMAN_C_STAR: f64 = 1.1097e8;
/// Chapman reference density `rho_0` \[kg/m^3\].
pub const CHAPMAN_RHO0_KG_M3: f64 = 1.225;
/// Chapman reference circular speed `V_c` \[m/s\].
pub const CHAPMAN_VC_M_S: f64 = 7905.4;
/// Chapman speed exponent `m` \[-\].
pub const CHAPMAN_SPEED_EXPONENT: f64 = 3.15;
/// Standard gravity used to express g-loads, eq. 2.1 \[m/s^2\].
pub const G0_M_S2: f64 = 9.806_65;
/// Highest accepted reference speed \[m/s\]: the top of the validated range (docs/validation/vinh-numerical.md).
/// Thesis sec. 8.2.1 reports complex numbers for entry speeds above 11000 m/s. With the ERRATA
/// corrections the skip closed form stays real and accurate up to this limit (measured); what
/// does fail above about 11 km/s is the ballistic arc: the local escape speed at 122 km is
/// 11.07 km/s, and an exit above it makes the conic hyperbolic, reported as
/// [`VinhError::EscapeTrajectory`] by [`crate::vinh::ballistic`].
pub const MAX_ENTRY_SPEED_M_S: f64 = 14_000.0;

/// Central-gravity, spherical, non-rotating planet.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Planet<S> {
    /// Gravitational parameter `mu` \[m^3/s^2\].
    pub mu_m3_s2: S,
    /// Surface radius `R` \[m\] (altitude zero).
    pub radius_m: S,
}

impl<S: Real> Planet<S> {
    /// Earth as in the thesis: `mu = 3.986004418e14 m^3/s^2`, `R = 6378137 m`.
    #[must_use]
    pub fn earth() -> Self {
        Self {
            mu_m3_s2: k(crate::energy::EARTH_MU_M3_S2),
            radius_m: k(crate::energy::EARTH_RADIUS_M),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), VinhError> {
        if !(self.mu_m3_s2.is_finite() && self.radius_m.is_finite()) {
            return Err(VinhError::NonFiniteInput);
        }
        if self.mu_m3_s2 <= S::ZERO || self.radius_m <= S::ZERO {
            return Err(VinhError::InvalidPlanet);
        }
        Ok(())
    }
}

/// Isothermal exponential atmosphere `rho(r) = rho0 exp(-(r - ref_radius)/H_s)` (thesis eq. 3.89).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ExpAtmosphere<S> {
    /// Density at `ref_radius_m` \[kg/m^3\].
    pub rho0_kg_m3: S,
    /// Scale height `H_s` \[m\].
    pub scale_height_m: S,
    /// Radius where the density is `rho0_kg_m3` \[m\] (normally the planet radius).
    pub ref_radius_m: S,
}

impl<S: Real> ExpAtmosphere<S> {
    /// Earth, `rho0 = 1.225 kg/m^3` at `R = 6378137 m`, `H_s = 7200 m`. The thesis does not
    /// state its `H_s`; 7200 m is a common Earth value (and reproduces, with the SRM data, the
    /// thesis' sec. 9.2 glide entry at 100 km: see docs/validation/vinh-numerical.md).
    #[must_use]
    pub fn earth() -> Self {
        Self {
            rho0_kg_m3: k(1.225),
            scale_height_m: k(7200.0),
            ref_radius_m: k(crate::energy::EARTH_RADIUS_M),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), VinhError> {
        if !(self.rho0_kg_m3.is_finite()
            && self.scale_height_m.is_finite()
            && self.ref_radius_m.is_finite())
        {
            return Err(VinhError::NonFiniteInput);
        }
        if self.rho0_kg_m3 <= S::ZERO || self.scale_height_m <= S::ZERO {
            return Err(VinhError::InvalidAtmosphere);
        }
        Ok(())
    }

    /// Density \[kg/m^3\] at radius `radius_m` \[m\] without validation (the one definition of
    /// the model's density; [`ExpAtmosphere::density_kg_m3`] checks it).
    #[inline]
    pub(crate) fn density_unchecked(&self, radius_m: S) -> S {
        self.rho0_kg_m3 * (-(radius_m - self.ref_radius_m) / self.scale_height_m).exp()
    }

    /// Density \[kg/m^3\] at radius `radius_m` \[m\].
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`] for a non-finite radius, [`VinhError::InvalidAtmosphere`]
    /// for an invalid model, [`VinhError::NonFiniteResult`] if the density under- or overflows.
    pub fn density_kg_m3(&self, radius_m: S) -> Result<S, VinhError> {
        self.validate()?;
        if !radius_m.is_finite() {
            return Err(VinhError::NonFiniteInput);
        }
        let rho = self.density_unchecked(radius_m);
        if rho > S::ZERO {
            finite(rho)
        } else {
            Err(VinhError::NonFiniteResult)
        }
    }
}

/// Vehicle constants with a parabolic drag polar `C_D = C_D0 + K C_L^2` (eq. 3.19).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VehicleParams<S> {
    /// Mass `m` \[kg\].
    pub mass_kg: S,
    /// Aerodynamic reference area `S` \[m^2\].
    pub reference_area_m2: S,
    /// Zero-lift drag coefficient `C_D0` \[-\].
    pub cd0: S,
    /// Induced-drag factor `K` \[-\].
    pub k_polar: S,
    /// Nose radius `R_N` for the Chapman heat flux \[m\].
    pub nose_radius_m: S,
}

impl<S: Real> VehicleParams<S> {
    pub(crate) fn validate(&self) -> Result<(), VinhError> {
        let all = [
            self.mass_kg,
            self.reference_area_m2,
            self.cd0,
            self.k_polar,
            self.nose_radius_m,
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(VinhError::NonFiniteInput);
        }
        if self.cd0 <= S::ZERO {
            return Err(VinhError::NonPositiveZeroLiftDrag);
        }
        if self.mass_kg <= S::ZERO
            || self.reference_area_m2 <= S::ZERO
            || self.k_polar <= S::ZERO
            || self.nose_radius_m <= S::ZERO
        {
            return Err(VinhError::InvalidVehicle);
        }
        Ok(())
    }

    /// Lift coefficient of maximum L/D, `C_L* = sqrt(C_D0 / K)` \[-\].
    ///
    /// # Errors
    /// As for validation: [`VinhError::NonFiniteInput`], [`VinhError::NonPositiveZeroLiftDrag`],
    /// [`VinhError::InvalidVehicle`].
    #[inline]
    pub fn cl_max_ld(&self) -> Result<S, VinhError> {
        self.validate()?;
        finite((self.cd0 / self.k_polar).sqrt_fast())
    }

    /// Maximum lift-to-drag ratio `E* = 1 / (2 sqrt(K C_D0))` \[-\] (eq. 3.18).
    ///
    /// # Errors
    /// As for [`VehicleParams::cl_max_ld`].
    pub fn max_lift_to_drag(&self) -> Result<S, VinhError> {
        self.validate()?;
        finite(S::ONE / (k::<S>(2.0) * (self.k_polar * self.cd0).sqrt_fast()))
    }
}

/// Lift setting: `lambda = C_L / sqrt(C_D0/K)` (eq. 3.21) and the vertical fraction
/// `cos(sigma)` of the lift (bank angle `sigma`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LiftControl<S> {
    /// Lift parameter `lambda` \[-\], `>= 0` (1 at maximum L/D, 0 ballistic).
    pub lambda: S,
    /// Vertical fraction of the lift `cos(sigma)` \[-\], in `[-1, 1]`.
    pub vertical_fraction: S,
}

impl<S: Real> LiftControl<S> {
    /// Maximum L/D, lift vector up (`lambda = 1`, `sigma = 0`).
    #[must_use]
    pub fn max_ld_lift_up() -> Self {
        Self {
            lambda: S::ONE,
            vertical_fraction: S::ONE,
        }
    }

    /// From a total lift coefficient `c_l` \[-\] and bank angle `bank_rad` \[rad\].
    ///
    /// # Errors
    /// [`VinhError::NonFiniteInput`] and the vehicle's validation errors.
    pub fn from_lift_coefficient(
        vehicle: &VehicleParams<S>,
        c_l: S,
        bank_rad: S,
    ) -> Result<Self, VinhError> {
        if !(c_l.is_finite() && bank_rad.is_finite()) {
            return Err(VinhError::NonFiniteInput);
        }
        let cl_star = vehicle.cl_max_ld()?;
        let out = Self {
            lambda: finite(c_l / cl_star)?,
            vertical_fraction: bank_rad.cos(),
        };
        out.validate()?;
        Ok(out)
    }

    pub(crate) fn validate(&self) -> Result<(), VinhError> {
        if !(self.lambda.is_finite() && self.vertical_fraction.is_finite()) {
            return Err(VinhError::NonFiniteInput);
        }
        if self.lambda < S::ZERO || self.vertical_fraction.abs() > S::ONE {
            return Err(VinhError::InvalidLiftControl);
        }
        Ok(())
    }
}

/// Planar state at the reference point (atmospheric entry, or any point taken as reference).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EntryState<S> {
    /// Distance from the planet centre `r_E` \[m\].
    pub radius_m: S,
    /// Planet-relative speed `V_E` \[m/s\].
    pub speed_m_s: S,
    /// Flight-path angle `gamma_E` \[rad\], positive above the horizontal.
    pub flight_path_angle_rad: S,
}

impl<S: Real> EntryState<S> {
    #[inline]
    pub(crate) fn validate(&self, planet: &Planet<S>) -> Result<(), VinhError> {
        if !(self.radius_m.is_finite()
            && self.speed_m_s.is_finite()
            && self.flight_path_angle_rad.is_finite())
        {
            return Err(VinhError::NonFiniteInput);
        }
        if self.radius_m <= planet.radius_m || self.speed_m_s <= S::ZERO {
            return Err(VinhError::UnphysicalState);
        }
        if self.speed_m_s > k(MAX_ENTRY_SPEED_M_S) {
            return Err(VinhError::EntrySpeedTooHigh);
        }
        if self.flight_path_angle_rad.abs() >= S::PI.half() {
            return Err(VinhError::FlightPathAngleOutOfDomain);
        }
        Ok(())
    }
}

/// The non-dimensional constants of one set-up (see the module table).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Constants<S> {
    /// `E*`, maximum lift-to-drag ratio \[-\] (eq. 3.18).
    pub e_star: S,
    /// `B` \[-\] (eq. 3.20).
    pub b: S,
    /// `lambda` (total lift) \[-\] (eq. 3.21).
    pub lambda: S,
    /// `k1 = B lambda cos(sigma)` \[-\] (eq. 3.32).
    pub k1: S,
    /// `eta` \[-\] (eq. 3.25).
    pub eta: S,
    /// `k = 2 / (eta s)` \[-\] (eq. 3.27).
    pub k: S,
    /// `alpha = g_E r_E / V_E^2` \[-\] (eq. 3.28).
    pub alpha: S,
    /// `s = r_E / H_s` \[-\].
    pub s: S,
    /// `sqrt(s)` \[-\].
    pub sqrt_s: S,
    /// `c = phi_E = -sqrt(s) sin(gamma_E)` \[-\].
    pub c: S,
    /// Vertical lift-to-drag ratio `E = 2 E* lambda cos(sigma) / (1 + lambda^2)` \[-\] (ERRATA:
    /// the `E` of eq. 3.68-3.79 is the actual L/D, not `E*`).
    pub e_vertical: S,
}

/// Non-dimensional set-up: constants plus the dimensional data needed to convert back.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NonDim<S> {
    pub(crate) c: Constants<S>,
    pub(crate) entry: EntryState<S>,
    pub(crate) planet: Planet<S>,
    pub(crate) atmosphere: ExpAtmosphere<S>,
    pub(crate) vehicle: VehicleParams<S>,
    pub(crate) lift: LiftControl<S>,
    pub(crate) scale_height_m: S,
    pub(crate) rho_e: S,
    pub(crate) g_e: S,
    /// Chapman heat flux at the reference state \[W/m^2\].
    pub(crate) q_e: S,
    /// Drag acceleration at the reference state \[m/s^2\].
    pub(crate) drag_e: S,
    /// Total-lift acceleration at the reference state \[m/s^2\].
    pub(crate) lift_e: S,
    /// g-load at the reference state `sqrt(drag_e^2 + lift_e^2)/g0` \[-\].
    pub(crate) g_load_e: S,
}

/// Chapman heat flux \[W/m^2\] (thesis eq. 2.2) for nose radius `nose_radius_m` \[m\], density
/// `rho` \[kg/m^3\] and speed `v` \[m/s\]: `c*/sqrt(R_N) sqrt(rho/rho_0) (V/V_c)^3.15`. The one
/// definition of the predictor model's heat flux (closed forms and numerical predictor).
#[inline]
#[must_use]
pub(crate) fn chapman_heat_flux_w_m2<S: Real>(nose_radius_m: S, rho: S, v: S) -> S {
    k::<S>(CHAPMAN_C_STAR) / nose_radius_m.sqrt_fast()
        * (rho / k(CHAPMAN_RHO0_KG_M3)).sqrt_fast()
        * (v / k(CHAPMAN_VC_M_S)).powf(k(CHAPMAN_SPEED_EXPONENT))
}

/// Drag and total-lift accelerations `(D/m, L/m)` \[m/s^2\] of `vehicle` at lift parameter
/// `lambda` (`sqrt_cd0_k = sqrt(C_D0/K)`, `one_l2 = 1 + lambda^2`, passed in so callers that
/// have them do not recompute them: soft float on the Cortex-M3), density `rho` \[kg/m^3\] and
/// speed `v` \[m/s\]: `D/m = rho V^2 S/(2m) C_D0 (1 + lambda^2)`,
/// `L/m = rho V^2 S/(2m) sqrt(C_D0/K) lambda`. The one definition of the predictor model's
/// aerodynamics (closed forms and numerical predictor).
#[inline]
#[must_use]
pub(crate) fn aero_accelerations_m_s2<S: Real>(
    vehicle: &VehicleParams<S>,
    sqrt_cd0_k: S,
    lambda: S,
    one_l2: S,
    rho: S,
    v: S,
) -> (S, S) {
    let qdyn_s_m = rho * v * v * vehicle.reference_area_m2 / (k::<S>(2.0) * vehicle.mass_kg);
    (
        qdyn_s_m * vehicle.cd0 * one_l2,
        qdyn_s_m * sqrt_cd0_k * lambda,
    )
}

/// g-load `sqrt(D^2 + L^2)/(m g0)` \[-\] (eq. 2.1) from the drag and lift accelerations
/// \[m/s^2\].
#[inline]
#[must_use]
pub(crate) fn g_load_of<S: Real>(drag_m_s2: S, lift_m_s2: S) -> S {
    (drag_m_s2 * drag_m_s2 + lift_m_s2 * lift_m_s2).sqrt_fast() / k(G0_M_S2)
}

/// Smallest accepted `|k1|` for float type `S`: `64 * EPSILON` (1.4e-14 in `f64`, 7.6e-6 in
/// `f32`). The closed forms divide by `k1`; below this the cancellations in `(c - phi)/k1` lose
/// all significant digits.
pub(crate) fn k1_min<S: Real>() -> S {
    k::<S>(64.0) * S::EPSILON
}

impl<S: Real> NonDim<S> {
    /// Build the set-up at reference state `entry`.
    ///
    /// # Errors
    /// Validation errors of every input ([`VinhError::NonFiniteInput`],
    /// [`VinhError::InvalidPlanet`], [`VinhError::InvalidAtmosphere`],
    /// [`VinhError::InvalidVehicle`], [`VinhError::NonPositiveZeroLiftDrag`],
    /// [`VinhError::InvalidLiftControl`], [`VinhError::UnphysicalState`],
    /// [`VinhError::EntrySpeedTooHigh`], [`VinhError::FlightPathAngleOutOfDomain`]) and
    /// [`VinhError::NonFiniteResult`] if a constant under- or overflows.
    pub fn new(
        planet: &Planet<S>,
        atmosphere: &ExpAtmosphere<S>,
        vehicle: &VehicleParams<S>,
        lift: &LiftControl<S>,
        entry: &EntryState<S>,
    ) -> Result<Self, VinhError> {
        planet.validate()?;
        atmosphere.validate()?;
        vehicle.validate()?;
        lift.validate()?;
        entry.validate(planet)?;
        let two: S = k(2.0);
        let r_e = entry.radius_m;
        let v_e = entry.speed_m_s;
        let h_s = atmosphere.scale_height_m;
        let rho_e = atmosphere.density_kg_m3(r_e)?;
        let g_e = finite(planet.mu_m3_s2 / (r_e * r_e))?;
        let sqrt_cd0_k = finite((vehicle.cd0 / vehicle.k_polar).sqrt_fast())?;
        let e_star = finite(S::ONE / (two * (vehicle.k_polar * vehicle.cd0).sqrt_fast()))?;
        let b =
            finite(rho_e * vehicle.reference_area_m2 * r_e / (two * vehicle.mass_kg) * sqrt_cd0_k)?;
        let s = finite(r_e / h_s)?;
        let sqrt_s = finite(s.sqrt_fast())?;
        let eta = finite(b / (e_star * sqrt_s))?;
        let kk = finite(two / (eta * s))?;
        let alpha = finite(g_e * r_e / (v_e * v_e))?;
        let lambda = lift.lambda;
        let k1 = finite(b * lambda * lift.vertical_fraction)?;
        let c = finite(-sqrt_s * sin_cos(entry.flight_path_angle_rad).0)?;
        let one_l2 = S::ONE + lambda * lambda;
        let e_vertical = finite(two * e_star * lambda * lift.vertical_fraction / one_l2)?;
        let q_e = finite(chapman_heat_flux_w_m2(vehicle.nose_radius_m, rho_e, v_e))?;
        let (drag_e, lift_e) =
            aero_accelerations_m_s2(vehicle, sqrt_cd0_k, lambda, one_l2, rho_e, v_e);
        let drag_e = finite(drag_e)?;
        let lift_e = finite(lift_e)?;
        let g_load_e = finite(g_load_of(drag_e, lift_e))?;
        Ok(Self {
            c: Constants {
                e_star,
                b,
                lambda,
                k1,
                eta,
                k: kk,
                alpha,
                s,
                sqrt_s,
                c,
                e_vertical,
            },
            entry: *entry,
            planet: *planet,
            atmosphere: *atmosphere,
            vehicle: *vehicle,
            lift: *lift,
            scale_height_m: h_s,
            rho_e,
            g_e,
            q_e,
            drag_e,
            lift_e,
            g_load_e,
        })
    }

    /// The non-dimensional constants.
    #[must_use]
    pub fn constants(&self) -> Constants<S> {
        self.c
    }

    /// The reference (entry) state.
    #[must_use]
    pub fn entry(&self) -> EntryState<S> {
        self.entry
    }

    /// Density at the reference radius `rho_E` \[kg/m^3\].
    #[must_use]
    pub fn entry_density_kg_m3(&self) -> S {
        self.rho_e
    }

    /// Gravity at the reference radius `g_E = mu / r_E^2` \[m/s^2\].
    #[must_use]
    pub fn entry_gravity_m_s2(&self) -> S {
        self.g_e
    }

    /// `x` of the planet surface, `(r_E - R)/H_s` \[-\]: the deepest admissible `x`.
    #[must_use]
    pub fn surface_x(&self) -> S {
        (self.entry.radius_m - self.planet.radius_m) / self.scale_height_m
    }

    /// Radius \[m\] from `x`: `r = r_E - H_s x` (eq. 3.59).
    #[must_use]
    pub fn radius_from_x(&self, x: S) -> S {
        self.entry.radius_m - self.scale_height_m * x
    }

    /// `x = (r_E - r)/H_s` \[-\] from radius \[m\].
    #[must_use]
    pub fn x_from_radius(&self, radius_m: S) -> S {
        (self.entry.radius_m - radius_m) / self.scale_height_m
    }

    /// Speed \[m/s\] from `eta v`: `V = V_E exp(-eta v / 2)` (eq. 3.60).
    #[must_use]
    pub fn speed_from_eta_v(&self, eta_v: S) -> S {
        self.entry.speed_m_s * (-eta_v.half()).exp()
    }

    /// Flight-path angle \[rad\] from `phi`: `gamma = asin(-phi / sqrt(s))` (eq. 3.61).
    ///
    /// # Errors
    /// [`VinhError::FlightPathAngleOutOfDomain`] if `|phi| >= sqrt(s)`.
    pub fn fpa_from_phi(&self, phi: S) -> Result<S, VinhError> {
        let sn = -phi / self.c.sqrt_s;
        if !sn.is_finite() {
            return Err(VinhError::NonFiniteResult);
        }
        if sn.abs() >= S::ONE {
            return Err(VinhError::FlightPathAngleOutOfDomain);
        }
        Ok(asin_signed(sn))
    }

    /// Range angle `theta = tau / sqrt(s)` \[rad\] (eq. 3.22).
    #[must_use]
    pub fn range_angle_from_tau(&self, tau: S) -> S {
        tau / self.c.sqrt_s
    }

    /// Chapman heat flux \[W/m^2\] at depth `x` and `eta v` (eq. 3.58 with `b = 1/2`, `M = 3.15`).
    #[must_use]
    pub fn heat_flux_w_m2(&self, x: S, eta_v: S) -> S {
        self.q_e * (x.half() - k::<S>(CHAPMAN_SPEED_EXPONENT / 2.0) * eta_v).exp()
    }

    /// Drag acceleration \[m/s^2\] at `x`, `eta v` (eq. 3.56 times `g_E`).
    #[must_use]
    pub fn drag_acc_m_s2(&self, x: S, eta_v: S) -> S {
        self.drag_e * (x - eta_v).exp()
    }

    /// Lift acceleration \[m/s^2\] of the total lift at `x`, `eta v` (eq. 3.57 times `g_E`).
    #[must_use]
    pub fn lift_acc_m_s2(&self, x: S, eta_v: S) -> S {
        self.lift_e * (x - eta_v).exp()
    }

    /// g-load `sqrt(L^2 + D^2)/(m g0)` \[-\] at `x`, `eta v` (eq. 2.1).
    #[must_use]
    pub fn g_load(&self, x: S, eta_v: S) -> S {
        self.g_load_e * (x - eta_v).exp()
    }

    /// Drag and total-lift accelerations \[m/s^2\] and g-load \[-\] at `x`, `eta v`: the
    /// values of [`NonDim::drag_acc_m_s2`], [`NonDim::lift_acc_m_s2`] and [`NonDim::g_load`]
    /// from one exponential.
    #[must_use]
    pub(crate) fn aero_loads(&self, x: S, eta_v: S) -> (S, S, S) {
        let e = (x - eta_v).exp();
        (self.drag_e * e, self.lift_e * e, self.g_load_e * e)
    }

    /// Vehicle of this set-up.
    #[must_use]
    pub fn vehicle(&self) -> VehicleParams<S> {
        self.vehicle
    }

    /// Planet of this set-up.
    #[must_use]
    pub fn planet(&self) -> Planet<S> {
        self.planet
    }

    /// Atmosphere of this set-up.
    #[must_use]
    pub fn atmosphere(&self) -> ExpAtmosphere<S> {
        self.atmosphere
    }

    /// Lift setting of this set-up.
    #[must_use]
    pub fn lift(&self) -> LiftControl<S> {
        self.lift
    }

    /// Scale height `H_s` \[m\].
    #[must_use]
    pub fn scale_height_m(&self) -> S {
        self.scale_height_m
    }
}
