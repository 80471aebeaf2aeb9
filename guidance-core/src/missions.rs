//! Reference missions, each defined once: the firmware (smoke test and PIL binary), the
//! simulator's SIL and PIL runs and the CLI's built-in scenario all take it from here.
//!
//! A [`Mission`] is everything the guidance of a mission needs: the node table (nodes, the
//! independent variable and the angle bounds), the interpolation, the guidance period and
//! rate limits, the initial attitude, and the entry-interface state that defines E-hat = 1.
//! What a simulator adds around it (vehicle model, environment, termination) is not here.
//!
//! [`horus2b_reference`]: the HORUS-2B nominal mission of the thesis (sec. 2.2 and 7.4);
//! [`srm_glide`]: the SRM capsule's energy-indexed glide from the thesis' sec. 9.2 entry.
//!
//! The reference vehicles' parameters a firmware needs are here too: mass, area, nose radius,
//! limits ([`HORUS2B_LIMITS`], [`SRM_LIMITS`]) and the parabolic drag polar the re-planner's
//! predictor uses ([`horus2b_vehicle`], its per-Mach table [`HORUS2B_DRAG_POLAR`], and
//! [`srm_vehicle`]). They are the values host-sim flies (a host-sim test checks both).
//!
//! ```
//! use guidance_core::missions::{horus2b_reference, HORUS2B_LIMITS, horus2b_vehicle};
//! let mission = horus2b_reference::<f32>()?;
//! let mut guidance = mission.guidance(mission.earth_energy_normalizer()?)?;
//! assert_eq!(guidance.command(), mission.initial);
//! let polar = horus2b_vehicle::<f32>();              // Mach-20 polar of thesis table 8.1
//! assert_eq!((polar.cd0, polar.k_polar), (0.0488, 1.147));
//! assert_eq!(HORUS2B_LIMITS.heat_flux_w_m2, 500e3);
//! # Ok::<(), guidance_core::GuidanceError>(())
//! ```

use crate::command::Command;
use crate::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use crate::error::GuidanceError;
use crate::guidance::{Guidance, GuidanceConfig};
use crate::interp::Interpolation;
use crate::nodes::{AngleBounds, DEFAULT_NODE_CAPACITY, Independent, NodeTable, NodeTableError};
use crate::rate::RateLimits;
use crate::replan::ReplanLimits;
use crate::scalar::{Real, Scalar};
use crate::vinh::nondim::VehicleParams;

/// Degrees to radians, in `f64`.
const DEG_TO_RAD: f64 = core::f64::consts::PI / 180.0;

/// The HORUS-2B nominal guidance table of thesis eq. 2.3: rows `(t \[s\], alpha \[deg\],
/// sigma \[deg\])`, time-indexed.
pub const HORUS2B_REFERENCE_NODES_DEG: [(f64, f64, f64); 7] = [
    (0.0, 40.0, 0.0),
    (264.0, 40.0, 0.0),
    (290.0, 40.0, 79.6),
    (554.0, 40.0, 59.8),
    (686.0, 40.0, 59.8),
    (924.0, 40.0, 59.8),
    (1319.0, 11.5, 54.0),
];

/// The entry-interface state of a mission (planet-relative; SI units, radians). `f64`: it
/// configures guidance and simulators; guidance only uses altitude and speed (E-hat = 1).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EntryInterface {
    /// Altitude above the spherical planet \[m\].
    pub altitude_m: f64,
    /// Planet-relative speed \[m/s\].
    pub speed_m_s: f64,
    /// Planet-relative flight-path angle \[rad\] (negative: descending).
    pub flight_path_angle_rad: f64,
    /// Heading, clockwise from north \[rad\].
    pub heading_rad: f64,
    /// Geocentric latitude \[rad\].
    pub latitude_rad: f64,
    /// Longitude, positive east \[rad\].
    pub longitude_rad: f64,
}

/// HORUS-2B entry interface of thesis table 2.1: 122 km, 7435.5 m/s, -1.43 deg flight-path
/// angle, 70.75 deg heading, 22.3 deg S, 106.7 deg W.
pub const HORUS2B_ENTRY: EntryInterface = EntryInterface {
    altitude_m: 122_000.0,
    speed_m_s: 7435.5,
    flight_path_angle_rad: -1.43 * DEG_TO_RAD,
    heading_rad: 70.75 * DEG_TO_RAD,
    latitude_rad: -22.3 * DEG_TO_RAD,
    longitude_rad: -106.7 * DEG_TO_RAD,
};

