//! Files of a re-entry optimisation run ([`super`]): per-generation records (generations.csv
//! and .json), populations (population/gen_NNNN.csv), the final front (front.csv and one
//! scenario file per member in front/, flyable by `host-sim simulate --scenario`), the
//! trajectories of three chosen members (front/member_NN/) and plots (fronts.svg,
//! hypervolume.svg, feasible.svg, objectives.svg, trajectories.svg).

use std::path::Path;

use crate::design::AnalyticalModel;
use crate::optim::Individual;
use crate::optim::run::{Record, front_order, population_csv, records_csv};
use crate::report::{ReportError, RunDir, write_atomic};
use crate::report::{Series, line_plot_svg};
use crate::scenario::{Scenario, scenario_to_toml, simulate_scenario};
use crate::sim::SimResult;

/// Write one generation's population (population/gen_NNNN.csv).
///
/// # Errors
/// [`ReportError`].
pub fn write_generation(
    dir: &Path,
    pop: &[Individual<Vec<f64>>],
    generation: u64,
) -> Result<(), ReportError> {
    write_atomic(
        &dir.join("population")
            .join(format!("gen_{generation:04}.csv")),
        population_csv(pop)?.as_bytes(),
    )
}

fn plot(
    dir: &Path,
    name: &str,
    title: &str,
    x: &str,
    y: &str,
    s: &[Series],
) -> Result<(), ReportError> {
    write_atomic(&dir.join(name), line_plot_svg(title, x, y, s)?.as_bytes())
}

fn series(label: String, points: Vec<(f64, f64)>) -> Series {
    Series {
        label,
        points,
        dashed: false,
    }
}

/// Fly a chosen front member with the problem's simulator and write its run directory
/// (trajectory, summary, plots); `None` if it fails (the member is left out of the plot).
fn member_run(
    sc: &Scenario,
    analytical: Option<&AnalyticalModel>,
    run_dir: &Path,
) -> Option<SimResult> {
    let Some(m) = analytical else {
        return simulate_scenario(sc, "front member", run_dir, &mut |_| {})
            .ok()
            .map(|run| run.result);
    };
    let run = m.fly(sc).ok()?;
    let summary = crate::report::summary_report(
        &run.result,
        &sc.name,
        &m.vehicle().name,
        &crate::analytic::environment_label(m.atmosphere()),
        sc.environment.planet.radius_m,
    );
    let limits = m.vehicle().limits;
    crate::report::write_run(
        run_dir,
        &run.result,
        &summary,
        &crate::report::PlotLimits::of_vehicle(&limits),
    )
    .ok()?;
    Some(run.result)
}

/// The front directory (front/): one scenario file per member and the trajectories of three
/// chosen members, written into a staging directory and put in place whole (no member of a
/// previous front is left beside them). Returns the chosen trajectories' series.
fn write_front_dir(
    dir: &Path,
    front_scenarios: Vec<Option<Scenario>>,
    base: &str,
    analytical: Option<&AnalyticalModel>,
) -> Result<Vec<Series>, ReportError> {
    let n = front_scenarios.len();
    let mut fdir = RunDir::begin_owned(&dir.join("front"))?;
    let mut chosen = Vec::new();
    for (k, sc) in front_scenarios.into_iter().enumerate() {
        let Some(mut sc) = sc else {
            continue;
        };
        sc.name = format!("{base}-member-{k:02}");
        fdir.write(
            format!("member_{k:02}.toml"),
            scenario_to_toml(&sc).as_bytes(),
        )?;
        if k == 0 || k + 1 == n || k == n / 2 {
            chosen.push((k, sc));
        }
    }
    chosen.dedup_by_key(|(k, _)| *k);
    let mut traj = Vec::new();
    for (k, sc) in &chosen {
        let run_dir = fdir.staging().join(format!("member_{k:02}"));
        if let Some(result) = member_run(sc, analytical, &run_dir) {
            let pts = result
                .samples
                .iter()
                .map(|s| (s.state.speed_m_s / 1e3, s.conditions.altitude_m / 1e3))
                .collect();
            traj.push(series(format!("member {k:02}"), pts));
        }
    }
    fdir.commit()?;
    Ok(traj)
}

