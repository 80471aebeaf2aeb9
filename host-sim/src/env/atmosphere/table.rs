//! A tabulated atmosphere read from a CSV file (for other planets, or measured profiles):
//! density interpolated log-linearly in altitude (exact for an exponential layer), temperature
//! linearly; pressure `p = rho R T` and speed of sound `a = sqrt(gamma R T)` with the gas
//! constant `R` and heat-capacity ratio `gamma` given with the table.
//!
//! File: a header line naming the columns, then one row per altitude (strictly increasing);
//! `#` starts a comment line. Columns: `altitude_m` (or `altitude_km`), `density_kg_m3`, and
//! one of `temperature_k` or `speed_of_sound_m_s` (then `T = a^2 / (gamma R)`).
//!
//! ```text
//! altitude_km,density_kg_m3,temperature_k
//! 0,1.225,288.15
//! 10,0.41351,223.25
//! ```
//!
//! Below the first altitude the first row holds; above the last the density and pressure are
//! zero (the [`Atmosphere`] contract) and the temperature holds.

use std::path::Path;

use super::{Atmosphere, AtmosphereState};

/// A tabulated atmosphere (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct TabulatedAtmosphere {
    altitude_m: Vec<f64>,
    ln_density: Vec<f64>,
    temperature_k: Vec<f64>,
    gas_constant_j_kg_k: f64,
    heat_capacity_ratio: f64,
}

/// Why an atmosphere table was rejected; names the file, the line and the value.
#[derive(Debug, thiserror::Error)]
pub enum TableAtmosphereError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Read {
        /// File name as given.
        file: String,
        /// Operating-system error.
        source: std::io::Error,
    },
    /// A header, row or value is wrong.
    #[error("{file}: line {line}: `{value}`: {reason}")]
    Content {
        /// File name as given.
        file: String,
        /// 1-based line number (0: the whole file).
        line: usize,
        /// The offending text.
        value: String,
        /// What is required.
        reason: &'static str,
    },
}

/// Which thermal column the table has.
#[derive(Clone, Copy)]
enum Thermal {
    Temperature,
    SpeedOfSound,
}

impl TabulatedAtmosphere {
    /// Parse a table from CSV text (`file` names it in errors) with gas constant
    /// `gas_constant_j_kg_k` \[J/(kg K)\] and heat-capacity ratio `heat_capacity_ratio` \[-\].
    ///
    /// # Errors
    /// [`TableAtmosphereError::Content`] for a bad header, row, value or order, or fewer than
    /// two rows, or non-positive gas constants.
    pub fn from_csv_str(
        text: &str,
        file: &str,
        gas_constant_j_kg_k: f64,
        heat_capacity_ratio: f64,
    ) -> Result<Self, TableAtmosphereError> {
        let err = |line: usize, value: &str, reason: &'static str| TableAtmosphereError::Content {
            file: file.to_string(),
            line,
            value: value.to_string(),
            reason,
        };
        for (name, v) in [
            ("gas_constant_j_kg_k", gas_constant_j_kg_k),
            ("heat_capacity_ratio", heat_capacity_ratio),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(err(
                    0,
                    &format!("{name} = {}", crate::num_fmt::Compact(v)),
                    "must be finite and positive",
                ));
            }
        }
        let mut rows = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (hline, header) = rows.next().ok_or_else(|| err(0, "", "empty table"))?;
        let cols: Vec<&str> = header.split(',').map(str::trim).collect();
        let (alt_scale, thermal) = match cols[..] {
            ["altitude_m", "density_kg_m3", "temperature_k"] => (1.0, Thermal::Temperature),
            ["altitude_km", "density_kg_m3", "temperature_k"] => (1e3, Thermal::Temperature),
            ["altitude_m", "density_kg_m3", "speed_of_sound_m_s"] => (1.0, Thermal::SpeedOfSound),
            ["altitude_km", "density_kg_m3", "speed_of_sound_m_s"] => (1e3, Thermal::SpeedOfSound),
            _ => {
                return Err(err(
                    hline,
                    header,
                    "header must be altitude_m|altitude_km, density_kg_m3, temperature_k|speed_of_sound_m_s",
                ));
            }
        };
        let mut t = Self {
            altitude_m: Vec::new(),
            ln_density: Vec::new(),
            temperature_k: Vec::new(),
            gas_constant_j_kg_k,
            heat_capacity_ratio,
        };
        for (line, row) in rows {
            let vals: Vec<Option<f64>> = row.split(',').map(|c| c.trim().parse().ok()).collect();
            let [Some(h), Some(rho), Some(th)] = vals[..] else {
                return Err(err(line, row, "needs three numbers"));
            };
            let h = h * alt_scale;
            if !(h.is_finite() && rho.is_finite() && rho > 0.0 && th.is_finite() && th > 0.0) {
                return Err(err(
                    line,
                    row,
                    "altitude must be finite; density and temperature (or speed of sound) finite and positive",
                ));
            }
            if t.altitude_m.last().is_some_and(|&prev| h <= prev) {
                return Err(err(line, row, "altitudes must increase strictly"));
            }
            let temperature = match thermal {
                Thermal::Temperature => th,
                Thermal::SpeedOfSound => th * th / (heat_capacity_ratio * gas_constant_j_kg_k),
            };
            t.altitude_m.push(h);
            t.ln_density.push(rho.ln());
            t.temperature_k.push(temperature);
        }
        if t.altitude_m.len() < 2 {
            return Err(err(0, header, "needs at least two rows"));
        }
        Ok(t)
    }

    /// Read a table from a CSV file (see [`TabulatedAtmosphere::from_csv_str`]).
    ///
    /// # Errors
    /// [`TableAtmosphereError`] naming the file.
    pub fn from_csv_file(
        path: &Path,
        gas_constant_j_kg_k: f64,
        heat_capacity_ratio: f64,
    ) -> Result<Self, TableAtmosphereError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| TableAtmosphereError::Read {
            file: file.clone(),
            source,
        })?;
        Self::from_csv_str(&text, &file, gas_constant_j_kg_k, heat_capacity_ratio)
    }

    /// Gas constant \[J/(kg K)\].
    #[must_use]
    pub fn gas_constant_j_kg_k(&self) -> f64 {
        self.gas_constant_j_kg_k
    }

    /// Heat-capacity ratio \[-\].
    #[must_use]
    pub fn heat_capacity_ratio(&self) -> f64 {
        self.heat_capacity_ratio
    }

    fn state_of(&self, rho: f64, temperature_k: f64) -> AtmosphereState {
        let r = self.gas_constant_j_kg_k;
        AtmosphereState {
            temperature_k,
            pressure_pa: rho * r * temperature_k,
            density_kg_m3: rho,
            speed_of_sound_m_s: (self.heat_capacity_ratio * r * temperature_k).sqrt(),
        }
    }
}

