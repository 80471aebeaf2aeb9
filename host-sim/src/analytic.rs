//! Analytical simulator: trajectories from the Vinh, Kim & Greenwood second-order closed forms of
//! `guidance_core::vinh` (thesis sec. 3.5), returned in the numerical simulator's own output
//! types ([`SimResult`]: [`Sample`] rows and a [`Summary`]), so [`crate::report`] writes the
//! same trajectory CSV, summary JSON and SVG plots for both.
//!
//! The closed forms are only *called* here (skip: [`SkipSolution`], glide: [`GlideSolution`]);
//! this module converts their planar points into samples:
//!
//! * Placement: the closed forms are planar (range angle `theta` only). The trajectory is laid
//!   on the great circle through the entry position in the entry heading ([`Placement`]), so
//!   latitude, longitude and heading are defined; the planet does not rotate (the closed forms'
//!   assumption).
//! * Time: the closed forms have no time. It is the quadrature `t = integral r / (V cos gamma)
//!   d theta` (from `d theta / dt = V cos gamma / r`, eq. 3.15) by the trapezoidal rule over
//!   the samples; the heat load is the trapezoidal integral of the heat flux over that time.
//! * Peaks: peak heat flux and g-load are the closed forms' own maximisations
//!   ([`SkipSolution::peak_heat_flux`], [`GlideSolution::peak_heat_flux`], ...); their times
//!   are interpolated in range angle. The g-load rate is the largest finite difference between
//!   samples (the closed forms are smooth, so this is a lower bound of a real vehicle's).
//! * Attitude: the samples carry the bank angle; the angle of attack is 0 (the closed forms,
//!   and the constant-`C_L` polar vehicle of the comparison runs, are parameterised by `C_L`).
//! * Termination: the glide ends at an altitude or a speed ([`GlideEnd`]) and is reported as
//!   [`TerminationReason::Altitude`] or [`TerminationReason::Mach`] (the speed of sound of the
//!   isothermal exponential atmosphere is constant, so a speed is a Mach number). The skip ends
//!   where it climbs back through its entry radius; `sim::TerminationReason` has no
//!   "atmosphere exit" reason, so it is reported as [`TerminationReason::Altitude`] with one
//!   exit recorded in [`Summary::exits`] and [`Summary::interface_crossings_s`].
//!
//! # Vehicle model ([`AnalyticVehicle`])
//! The closed forms need a parabolic drag polar `C_D = C_D0 + K C_L^2`:
//! * vehicles with a polar ([`crate::vehicle::Aerodynamics::drag_polar`], e.g. HORUS-2B, thesis
//!   table 8.1) use it at one representative Mach number (default [`DEFAULT_POLAR_MACH`],
//!   hypersonic), and are steered by the lift coefficient (`lambda = C_L / C_L*`) and bank;
//! * trim-only vehicles (the SRM capsule, which has no polar) get the polar on which their trim
//!   point is the maximum-L/D point: `C_D0 = C_D,trim / 2`, `K = C_D0 / C_L,trim^2`, so
//!   `lambda = 1`, `E* = (L/D)_trim` and the polar reproduces the trim `C_D` exactly. They are
//!   steered by bank only: vertical lift coefficient `C_L,trim cos(sigma)`. For the SRM this
//!   gives C_D0 = 0.2816, K = 0.1722 (E* = 2.27); guidance-core's Vinh validation uses the polar
//!   back-derived from thesis sec. 9.2 instead (C_D0 = 0.2576, K = 0.1879, same E*), on which
//!   the trim point C_L = 1.2786 lies within 0.3 % in C_D. Both fly the same trim lift and drag.
//!
//! # Atmosphere
//! The closed forms assume an isothermal exponential atmosphere. [`fit_us76`] gives the one
//! through the US76 densities at two altitudes of the flight band (default
//! [`DEFAULT_FIT_ALTITUDES_M`]); the same [`ExponentialAtmosphere`] drives the simplified
//! numerical environment in [`crate::compare`], so that comparison isolates the closed forms'
//! own approximations.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::vinh::{
    self, EntryState, ExpAtmosphere, GlideSolution, LiftControl, NonDim, SkipSolution,
    VehicleParams, VinhError,
};
use nalgebra::Vector3;

