//! `host-sim dispersions`: a Monte Carlo campaign of one scenario (docs/reference/campaigns.md).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use super::error::CliError;
use crate::campaign::output::write_campaign;
use crate::campaign::run::{Replay, replay_case};
use crate::campaign::{Campaign, CampaignSetup, DispersionSettings, Mode, parse_settings};
use crate::pil::{
    PilCaseCheck, PilConfig, PilError, check_pil_cases, fly_campaign_pil, machine_of_elf, pil_mode,
    write_pil_checks,
};
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
    /// Processor in the loop: after the campaign, fly its nominal flight and cases 0..K
    /// (`--pil-cases K`) again with the guidance in this `pil` firmware ELF under QEMU, in the
    /// fullest re-planning mode of `--modes`, and compare each with its SIL record (twin bit
    /// for bit, same reversals and re-plans, same ending, miss within the re-planner's plus
    /// the terminal law's tolerance). Writes `pil-cases.csv`; exits non-zero if a flight
    /// breaks a tolerance (docs/guides/pil.md).
    #[arg(
        long,
        value_name = "ELF",
        requires = "pil_cases",
        conflicts_with = "case"
    )]
    pub pil: Option<PathBuf>,
    /// With --pil: how many of the campaign's cases (from 0) to fly in PIL, 1 to -n.
    #[arg(long, value_name = "K", requires = "pil")]
    pub pil_cases: Option<u32>,
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
    let modes = a
        .modes
        .iter()
        .map(|m| Mode::by_name(m))
        .collect::<Result<Vec<_>, _>>()?;
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
    let campaign = Campaign::new(&sc, &file, settings, "command line", modes)?;
    let (setup, settings, modes) = (campaign.setup(), campaign.settings(), campaign.modes());
    if let Some(index) = a.case {
        return replay(setup, settings, modes, index, &dir, out);
    }
    // The PIL leg's inputs, checked before the campaign flies.
    let pil = match (&a.pil, a.pil_cases) {
        (Some(elf), Some(k)) => {
            check_pil_cases(k, settings)?;
            let cfg = PilConfig::new(elf.clone());
            cfg.check_tools().map_err(|e| match e {
                PilError::ElfMissing(p) => CliError::Argument {
                    field: "--pil",
                    value: p.display().to_string(),
                    reason: "no such firmware ELF (build it: cargo xtask pil, or cargo build -p \
                             onboard-demo --profile firmware --target thumbv7em-none-eabihf: \
                             target/thumbv7em-none-eabihf/firmware/pil)",
                },
                e => CliError::Pil(e),
            })?;
            Some((cfg, k, pil_mode(setup, modes)?))
        }
        _ => None,
    };
    let progress = !a.quiet && std::io::stderr().is_terminal();
    let res = campaign.run(Some(dir.clone()), a.threads, progress)?;
    let files = write_campaign(&dir, setup, settings, &res)?;
    let wall = started.elapsed().as_secs_f64();
    let flown = settings.cases as usize * modes.len() - res.resumed;
    writeln!(
        out,
        "{}: {} cases x {} modes ({} resumed) in {wall:.1} s ({:.2} flights/s); target {:.3} deg, {:.3} deg, downrange {:.1} km",
        sc.name,
        settings.cases,
        modes.len(),
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
    match pil {
        Some((cfg, k, mode)) => pil_leg(setup, settings, &res, mode, k, &cfg, &dir, out),
        None => Ok(()),
    }
}

/// `--pil ELF --pil-cases K`: the campaign's PIL leg ([`fly_campaign_pil`]), one line per
/// flight, `pil-cases.csv` in `dir`; an error if a flight breaks a tolerance.
#[allow(clippy::too_many_arguments)]
fn pil_leg(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    res: &crate::campaign::run::CampaignOutput,
    mode: Mode,
    k: u32,
    cfg: &PilConfig,
    dir: &std::path::Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let started = std::time::Instant::now();
    let machine = machine_of_elf(&cfg.elf);
    writeln!(
        out,
        "PIL: {} ({}), {}: the nominal flight and {} against their SIL records",
        cfg.elf.display(),
        machine.description,
        mode.name(),
        if k == 1 {
            "case 0".to_string()
        } else {
            format!("cases 0-{}", k - 1)
        }
    )?;
    let checks = fly_campaign_pil(setup, settings, res, mode, k, cfg)?;
    for c in &checks {
        writeln!(out, "{}", pil_line(c))?;
    }
    let file = write_pil_checks(dir, &checks)?;
    let failed = checks.iter().filter(|c| !c.passed()).count();
    writeln!(
        out,
        "PIL: {} of {} flights within the tolerances in {:.1} s; wrote {}",
        checks.len() - failed,
        checks.len(),
        started.elapsed().as_secs_f64(),
        file.display()
    )?;
    if failed > 0 {
        return Err(CliError::PilTolerance {
            failed,
            total: checks.len(),
            file,
        });
    }
    Ok(())
}

/// One flight of the PIL leg, as printed.
fn pil_line(c: &PilCaseCheck) -> String {
    let case = c
        .index
        .map_or_else(|| "nominal".to_string(), |i| format!("case {i}"));
    match &c.outcome {
        Err(e) => format!("  {case:<10} FAILED: {e}"),
        Ok(s) => format!(
            "  {case:<10} twin {}/{} ticks equal; reversals {}/{}, re-plans {}/{} (PIL/SIL): {}; \
             interface {}/{}; miss {:.3}/{:.3} km, |diff| {:.3} km (bound {:.3} km): {}",
            s.twin.ticks - s.twin.mismatches,
            s.twin.ticks,
            s.pil_reversals,
            s.sil_reversals,
            s.pil_replans,
            s.sil_replans,
            if s.same_counts { "same" } else { "DIFFER" },
            s.pil_reached_interface,
            s.sil_reached_interface,
            s.pil_miss_m / 1e3,
            s.sil_miss_m / 1e3,
            s.miss_diff_m / 1e3,
            s.bound_m / 1e3,
            if c.passed() { "ok" } else { "OUTSIDE" },
        ),
    }
}
