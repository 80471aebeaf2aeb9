//! Dispersion settings: the `[dispersions]` TOML section (distributions and 3-sigma values),
//! with documented defaults, validated with errors that name the field.

use serde::{Deserialize, Serialize};

use super::CampaignError;
use crate::scenario::guidance_layers::scenario_key;
use crate::toml_input::TomlInputError;

/// One dispersed quantity: a distribution and its 3-sigma value (in the field's unit).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dispersion {
    /// `"normal"` (Gaussian, standard deviation `three_sigma / 3`, truncated at 3 sigma so
    /// every draw is physical) or `"uniform"` (the same standard deviation: half-width
    /// `three_sigma / sqrt(3)`).
    pub distribution: String,
    /// The 3-sigma value, `>= 0` (0: not dispersed).
    pub three_sigma: f64,
}

impl Dispersion {
    fn normal(three_sigma: f64) -> Self {
        Self {
            distribution: "normal".into(),
            three_sigma,
        }
    }
}

/// The `[dispersions]` section. Units are those of the field name (km, m/s, deg, fraction).
/// Defaults (3 sigma, all normal): entry altitude 1 km, speed 20 m/s, flight-path angle
/// 0.05 deg, heading 0.2 deg, latitude and longitude 0.1 deg each; density bias 10 % and an
/// altitude-varying density wave of 10 % (wavelength 20 km, random phase); lift and drag
/// coefficients 5 % each; mass 3 %.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DispersionSettings {
    /// Number of flights, `>= 1`.
    pub cases: u32,
    /// Seed of the campaign (each case draws from its own generator seeded by (seed, index)).
    pub seed: u64,
    /// Entry altitude \[km\].
    pub altitude_km: Dispersion,
    /// Entry speed \[m/s\].
    pub speed_m_s: Dispersion,
    /// Entry flight-path angle \[deg\].
    pub flight_path_angle_deg: Dispersion,
    /// Entry heading \[deg\].
    pub heading_deg: Dispersion,
    /// Entry latitude \[deg\].
    pub latitude_deg: Dispersion,
    /// Entry longitude \[deg\].
    pub longitude_deg: Dispersion,
    /// Density scale bias (fraction: 0.1 = 10 %).
    pub density_bias: Dispersion,
    /// Amplitude of the density scale's altitude wave (fraction).
    pub density_wave: Dispersion,
    /// Wavelength of the density wave \[km\], `> 0`.
    pub density_wavelength_km: f64,
    /// Lift-coefficient scale (fraction).
    pub lift: Dispersion,
    /// Drag-coefficient scale (fraction).
    pub drag: Dispersion,
    /// Mass scale (fraction).
    pub mass: Dispersion,
    /// IMU bias of each sensed acceleration (lift, drag), constant over a flight \[m/s^2\].
    pub imu_bias_m_s2: Dispersion,
    /// IMU scale-factor error of each sensed acceleration, constant over a flight (fraction).
    pub imu_scale_factor: Dispersion,
    /// IMU white noise of each sensed acceleration per 2 s sample, standard deviation
    /// \[m/s^2\], `>= 0`.
    pub imu_noise_m_s2: f64,
    /// Terminal interface \[m/s\]: the energy where the nominal flight slows to this speed
    /// (e.g. the start of the terminal area); absent: the scenario's own end.
    pub interface_speed_m_s: Option<f64>,
}

impl Default for DispersionSettings {
    fn default() -> Self {
        Self {
            cases: 100,
            seed: 20_261_130,
            altitude_km: Dispersion::normal(1.0),
            speed_m_s: Dispersion::normal(20.0),
            flight_path_angle_deg: Dispersion::normal(0.05),
            heading_deg: Dispersion::normal(0.2),
            latitude_deg: Dispersion::normal(0.1),
            longitude_deg: Dispersion::normal(0.1),
            density_bias: Dispersion::normal(0.10),
            density_wave: Dispersion::normal(0.10),
            density_wavelength_km: 20.0,
            lift: Dispersion::normal(0.05),
            drag: Dispersion::normal(0.05),
            mass: Dispersion::normal(0.03),
            imu_bias_m_s2: Dispersion::normal(0.01),
            imu_scale_factor: Dispersion::normal(0.001),
            imu_noise_m_s2: 0.005,
            interface_speed_m_s: None,
        }
    }
}