use crate::dynamics::{Attitude, FlightConditions, SphericalState};
use crate::env::{
    Atmosphere, ExponentialAtmosphere, Planet, Us76, atmosphere::ExponentialAtmosphereError,
};
use crate::sim::{
    Peak, Sample, SampleKind, SimResult, Summary, TerminationReason, Violations, great_circle,
    violation,
};
use crate::vehicle::{DragPolar, PolarAerodynamics, Vehicle, VehicleLimits};

/// Mach number at which a tabulated drag polar is taken by default (hypersonic; HORUS-2B's
/// table 8.1 polar at Mach 20).
pub const DEFAULT_POLAR_MACH: f64 = 20.0;
/// Default altitudes [m] through which the exponential atmosphere is fitted to US76 (the band
/// of a capsule glide or skip from 100 km).
pub const DEFAULT_FIT_ALTITUDES_M: (f64, f64) = (50_000.0, 100_000.0);
/// Default number of trajectory samples.
pub const DEFAULT_POINTS: usize = 201;
/// Smallest and largest accepted number of samples.
pub const POINTS_RANGE: (usize, usize) = (3, 100_000);

/// Analytical-simulator failures.
#[derive(Debug, thiserror::Error)]
pub enum AnalyticError {
    /// The vehicle cannot be described by a drag polar.
    #[error("vehicle `{vehicle}`: {reason}")]
    Vehicle {
        /// Vehicle name.
        vehicle: String,
        /// Why.
        reason: String,
    },
    /// A setting is out of range.
    #[error("invalid setting `{field}` = {value}: {reason}")]
    Setting {
        /// Setting name (with unit).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is required.
        reason: &'static str,
    },
    /// The closed form is outside its domain of validity (typed, from guidance-core).
    #[error("{phase} closed form out of domain: {error}")]
    Domain {
        /// `"skip"` or `"glide"`.
        phase: &'static str,
        /// The closed form's error.
        error: VinhError,
    },
    /// The exponential atmosphere could not be built.
    #[error(transparent)]
    Atmosphere(#[from] ExponentialAtmosphereError),
}

fn setting(field: &'static str, value: f64, reason: &'static str) -> AnalyticError {
    AnalyticError::Setting {
        field,
        value,
        reason,
    }
}

/// A vehicle as the closed forms see it: mass properties and a parabolic drag polar.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyticVehicle {
    /// Name (for reports).
    pub name: String,
    /// Mass [kg].
    pub mass_kg: f64,
    /// Reference area [m^2].
    pub reference_area_m2: f64,
    /// Nose radius [m].
    pub nose_radius_m: f64,
    /// Drag polar `C_D = C_D0 + K C_L^2`.
    pub polar: DragPolar,
    /// For trim-only vehicles: the fixed total lift coefficient (then steered by bank only).
    pub trim_cl: Option<f64>,
    /// Operational limits (for the violations of the summary).
    pub limits: VehicleLimits,
}

/// Constant lift setting: total lift coefficient and bank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiftSetting {
    /// Total lift coefficient `C_L` [-].
    pub cl: f64,
    /// Bank angle `sigma` [rad] (0: lift up).
    pub bank_rad: f64,
}

impl LiftSetting {
    /// Vertical lift coefficient `C_L cos(sigma)` [-].
    #[must_use]
    pub fn vertical_cl(&self) -> f64 {
        self.cl * self.bank_rad.cos()
    }
}

