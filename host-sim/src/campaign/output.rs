//! Writing a campaign: `summary.json` (settings, target, statistics per mode, nominal flights,
//! failed cases with their errors),
//! `cases-<mode>.csv` (one row per flight) and the report's figures per mode (SVG and PNG,
//! [`super::report`]), each written atomically.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::report::report_files;
use super::run::{CampaignOutput, CaseFailure};
use super::settings::DispersionSettings;
use super::setup::CampaignSetup;
use super::stats::ModeStats;
use super::{CampaignError, CaseResult};
use crate::report::write_atomic;

#[derive(Serialize)]
struct Summary<'a> {
    scenario: &'a str,
    settings: &'a DispersionSettings,
    target_latitude_deg: f64,
    target_longitude_deg: f64,
    target_downrange_km: f64,
    interface_speed_m_s: f64,
    /// The nominal flight's altitude there \[m\].
    interface_altitude_m: f64,
    /// Its E-hat there (of the nominal entry) \[-\].
    interface_normalized_energy: f64,
    /// The interface as given (`null`: the nominal end).
    interface: Option<crate::scenario::TerminalInterface>,
    nominal: &'a [CaseResult],
    stats: &'a [ModeStats],
    failed: &'a [CaseFailure],
}

/// Write the campaign into `dir`; returns the files written.
///
/// # Errors
/// [`CampaignError::Report`] naming the path.
pub fn write_campaign(
    dir: &Path,
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    out: &CampaignOutput,
) -> Result<Vec<PathBuf>, CampaignError> {
    // The figures first: their replayed flights end early on a stop request (Ctrl-C), and
    // then nothing of the campaign is written (no summary of an interrupted run).
    let figures = report_files(setup, settings, out)?;
    let mut files = Vec::new();
    let r = setup.planet_radius_m;
    let s = Summary {
        scenario: &setup.scenario.name,
        settings,
        target_latitude_deg: setup.target().latitude_rad.to_degrees(),
        target_longitude_deg: setup.target().longitude_rad.to_degrees(),
        target_downrange_km: setup.target_downrange_rad * r / 1e3,
        interface_speed_m_s: setup.interface_speed_m_s,
        interface_altitude_m: setup.interface_altitude_m(),
        interface_normalized_energy: setup.interface_normalized_energy(),
        interface: setup.interface,
        nominal: &out.nominal,
        stats: &out.stats,
        failed: &out.failed,
    };
    let p = dir.join("summary.json");
    let json = serde_json::to_vec_pretty(&s).map_err(crate::report::ReportError::from)?;
    write_atomic(&p, &json)?;
    files.push(p);
    for (m, cases) in &out.cases {
        let mut csv = String::from(
            "index,miss_km,downrange_km,crossrange_km,peak_heat_flux_kw_m2,peak_g_load,\
             peak_g_load_rate_per_s,reversals,replans,fall_backs,reached_interface,\
             final_altitude_km,final_speed_m_s,flight_time_s\n",
        );
        for c in cases {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                c.index,
                c.miss_m / 1e3,
                c.downrange_error_m / 1e3,
                c.crossrange_error_m / 1e3,
                c.peak_heat_flux_w_m2 / 1e3,
                c.peak_g_load,
                c.peak_g_load_rate_per_s,
                c.reversals,
                c.replans,
                c.fall_backs,
                c.reached_interface,
                c.final_altitude_m / 1e3,
                c.final_speed_m_s,
                c.flight_time_s
            );
        }
        let p = dir.join(format!("cases-{}.csv", m.name()));
        write_atomic(&p, csv.as_bytes())?;
        files.push(p);
    }
    for (name, bytes) in figures {
        let p = dir.join(name);
        write_atomic(&p, &bytes)?;
        files.push(p);
    }
    Ok(files)
}
