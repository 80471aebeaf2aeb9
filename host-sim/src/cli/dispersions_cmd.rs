//! `host-sim dispersions`: a Monte Carlo campaign of one scenario (docs/reference/campaigns.md).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use super::error::CliError;
use crate::campaign::output::write_campaign;
use crate::campaign::run::{Replay, RunOptions, replay_case};
use crate::campaign::{CampaignSetup, DispersionSettings, Mode, parse_settings, run_campaign};
use crate::scenario::{Scenario, read_scenario};

/// Arguments of `dispersions`.
#[derive(Debug, clap::Args)]
pub struct DispersionsArgs {
    /// Scenario TOML file (default: built-in HORUS-2B reference mission).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Built-in scenario instead of a file: horus-2b-reference (default) or srm-glide.
    #[arg(long, value_name = "NAME", conflicts_with = "scenario")]
    pub builtin: Option<String>,
    /// TOML file with a `[dispersions]` section (default: the documented defaults).
    #[arg(long, value_name = "FILE")]
    pub settings: Option<PathBuf>,
    /// Number of flights per mode (overrides the settings).
    #[arg(long, short = 'n')]
    pub cases: Option<u32>,
    /// Terminal interface speed [m/s] (overrides the settings; default: the scenario's end).
    #[arg(long, value_name = "M/S")]
    pub interface_speed: Option<f64>,
    /// Seed (overrides the settings).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Modes: stored, stored-reversals, replan-reversals, replan-estimation (comma separated;
    /// default all).
    #[arg(long, value_delimiter = ',')]
    pub modes: Vec<String>,
    /// Output directory (default: `runs/dispersions-<scenario>/`); case results there are
    /// reused (resume).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Do not show a progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Fly only case ID (from 0) of the campaign, in each mode, and compare each record with
    /// the one in the output directory (`--out`): "reproduces" when byte for byte equal.
    #[arg(long, value_name = "ID")]
    pub case: Option<u32>,
}

/// Wrap a campaign error for the CLI.
impl From<crate::campaign::CampaignError> for CliError {
    fn from(e: crate::campaign::CampaignError) -> Self {
        CliError::Campaign(Box::new(e))
    }
}

/// `--case ID`: fly the case alone in each mode, print its record and whether it reproduces
/// the one in `dir`.
fn replay(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    modes: &[Mode],
    index: u32,
    dir: &std::path::Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let mut differ = Vec::new();
    for &mode in modes {
        let (r, found) = replay_case(setup, settings, mode, index, Some(dir))?;
        writeln!(
            out,
            "{}: case {index} {}: miss {:.3} km, {} reversals, {} re-plans: {}",
            setup.scenario.name,
            mode.name(),
            r.miss_m / 1e3,
            r.reversals,
            r.replans,
            match found {
                Replay::Same => "reproduces its record bit for bit",
                Replay::Differs => "DIFFERS from its record",
                Replay::NoRecord => "no record in the output directory",
            }
        )?;
        if found == Replay::Differs {
            differ.push(mode.name());
        }
    }
    if differ.is_empty() {
        Ok(())
    } else {
        Err(CliError::Argument {
            field: "case",
            value: index.to_string(),
            reason: "the replayed flight differs from the record in the output directory \
                     (other inputs, or other code)",
        })
    }
}

