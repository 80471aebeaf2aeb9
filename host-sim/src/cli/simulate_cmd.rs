//! `host-sim simulate`: load (or pick) a scenario, print it or fly it with a progress bar, and
//! print the one-line summary.

use std::io::{IsTerminal, Write};
use std::path::Path;

use super::{
    CliError, Flight, RunOutput, Scenario, SimulateArgs, load_vehicle, parse_scenario,
    scenario_to_toml, simulate_scenario, write_flight,
};
use crate::pil;

/// Fly the reference mission in PIL with firmware `elf`, write the run directory and print
/// the link statistics.
fn pil_run(
    sc: &Scenario,
    elf: &Path,
    dir: &Path,
    out: &mut dyn Write,
) -> Result<RunOutput, CliError> {
    let started = std::time::Instant::now();
    let (result, stats) = pil::fly_reference_pil(pil::PilConfig::new(elf.to_path_buf()))?;
    let wall = started.elapsed().as_secs_f64();
    writeln!(
        out,
        "PIL: {} frames with {} in {wall:.2} s ({:.0} frames/s)",
        stats.frames,
        elf.display(),
        stats.frames as f64 / wall.max(1e-9)
    )?;
    let flight = Flight {
        result,
        vehicle: load_vehicle(&sc.vehicle)?,
        environment: sc.environment.build(),
    };
    write_flight(sc, &format!("{} (PIL)", sc.name), flight, dir)
}

/// Run `simulate` with arguments `a`, writing normal output to `out`.
pub(super) fn run(a: &SimulateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (sc, file) = match &a.scenario {
        Some(p) => {
            let file = p.display().to_string();
            let text = std::fs::read_to_string(p)
                .map_err(|e| CliError::Scenario(format!("{file}: cannot read: {e}")))?;
            let base = p.parent().unwrap_or(Path::new("."));
            (parse_scenario(&text, &file, base)?, file)
        }
        None => {
            let name = a.builtin.as_deref().unwrap_or("horus-2b-reference");
            let sc = Scenario::builtin(name).ok_or_else(|| {
                CliError::Scenario(format!(
                    "command line: option `--builtin` = {name:?}: unknown scenario (known: {})",
                    Scenario::BUILTIN.join(", ")
                ))
            })?;
            (sc, format!("(built-in scenario {name})"))
        }
    };
    if a.print_scenario {
        out.write_all(scenario_to_toml(&sc).as_bytes())?;
        return Ok(());
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
    let mut progress = |t: f64, h: f64| {
        bar.set_message(format!(
            "t = {t:7.1} s (max {max_t:.0} s), h = {:6.2} km",
            h / 1e3
        ));
        bar.tick();
    };
    let run = if let Some(elf) = &a.pil {
        bar.finish_and_clear();
        pil_run(&sc, elf, &dir, out)?
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
    writeln!(out, "wrote {}", dir.display())?;
    Ok(())
}
