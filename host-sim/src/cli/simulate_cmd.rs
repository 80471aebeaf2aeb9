//! `host-sim simulate`: load (or pick) a scenario, print it or fly it with a progress bar, and
//! print the one-line summary.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use super::error::CliError;
use crate::scenario::{
    Flight, RunOutput, Scenario, read_scenario, scenario_to_toml, simulate_scenario, write_flight,
};
use crate::{pil, report};

/// Arguments of `simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// Scenario TOML file (default: built-in HORUS-2B reference mission).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Output directory (default: `runs/<scenario-name>/`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Built-in scenario instead of a file: horus-2b-reference (default) or srm-glide.
    #[arg(long, value_name = "NAME", conflicts_with = "scenario")]
    pub builtin: Option<String>,
    /// Print the scenario (default or loaded) as annotated TOML (each key's unit, range and default; file paths absolute) and exit without simulating.
    #[arg(long)]
    pub print_scenario: bool,
    /// Do not show a progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Processor in the loop: fly the scenario with the guidance of this firmware ELF
    /// (`onboard-demo`'s `pil` binary) running in QEMU (see `host_sim::pil`): the stack the
    /// scenario flies in SIL is uploaded as one set-up image; a hard-float ELF runs on the
    /// Cortex-M4F (`f32`), a soft-float one on the Cortex-M3 (fixed-point tick, `f32` layers).
    #[arg(long, value_name = "ELF")]
    pub pil: Option<PathBuf>,
    /// With --pil: inject seeded link faults on the nav frames, each of drop, corruption and
    /// delay past the tick with this probability (0 to 0.3).
    #[arg(long, value_name = "P", requires = "pil")]
    pub pil_fault_rate: Option<f64>,
    /// Seed of the fault injector (with --pil-fault-rate).
    #[arg(
        long,
        value_name = "SEED",
        default_value_t = 1,
        requires = "pil_fault_rate"
    )]
    pub pil_fault_seed: u64,
}

/// Fly scenario `sc` in PIL with firmware `elf`, write the run directory and print the link
/// statistics.
fn pil_run(
    sc: &Scenario,
    file: &str,
    elf: &Path,
    faults: Option<pil::FaultConfig>,
    dir: &Path,
    out: &mut dyn Write,
) -> Result<RunOutput, CliError> {
    let started = std::time::Instant::now();
    let mut cfg = pil::PilConfig::new(elf.to_path_buf());
    cfg.faults = faults;
    let (run, record) = pil::fly_scenario_pil(sc, file, cfg);
    let pil::ScenarioPil {
        result,
        stats,
        twin,
        stack,
        image_bytes,
    } = match run {
        Ok(r) => r,
        Err(e) => {
            // Keep the record up to the failure, marked, beside (not in) the run directory.
            let failed = failed_record_path(dir);
            if !record.exchanges().is_empty() {
                if let Some(parent) = failed.parent().filter(|p| !p.as_os_str().is_empty()) {
                    std::fs::create_dir_all(parent)?;
                }
                crate::report::write_atomic(&failed, record.to_csv().as_bytes())?;
                writeln!(
                    out,
                    "PIL run failed; frames exchanged up to the failure (marked): {}",
                    failed.display()
                )?;
            }
            return Err(e.into());
        }
    };
    let wall = started.elapsed().as_secs_f64();
    writeln!(
        out,
        "PIL: {} frames with {} in {wall:.2} s ({:.0} frames/s); firmware stack {}",
        stats.frames,
        elf.display(),
        stats.frames as f64 / wall.max(1e-9),
        stats
            .firmware_stack_bytes
            .map_or_else(|| "not reported".to_string(), |b| format!("{b} bytes"))
    )?;
    if let (Some(ticks), Some(overruns), Some(max_us)) = (
        stats.firmware_ticks,
        stats.firmware_overruns,
        stats.firmware_max_tick_us,
    ) {
        writeln!(
            out,
            "PIL tick timing (firmware tick timer; under QEMU emulator wall time): {ticks} ticks, {overruns} over the guidance period, longest {max_us} us"
        )?;
    }
    writeln!(
        out,
        "PIL set-up image {image_bytes} B; host twin (the image in the firmware's scalars): {} of {} ticks differ{}",
        twin.mismatches,
        twin.ticks,
        twin.first
            .as_ref()
            .map_or_else(String::new, |(t, what)| format!(
                ", first at t = {t} s: {what}"
            ))
    )?;
    if faults.is_some() {
        let f = stats.faults;
        writeln!(
            out,
            "PIL link faults: {} dropped, {} corrupted, {} delayed past their tick; {} retries, {} ticks on the held command; firmware counted {}",
            f.dropped,
            f.corrupted,
            f.delayed,
            f.retries,
            f.missed_ticks,
            stats
                .firmware_faults
                .map_or_else(|| "?".to_string(), |n| n.to_string())
        )?;
    }
    let flight = Flight {
        result,
        vehicle: sc.load_vehicle()?,
        environment: sc.environment.build(),
        stack,
    };
    Ok(write_flight(
        sc,
        &format!("{} (PIL)", sc.name),
        flight,
        Some(pil_summary(&stats, faults)),
        dir,
    )?)
}