/// A validated distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Distribution {
    /// Gaussian truncated at 3 sigma, with this standard deviation.
    Normal {
        /// Standard deviation.
        sigma: f64,
    },
    /// Uniform with this half-width.
    Uniform {
        /// Half-width.
        half_width: f64,
    },
}

/// Most flights per mode of one campaign.
pub const MAX_CASES: u32 = 1_000_000;

impl DispersionSettings {
    /// The dispersions by field name (for validation and drawing, in a fixed order).
    #[must_use]
    pub fn fields(&self) -> [(&'static str, &Dispersion); 13] {
        [
            ("altitude_km", &self.altitude_km),
            ("speed_m_s", &self.speed_m_s),
            ("flight_path_angle_deg", &self.flight_path_angle_deg),
            ("heading_deg", &self.heading_deg),
            ("latitude_deg", &self.latitude_deg),
            ("longitude_deg", &self.longitude_deg),
            ("density_bias", &self.density_bias),
            ("density_wave", &self.density_wave),
            ("lift", &self.lift),
            ("drag", &self.drag),
            ("mass", &self.mass),
            ("imu_bias_m_s2", &self.imu_bias_m_s2),
            ("imu_scale_factor", &self.imu_scale_factor),
        ]
    }

    /// Check every field.
    ///
    /// # Errors
    /// [`CampaignError::Setting`] naming the field (`dispersions.<field>`) and the value: zero
    /// cases, a negative or non-finite 3-sigma value, an unknown distribution, a non-positive
    /// wavelength, a density or mass dispersion of 30 % or more at 3 sigma (the density scale is
    /// kept within [0.5, 1.5], the mass must stay positive), a bad guidance setting
    /// ([`CampaignGuidance::validate`](crate::scenario::guidance_layers::CampaignGuidance::validate)).
    pub fn validate(&self, file: &str) -> Result<(), CampaignError> {
        let bad = |field: &str, value: String, reason: &str| CampaignError::Setting {
            file: file.to_string(),
            field: format!("dispersions.{field}"),
            value,
            reason: reason.into(),
        };
        if self.cases == 0 {
            return Err(bad("cases", "0".into(), "at least one flight is needed"));
        }
        if self.cases > MAX_CASES {
            return Err(bad(
                "cases",
                self.cases.to_string(),
                "at most 1000000 flights per mode (-n)",
            ));
        }
        for (name, d) in self.fields() {
            distribution_of(d).map_err(|reason| {
                bad(
                    &format!("{name}.distribution"),
                    d.distribution.clone(),
                    reason,
                )
            })?;
            if !(d.three_sigma.is_finite() && d.three_sigma >= 0.0) {
                return Err(bad(
                    &format!("{name}.three_sigma"),
                    crate::num_fmt::compact(d.three_sigma),
                    "must be finite and >= 0",
                ));
            }
            // Absurd but finite spreads (a 3-sigma of 1e300 m/s) are refused with the range.
            let max = max_three_sigma(name);
            if d.three_sigma > max {
                return Err(bad(
                    &format!("{name}.three_sigma"),
                    crate::num_fmt::compact(d.three_sigma),
                    &format!("must be within [0, {}]", crate::num_fmt::compact(max)),
                ));
            }
        }
        for (name, d) in [
            ("density_bias", &self.density_bias),
            ("density_wave", &self.density_wave),
            ("mass", &self.mass),
        ] {
            if d.three_sigma >= 0.3 {
                return Err(bad(
                    &format!("{name}.three_sigma"),
                    crate::num_fmt::compact(d.three_sigma),
                    "must be < 0.3 (30 %)",
                ));
            }
        }
        if let Some(v) = self.interface_speed_m_s
            && !(v.is_finite() && v > 0.0)
        {
            return Err(bad(
                "interface_speed_m_s",
                crate::num_fmt::compact(v),
                "must be finite and > 0",
            ));
        }
        if !(self.imu_noise_m_s2.is_finite() && self.imu_noise_m_s2 >= 0.0) {
            return Err(bad(
                "imu_noise_m_s2",
                crate::num_fmt::compact(self.imu_noise_m_s2),
                "must be finite and >= 0",
            ));
        }
        if self.imu_scale_factor.three_sigma >= 0.3 {
            return Err(bad(
                "imu_scale_factor.three_sigma",
                crate::num_fmt::compact(self.imu_scale_factor.three_sigma),
                "must be < 0.3 (30 %)",
            ));
        }
        if !(self.density_wavelength_km.is_finite() && self.density_wavelength_km > 0.0) {
            return Err(bad(
                "density_wavelength_km",
                crate::num_fmt::compact(self.density_wavelength_km),
                "must be finite and > 0",
            ));
        }
        Ok(())
    }
}

/// Largest 3-sigma value of each dispersion, in the field's unit: a bound on absurd spreads
/// (a draw beyond it leaves any entry corridor or makes a coefficient negative), wide enough
/// for campaigns that probe failures on purpose.
fn max_three_sigma(name: &str) -> f64 {
    match name {
        "altitude_km" => 1000.0,
        "speed_m_s" => 5000.0,
        "flight_path_angle_deg" => 30.0,
        "heading_deg" | "latitude_deg" => 90.0,
        "longitude_deg" => 180.0,
        "lift" | "drag" => 0.9,
        "imu_bias_m_s2" => 10.0,
        // The density, wave, mass and IMU scale-factor bounds (< 0.3) are checked below.
        _ => 1.0,
    }
}

/// The validated distribution of `d`.
///
/// # Errors
/// A reason if the name is unknown.
pub fn distribution_of(d: &Dispersion) -> Result<Distribution, &'static str> {
    let sigma = d.three_sigma / 3.0;
    match d.distribution.as_str() {
        "normal" => Ok(Distribution::Normal { sigma }),
        "uniform" => Ok(Distribution::Uniform {
            half_width: sigma * 3f64.sqrt(),
        }),
        _ => Err("unknown distribution (known: normal, uniform)"),
    }
}