/// A mission's guidance set-up (module docs), over a node table of capacity `N`.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Mission<S, const N: usize = DEFAULT_NODE_CAPACITY> {
    /// Short name (also the simulator's default run directory).
    pub name: &'static str,
    /// Node table: nodes, independent variable and angle bounds \[rad\].
    pub table: NodeTable<S, N>,
    /// Interpolation between the nodes.
    pub interpolation: Interpolation<S>,
    /// Guidance period \[s\] and attitude-rate limits \[rad/s\].
    pub config: GuidanceConfig<S>,
    /// Attitude at the start \[rad\].
    pub initial: Command<S>,
    /// Entry-interface state (defines E-hat = 1).
    pub entry: EntryInterface,
}

impl<S: Scalar, const N: usize> Mission<S, N> {
    /// The E-hat map of this mission for a planet (`mu_m3_s2` \[m^3/s^2\], spherical radius
    /// `planet_radius_m` \[m\]): E-hat = 1 at the entry interface.
    ///
    /// # Errors
    /// As [`EnergyNormalizer::new`].
    pub fn energy_normalizer(
        &self,
        mu_m3_s2: f64,
        planet_radius_m: f64,
    ) -> Result<EnergyNormalizer<S>, GuidanceError> {
        EnergyNormalizer::new(
            mu_m3_s2,
            planet_radius_m,
            planet_radius_m + self.entry.altitude_m,
            self.entry.speed_m_s,
        )
    }

    /// [`Mission::energy_normalizer`] for the thesis' spherical Earth
    /// ([`EARTH_MU_M3_S2`], [`EARTH_RADIUS_M`]).
    ///
    /// # Errors
    /// As [`EnergyNormalizer::new`].
    pub fn earth_energy_normalizer(&self) -> Result<EnergyNormalizer<S>, GuidanceError> {
        self.energy_normalizer(EARTH_MU_M3_S2, EARTH_RADIUS_M)
    }

    /// The flight guidance of this mission, with `energy` as its E-hat map.
    ///
    /// # Errors
    /// As [`Guidance::new`].
    pub fn guidance(&self, energy: EnergyNormalizer<S>) -> Result<Guidance<S, N>, GuidanceError> {
        Guidance::new(
            self.config,
            self.table.clone(),
            self.interpolation,
            energy,
            self.initial,
        )
    }

    /// The same mission with node capacity `M` (e.g. the host's
    /// [`crate::nodes::HOST_NODE_CAPACITY`]).
    ///
    /// # Errors
    /// [`NodeTableError::TooManyNodes`] if the table does not fit `M`.
    pub fn to_capacity<const M: usize>(&self) -> Result<Mission<S, M>, NodeTableError> {
        Ok(Mission {
            name: self.name,
            table: self.table.to_capacity()?,
            interpolation: self.interpolation,
            config: self.config,
            initial: self.initial,
            entry: self.entry,
        })
    }
}

/// The HORUS-2B nominal reference mission (thesis sec. 2.2 and 7.4): the time-indexed table
/// of eq. 2.3 ([`HORUS2B_REFERENCE_NODES_DEG`]) with linear interpolation, the thesis angle
/// bounds of sec. 4.2.1 (alpha 0..45 deg, **sigma 0..90 deg**), the 2 s period and the
/// 5 deg/s and 15 deg/s rate limits of table 2.1, initial attitude alpha 40 deg, sigma 0 deg,
/// and the entry interface [`HORUS2B_ENTRY`].
///
/// # Errors
/// Only if `S` cannot represent the values (never for `f32`, `f64`, `Fixed`).
pub fn horus2b_reference<S: Scalar>() -> Result<Mission<S>, GuidanceError> {
    let table = NodeTable::from_deg(
        Independent::TimeS,
        &HORUS2B_REFERENCE_NODES_DEG,
        AngleBounds::thesis_default(),
    )?;
    Ok(Mission {
        name: "horus-2b-reference",
        table,
        interpolation: Interpolation::Linear,
        config: GuidanceConfig {
            period_s: S::from_f64(2.0),
            rates: RateLimits::thesis_default(),
        },
        initial: Command::from_deg(40.0, 0.0).ok_or(GuidanceError::InvalidConfig)?,
        entry: HORUS2B_ENTRY,
    })
}

