//! `host-sim vehicles`: the built-in vehicles as CSV.

use std::io::Write;

use super::error::CliError;
use crate::vehicle;

/// Run `vehicles`, writing the CSV to `out`.
pub(super) fn run(out: &mut dyn Write) -> Result<(), CliError> {
    writeln!(
        out,
        "name,mass_kg,reference_area_m2,nose_radius_m,max_heat_flux_kw_m2,max_g_load,max_g_load_rate_per_s"
    )?;
    for n in vehicle::list() {
        let v = vehicle::by_name(n)?;
        writeln!(
            out,
            "{},{},{},{},{},{},{}",
            v.name,
            v.mass_kg,
            v.reference_area_m2,
            v.nose_radius_m,
            v.limits.heat_flux_w_m2 / 1e3,
            v.limits.g_load,
            v.limits.g_load_rate_per_s
        )?;
    }
    Ok(())
}
