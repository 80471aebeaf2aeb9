//! `host-sim simulate`: load (or pick) a scenario, print it or fly it with a progress bar, and
//! print the one-line summary.

use std::io::{IsTerminal, Write};
use std::path::Path;

use super::{
    CliError, Scenario, SimulateArgs, parse_scenario, scenario_to_toml, simulate_scenario,
};

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
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(&sc.name));
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
    let res = simulate_scenario(&sc, &file, &dir, &mut progress);
    bar.finish_and_clear();
    let run = res?;
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