/// Operational limits of a vehicle (SI units, radians).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VehicleLimits {
    /// Stagnation-point heat flux (Chapman) \[W/m^2\].
    pub heat_flux_w_m2: f64,
    /// Aerodynamic load \[g0\].
    pub g_load: f64,
    /// Rate of the g-load \[1/s\].
    pub g_load_rate_per_s: f64,
    /// Angle-of-attack rate \[rad/s\].
    pub alpha_rate_rad_s: f64,
    /// Bank-angle rate \[rad/s\].
    pub sigma_rate_rad_s: f64,
}

impl VehicleLimits {
    /// The heat-flux and g-load limits as the re-planner and the path bound take them.
    #[must_use]
    pub fn load_limits<S: Real>(&self) -> ReplanLimits<S> {
        ReplanLimits {
            heat_flux_w_m2: S::from_f64(self.heat_flux_w_m2),
            g_load: S::from_f64(self.g_load),
        }
    }

    /// The attitude-rate limits as the guidance takes them.
    #[must_use]
    pub fn rate_limits<S: Scalar>(&self) -> RateLimits<S> {
        RateLimits {
            alpha_rad_s: S::from_f64(self.alpha_rate_rad_s),
            sigma_rad_s: S::from_f64(self.sigma_rate_rad_s),
        }
    }
}

/// HORUS-2B mass \[kg\] (thesis table 2.1).
pub const HORUS2B_MASS_KG: f64 = 26_029.0;
/// HORUS-2B aerodynamic reference area \[m^2\] (thesis table 2.1).
pub const HORUS2B_REFERENCE_AREA_M2: f64 = 110.0;
/// HORUS-2B nose radius \[m\] (thesis table 2.1).
pub const HORUS2B_NOSE_RADIUS_M: f64 = 0.8;

/// HORUS-2B limits (thesis table 2.1): heat flux 500 kW/m^2, g-load 3, g-load rate 0.5 1/s,
/// angle-of-attack rate 5 deg/s, bank rate 15 deg/s.
pub const HORUS2B_LIMITS: VehicleLimits = VehicleLimits {
    heat_flux_w_m2: 500.0e3,
    g_load: 3.0,
    g_load_rate_per_s: 0.5,
    alpha_rate_rad_s: 5.0 * DEG_TO_RAD,
    sigma_rate_rad_s: 15.0 * DEG_TO_RAD,
};

/// HORUS-2B parabolic drag polar `C_D = C_D0 + K C_L^2` per Mach number (thesis table 8.1):
/// rows `(Mach, C_D0, K)`, increasing Mach.
pub const HORUS2B_DRAG_POLAR: [(f64, f64, f64); 7] = [
    (1.2, 0.03067, 0.6481),
    (1.5, 0.04055, 0.5907),
    (2.0, 0.04582, 0.715),
    (3.0, 0.04302, 0.8864),
    (5.0, 0.05561, 0.948),
    (10.0, 0.05408, 1.016),
    (20.0, 0.0488, 1.147),
];

/// HORUS-2B for the re-planner's predictor at hypersonic speed: mass, area and nose radius of
/// table 2.1 with the Mach-20 polar of table 8.1 (`C_D0 = 0.0488`, `K = 1.147`; maximum L/D
/// 2.11 at `C_L* = 0.206`).
#[must_use]
pub fn horus2b_vehicle<S: Real>() -> VehicleParams<S> {
    horus2b_vehicle_at_mach(20.0)
}