/// Run the command.
///
/// # Errors
/// [`CliError`] naming the file, field and value of a bad input.
pub fn run(a: &DispersionsArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (sc, file) = match (&a.scenario, &a.builtin) {
        (Some(p), _) => (read_scenario(p)?, p.display().to_string()),
        (None, Some(name)) => (Scenario::try_builtin(name)?, format!("builtin:{name}")),
        (None, None) => (Scenario::default(), "builtin:horus-2b-reference".into()),
    };
    let mut settings = match &a.settings {
        Some(p) => {
            let f = p.display().to_string();
            let text = std::fs::read_to_string(p)?;
            let settings = parse_settings(&text, &f)?;
            // A settings file states its settings: without the section it would silently run
            // the defaults (a misspelt or missing table).
            if text
                .parse::<toml::Table>()
                .is_ok_and(|t| !t.contains_key("dispersions"))
            {
                return Err(crate::campaign::CampaignError::Setting {
                    file: f,
                    field: "dispersions".into(),
                    value: "(missing)".into(),
                    reason: "the file has no [dispersions] section; write the settings under \
                             [dispersions] (or drop --settings for the documented defaults)"
                        .into(),
                }
                .into());
            }
            settings
        }
        None => DispersionSettings::default(),
    };
    if let Some(n) = a.cases {
        settings.cases = n;
    }
    if let Some(v) = a.interface_speed {
        settings.interface_speed_m_s = Some(v);
    }
    if let Some(s) = a.seed {
        settings.seed = s;
    }
    settings.validate("command line")?;
    let mut modes = Vec::new();
    for m in &a.modes {
        let mode = Mode::ALL
            .into_iter()
            .find(|x| x.name() == m)
            .ok_or_else(|| CliError::Argument {
                field: "modes",
                value: m.clone(),
                reason: "unknown mode (stored, stored-reversals, replan-reversals, replan-estimation)",
            })?;
        modes.push(mode);
    }
    if a.threads == Some(0) {
        return Err(CliError::Argument {
            field: "threads",
            value: "0".into(),
            reason: "must be >= 1",
        });
    }
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("runs").join(format!("dispersions-{}", sc.name)));
    let started = std::time::Instant::now();
    let setup = CampaignSetup::new(&sc, &file, settings.interface_speed_m_s)?;
    if modes.is_empty() {
        modes = setup.modes();
    }
    setup.check_modes(&modes)?;
    if let Some(index) = a.case {
        return replay(&setup, &settings, &modes, index, &dir, out);
    }
    let opts = RunOptions {
        modes,
        out_dir: Some(dir.clone()),
        threads: a.threads,
        progress: !a.quiet && std::io::stderr().is_terminal(),
    };
    let res = run_campaign(&setup, &settings, &opts)?;
    let files = write_campaign(&dir, &setup, &settings, &res)?;
    let wall = started.elapsed().as_secs_f64();
    let flown = settings.cases as usize * opts.modes.len() - res.resumed;
    writeln!(
        out,
        "{}: {} cases x {} modes ({} resumed) in {wall:.1} s ({:.2} flights/s); target {:.3} deg, {:.3} deg, downrange {:.1} km",
        sc.name,
        settings.cases,
        opts.modes.len(),
        res.resumed,
        flown as f64 / wall.max(1e-9),
        setup.target().latitude_rad.to_degrees(),
        setup.target().longitude_rad.to_degrees(),
        setup.target_downrange_rad * setup.planet_radius_m / 1e3
    )?;
    writeln!(
        out,
        "{:<18} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} | {:>6} {:>6} {:>6} | >5%: q g gdot | rev  replans fallbk | failed | nominal miss",
        "mode",
        "mean km",
        "std km",
        "p50 km",
        "p95 km",
        "p99 km",
        "worst km",
        "q/lim",
        "g/lim",
        "gd/lim"
    )?;
    for (s, nom) in res.stats.iter().zip(&res.nominal) {
        writeln!(
            out,
            "{:<18} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>9.2} | {:>6.3} {:>6.3} {:>6.3} | {:>3} {:>3} {:>3}  | {:>4.1} {:>7.1} {:>6.1} | {:>6} | {:.2} km",
            s.mode.name(),
            s.miss_km.mean,
            s.miss_km.std,
            s.miss_km.p50,
            s.miss_km.p95,
            s.miss_km.p99,
            s.miss_km.worst,
            s.heat_flux_ratio.worst,
            s.g_load_ratio.worst,
            s.g_load_rate_ratio.worst,
            s.over_limit_5pct[0],
            s.over_limit_5pct[1],
            s.over_limit_5pct[2],
            s.reversals.mean,
            s.replans.mean,
            s.fall_backs.mean,
            s.failed,
            nom.miss_m / 1e3
        )?;
    }
    for f in res.failed.iter().take(10) {
        writeln!(
            out,
            "FAILED {} case {}: {}",
            f.mode.name(),
            f.index,
            f.error
        )?;
    }
    if !res.failed.is_empty() {
        writeln!(
            out,
            "{} flights failed (recorded in summary.json; not in the statistics)",
            res.failed.len()
        )?;
    }
    writeln!(out, "wrote {} files to {}", files.len(), dir.display())?;
    Ok(())
}