impl AnalyticVehicle {
    /// From a simulator vehicle: its drag polar at Mach `polar_mach`, or for a trim-only vehicle
    /// the polar with the trim point at maximum L/D (module documentation).
    ///
    /// # Errors
    /// [`AnalyticError::Vehicle`] if the vehicle has neither a polar nor fixed trim
    /// coefficients, or they are not finite and positive.
    pub fn from_vehicle(vehicle: &Vehicle, polar_mach: f64) -> Result<Self, AnalyticError> {
        let err = |reason: String| AnalyticError::Vehicle {
            vehicle: vehicle.name.clone(),
            reason,
        };
        if !polar_mach.is_finite() || polar_mach <= 0.0 {
            return Err(setting(
                "polar_mach",
                polar_mach,
                "must be finite and positive",
            ));
        }
        let (polar, trim_cl) = if let Some(p) = vehicle.aero.drag_polar(polar_mach) {
            (p, None)
        } else if !vehicle.aero.controls_alpha() {
            let trim = vehicle.aero.coefficients(polar_mach, 0.0);
            if !(trim.cl.is_finite() && trim.cl > 0.0 && trim.cd.is_finite() && trim.cd > 0.0) {
                return Err(err(format!(
                    "trim coefficients C_L = {}, C_D = {} must be finite and positive",
                    trim.cl, trim.cd
                )));
            }
            let cd0 = trim.cd / 2.0;
            (
                DragPolar {
                    cd0,
                    k: cd0 / (trim.cl * trim.cl),
                },
                Some(trim.cl),
            )
        } else {
            return Err(err(
                "no drag polar (give one in the vehicle file: aero kind `drag_polar`)".into(),
            ));
        };
        if !(polar.cd0.is_finite() && polar.cd0 > 0.0 && polar.k.is_finite() && polar.k > 0.0) {
            return Err(err(format!(
                "drag polar at Mach {polar_mach}: C_D0 = {}, K = {} must be finite and positive",
                polar.cd0, polar.k
            )));
        }
        Ok(Self {
            name: vehicle.name.clone(),
            mass_kg: vehicle.mass_kg,
            reference_area_m2: vehicle.reference_area_m2,
            nose_radius_m: vehicle.nose_radius_m,
            polar,
            trim_cl,
            limits: vehicle.limits,
        })
    }

    /// The closed forms' vehicle constants.
    #[must_use]
    pub fn params(&self) -> VehicleParams<f64> {
        VehicleParams {
            mass_kg: self.mass_kg,
            reference_area_m2: self.reference_area_m2,
            cd0: self.polar.cd0,
            k_polar: self.polar.k,
            nose_radius_m: self.nose_radius_m,
        }
    }

    /// Lift setting giving vertical lift coefficient `cl_vertical` [-]: for trim-only vehicles
    /// the trim `C_L` banked to `acos(cl_vertical / C_L,trim)`, otherwise `C_L = cl_vertical`
    /// with the lift vector up.
    ///
    /// # Errors
    /// [`AnalyticError::Setting`] if `cl_vertical` is not finite, negative, or above the trim
    /// `C_L` of a trim-only vehicle.
    pub fn lift_for_vertical_cl(&self, cl_vertical: f64) -> Result<LiftSetting, AnalyticError> {
        if !(cl_vertical.is_finite() && cl_vertical >= 0.0) {
            return Err(setting(
                "cl_vertical",
                cl_vertical,
                "must be finite and >= 0",
            ));
        }
        match self.trim_cl {
            Some(trim) => {
                if cl_vertical > trim {
                    return Err(setting(
                        "cl_vertical",
                        cl_vertical,
                        "must not exceed the trim lift coefficient of a bank-only vehicle",
                    ));
                }
                Ok(LiftSetting {
                    cl: trim,
                    bank_rad: (cl_vertical / trim).acos(),
                })
            }
            None => Ok(LiftSetting {
                cl: cl_vertical,
                bank_rad: 0.0,
            }),
        }
    }

    /// The closed forms' lift control (`lambda = C_L / C_L*`, vertical fraction `cos(sigma)`).
    ///
    /// # Errors
    /// [`AnalyticError::Domain`] for an invalid setting (negative `C_L`, non-finite values).
    pub fn lift_control(&self, lift: &LiftSetting) -> Result<LiftControl<f64>, AnalyticError> {
        LiftControl::from_lift_coefficient(&self.params(), lift.cl, lift.bank_rad).map_err(
            |error| AnalyticError::Domain {
                phase: "lift setting",
                error,
            },
        )
    }

    /// A simulator vehicle flying this polar at constant `C_L = lift.cl` (Mach and angle of
    /// attack independent): what the closed forms assume, for the numerical comparison runs.
    #[must_use]
    pub fn constant_lift_vehicle(&self, lift: &LiftSetting) -> Vehicle {
        Vehicle {
            name: format!("{} (polar, C_L = {})", self.name, lift.cl),
            mass_kg: self.mass_kg,
            reference_area_m2: self.reference_area_m2,
            nose_radius_m: self.nose_radius_m,
            limits: self.limits,
            aero: Box::new(PolarAerodynamics {
                polar: self.polar,
                cl: vec![lift.cl],
                alpha_min_deg: None,
                alpha_max_deg: None,
            }),
        }
    }
}

