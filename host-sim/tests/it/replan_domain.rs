//! The domain where re-planning is used (issue 10 items 5-6, docs/validation/vinh-numerical.md "The re-planning
//! domain"): every re-plan the re-planner applies in host-sim's closed-loop scenarios and
//! dispersion campaigns, recomputed from the state and model of its tick, and the range its
//! predictor gave at the solved vertical lift fraction compared with numerical integration of
//! the same equations (planar motion over the predictor's non-rotating spherical planet with its
//! effective `mu`, its exponential atmosphere and its polar, constant lift, from the navigated
//! radius, speed and flight-path angle to the predictor's final speed).

use guidance_core::replan::{
    PredictorMode, ReplanCase, ReplanReport, ReplanResult, ReplanSolver, ReplanningConfig, replan,
};
use guidance_core::vinh::{
    ExpAtmosphere, LiftControl, PeakMode, Planet, Prediction, VehicleParams, predict_with,
};
use host_sim::campaign::flight::{ReplanLog, fly_case_logged};
use host_sim::campaign::{CampaignSetup, Mode, parse_settings};
use host_sim::env::{Environment, ExponentialAtmosphere};
use host_sim::replan_loop::{ReplanLoop, predictor_model};
use host_sim::scenario::Scenario;
use host_sim::sim::ReportContext;

use super::replan_loop as rl;

const DEG: f64 = std::f64::consts::PI / 180.0;

