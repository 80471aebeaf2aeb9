//! Reference missions, each defined once: the firmware (smoke test and PIL binary), the
//! simulator's SIL and PIL runs and the CLI's built-in scenario all take it from here.
//!
//! A [`Mission`] is everything the guidance of a mission needs: the node table (nodes, the
//! independent variable and the angle bounds), the interpolation, the guidance period and
//! rate limits, the initial attitude, and the entry-interface state that defines E-hat = 1.
//! What a simulator adds around it (vehicle model, environment, termination) is not here.
//!
//! [`horus2b_reference`]: the HORUS-2B nominal mission of the thesis (sec. 2.2 and 7.4).

use crate::command::Command;
use crate::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use crate::error::GuidanceError;
use crate::guidance::{Guidance, GuidanceConfig};
use crate::interp::Interpolation;
use crate::nodes::{AngleBounds, DEFAULT_NODE_CAPACITY, Independent, NodeTable, NodeTableError};
use crate::rate::RateLimits;
use crate::scalar::Scalar;

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