/// The exponential atmosphere through the US76 densities at `h1_m` and `h2_m` [m].
///
/// # Errors
/// As [`ExponentialAtmosphere::fitted_to`] (e.g. equal altitudes, non-positive density).
pub fn fit_us76(h1_m: f64, h2_m: f64) -> Result<ExponentialAtmosphere, AnalyticError> {
    Ok(ExponentialAtmosphere::fitted_to(&Us76::new(), h1_m, h2_m)?)
}

/// The closed forms' planet: Earth's `mu` and radius, no rotation.
#[must_use]
pub fn planet() -> Planet {
    Planet::earth_non_rotating()
}

fn vinh_planet(p: &Planet) -> vinh::Planet<f64> {
    vinh::Planet {
        mu_m3_s2: p.mu_m3_s2,
        radius_m: p.radius_m,
    }
}

fn vinh_atmosphere(a: &ExponentialAtmosphere, p: &Planet) -> ExpAtmosphere<f64> {
    ExpAtmosphere {
        rho0_kg_m3: a.rho0_kg_m3(),
        scale_height_m: a.scale_height_m(),
        ref_radius_m: p.radius_m + a.reference_altitude_m(),
    }
}

/// Where the planar trajectory starts on the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Latitude [rad].
    pub latitude_rad: f64,
    /// Longitude [rad].
    pub longitude_rad: f64,
    /// Heading [rad], clockwise from north.
    pub heading_rad: f64,
}

impl Default for Placement {
    /// On the equator at longitude 0, heading east.
    fn default() -> Self {
        Self {
            latitude_rad: 0.0,
            longitude_rad: 0.0,
            heading_rad: std::f64::consts::FRAC_PI_2,
        }
    }
}

impl Placement {
    /// The placement part of a spherical state.
    #[must_use]
    pub fn of(s: &SphericalState) -> Self {
        Self {
            latitude_rad: s.latitude_rad,
            longitude_rad: s.longitude_rad,
            heading_rad: s.heading_rad,
        }
    }

    /// Latitude, longitude and heading [rad] after range angle `theta_rad` along the great
    /// circle.
    fn along(&self, theta_rad: f64) -> (f64, f64, f64) {
        let (sl, cl) = self.latitude_rad.sin_cos();
        let (so, co) = self.longitude_rad.sin_cos();
        let up = Vector3::new(cl * co, cl * so, sl);
        let east = Vector3::new(-so, co, 0.0);
        let north = Vector3::new(-sl * co, -sl * so, cl);
        let (sh, ch) = self.heading_rad.sin_cos();
        let t0 = north * ch + east * sh;
        let (st, ct) = theta_rad.sin_cos();
        let p = up * ct + t0 * st;
        let t = t0 * ct - up * st;
        let lat = p.z.clamp(-1.0, 1.0).asin();
        let lon = p.y.atan2(p.x);
        let (slat, clat) = lat.sin_cos();
        let (slon, clon) = lon.sin_cos();
        let e = Vector3::new(-slon, clon, 0.0);
        let n = Vector3::new(-slat * clon, -slat * slon, clat);
        let mut heading = t.dot(&e).atan2(t.dot(&n));
        if heading < 0.0 {
            heading += std::f64::consts::TAU;
        }
        (lat, lon, heading)
    }
}

/// How a glide ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GlideEnd {
    /// At this altitude [m] (below the glide start).
    Altitude {
        /// Final altitude [m].
        altitude_m: f64,
    },
    /// At this fraction of the imposed entry speed [-], in (0, 1).
    SpeedFraction {
        /// Final speed over entry speed [-].
        fraction: f64,
    },
}

/// Which closed form produced a trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// Atmospheric skip, entry to exit (thesis sec. 3.5.1).
    Skip,
    /// Equilibrium glide (thesis sec. 3.5.2).
    Glide,
}