/// Range angle [rad] of the planar equations of motion over `planet` (central gravity,
/// non-rotating), `atmosphere`, the polar of `vehicle` at `lift`, from `(r, v, gamma)` until
/// the speed falls to `v_f` (linear interpolation in speed over the last step). RK4 with a
/// 0.25 s step (halving it changes the range angle by < 1e-7 relative on the SRM glide).
/// `None` if the vehicle reaches the surface or 20 000 s pass first.
pub fn integrated_range_angle(
    planet: &Planet<f64>,
    atmosphere: &ExpAtmosphere<f64>,
    vehicle: &VehicleParams<f64>,
    lift: &LiftControl<f64>,
    state: (f64, f64, f64),
    v_f: f64,
    dt: f64,
) -> Option<f64> {
    let cl_star = (vehicle.cd0 / vehicle.k_polar).sqrt();
    let cl = lift.lambda * cl_star;
    let cd = vehicle.cd0 + vehicle.k_polar * cl * cl;
    let b = vehicle.reference_area_m2 / (2.0 * vehicle.mass_kg);
    let rhs = |y: [f64; 4]| -> [f64; 4] {
        let [r, v, g, _] = y;
        let rho = atmosphere.rho0_kg_m3
            * (-(r - atmosphere.ref_radius_m) / atmosphere.scale_height_m).exp();
        let q = rho * v * v * b;
        let grav = planet.mu_m3_s2 / (r * r);
        [
            v * g.sin(),
            -q * cd - grav * g.sin(),
            q * cl * lift.vertical_fraction / v - (grav / v - v / r) * g.cos(),
            v * g.cos() / r,
        ]
    };
    let mut y = [state.0, state.1, state.2, 0.0];
    let mut t = 0.0;
    if y[1].partial_cmp(&v_f) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    while t < 20_000.0 {
        let k1 = rhs(y);
        let k2 = rhs(std::array::from_fn(|i| y[i] + 0.5 * dt * k1[i]));
        let k3 = rhs(std::array::from_fn(|i| y[i] + 0.5 * dt * k2[i]));
        let k4 = rhs(std::array::from_fn(|i| y[i] + dt * k3[i]));
        let n: [f64; 4] =
            std::array::from_fn(|i| y[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        if n[0] <= planet.radius_m {
            return None;
        }
        if n[1] <= v_f {
            let s = (y[1] - v_f) / (y[1] - n[1]);
            return Some(y[3] + s * (n[3] - y[3]));
        }
        y = n;
        t += dt;
    }
    None
}

/// One applied re-plan, recomputed.
#[derive(Clone, Debug)]
pub struct Point {
    pub scenario: String,
    pub altitude_km: f64,
    pub speed_m_s: f64,
    pub gamma_deg: f64,
    /// Total L/D of the predictor's polar at the solver's lambda (after the estimate).
    pub lift_to_drag: f64,
    pub fraction: f64,
    pub case: ReplanCase,
    /// true: the chain (skip first) was used; false: the glide (or the numerical predictor).
    pub chain: bool,
    /// true: the solve used the numerical predictor (`Numerical`, or a `Hybrid` solve out of
    /// the closed forms' validated domain).
    pub numerical: bool,
    pub prediction: Prediction<f64>,
    /// Numerical range angle [rad] (None: no end at the final speed).
    pub reference_rad: Option<f64>,
    /// Glide start radius minus the state's radius [km].
    pub start_offset_km: f64,
    /// The glide-mode prediction with the sink term at the same fraction (glide points only).
    pub with_sink_rad: Option<f64>,
    /// Flight-path angle the glide imposes at its start radius (eq. 3.79) [deg].
    pub glide_gamma_deg: f64,
}

impl Point {
    pub fn error_pct(&self) -> Option<f64> {
        self.reference_rad
            .map(|r| 100.0 * (self.prediction.range_angle_rad - r) / r)
    }
}

/// Recompute the re-plans of `log` flown with `config` (the solver is deterministic: the same
/// inputs give the reported case bit for bit, checked) and compare each applied one with the
/// integration.
pub fn recompute(scenario: &str, config: &ReplanningConfig<f64>, log: &ReplanLog) -> Vec<Point> {
    let mut out = Vec::new();
    for (rep, ctx) in log {
        if !rep.applied {
            continue;
        }
        let (res, model, numerical) = rerun(config, rep, ctx);
        assert_eq!(
            res.case, rep.case,
            "{scenario}: re-plan at {} s",
            rep.time_s
        );
        assert_eq!(
            res.prediction.map(|p| p.range_m),
            rep.predicted_range_m,
            "{scenario}"
        );
        let Some(prediction) = res.prediction else {
            continue;
        };
        let (planet, atm, veh) = model;
        let s = &config.solver;
        let f = res.vertical_fraction;
        let lift = LiftControl {
            lambda: s.lambda,
            vertical_fraction: f,
        };
        let nav = ctx.nav;
        let state = guidance_core::vinh::EntryState {
            radius_m: nav.radius_m,
            speed_m_s: nav.speed_m_s,
            flight_path_angle_rad: nav.flight_path_angle_rad,
        };
        let chain_ok = |fr: f64| {
            predict_with(
                &planet,
                &atm,
                &veh,
                &LiftControl {
                    lambda: s.lambda,
                    vertical_fraction: fr,
                },
                &state,
                &s.predictor,
                PeakMode::RangeOnly,
            )
            .is_ok()
        };
        let chain = !numerical
            && match s.mode {
                PredictorMode::Chain => true,
                PredictorMode::Glide | PredictorMode::Numerical => false,
                // A hybrid solve on the closed forms is Auto's (AutoSink's).
                PredictorMode::Auto
                | PredictorMode::AutoSink
                | PredictorMode::Hybrid
                | PredictorMode::HybridSink => {
                    chain_ok(s.min_vertical_fraction) && chain_ok(s.max_vertical_fraction)
                }
            };
        let reference = integrated_range_angle(
            &planet,
            &atm,
            &veh,
            &lift,
            (nav.radius_m, nav.speed_m_s, nav.flight_path_angle_rad),
            s.predictor.final_speed_m_s,
            0.25,
        );
        let cl = (veh.cd0 / veh.k_polar).sqrt() * s.lambda;
        let with_sink = (!chain && !numerical)
            .then(|| {
                guidance_core::replan::predict_glide_with_sink(
                    &planet,
                    &atm,
                    &veh,
                    &lift,
                    &state,
                    &s.predictor,
                    PeakMode::RangeOnly,
                )
                .ok()
                .map(|p| p.range_angle_rad)
            })
            .flatten();
        let glide_gamma_deg = guidance_core::vinh::GlideSolution::new(
            &planet,
            &atm,
            &veh,
            &lift,
            prediction.glide_start_radius_m,
        )
        .map_or(f64::NAN, |g| g.imposed_entry().flight_path_angle_rad / DEG);
        out.push(Point {
            glide_gamma_deg,
            with_sink_rad: with_sink,
            scenario: scenario.into(),
            altitude_km: (nav.radius_m - planet.radius_m) / 1e3,
            speed_m_s: nav.speed_m_s,
            gamma_deg: nav.flight_path_angle_rad / DEG,
            lift_to_drag: cl / (veh.cd0 + veh.k_polar * cl * cl),
            fraction: f,
            case: res.case,
            chain,
            numerical,
            prediction,
            reference_rad: reference,
            start_offset_km: (prediction.glide_start_radius_m - nav.radius_m) / 1e3,
        });
    }
    out
}

type Model = (Planet<f64>, ExpAtmosphere<f64>, VehicleParams<f64>);

/// The solve of a logged re-plan, redone from its tick's state and model, and whether it used
/// the numerical predictor (the resumable solver run to its end gives `replan`'s answer bit for
/// bit, checked).
fn rerun(
    config: &ReplanningConfig<f64>,
    rep: &ReplanReport<f64>,
    ctx: &ReportContext,
) -> (ReplanResult<f64>, Model, bool) {
    let m = &config.model;
    let planet = m.effective_planet(&ctx.nav, config.solver.predictor.final_speed_m_s);
    let (atm, veh) = ctx
        .aero_scales
        .and_then(|a| a.apply(&m.atmosphere, &m.vehicle))
        .unwrap_or((m.atmosphere, m.vehicle));
    let res = replan(
        &planet,
        &atm,
        &veh,
        &ctx.nav,
        rep.range_to_go_m,
        &config.limits,
        &config.solver,
    );
    let mut solver = ReplanSolver::new(
        &planet,
        &atm,
        &veh,
        &ctx.nav,
        rep.range_to_go_m,
        &config.limits,
        &config.solver,
    );
    let stepped = loop {
        if let Some(r) = solver.run(u8::MAX) {
            break r;
        }
    };
    assert_eq!(stepped, res, "resumable solver against replan");
    (res, (planet, atm, veh), solver.uses_numerical())
}

fn log_of(lp: &ReplanLoop) -> ReplanLog {
    lp.reports
        .iter()
        .copied()
        .zip(lp.contexts.iter().copied())
        .collect()
}

/// Label suffix of a predictor mode in the harness' rows (`Auto`: none).
fn mode_label(mode: PredictorMode) -> String {
    match mode {
        PredictorMode::Auto => String::new(),
        m => format!(", {m:?}"),
    }
}

/// The SRM closed-loop runs of `replan_loop` (simplified environment, five dispersions),
/// re-planning with the predictor `mode`.
pub fn srm_simplified(mode: PredictorMode) -> Vec<Point> {
    let total = rl::fly_stored(&rl::setup(1.0, 0.0))
        .summary
        .flown_range_angle_rad;
    let target = guidance_core::replan::RangeTarget::FlownRangeAngle { total_rad: total };
    let mut out = Vec::new();
    for (density, dgamma_deg) in [(1.0, 0.0), (1.1, 0.0), (0.9, 0.0), (1.0, -0.2), (1.0, 0.1)] {
        let s = rl::setup(density, dgamma_deg);
        let rc = rl::replanning_config(target, rl::EVERY, mode);
        let (_, lp) = rl::fly_replanning(&s, rc);
        out.extend(recompute(
            &format!(
                "SRM simplified, density x{density}, gamma {dgamma_deg:+} deg{}",
                mode_label(mode)
            ),
            &rc,
            &log_of(&lp),
        ));
    }
    out
}

/// The SRM closed-loop runs of `replan_loop` in the full environment (headings 0 and 270 deg,
/// flight-path-angle dispersions -0.2 and +0.1 deg), re-planning with the predictor `mode`.
pub fn srm_full(mode: PredictorMode) -> Vec<Point> {
    let mut out = Vec::new();
    for heading in [0.0, 270.0] {
        for run in rl::full_environment_runs_with(heading, &[-0.2, 0.1], mode) {
            out.extend(recompute(
                &format!(
                    "SRM full, heading {heading}, gamma {:+} deg{}",
                    run.dgamma_deg,
                    mode_label(mode)
                ),
                &run.config,
                &log_of(&run.lp),
            ));
        }
    }
    out
}

/// `cases` dispersed flights (default dispersions, seed of the defaults) of the built-in
/// scenario `sc` in both re-planning modes, with the default layer settings and the
/// re-planner's predictor `predictor` (`"closed-form"`, `"numerical"`, `"hybrid"`).
pub fn campaign(
    name: &str,
    sc: &Scenario,
    interface: Option<f64>,
    cases: u32,
    predictor: &str,
) -> Vec<Point> {
    let settings = parse_settings("", "(harness)").unwrap();
    let layers = host_sim::campaign::CampaignGuidance {
        predictor: match predictor {
            "closed-form" => host_sim::campaign::CampaignPredictor::ClosedForm,
            "numerical" => host_sim::campaign::CampaignPredictor::Numerical,
            _ => host_sim::campaign::CampaignPredictor::Hybrid,
        },
        ..Default::default()
    };
    let interface =
        interface.map(|speed_m_s| host_sim::scenario::TerminalInterface::Speed { speed_m_s });
    let mut setup = CampaignSetup::with_guidance(sc, name, interface, &layers).unwrap();
    // The numerical predictions end at the final speed here, as `recompute`'s solve and its
    // reference integration do (the campaigns end them at the interface energy:
    // `ReplanLayer::final_energy_j_kg`, tested in guidance-core's numerical_predictor).
    if let Some(r) = setup.stack.replan.as_mut() {
        r.final_energy_j_kg = None;
    }
    let label = if predictor == "closed-form" {
        String::new()
    } else {
        format!(", {predictor}")
    };
    let mut out = Vec::new();
    for mode in [Mode::ReplanReversals, Mode::ReplanEstimation] {
        for i in 0..cases {
            let draw = host_sim::campaign::draw::draw_case(&settings, i);
            let (_, log) = fly_case_logged(&setup, Some(&draw), mode).unwrap();
            out.extend(recompute(
                &format!("{name} campaign {mode:?}{label}"),
                &setup.stack_of(mode).replanning_config().unwrap(),
                &log,
            ));
        }
    }
    out
}

fn summarise(points: &[Point]) {
    let mut names: Vec<&str> = points.iter().map(|p| p.scenario.as_str()).collect();
    names.dedup();
    println!(
        "| scenario | re-plans | chain / glide | h [km] | V [km/s] | gamma [deg] | L/D | cos(sigma) | start offset [km] | range error [%] min / max | |err| > 3 % | > 500 km to go: |err| max [%], > 3 % | in domain | in domain: |err| max [%] |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mm = |it: &mut dyn Iterator<Item = f64>| {
        it.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        })
    };
    for name in names {
        let ps: Vec<&Point> = points.iter().filter(|p| p.scenario == name).collect();
        let chain = ps.iter().filter(|p| p.chain).count();
        let h = mm(&mut ps.iter().map(|p| p.altitude_km));
        let v = mm(&mut ps.iter().map(|p| p.speed_m_s / 1e3));
        let g = mm(&mut ps.iter().map(|p| p.gamma_deg));
        let e = mm(&mut ps.iter().map(|p| p.lift_to_drag));
        let f = mm(&mut ps.iter().map(|p| p.fraction));
        let o = mm(&mut ps.iter().map(|p| p.start_offset_km));
        let err = mm(&mut ps.iter().filter_map(|p| p.error_pct()));
        let bad = ps
            .iter()
            .filter(|p| p.error_pct().is_none_or(|e| e.abs() > 3.0))
            .count();
        let far: Vec<&&Point> = ps
            .iter()
            .filter(|p| p.reference_rad.is_some_and(|r| r * 6_378_137.0 > 500e3))
            .collect();
        let far_max = far
            .iter()
            .filter_map(|p| p.error_pct())
            .fold(0.0_f64, |a, e| a.max(e.abs()));
        let far_bad = far
            .iter()
            .filter(|p| p.error_pct().is_none_or(|e| e.abs() > 3.0))
            .count();
        let inside: Vec<&&Point> = ps
            .iter()
            .filter(|p| p.prediction.validity == guidance_core::vinh::Validity::InDomain)
            .collect();
        let in_max = inside
            .iter()
            .map(|p| p.error_pct().map_or(f64::INFINITY, f64::abs))
            .fold(0.0_f64, f64::max);
        println!(
            "| {name} | {} | {chain} / {} | {:.1}-{:.1} | {:.2}-{:.2} | {:.2}-{:.2} | {:.2}-{:.2} | {:.2}-{:.2} | {:.1}-{:.1} | {:+.2} / {:+.2} | {bad} | {far_max:.2}, {far_bad} of {} | {} | {in_max:.2} |",
            ps.len(),
            ps.len() - chain,
            h.0,
            h.1,
            v.0,
            v.1,
            g.0,
            g.1,
            e.0,
            e.1,
            f.0,
            f.1,
            o.0,
            o.1,
            err.0,
            err.1,
            far.len(),
            inside.len(),
        );
    }
}