/// The settings file: an optional `[dispersions]` table (other tables, e.g. a scenario's, are
/// ignored).
#[derive(Debug, Default, Deserialize)]
struct SettingsFile {
    #[serde(default)]
    dispersions: DispersionSettings,
}

/// Parse the `[dispersions]` section of a TOML text (defaults for missing fields) and
/// validate it (through the one TOML reading path, [`crate::toml_input`]).
///
/// # Errors
/// [`CampaignError::Toml`] for bad TOML, [`CampaignError::Setting`] for an unknown or
/// mistyped field or a bad value (naming it).
pub fn parse_settings(text: &str, file: &str) -> Result<DispersionSettings, CampaignError> {
    if let Ok(doc) = text.parse::<toml::Table>()
        && let Some(old) = doc
            .get("dispersions")
            .and_then(|d| d.get("guidance"))
            .and_then(toml::Value::as_table)
    {
        return Err(moved_guidance(old, file));
    }
    let (f, _): (SettingsFile, _) = crate::toml_input::parse(text).map_err(|e| match e {
        TomlInputError::Syntax(source) => CampaignError::Toml {
            file: file.into(),
            source,
        },
        TomlInputError::Field {
            field,
            value,
            reason,
        } => CampaignError::Setting {
            file: file.into(),
            field,
            value,
            reason,
        },
    })?;
    f.dispersions.validate(file)?;
    Ok(f.dispersions)
}

/// The error for a `[dispersions.guidance]` table (the guidance is the scenario's now): each
/// key it holds with its scenario key.
fn moved_guidance(old: &toml::Table, file: &str) -> CampaignError {
    let moved: Vec<String> = old
        .keys()
        .map(|k| {
            let new = scenario_key(k);
            if new == *k {
                format!("{k}: no such setting")
            } else {
                let (section, key) = new
                    .strip_prefix("guidance.")
                    .and_then(|r| r.split_once('.'))
                    .unwrap_or(("?", k));
                format!("{k} -> [guidance.{section}] {key}")
            }
        })
        .collect();
    CampaignError::Setting {
        file: file.into(),
        field: "dispersions.guidance".into(),
        value: format!("{{{}}}", old.keys().cloned().collect::<Vec<_>>().join(", ")),
        reason: format!(
            "the guidance is written in the scenario now, one section per layer (a layer \
             absent is off; docs/reference/guidance-stack.md): {}",
            moved.join("; ")
        ),
    }
}
