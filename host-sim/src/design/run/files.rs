//! Files of a re-entry optimisation run ([`super`]): per-generation records (generations.csv
//! and .json), populations (population/gen_NNNN.csv), the final front (front.csv and one
//! scenario file per member in front/, flyable by `host-sim simulate --scenario`), the
//! trajectories of three chosen members (front/member_NN/; of a robust run also their
//! campaign report in front/member_NN/campaign/, as `host-sim dispersions` writes it) and
//! plots (fronts.svg, hypervolume.svg, feasible.svg, objectives.svg, trajectories.svg).

use std::path::Path;

use crate::campaign::output::write_campaign;
use crate::design::{AnalyticalModel, Objectives, RobustProblem};
use crate::optim::run::{Record, front_order, population_csv, records_csv};
use crate::optim::{Evaluator, Individual, Threads};
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

/// How the chosen front members are flown for their files.
pub struct MemberFlights<'a> {
    /// The analytical simulator of an analytical problem (`None`: the numerical one).
    pub analytical: Option<&'a AnalyticalModel>,
    /// The robust problem whose campaign each chosen member flies again for its report.
    pub robust: Option<&'a RobustProblem>,
    /// The nominal problem's objective settings (its axis labels).
    pub objectives: &'a Objectives,
    /// Threads for those campaigns (their results do not depend on them).
    pub threads: &'a Threads,
    /// A nominal front's decisions, flown in the robust problem's campaign for
    /// nominal-front.csv and robust-vs-nominal.svg (empty: no comparison).
    pub nominal_front: &'a [Vec<f64>],
}

impl MemberFlights<'_> {
    /// The objectives' axis labels: the robust statistics', or the nominal problem's.
    fn objective_labels(&self) -> Vec<String> {
        self.robust.map_or_else(
            || self.objectives.labels(),
            |p| {
                p.config()
                    .objectives
                    .iter()
                    .map(|s| s.label().to_string())
                    .collect()
            },
        )
    }
}

/// Fly a robust problem's campaign of a chosen member again and write its report into
/// `dir` (summary.json, cases-<mode>.csv, footprint, miss CDF, limit ratios); the training
/// campaign exactly (the same draws). Nothing is written if the campaign cannot be flown.
fn member_campaign(p: &RobustProblem, sc: &Scenario, threads: usize, dir: &Path) {
    let Ok(campaign) = p.campaign(sc) else {
        return;
    };
    let Ok(out) = campaign.run(None, Some(threads), false) else {
        return;
    };
    // A member whose report cannot be written is left without one, as one whose flight
    // fails is left out of the trajectories.
    if std::fs::create_dir_all(dir).is_ok() {
        let _ = write_campaign(dir, campaign.setup(), campaign.settings(), &out);
    }
}

/// The nominal front flown in the robust problem's campaign: nominal-front.csv (its
/// decisions with their robust objectives and constraint, a population file) and, with two
/// objectives or more, robust-vs-nominal.svg (both fronts in the first two robust
/// objectives; nominal members that break the constraint are drawn too, they are the point).
fn write_nominal_comparison(
    dir: &Path,
    p: &RobustProblem,
    threads: &Threads,
    nominal: &[Vec<f64>],
    robust_front: &[Individual<Vec<f64>>],
    labels: &[String],
) -> Result<(), ReportError> {
    let flown: Vec<Individual<Vec<f64>>> = threads
        .evaluate(p, nominal)
        .into_iter()
        .zip(nominal)
        .enumerate()
        .filter_map(|(k, (e, x))| {
            let e = e.ok()?;
            Individual::from_evaluation(x.clone(), e, k, labels.len(), 1).ok()
        })
        .collect();
    write_atomic(
        &dir.join("nominal-front.csv"),
        population_csv(&flown)?.as_bytes(),
    )?;
    let (Some(x), Some(y)) = (labels.first(), labels.get(1)) else {
        return Ok(());
    };
    let points = |pop: &[Individual<Vec<f64>>]| {
        let mut v: Vec<(f64, f64)> = pop
            .iter()
            .filter_map(|i| Some((*i.objectives.first()?, *i.objectives.get(1)?)))
            .filter(|(a, b)| a.is_finite() && b.is_finite())
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let (feasible, infeasible): (Vec<_>, Vec<_>) =
        flown.into_iter().partition(|i| i.violation <= 0.0);
    let mut s = vec![series("robust front".into(), points(robust_front))];
    s.push(series(
        "nominal front, flown in the campaign".into(),
        points(&feasible),
    ));
    if !infeasible.is_empty() {
        s.push(Series {
            label: "nominal members over the violation limit".into(),
            points: points(&infeasible),
            dashed: true,
        });
    }
    plot(
        dir,
        "robust-vs-nominal.svg",
        "Robust front against the nominal front (same campaign)",
        x,
        y,
        &s,
    )
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
    members: &MemberFlights<'_>,
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
        if let Some(p) = members.robust {
            member_campaign(p, sc, members.threads.count(), &run_dir.join("campaign"));
        }
        if let Some(result) = member_run(sc, members.analytical, &run_dir) {
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
/// member, named after the problem's `base`), chosen trajectories (flown as `members` says;
/// with a robust problem's campaign report beside each), plots.
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
    members: &MemberFlights<'_>,
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
    let traj = write_front_dir(dir, front_scenarios, base, members)?;
    let labels = members.objective_labels();
    let label = |k: usize| labels.get(k).map_or("objective [-]", String::as_str);
    if let (Some(p), false) = (members.robust, members.nominal_front.is_empty()) {
        write_nominal_comparison(
            dir,
            p,
            members.threads,
            members.nominal_front,
            &front,
            &labels,
        )?;
    }
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
    // The first two objectives (a one-objective run has no front to draw).
    let fronts: Vec<Series> = picks
        .iter()
        .filter_map(|&i| records.get(i))
        .filter(|r| !r.front.is_empty())
        .map(|r| {
            series(
                format!("generation {}", r.generation),
                r.front
                    .iter()
                    .filter_map(|f| Some((*f.first()?, *f.get(1)?)))
                    .collect(),
            )
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    if !fronts.is_empty() {
        plot(
            dir,
            "fronts.svg",
            "Feasible fronts",
            label(0),
            label(1),
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
    // Best and mean of each objective, named by its label (no objective is indexed past
    // what a record holds).
    let objective_series: Vec<Series> = (0..labels.len())
        .flat_map(|k| {
            let at = move |v: &[f64]| v.get(k).copied().unwrap_or(f64::NAN);
            [
                series(format!("best {}", label(k)), per_gen(&|r| at(&r.best))),
                series(format!("mean {}", label(k)), per_gen(&|r| at(&r.mean))),
            ]
        })
        .collect();
    plot(
        dir,
        "objectives.svg",
        "Best and mean feasible objectives",
        "generation",
        "objective [-]",
        &objective_series,
    )?;
    Ok(())
}