/// Per scenario: how many applied re-plans used the closed forms and how many the numerical
/// predictor (a `Hybrid` solve falls back to it when an end of the interval is not
/// `InDomain`), with the range error of each group against the reference integration.
fn summarise_hybrid(points: &[Point]) {
    let mut names: Vec<&str> = points.iter().map(|p| p.scenario.as_str()).collect();
    names.dedup();
    println!(
        "\n| scenario | re-plans | closed forms | of which InDomain | closed forms: |err| max [%], > 3 % | numerical | numerical: |err| median / max [%] |"
    );
    println!("|---|---|---|---|---|---|---|");
    let abs_err = |p: &&Point| p.error_pct().map_or(f64::INFINITY, f64::abs);
    for name in names {
        let ps: Vec<&Point> = points.iter().filter(|p| p.scenario == name).collect();
        let (num, closed): (Vec<&Point>, Vec<&Point>) = ps.iter().partition(|p| p.numerical);
        let in_domain = closed
            .iter()
            .filter(|p| p.prediction.validity == guidance_core::vinh::Validity::InDomain)
            .count();
        let closed_max = closed.iter().map(abs_err).fold(0.0_f64, f64::max);
        let closed_bad = closed.iter().filter(|p| abs_err(p) > 3.0).count();
        let mut num_err: Vec<f64> = num.iter().map(abs_err).collect();
        num_err.sort_by(f64::total_cmp);
        let median = num_err.get(num_err.len() / 2).copied().unwrap_or(f64::NAN);
        let num_max = num_err.last().copied().unwrap_or(f64::NAN);
        println!(
            "| {name} | {} | {} | {in_domain} | {closed_max:.2}, {closed_bad} | {} | {median:.4} / {num_max:.4} |",
            ps.len(),
            closed.len(),
            num.len(),
        );
    }
}