/// The PIL part of summary.json: the link statistics of `stats`, with the fault counts when
/// `faults` were injected.
fn pil_summary(stats: &pil::PilStats, faults: Option<pil::FaultConfig>) -> report::PilOut {
    let f = stats.faults;
    report::PilOut {
        frames: stats.frames,
        firmware_stack_bytes: stats.firmware_stack_bytes,
        link_faults: faults.map(|c| report::LinkFaultsOut {
            p_drop: c.p_drop,
            p_corrupt: c.p_corrupt,
            p_delay: c.p_delay,
            seed: c.seed,
            dropped: f.dropped,
            corrupted: f.corrupted,
            delayed: f.delayed,
            retries: f.retries,
            missed_ticks: f.missed_ticks,
            firmware_counted: stats.firmware_faults,
        }),
    }
}

/// Where a failed PIL run's frame record goes: `<dir>.failed-pil-record.csv`.
#[must_use]
pub fn failed_record_path(dir: &Path) -> PathBuf {
    let mut name = dir.file_name().unwrap_or_default().to_os_string();
    name.push(".failed-pil-record.csv");
    dir.with_file_name(name)
}

/// Run `simulate` with arguments `a`, writing normal output to `out`.
pub(super) fn run(a: &SimulateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (sc, file) = match &a.scenario {
        Some(p) => (read_scenario(p)?, p.display().to_string()),
        None => {
            let name = a.builtin.as_deref().unwrap_or("horus-2b-reference");
            (
                Scenario::try_builtin(name)?,
                format!("(built-in scenario {name})"),
            )
        }
    };
    if a.print_scenario {
        out.write_all(scenario_to_toml(&sc).as_bytes())?;
        return Ok(());
    }
    // Before the flight, so they are seen even if it fails.
    for w in crate::scenario::input_warnings(&sc) {
        writeln!(out, "warning: {w}")?;
    }
    let dir = a.out.clone().unwrap_or_else(|| {
        let suffix = if a.pil.is_some() { "-pil" } else { "" };
        Path::new("runs").join(format!("{}{suffix}", sc.name))
    });
    let show = !a.quiet && std::io::stderr().is_terminal();
    let bar = if show {
        indicatif::ProgressBar::new_spinner()
    } else {
        indicatif::ProgressBar::hidden()
    };
    let max_t = sc.termination.max_time_s;
    let mut progress = |p: crate::sim::Progress| {
        let (t, h) = (p.time_s, p.altitude_m);
        bar.set_message(format!(
            "t = {t:7.1} s (max {max_t:.0} s), h = {:6.2} km",
            h / 1e3
        ));
        bar.tick();
    };
    let run = if let Some(elf) = &a.pil {
        bar.finish_and_clear();
        let faults = match a.pil_fault_rate {
            Some(p) if (0.0..=0.3).contains(&p) => Some(pil::FaultConfig {
                seed: a.pil_fault_seed,
                p_drop: p,
                p_corrupt: p,
                p_delay: p,
            }),
            Some(p) => {
                return Err(CliError::Argument {
                    field: "--pil-fault-rate",
                    value: crate::num_fmt::compact(p),
                    reason: "must be a probability in [0, 0.3]",
                });
            }
            None => None,
        };
        pil_run(&sc, &file, elf, faults, &dir, out)?
    } else {
        let res = simulate_scenario(&sc, &file, &dir, &mut progress);
        bar.finish_and_clear();
        res?
    };
    let s = &run.summary;
    writeln!(
        out,
        "{}: {:?} after {:.1} s; range {:.2} deg ({:.0} km); heat load {:.1} MJ/m^2; peak q {:.1} kW/m^2; peak g {:.2}; peak g-dot {:.3} 1/s; skips {}; RHS evaluations {}",
        s.scenario,
        s.termination,
        s.flight_time_s,
        s.range_angle_deg,
        s.range_km,
        s.heat_load_mj_m2,
        s.peak_heat_flux_kw_m2.value,
        s.peak_g_load.value,
        s.peak_g_load_rate_per_s.value,
        s.skips,
        s.rhs_evals
    )?;
    if let Some(t) = &s.target {
        writeln!(
            out,
            "guidance stack ({}): miss {:.2} km from the target ({:.4} deg, {:.4} deg) (downrange {:+.2} km, crossrange {:+.2} km){}; {} reversals, {} re-plans ({} fall-backs)",
            t.mode,
            t.miss_km,
            t.latitude_deg,
            t.longitude_deg,
            t.downrange_error_km,
            t.crossrange_error_km,
            if t.reached_interface {
                ""
            } else {
                ", terminal interface not reached"
            },
            t.reversals,
            t.replans,
            t.fall_backs
        )?;
    }
    // The input warnings were printed before the flight.
    for w in run
        .warnings
        .iter()
        .filter(|w| matches!(w, crate::scenario::Warning::LimitExceeded { .. }))
    {
        writeln!(out, "warning: {w}")?;
    }
    writeln!(out, "wrote {}", dir.display())?;
    Ok(())
}