/// Write the final files: records, population, front (the feasible front of `result`: the
/// population, or the external archive), member scenarios (`scenarios`: one per `result`
/// member, named after the problem's `base`), chosen trajectories (flown by the problem's
/// simulator: `analytical` for an analytical problem), plots.
///
/// # Errors
/// [`ReportError`].
#[allow(clippy::too_many_arguments)] // the final files need exactly these inputs
pub fn write_final(
    dir: &Path,
    scenarios: &[Option<Scenario>],
    pop: &[Individual<Vec<f64>>],
    result: &[Individual<Vec<f64>>],
    records: &[Record],
    base: &str,
    analytical: Option<&AnalyticalModel>,
) -> Result<(), ReportError> {
    // The front, sorted by range objective, without repeated members, with one scenario file
    // per member.
    let idx = front_order(result);
    let front: Vec<Individual<Vec<f64>>> = idx.iter().map(|&i| result[i].clone()).collect();
    let front_scenarios: Vec<Option<Scenario>> = idx
        .iter()
        .map(|&i| scenarios.get(i).cloned().flatten())
        .collect();
    // The front directory first: its flights are the long part, and a Ctrl-C during them
    // leaves no final file.
    let traj = write_front_dir(dir, front_scenarios, base, analytical)?;
    write_atomic(
        &dir.join("generations.csv"),
        records_csv(records)?.as_bytes(),
    )?;
    let json = serde_json::to_string_pretty(records).map_err(ReportError::Json)?;
    write_atomic(&dir.join("generations.json"), json.as_bytes())?;
    write_atomic(&dir.join("population.csv"), population_csv(pop)?.as_bytes())?;
    write_atomic(&dir.join("front.csv"), population_csv(&front)?.as_bytes())?;
    if !traj.is_empty() {
        plot(
            dir,
            "trajectories.svg",
            "Chosen front members",
            "velocity [km/s]",
            "altitude [km]",
            &traj,
        )?;
    }
    // Fronts at selected generations.
    let n = records.len();
    let mut picks: Vec<usize> = [0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)].to_vec();
    picks.dedup();
    let fronts: Vec<Series> = picks
        .iter()
        .filter_map(|&i| records.get(i))
        .filter(|r| !r.front.is_empty())
        .map(|r| {
            series(
                format!("generation {}", r.generation),
                r.front.iter().map(|f| (f[0], f[1])).collect(),
            )
        })
        .collect();
    if !fronts.is_empty() {
        plot(
            dir,
            "fronts.svg",
            "Feasible fronts",
            "f_r = -theta/pi [-]",
            "f_Q = heat load [scaled]",
            &fronts,
        )?;
    }
    let per_gen = |f: &dyn Fn(&Record) -> f64| -> Vec<(f64, f64)> {
        records
            .iter()
            .map(|r| (r.generation as f64, f(r)))
            .filter(|p| p.1.is_finite())
            .collect()
    };
    plot(
        dir,
        "hypervolume.svg",
        "Hypervolume",
        "generation",
        "hypervolume [-]",
        &[series("hypervolume".into(), per_gen(&|r| r.hypervolume))],
    )?;
    plot(
        dir,
        "feasible.svg",
        "Feasible fraction",
        "generation",
        "feasible fraction [-]",
        &[series("feasible".into(), per_gen(&|r| r.feasible_fraction))],
    )?;
    plot(
        dir,
        "objectives.svg",
        "Best and mean feasible objectives",
        "generation",
        "objective [-]",
        &[
            series("best f_r".into(), per_gen(&|r| r.best[0])),
            series("mean f_r".into(), per_gen(&|r| r.mean[0])),
            series("best f_Q".into(), per_gen(&|r| r.best[1])),
            series("mean f_Q".into(), per_gen(&|r| r.mean[1])),
        ],
    )?;
    Ok(())
}