/// HORUS-2B with its polar at `mach` \[-\]: [`HORUS2B_DRAG_POLAR`] linear in Mach between
/// the tabulated Mach numbers, clamped outside them (a NaN Mach gives the Mach-20 polar).
#[must_use]
pub fn horus2b_vehicle_at_mach<S: Real>(mach: f64) -> VehicleParams<S> {
    let (mut cd0, mut k) = (0.0488, 1.147);
    let first = HORUS2B_DRAG_POLAR
        .first()
        .copied()
        .unwrap_or((1.2, 0.03067, 0.6481));
    if mach <= first.0 {
        (cd0, k) = (first.1, first.2);
    }
    for w in HORUS2B_DRAG_POLAR.windows(2) {
        if let [a, b] = w {
            if mach == b.0 {
                (cd0, k) = (b.1, b.2);
            } else if mach > a.0 && mach < b.0 {
                let t = (mach - a.0) / (b.0 - a.0);
                (cd0, k) = (a.1 + t * (b.1 - a.1), a.2 + t * (b.2 - a.2));
            }
        }
    }
    VehicleParams {
        mass_kg: S::from_f64(HORUS2B_MASS_KG),
        reference_area_m2: S::from_f64(HORUS2B_REFERENCE_AREA_M2),
        cd0: S::from_f64(cd0),
        k_polar: S::from_f64(k),
        nose_radius_m: S::from_f64(HORUS2B_NOSE_RADIUS_M),
    }
}

/// SRM capsule mass \[kg\] (thesis table 2.3).
pub const SRM_MASS_KG: f64 = 38.77;
/// SRM capsule reference area \[m^2\] (thesis table 2.3, the disc of 0.75 m).
pub const SRM_REFERENCE_AREA_M2: f64 = 0.441;
/// SRM capsule nose radius \[m\] (thesis table 2.3).
pub const SRM_NOSE_RADIUS_M: f64 = 0.9;
/// SRM trim lift coefficient \[-\]: the thesis' maximum C_L of the capsule (sec. 8.1.5).
pub const SRM_TRIM_CL: f64 = 1.2786;
/// SRM trim lift-to-drag ratio \[-\] (the thesis' SRM E* of 2.27).
pub const SRM_TRIM_LIFT_TO_DRAG: f64 = 2.27;

/// SRM limits: the thesis uses HORUS-2B's constraint values for both vehicles (sec. 4.2.3).
pub const SRM_LIMITS: VehicleLimits = HORUS2B_LIMITS;

/// The SRM capsule for the re-planner's predictor: the parabolic polar whose maximum-L/D
/// point is the trim point (`lambda = 1` flies [`SRM_TRIM_CL`] at [`SRM_TRIM_LIFT_TO_DRAG`]):
/// `C_D0 = C_D,trim / 2`, `K = C_D0 / C_L,trim^2`.
#[must_use]
pub fn srm_vehicle<S: Real>() -> VehicleParams<S> {
    let cd0 = SRM_TRIM_CL / SRM_TRIM_LIFT_TO_DRAG / 2.0;
    VehicleParams {
        mass_kg: S::from_f64(SRM_MASS_KG),
        reference_area_m2: S::from_f64(SRM_REFERENCE_AREA_M2),
        cd0: S::from_f64(cd0),
        k_polar: S::from_f64(cd0 / (SRM_TRIM_CL * SRM_TRIM_CL)),
        nose_radius_m: S::from_f64(SRM_NOSE_RADIUS_M),
    }
}

/// SRM glide entry (thesis sec. 9.2): 100 km, 7658.34 m/s, -0.056 deg, heading 90 deg (east)
/// from latitude and longitude 0.
pub const SRM_GLIDE_ENTRY: EntryInterface = EntryInterface {
    altitude_m: 100_000.0,
    speed_m_s: 7658.34,
    flight_path_angle_rad: -0.056 * DEG_TO_RAD,
    heading_rad: 90.0 * DEG_TO_RAD,
    latitude_rad: 0.0,
    longitude_rad: 0.0,
};

/// The SRM glide's bank-only table: rows `(E-hat [-], alpha [deg], sigma [deg])`
/// (illustrative nodes; the thesis does not print its optimised ones).
pub const SRM_GLIDE_NODES_DEG: [(f64, f64, f64); 4] = [
    (1.0, 0.0, 0.0),
    (0.8, 0.0, 40.0),
    (0.4, 0.0, 60.0),
    (0.0, 0.0, 0.0),
];

