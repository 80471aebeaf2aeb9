//! `host-sim atmosphere`: an atmosphere model's state at altitudes given in km, as CSV.

use std::io::Write;

use clap::ValueEnum;

use super::error::CliError;
use crate::env::{Atmosphere, ExponentialAtmosphere, Us76};

/// Atmosphere model choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AtmosphereModel {
    /// U.S. Standard Atmosphere 1976.
    Us76,
    /// Exponential, rho0 = 1.225 kg/m^3, H = 7.2 km.
    Exponential,
}

/// Arguments of `atmosphere`.
#[derive(Debug, clap::Args)]
pub struct AtmosphereArgs {
    /// Model.
    #[arg(long, value_enum, default_value = "us76")]
    pub model: AtmosphereModel,
    /// Altitudes (km) (default 0, 10, ..., 120).
    #[arg(value_name = "ALTITUDE_KM", allow_negative_numbers = true)]
    pub altitudes_km: Vec<f64>,
}

/// Run `atmosphere` with arguments `a`, writing the CSV to `out`.
pub(super) fn run(a: AtmosphereArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let model: Box<dyn Atmosphere> = match a.model {
        AtmosphereModel::Us76 => Box::new(Us76::new()),
        AtmosphereModel::Exponential => Box::new(ExponentialAtmosphere::earth()),
    };
    let alts = if a.altitudes_km.is_empty() {
        (0..=12).map(|k| f64::from(k) * 10.0).collect()
    } else {
        a.altitudes_km
    };
    writeln!(
        out,
        "altitude_km,temperature_k,pressure_pa,density_kg_m3,speed_of_sound_m_s"
    )?;
    for h in alts {
        if !h.is_finite() || !(-5.0..=1000.0).contains(&h) {
            return Err(CliError::Argument {
                field: "ALTITUDE_KM",
                value: h.to_string(),
                reason: "must be within [-5, 1000] km",
            });
        }
        let st = model.state(h * 1e3);
        writeln!(
            out,
            "{h},{:.4},{:.6e},{:.6e},{:.3}",
            st.temperature_k, st.pressure_pa, st.density_kg_m3, st.speed_of_sound_m_s
        )?;
    }
    Ok(())
}
