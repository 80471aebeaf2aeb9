//! The dispersed values of one case, drawn from a generator seeded by (campaign seed, case
//! index) alone, so a case is the same whatever the thread count, the order of evaluation or
//! which cases were already done (resume).

use serde::{Deserialize, Serialize};

use super::settings::{DispersionSettings, Distribution, distribution_of};
use crate::optim::OptimRng;

/// The dispersed values of one case (offsets in SI units and radians; scales as fractions).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CaseDraw {
    /// Case index.
    pub index: u32,
    /// Entry altitude offset \[m\].
    pub altitude_m: f64,
    /// Entry speed offset \[m/s\].
    pub speed_m_s: f64,
    /// Entry flight-path angle offset \[rad\].
    pub flight_path_angle_rad: f64,
    /// Entry heading offset \[rad\].
    pub heading_rad: f64,
    /// Entry latitude offset \[rad\].
    pub latitude_rad: f64,
    /// Entry longitude offset \[rad\].
    pub longitude_rad: f64,
    /// Density scale bias (fraction).
    pub density_bias: f64,
    /// Density wave amplitude (fraction).
    pub density_wave: f64,
    /// Density wave phase \[rad\].
    pub density_phase_rad: f64,
    /// Density wavelength \[m\] (from the settings, not drawn).
    pub density_wavelength_m: f64,
    /// Lift-coefficient scale offset (fraction).
    pub lift: f64,
    /// Drag-coefficient scale offset (fraction).
    pub drag: f64,
    /// Mass scale offset (fraction).
    pub mass: f64,
    /// IMU bias of the sensed lift acceleration \[m/s^2\] (absent in case files of earlier
    /// versions: 0).
    #[serde(default)]
    pub imu_lift_bias_m_s2: f64,
    /// IMU bias of the sensed drag acceleration \[m/s^2\].
    #[serde(default)]
    pub imu_drag_bias_m_s2: f64,
    /// IMU scale-factor error of the sensed lift acceleration (fraction).
    #[serde(default)]
    pub imu_lift_scale: f64,
    /// IMU scale-factor error of the sensed drag acceleration (fraction).
    #[serde(default)]
    pub imu_drag_scale: f64,
    /// IMU white noise per sample, standard deviation \[m/s^2\] (from the settings, not
    /// drawn).
    #[serde(default)]
    pub imu_noise_m_s2: f64,
    /// Seed of the case's IMU noise generator (from the campaign seed and the case index).
    #[serde(default)]
    pub imu_noise_seed: u64,
}

/// Stream constant mixed into the campaign seed for the IMU noise generator of a case (a
/// generator of its own, so the noise never shifts the other draws).
pub const IMU_NOISE_STREAM: u64 = 0x494D_555F_4E4F_4953;

/// The generator seed of case `index` (a SplitMix64 mix of seed and index).
#[must_use]
pub fn case_seed(seed: u64, index: u32) -> u64 {
    let mut z = seed ^ (u64::from(index).wrapping_add(1)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A standard normal draw truncated at 3 (Box-Muller, rejection above 3; written here so the
/// bit pattern never depends on a distribution crate).
pub(crate) fn standard_normal_3(rng: &mut OptimRng) -> f64 {
    loop {
        let u1 = 1.0 - rng.uniform(); // (0, 1]
        let u2 = rng.uniform();
        let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        if z.abs() <= 3.0 {
            return z;
        }
    }
}

fn draw_one(rng: &mut OptimRng, d: Distribution) -> f64 {
    match d {
        Distribution::Normal { sigma } => sigma * standard_normal_3(rng),
        Distribution::Uniform { half_width } => half_width * (2.0 * rng.uniform() - 1.0),
    }
}

/// Draw case `index` of a validated campaign (always the same numbers for a (seed, index)).
#[must_use]
pub fn draw_case(s: &DispersionSettings, index: u32) -> CaseDraw {
    let mut rng = OptimRng::new(case_seed(s.seed, index));
    let d = |rng: &mut OptimRng, x: &super::settings::Dispersion| {
        // Validated settings: the distribution is known.
        distribution_of(x).map_or(0.0, |dist| draw_one(rng, dist))
    };
    let deg = std::f64::consts::PI / 180.0;
    CaseDraw {
        index,
        altitude_m: d(&mut rng, &s.altitude_km) * 1000.0,
        speed_m_s: d(&mut rng, &s.speed_m_s),
        flight_path_angle_rad: d(&mut rng, &s.flight_path_angle_deg) * deg,
        heading_rad: d(&mut rng, &s.heading_deg) * deg,
        latitude_rad: d(&mut rng, &s.latitude_deg) * deg,
        longitude_rad: d(&mut rng, &s.longitude_deg) * deg,
        density_bias: d(&mut rng, &s.density_bias),
        density_wave: d(&mut rng, &s.density_wave),
        density_phase_rad: rng.uniform() * std::f64::consts::TAU,
        density_wavelength_m: s.density_wavelength_km * 1000.0,
        lift: d(&mut rng, &s.lift),
        drag: d(&mut rng, &s.drag),
        mass: d(&mut rng, &s.mass),
        // Drawn after the others: the values above are those of earlier versions.
        imu_lift_bias_m_s2: d(&mut rng, &s.imu_bias_m_s2),
        imu_drag_bias_m_s2: d(&mut rng, &s.imu_bias_m_s2),
        imu_lift_scale: d(&mut rng, &s.imu_scale_factor),
        imu_drag_scale: d(&mut rng, &s.imu_scale_factor),
        imu_noise_m_s2: s.imu_noise_m_s2,
        imu_noise_seed: case_seed(s.seed ^ IMU_NOISE_STREAM, index),
    }
}