/// An analytical trajectory.
#[derive(Clone, Debug)]
pub struct AnalyticRun {
    /// Samples and summary, in the numerical simulator's types.
    pub result: SimResult,
    /// Which closed form.
    pub phase: Phase,
    /// Entry state (for the glide: the state imposed by eq. 3.78/3.79).
    pub entry: SphericalState,
    /// Lowest altitude [m] (skip: the closed form's deepest point; glide: the end).
    pub deepest_altitude_m: f64,
    /// Lift setting flown.
    pub lift: LiftSetting,
    /// The exponential atmosphere of the closed forms.
    pub atmosphere: ExponentialAtmosphere,
}

/// One planar point of a closed form.
#[derive(Clone, Copy, Debug)]
struct Planar {
    theta: f64,
    radius: f64,
    speed: f64,
    gamma: f64,
    heat_flux: f64,
    drag_acc: f64,
    lift_acc: f64,
    g_load: f64,
}

impl From<vinh::SkipPoint<f64>> for Planar {
    fn from(p: vinh::SkipPoint<f64>) -> Self {
        Self {
            theta: p.range_angle_rad,
            radius: p.radius_m,
            speed: p.speed_m_s,
            gamma: p.flight_path_angle_rad,
            heat_flux: p.heat_flux_w_m2,
            drag_acc: p.drag_acc_m_s2,
            lift_acc: p.lift_acc_m_s2,
            g_load: p.g_load,
        }
    }
}

impl From<vinh::GlidePoint<f64>> for Planar {
    fn from(p: vinh::GlidePoint<f64>) -> Self {
        Self {
            theta: p.range_angle_rad,
            radius: p.radius_m,
            speed: p.speed_m_s,
            gamma: p.flight_path_angle_rad,
            heat_flux: p.heat_flux_w_m2,
            drag_acc: p.drag_acc_m_s2,
            lift_acc: p.lift_acc_m_s2,
            g_load: p.g_load,
        }
    }
}

fn check_points(points: usize) -> Result<(), AnalyticError> {
    if (POINTS_RANGE.0..=POINTS_RANGE.1).contains(&points) {
        Ok(())
    } else {
        Err(setting(
            "points",
            points as f64,
            "must be within [3, 100000]",
        ))
    }
}