fn dump(points: &[Point]) {
    println!(
        "scenario,h_km,v,gamma_deg,ld,f,case,chain,skips,offset_km,pred_deg,ref_deg,err_pct,validity,sink_err_pct"
    );
    for p in points {
        println!(
            "{},{:.3},{:.1},{:.4},{:.3},{:.4},{:?},{},{},{:.3},{:.4},{:.4},{:.3},{:?},{:.3},{:.4}",
            p.scenario,
            p.altitude_km,
            p.speed_m_s,
            p.gamma_deg,
            p.lift_to_drag,
            p.fraction,
            p.case,
            p.chain,
            p.prediction.skips,
            p.start_offset_km,
            p.prediction.range_angle_rad / DEG,
            p.reference_rad.map_or(f64::NAN, |r| r / DEG),
            p.error_pct().unwrap_or(f64::NAN),
            p.prediction.validity,
            match (p.with_sink_rad, p.reference_rad) {
                (Some(a), Some(r)) => 100.0 * (a - r) / r,
                _ => f64::NAN,
            },
            p.glide_gamma_deg,
        );
    }
}

/// Measurement for docs/validation/vinh-numerical.md ("The re-planning domain"):
/// `cargo test -p host-sim --test it replan_domain::print_replanning_domain -- --ignored --nocapture`
#[test]
#[ignore]
fn print_replanning_domain() {
    let cases: u32 = std::env::var("DOMAIN_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let mut all = Vec::new();
    // Auto: the closed forms alone (for comparison); Hybrid: the scenario files' default.
    for mode in [PredictorMode::Auto, PredictorMode::Hybrid] {
        all.extend(srm_simplified(mode));
        all.extend(srm_full(mode));
    }
    for predictor in ["closed-form", "hybrid"] {
        all.extend(campaign(
            "srm-glide",
            &Scenario::srm_glide(),
            Some(2500.0),
            cases,
            predictor,
        ));
        all.extend(campaign(
            "horus-2b-reference",
            &Scenario::default(),
            None,
            cases,
            predictor,
        ));
    }
    summarise(&all);
    summarise_hybrid(&all);
    if std::env::var("DOMAIN_DUMP").is_ok() {
        dump(&all);
    }
}

/// The reference integration is converged: halving the step changes the range angle by less
/// than 1e-6 relative (SRM from its 100 km glide entry at three bank fractions).
#[test]
fn reference_integration_is_step_converged() {
    let veh = host_sim::vehicle::by_name("srm").unwrap();
    let env = Environment::simplified(ExponentialAtmosphere::earth());
    let m = predictor_model(&veh, &ExponentialAtmosphere::earth(), &env.planet, 20.0).unwrap();
    let r = env.planet.radius_m + 100e3;
    for f in [0.3, 0.7, 1.0] {
        let lift = LiftControl {
            lambda: 1.0,
            vertical_fraction: f,
        };
        let run = |dt| {
            integrated_range_angle(
                &m.planet,
                &m.atmosphere,
                &m.vehicle,
                &lift,
                (r, 7658.34, -0.056 * DEG),
                2500.0,
                dt,
            )
            .unwrap()
        };
        let (a, b) = (run(0.25), run(0.125));
        assert!((a - b).abs() < 1e-6 * b, "f {f}: {a} vs {b}");
    }
}

/// Bound on the range error of every prediction classed `InDomain` [%] (issue 10's goal).
const IN_DOMAIN_BOUND_PCT: f64 = 3.0;

/// Against integration of the predictor's own equations, over the re-plans the re-planner
/// applies in two closed-loop runs of the re-planning domain (SRM, simplified environment with a
/// 10 % thinner atmosphere than the predictor's; full environment heading west with a -0.2 deg
/// entry, which holds states below their glide start radius): every prediction classed
/// `InDomain` is within 3 % of the integrated range, and `InDomain` covers at least a quarter
/// of the glide-mode re-plans with more than 500 km to go (measured: 75 of 300 in domain,
/// worst 0.69 %). Measured before the domain was tightened to the random oracle's guarantee
/// (docs/validation/vinh-numerical.md): in-domain maximum 2.49 % over the whole domain (6 333
/// re-plans, scenarios and 20 + 20 campaign flights); 5.8 % before states more than 1 km below
/// their glide start radius were classed `Extrapolated(GlideBelowEquilibrium)`.
#[test]
fn validate_integration_replanning_domain_in_domain_is_within_3_percent() {
    let total = rl::fly_stored(&rl::setup(1.0, 0.0))
        .summary
        .flown_range_angle_rad;
    let target = guidance_core::replan::RangeTarget::FlownRangeAngle { total_rad: total };
    let s = rl::setup(0.9, 0.0);
    let rc = rl::replanning_config(target, rl::EVERY, PredictorMode::Auto);
    let (_, lp) = rl::fly_replanning(&s, rc);
    let mut points = recompute("SRM simplified, density x0.9", &rc, &log_of(&lp));
    for run in rl::full_environment_runs(270.0, &[-0.2]) {
        points.extend(recompute(
            "SRM full, heading 270, -0.2 deg",
            &run.config,
            &log_of(&run.lp),
        ));
    }
    let mut worst = 0.0_f64;
    let mut in_domain = 0;
    for p in &points {
        if p.prediction.validity != guidance_core::vinh::Validity::InDomain {
            continue;
        }
        in_domain += 1;
        let e = p.error_pct().unwrap_or(f64::INFINITY);
        assert!(
            e.abs() <= IN_DOMAIN_BOUND_PCT,
            "{}: {p:?}: in domain, range error {e:.2} %",
            p.scenario
        );
        worst = worst.max(e.abs());
    }
    // Coverage: glide-mode re-plans with more than 500 km to go (every chain is extrapolated:
    // the capture transition is not modelled).
    let far: Vec<&Point> = points
        .iter()
        .filter(|p| !p.chain && p.reference_rad.is_some_and(|r| r * 6_378_137.0 > 500e3))
        .collect();
    let far_in = far
        .iter()
        .filter(|p| p.prediction.validity == guidance_core::vinh::Validity::InDomain)
        .count();
    println!(
        "{} applied re-plans, {in_domain} in domain (worst error {worst:.2} %); glide mode with \
         > 500 km to go: {far_in} of {} in domain",
        points.len(),
        far.len()
    );
    // Measured 75 of 300 (210 before the domain was tightened to what the random oracle of
    // guidance-core/tests/it/vinh_oracle.rs guarantees): a 10 % thinner atmosphere keeps the
    // vehicle ~1-2 km below the model's equilibrium (GlideBelowEquilibrium), the glide start
    // falls below 80 km, the final speed (2.5 km/s) is below 0.34 of glide starts above
    // 7.35 km/s (GlideFinalSpeedRatio), and the start transient exceeds 1 % of a short glide's
    // range (GlideTransient). A coverage floor: the domain must not be empty here.
    assert!(
        far_in * 4 >= far.len(),
        "in domain {far_in} of {} far glide re-plans",
        far.len()
    );
}

/// Against integration of the predictor's own equations, with the hybrid predictor (the
/// scenario files' and the campaigns' default): every re-plan the re-planner applies is within
/// 3 % of the integrated range; a re-plan on the closed forms is `InDomain` (else the hybrid
/// would have flown the numerical prediction). Two `replan_loop` set-ups (SRM simplified with a
/// 10 % thinner atmosphere than the predictor's; full environment heading west, -0.2 deg) and
/// two dispersed flights of each built-in campaign in both re-planning modes. The whole domain
/// is measured by [`print_replanning_domain`] (docs/validation/vinh-numerical.md).
#[test]
fn validate_integration_replanning_domain_hybrid_is_within_3_percent() {
    let total = rl::fly_stored(&rl::setup(1.0, 0.0))
        .summary
        .flown_range_angle_rad;
    let target = guidance_core::replan::RangeTarget::FlownRangeAngle { total_rad: total };
    let s = rl::setup(0.9, 0.0);
    let rc = rl::replanning_config(target, rl::EVERY, PredictorMode::Hybrid);
    let (_, lp) = rl::fly_replanning(&s, rc);
    let mut points = recompute("SRM simplified, density x0.9, Hybrid", &rc, &log_of(&lp));
    for run in rl::full_environment_runs_with(270.0, &[-0.2], PredictorMode::Hybrid) {
        points.extend(recompute(
            "SRM full, heading 270, -0.2 deg, Hybrid",
            &run.config,
            &log_of(&run.lp),
        ));
    }
    points.extend(campaign(
        "srm-glide",
        &Scenario::srm_glide(),
        Some(2500.0),
        2,
        "hybrid",
    ));
    points.extend(campaign(
        "horus-2b-reference",
        &Scenario::default(),
        None,
        2,
        "hybrid",
    ));
    let (mut closed, mut numerical) = (0, 0);
    let (mut closed_worst, mut numerical_worst) = (0.0_f64, 0.0_f64);
    for p in &points {
        let e = p.error_pct().map_or(f64::INFINITY, f64::abs);
        assert!(
            e <= IN_DOMAIN_BOUND_PCT,
            "{}: {p:?}: range error {e:.2} %",
            p.scenario
        );
        if p.numerical {
            numerical += 1;
            numerical_worst = numerical_worst.max(e);
        } else {
            assert_eq!(
                p.prediction.validity,
                guidance_core::vinh::Validity::InDomain,
                "{}: {p:?}: a closed-form re-plan out of its domain",
                p.scenario
            );
            closed += 1;
            closed_worst = closed_worst.max(e);
        }
    }
    println!(
        "{} applied re-plans: {closed} on the closed forms (worst {closed_worst:.2} %), \
         {numerical} numerical (worst {numerical_worst:.3} %)",
        points.len()
    );
    // Both halves of the hybrid are exercised (the thinner atmosphere and the west heading hold
    // states below their glide equilibrium, out of the closed forms' domain).
    assert!(
        closed > 0 && numerical > 0,
        "{closed} closed, {numerical} numerical"
    );
}