/// The SRM capsule's energy-indexed glide (host-sim's built-in `srm-glide`): the table
/// [`SRM_GLIDE_NODES_DEG`] with linear interpolation and two-sided bank bounds (alpha 0..45
/// deg, sigma -180..180 deg as scenario files allow, so a lateral logic can reverse the bank), the 2 s period and the
/// 5 deg/s and 15 deg/s rate limits, initial attitude 0, 0, entry [`SRM_GLIDE_ENTRY`].
///
/// # Errors
/// Only if `S` cannot represent the values (never for `f32`, `f64`, `Fixed`).
pub fn srm_glide<S: Scalar>() -> Result<Mission<S>, GuidanceError> {
    let bounds = AngleBounds::from_deg(0.0, 45.0, -180.0, 180.0)?;
    let table = NodeTable::from_deg(Independent::NormalizedEnergy, &SRM_GLIDE_NODES_DEG, bounds)?;
    Ok(Mission {
        name: "srm-glide",
        table,
        interpolation: Interpolation::Linear,
        config: GuidanceConfig {
            period_s: S::from_f64(2.0),
            rates: SRM_LIMITS.rate_limits(),
        },
        initial: Command::from_deg(0.0, 0.0).ok_or(GuidanceError::InvalidConfig)?,
        entry: SRM_GLIDE_ENTRY,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fixed;

    const DEG: f64 = core::f64::consts::PI / 180.0;

    /// The mission is the thesis' numbers (eq. 2.3, table 2.1, sec. 4.2.1), in every type.
    #[test]
    fn horus2b_reference_is_the_thesis_mission() {
        let m = horus2b_reference::<f64>().unwrap();
        assert_eq!(m.table.len(), 7);
        assert_eq!(m.table.independent(), Independent::TimeS);
        let n = m.table.nodes();
        assert_eq!((n[2].x, n[2].sigma_rad), (290.0, 79.6 * DEG));
        assert_eq!((n[6].x, n[6].alpha_rad), (1319.0, 11.5 * DEG));
        let b = m.table.bounds();
        assert_eq!((b.alpha_min_rad, b.alpha_max_rad), (0.0, 45.0 * DEG));
        assert_eq!((b.sigma_min_rad, b.sigma_max_rad), (0.0, 90.0 * DEG));
        assert_eq!(m.interpolation, Interpolation::Linear);
        assert_eq!(m.config.period_s, 2.0);
        assert_eq!(m.config.rates.alpha_rad_s, 5.0 * DEG);
        assert_eq!(m.config.rates.sigma_rad_s, 15.0 * DEG);
        assert_eq!(m.initial, Command::from_deg(40.0, 0.0).unwrap());
        assert_eq!(m.entry.altitude_m, 122_000.0);
        assert_eq!(m.entry.speed_m_s, 7435.5);
        assert_eq!(m.entry.flight_path_angle_rad, (-1.43f64).to_radians());
        assert_eq!(m.entry.heading_rad, 70.75f64.to_radians());
        assert_eq!(m.entry.latitude_rad, (-22.3f64).to_radians());
        assert_eq!(m.entry.longitude_rad, (-106.7f64).to_radians());
        assert_eq!(horus2b_reference::<f32>().unwrap().table.len(), 7);
        assert_eq!(horus2b_reference::<Fixed>().unwrap().table.len(), 7);
    }

    /// Guidance built from the mission flies the table: E-hat 1 at entry, the bank step.
    #[test]
    fn mission_guidance_and_energy() {
        let m = horus2b_reference::<f64>().unwrap();
        let e = m.earth_energy_normalizer().unwrap();
        let r = EARTH_RADIUS_M + m.entry.altitude_m;
        assert!((e.normalized(r, m.entry.speed_m_s).unwrap() - 1.0).abs() < 1e-12);
        let mut g = m.guidance(e).unwrap();
        assert_eq!(g.command(), m.initial);
        let nav = crate::nav::NavState {
            time_s: 277.0,
            radius_m: r,
            speed_m_s: 7000.0,
            flight_path_angle_rad: 0.0,
            heading_rad: 0.0,
            latitude_rad: 0.0,
            longitude_rad: 0.0,
        };
        g.update(&nav).unwrap();
        assert!((g.target().sigma_rad - 79.6 * DEG * 13.0 / 26.0).abs() < 1e-12);
        let host: Mission<f64, 256> = m.to_capacity().unwrap();
        assert_eq!(host.table.nodes(), m.table.nodes());
        assert_eq!(
            m.to_capacity::<4>().unwrap_err(),
            NodeTableError::TooManyNodes
        );
    }
}