/// Skip from `entry` (planet-relative; descending) to the return to the entry radius, with
/// constant lift `lift`, in the exponential atmosphere `atmosphere`; `points` samples evenly
/// spaced in range angle.
///
/// # Errors
/// [`AnalyticError::Domain`] with the closed form's typed error (e.g.
/// [`VinhError::NoAtmosphericExit`] when the vehicle is captured, [`VinhError::NotDescending`]),
/// [`AnalyticError::Setting`] for a bad sample count.
pub fn skip_trajectory(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    atmosphere: &ExponentialAtmosphere,
    entry: &SphericalState,
    points: usize,
) -> Result<AnalyticRun, AnalyticError> {
    check_points(points)?;
    let dom = |error| AnalyticError::Domain {
        phase: "skip",
        error,
    };
    let planet = planet();
    let nd = NonDim::new(
        &vinh_planet(&planet),
        &vinh_atmosphere(atmosphere, &planet),
        &vehicle.params(),
        &vehicle.lift_control(lift)?,
        &EntryState {
            radius_m: entry.radius_m,
            speed_m_s: entry.speed_m_s,
            flight_path_angle_rad: entry.flight_path_angle_rad,
        },
    )
    .map_err(dom)?;
    let skip = SkipSolution::new(&nd).map_err(dom)?;
    let tau_exit = skip.tau_exit();
    let rows = (0..points)
        .map(|i| {
            let tau = if i + 1 == points {
                tau_exit
            } else {
                tau_exit * i as f64 / (points - 1) as f64
            };
            skip.point_at_tau(tau).map(Planar::from)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(dom)?;
    let peak_q = Planar::from(skip.peak_heat_flux().map_err(dom)?);
    let peak_g = Planar::from(skip.peak_g_load().map_err(dom)?);
    let deepest = skip.deepest_point().map_err(dom)?;
    let ctx = Ctx {
        vehicle,
        lift,
        atmosphere,
        planet,
        placement: Placement::of(entry),
    };
    let mut result = ctx.assemble(&rows, peak_q, peak_g, TerminationReason::Altitude);
    let t_exit = result.summary.flight_time_s;
    result.summary.exits = 1;
    result.summary.interface_crossings_s = vec![(t_exit, SampleKind::Exit)];
    Ok(AnalyticRun {
        result,
        phase: Phase::Skip,
        entry: *entry,
        deepest_altitude_m: deepest.radius_m - planet.radius_m,
        lift: *lift,
        atmosphere: *atmosphere,
    })
}

/// Equilibrium glide starting at `entry_altitude_m` [m] at `placement`, with the entry speed and
/// flight-path angle imposed by the method (eq. 3.78/3.79), constant lift `lift`, to `end`;
/// `points` samples evenly spaced in `u = V^2/(g_E r_E)`.
///
/// # Errors
/// [`AnalyticError::Domain`] with the closed form's typed error (e.g.
/// [`VinhError::GlideNearCircular`], [`VinhError::GlideSpeedOutOfDomain`] when the end is not
/// reached inside the method's domain), [`AnalyticError::Setting`] for a bad end or sample count.
pub fn glide_trajectory(
    vehicle: &AnalyticVehicle,
    lift: &LiftSetting,
    atmosphere: &ExponentialAtmosphere,
    entry_altitude_m: f64,
    placement: &Placement,
    end: GlideEnd,
    points: usize,
) -> Result<AnalyticRun, AnalyticError> {
    check_points(points)?;
    let dom = |error| AnalyticError::Domain {
        phase: "glide",
        error,
    };
    if !entry_altitude_m.is_finite() {
        return Err(setting(
            "entry_altitude_m",
            entry_altitude_m,
            "must be finite",
        ));
    }
    let planet = planet();
    let glide = GlideSolution::new(
        &vinh_planet(&planet),
        &vinh_atmosphere(atmosphere, &planet),
        &vehicle.params(),
        &vehicle.lift_control(lift)?,
        planet.radius_m + entry_altitude_m,
    )
    .map_err(dom)?;
    let e = glide.imposed_entry();
    let u_e = glide.u_entry();
    let u_end = match end {
        GlideEnd::SpeedFraction { fraction } => {
            if !(fraction.is_finite() && fraction > 0.0 && fraction < 1.0) {
                return Err(setting(
                    "end.speed_fraction",
                    fraction,
                    "must be within (0, 1)",
                ));
            }
            glide.u_from_speed(e.speed_m_s * fraction)
        }
        GlideEnd::Altitude { altitude_m } => {
            if !(altitude_m.is_finite() && altitude_m >= 0.0 && altitude_m < entry_altitude_m) {
                return Err(setting(
                    "end.altitude_m",
                    altitude_m,
                    "must be finite, >= 0 and below the entry altitude",
                ));
            }
            u_at_radius(&glide, planet.radius_m + altitude_m).map_err(dom)?
        }
    };
    let rows = (0..points)
        .map(|i| {
            let u = if i == 0 {
                u_e
            } else if i + 1 == points {
                u_end
            } else {
                u_e + (u_end - u_e) * i as f64 / (points - 1) as f64
            };
            glide.point_at_u(u).map(Planar::from)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(dom)?;
    let v_end = rows.last().map_or(e.speed_m_s, |p| p.speed);
    let peak_q = Planar::from(glide.peak_heat_flux(v_end).map_err(dom)?);
    let peak_g = Planar::from(glide.peak_g_load(v_end).map_err(dom)?);
    let entry = SphericalState {
        radius_m: e.radius_m,
        longitude_rad: placement.longitude_rad,
        latitude_rad: placement.latitude_rad,
        speed_m_s: e.speed_m_s,
        flight_path_angle_rad: e.flight_path_angle_rad,
        heading_rad: placement.heading_rad,
    };
    let ctx = Ctx {
        vehicle,
        lift,
        atmosphere,
        planet,
        placement: *placement,
    };
    let reason = match end {
        GlideEnd::Altitude { .. } => TerminationReason::Altitude,
        GlideEnd::SpeedFraction { .. } => TerminationReason::Mach,
    };
    let result = ctx.assemble(&rows, peak_q, peak_g, reason);
    let deepest = rows.iter().map(|p| p.radius).fold(f64::INFINITY, f64::min) - planet.radius_m;
    Ok(AnalyticRun {
        result,
        phase: Phase::Glide,
        entry,
        deepest_altitude_m: deepest,
        lift: *lift,
        atmosphere: *atmosphere,
    })
}

/// `u` in `(0, u_E)` where the glide's second-order radius is `radius_m`: scan down from `u_E`
/// (256 geometric steps to `1e-3 u_E`), then bisect (bounded).
fn u_at_radius(glide: &GlideSolution<f64>, radius_m: f64) -> Result<f64, VinhError> {
    let u_e = glide.u_entry();
    let below = |u: f64| glide.point_at_u(u).map(|p| p.radius_m < radius_m);
    let mut hi = u_e;
    let mut lo = None;
    for k in 1..=256 {
        let u = u_e * 10f64.powf(-3.0 * f64::from(k) / 256.0);
        if below(u)? {
            lo = Some(u);
            break;
        }
        hi = u;
    }
    let Some(mut lo) = lo else {
        return Err(VinhError::GlideSpeedOutOfDomain);
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Shared conversion from planar closed-form points to simulator samples.
struct Ctx<'a> {
    vehicle: &'a AnalyticVehicle,
    lift: &'a LiftSetting,
    atmosphere: &'a ExponentialAtmosphere,
    planet: Planet,
    placement: Placement,
}

impl Ctx<'_> {
    fn state(&self, p: &Planar) -> SphericalState {
        let (lat, lon, heading) = self.placement.along(p.theta);
        SphericalState {
            radius_m: p.radius,
            longitude_rad: lon,
            latitude_rad: lat,
            speed_m_s: p.speed,
            flight_path_angle_rad: p.gamma,
            heading_rad: heading,
        }
    }

    fn conditions(&self, p: &Planar) -> FlightConditions {
        let altitude_m = p.radius - self.planet.radius_m;
        let atm = self.atmosphere.state(altitude_m);
        let m = self.vehicle.mass_kg;
        FlightConditions {
            altitude_m,
            density_kg_m3: atm.density_kg_m3,
            airspeed_m_s: p.speed,
            mach: p.speed / atm.speed_of_sound_m_s,
            dynamic_pressure_pa: 0.5 * atm.density_kg_m3 * p.speed * p.speed,
            cl: self.lift.cl,
            cd: self.vehicle.polar.cd(self.lift.cl),
            lift_n: m * p.lift_acc,
            drag_n: m * p.drag_acc,
            heat_flux_w_m2: p.heat_flux,
            g_load: p.g_load,
        }
    }

    /// Samples (time by quadrature) and summary.
    fn assemble(
        &self,
        rows: &[Planar],
        peak_q: Planar,
        peak_g: Planar,
        termination: TerminationReason,
    ) -> SimResult {
        let first = rows.first().copied().unwrap_or(peak_q);
        let energy = EnergyNormalizer::<f64>::new(
            self.planet.mu_m3_s2,
            self.planet.radius_m,
            first.radius,
            first.speed,
        )
        .ok();
        let attitude = Attitude {
            alpha_rad: 0.0,
            sigma_rad: self.lift.bank_rad,
        };
        let pace = |p: &Planar| p.radius / (p.speed * p.gamma.cos());
        let mut samples: Vec<Sample> = Vec::with_capacity(rows.len());
        let (mut t, mut heat) = (0.0, 0.0);
        let mut g_rate = Peak::default();
        for (i, p) in rows.iter().enumerate() {
            if let Some(prev) = i.checked_sub(1).and_then(|j| rows.get(j)) {
                let dt = (p.theta - prev.theta) * 0.5 * (pace(prev) + pace(p));
                heat += 0.5 * (prev.heat_flux + p.heat_flux) * dt;
                t += dt;
                if dt > 0.0 {
                    let rate = ((p.g_load - prev.g_load) / dt).abs();
                    if rate > g_rate.value {
                        g_rate = Peak {
                            value: rate,
                            time_s: t,
                        };
                    }
                }
            }
            let state = self.state(p);
            let kind = if i == 0 {
                SampleKind::Start
            } else if i + 1 == rows.len() {
                SampleKind::End
            } else {
                SampleKind::Output
            };
            samples.push(Sample {
                time_s: t,
                state,
                attitude,
                conditions: self.conditions(p),
                heat_load_j_m2: heat,
                flown_range_rad: p.theta,
                normalized_energy: energy
                    .as_ref()
                    .and_then(|e| e.normalized(p.radius, p.speed).ok())
                    .unwrap_or(f64::NAN),
                kind,
            });
        }
        let time_at = |theta: f64| -> f64 {
            samples
                .windows(2)
                .find_map(|w| match w {
                    [a, b] if theta <= b.flown_range_rad => {
                        let span = b.flown_range_rad - a.flown_range_rad;
                        let f = if span > 0.0 {
                            ((theta - a.flown_range_rad) / span).clamp(0.0, 1.0)
                        } else {
                            0.0
                        };
                        Some(a.time_s + f * (b.time_s - a.time_s))
                    }
                    _ => None,
                })
                .unwrap_or(t)
        };
        let peak_heat = Peak {
            value: peak_q.heat_flux,
            time_s: time_at(peak_q.theta),
        };
        let peak_g_load = Peak {
            value: peak_g.g_load,
            time_s: time_at(peak_g.theta),
        };
        let range = match (samples.first(), samples.last()) {
            (Some(a), Some(b)) => great_circle(&a.state, &b.state),
            _ => 0.0,
        };
        let lim = &self.vehicle.limits;
        let summary = Summary {
            termination,
            flight_time_s: t,
            range_angle_rad: range,
            flown_range_angle_rad: rows.last().map_or(0.0, |p| p.theta),
            heat_load_j_m2: heat,
            peak_heat_flux_w_m2: peak_heat,
            peak_g_load,
            peak_g_load_rate_per_s: g_rate,
            exits: 0,
            skips: 0,
            interface_crossings_s: Vec::new(),
            violations: Violations {
                heat_flux: violation(peak_heat.value, lim.heat_flux_w_m2),
                g_load: violation(peak_g_load.value, lim.g_load),
                g_load_rate: violation(g_rate.value, lim.g_load_rate_per_s),
            },
            rhs_evals: 0,
            accepted_steps: 0,
            rejected_steps: 0,
            ticks: 0,
        };
        SimResult { samples, summary }
    }
}

/// Environment description of the analytical simulator for [`crate::report::summary_report`].
#[must_use]
pub fn environment_label(atmosphere: &ExponentialAtmosphere) -> String {
    format!(
        "analytical (Vinh second order): non-rotating sphere, central gravity, exponential \
         atmosphere rho0 = {:.4e} kg/m^3 at {:.1} km, H_s = {:.1} m",
        atmosphere.rho0_kg_m3(),
        atmosphere.reference_altitude_m() / 1e3,
        atmosphere.scale_height_m()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placement_follows_the_great_circle() {
        let p = Placement::default();
        let (lat, lon, h) = p.along(0.3);
        assert!(lat.abs() < 1e-15);
        assert!((lon - 0.3).abs() < 1e-15);
        assert!((h - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // Heading north from the equator: latitude grows with the range angle.
        let n = Placement {
            heading_rad: 0.0,
            ..Placement::default()
        };
        let (lat, lon, h) = n.along(0.2);
        assert!((lat - 0.2).abs() < 1e-12 && lon.abs() < 1e-12 && h.abs() < 1e-12);
    }

    #[test]
    fn trim_vehicle_polar_reproduces_trim_drag() {
        let srm = crate::vehicle::srm::vehicle();
        let av = AnalyticVehicle::from_vehicle(&srm, DEFAULT_POLAR_MACH).unwrap();
        let trim = crate::vehicle::srm::trim();
        assert!((av.polar.cd(trim.cl) - trim.cd).abs() < 1e-12);
        assert!((av.polar.cl_at_max_lift_to_drag() - trim.cl).abs() < 1e-12);
        let lift = av.lift_for_vertical_cl(0.5 * trim.cl).unwrap();
        assert!((lift.bank_rad.to_degrees() - 60.0).abs() < 1e-9);
        assert!((lift.vertical_cl() - 0.5 * trim.cl).abs() < 1e-12);
        assert!(av.lift_for_vertical_cl(2.0).is_err());
        assert!(av.lift_for_vertical_cl(f64::NAN).is_err());
    }
}