impl Atmosphere for TabulatedAtmosphere {
    fn state(&self, altitude_m: f64) -> AtmosphereState {
        let h = &self.altitude_m;
        let n = h.len();
        if altitude_m.is_nan() {
            return AtmosphereState {
                temperature_k: f64::NAN,
                pressure_pa: f64::NAN,
                density_kg_m3: f64::NAN,
                speed_of_sound_m_s: f64::NAN,
            };
        }
        let (Some(&first), Some(&last)) = (h.first(), h.last()) else {
            return self.state_of(0.0, 0.0);
        };
        if altitude_m <= first {
            return self.state_of(self.ln_density[0].exp(), self.temperature_k[0]);
        }
        if altitude_m > last {
            let t = self.temperature_k[n - 1];
            let mut s = self.state_of(0.0, t);
            s.pressure_pa = 0.0;
            return s;
        }
        // First index with h[i] >= altitude (1..n-1).
        let i = h.partition_point(|&x| x < altitude_m).clamp(1, n - 1);
        let f = (altitude_m - h[i - 1]) / (h[i] - h[i - 1]);
        let ln_rho = self.ln_density[i - 1] + f * (self.ln_density[i] - self.ln_density[i - 1]);
        let t = self.temperature_k[i - 1] + f * (self.temperature_k[i] - self.temperature_k[i - 1]);
        self.state_of(ln_rho.exp(), t)
    }

    fn name(&self) -> &'static str {
        "table"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CSV: &str = "# two layers\naltitude_km,density_kg_m3,temperature_k\n0,1.0,300\n10,0.1,200\n20,0.01,200\n";

    #[test]
    fn interpolates_density_log_linearly_and_temperature_linearly() {
        let t = TabulatedAtmosphere::from_csv_str(CSV, "a.csv", 287.0, 1.4).unwrap();
        let s = t.state(5_000.0);
        assert!((s.density_kg_m3 - 0.1f64.sqrt()).abs() < 1e-12);
        assert!((s.temperature_k - 250.0).abs() < 1e-9);
        assert!((s.pressure_pa - s.density_kg_m3 * 287.0 * 250.0).abs() < 1e-9);
        assert!((s.speed_of_sound_m_s - (1.4f64 * 287.0 * 250.0).sqrt()).abs() < 1e-9);
        assert_eq!(t.state(-5.0).density_kg_m3, 1.0);
        assert_eq!(t.state(10_000.0).density_kg_m3, 0.1f64.ln().exp());
        let top = t.state(25_000.0);
        assert_eq!((top.density_kg_m3, top.pressure_pa), (0.0, 0.0));
        assert!(t.state(f64::NAN).density_kg_m3.is_nan());
    }

    #[test]
    fn speed_of_sound_column_gives_the_temperature() {
        let csv = "altitude_m,density_kg_m3,speed_of_sound_m_s\n0,0.02,240\n1000,0.018,238\n";
        let t = TabulatedAtmosphere::from_csv_str(csv, "mars.csv", 188.9, 1.29).unwrap();
        assert!((t.state(0.0).speed_of_sound_m_s - 240.0).abs() < 1e-9);
    }

    #[test]
    fn bad_tables_name_file_line_and_value() {
        let e = |text: &str| {
            TabulatedAtmosphere::from_csv_str(text, "t.csv", 287.0, 1.4)
                .unwrap_err()
                .to_string()
        };
        let m = e("altitude_m,rho\n0,1\n");
        assert!(
            m.contains("t.csv") && m.contains("line 1") && m.contains("header"),
            "{m}"
        );
        let m = e("altitude_m,density_kg_m3,temperature_k\n0,1,300\n0,0.5,300\n");
        assert!(
            m.contains("line 3") && m.contains("0,0.5,300") && m.contains("increase"),
            "{m}"
        );
        let m = e("altitude_m,density_kg_m3,temperature_k\n0,-1,300\n10,0.5,300\n");
        assert!(m.contains("line 2") && m.contains("positive"), "{m}");
        let m = e("altitude_m,density_kg_m3,temperature_k\n0,1,300\n");
        assert!(m.contains("two rows"), "{m}");
        let m = e("altitude_m,density_kg_m3,temperature_k\n0,1,x\n1,1,1\n");
        assert!(m.contains("three numbers"), "{m}");
    }
}
