//! Closed-loop proof of onboard re-planning (SIL): `guidance-core`'s `ReplanningGuidance`
//! flying the SRM capsule in host-sim at the 2 s clock, against the stored profile alone.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Command, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent, Node, NodeTable};
use guidance_core::replan::{
    PredictorMode, RangeTarget, ReplanCase, ReplanConfig, ReplanLimits, ReplanningConfig,
    ReplanningGuidance, TargetPoint,
};
use guidance_core::vinh::PredictorConfig;
use host_sim::dynamics::{Dynamics, SphericalState};
use host_sim::env::{Environment, ExponentialAtmosphere};
use host_sim::replan_loop::{ReplanLoop, predictor_model};
use host_sim::sim::{CoreGuidance, SimConfig, SimResult, TerminationReason, simulate};

const DEG: f64 = std::f64::consts::PI / 180.0;

/// Final speed of the run and of the predictor [m/s].
const FINAL_SPEED_M_S: f64 = 2500.0;

fn entry(dgamma_deg: f64) -> SphericalState {
    let p = host_sim::env::Planet::earth_non_rotating();
    SphericalState {
        radius_m: p.radius_m + 100_000.0,
        longitude_rad: 0.0,
        latitude_rad: 0.0,
        speed_m_s: 7658.34,
        flight_path_angle_rad: (-0.056 + dgamma_deg) * DEG,
        heading_rad: 90.0 * DEG,
    }
}

/// The stored profile: the built-in SRM glide's bank schedule (0 deg at E-hat 1, 40 at 0.8,
/// 60 at 0.4, 0 at 0) sampled every 0.1 in E-hat (the same piecewise-linear profile).
fn stored_table() -> NodeTable<f64> {
    let sigma = |e: f64| -> f64 {
        if e >= 0.8 {
            40.0 * (1.0 - e) / 0.2
        } else if e >= 0.4 {
            40.0 + 20.0 * (0.8 - e) / 0.4
        } else {
            60.0 * e / 0.4
        }
    };
    let nodes: Vec<Node<f64>> = (0..=10)
        .map(|i| {
            let e = 1.0 - 0.1 * f64::from(i);
            Node {
                x: e,
                alpha_rad: 0.0,
                sigma_rad: sigma(e) * DEG,
            }
        })
        .collect();
    NodeTable::new(
        Independent::NormalizedEnergy,
        &nodes,
        AngleBounds {
            alpha_min_rad: 0.0,
            alpha_max_rad: 45.0 * DEG,
            sigma_min_rad: -90.0 * DEG,
            sigma_max_rad: 90.0 * DEG,
        },
    )
    .unwrap()
}

struct Setup {
    env: Environment,
    veh: host_sim::vehicle::Vehicle,
    cfg: SimConfig,
    energy: EnergyNormalizer<f64>,
}

fn setup(density_factor: f64, dgamma_deg: f64) -> Setup {
    let nominal = ExponentialAtmosphere::earth();
    let atm = ExponentialAtmosphere::new(
        nominal.rho0_kg_m3() * density_factor,
        nominal.scale_height_m(),
        nominal.reference_altitude_m(),
    )
    .unwrap();
    let env = Environment::simplified(atm);
    let veh = host_sim::vehicle::by_name("srm").unwrap();
    // Nominal entry defines E-hat = 1 for every run (the table is the same).
    let e0 = entry(0.0);
    let energy =
        EnergyNormalizer::new(env.planet.mu_m3_s2, env.planet.radius_m, e0.radius_m, e0.speed_m_s)
            .unwrap();
    let mut cfg = SimConfig::new(entry(dgamma_deg));
    let a = env.atmosphere.state(50_000.0).speed_of_sound_m_s;
    cfg.termination.altitude_m = Some(15_000.0);
    cfg.termination.mach = Some(FINAL_SPEED_M_S / a);
    cfg.termination.max_time_s = 5000.0;
    cfg.tolerances.rtol = 1e-7;
    Setup {
        env,
        veh,
        cfg,
        energy,
    }
}

fn initial() -> Command<f64> {
    Command {
        alpha_rad: 0.0,
        sigma_rad: 0.0,
    }
}

fn fly_stored(s: &Setup) -> SimResult {
    let g = guidance_core::guidance::Guidance::new(
        GuidanceConfig::thesis_default(),
        stored_table(),
        Interpolation::Linear,
        s.energy,
        initial(),
    )
    .unwrap();
    let dynm = Dynamics::from_environment(&s.env, &s.veh);
    simulate(dynm, CoreGuidance(g), &s.cfg, &mut |_, _| {}).unwrap().0
}

fn replanning_config(target: RangeTarget<f64>, every: u16, mode: PredictorMode) -> ReplanningConfig<f64> {
    let veh = host_sim::vehicle::by_name("srm").unwrap();
    let p = host_sim::env::Planet::earth_non_rotating();
    ReplanningConfig {
        every_n_ticks: every,
        target,
        limits: ReplanLimits {
            heat_flux_w_m2: 1e9,
            g_load: 1e3,
        },
        solver: ReplanConfig {
            lambda: 1.0,
            min_vertical_fraction: 0.05,
            max_vertical_fraction: 1.0,
            tolerance_m: 1000.0,
            max_iterations: 20,
            predictor: PredictorConfig {
                final_speed_m_s: FINAL_SPEED_M_S,
                max_skips: 4,
            },
            mode,
        },
        model: predictor_model(&veh, &ExponentialAtmosphere::earth(), &p, 20.0).unwrap(),
        apply_out_of_reach: true,
    }
}

fn fly_replanning(s: &Setup, rc: ReplanningConfig<f64>) -> (SimResult, ReplanLoop) {
    let g = ReplanningGuidance::new(
        GuidanceConfig::thesis_default(),
        stored_table(),
        Interpolation::Linear,
        s.energy,
        initial(),
        rc,
    )
    .unwrap();
    let dynm = Dynamics::from_environment(&s.env, &s.veh);
    simulate(dynm, ReplanLoop::new(g), &s.cfg, &mut |_, _| {}).unwrap()
}

fn end_point(r: &SimResult) -> TargetPoint<f64> {
    let e = r.samples.last().unwrap().state;
    TargetPoint {
        latitude_rad: e.latitude_rad,
        longitude_rad: e.longitude_rad,
    }
}

/// Great-circle distance [m] from the run's end to the target.
fn miss_m(r: &SimResult, t: &TargetPoint<f64>) -> f64 {
    let e = r.samples.last().unwrap().state;
    let a = host_sim::sim::great_circle(
        &e,
        &SphericalState {
            latitude_rad: t.latitude_rad,
            longitude_rad: t.longitude_rad,
            ..e
        },
    );
    a * host_sim::env::Planet::earth_non_rotating().radius_m
}

#[test]
#[ignore]
fn explore() {
    let nom = setup(1.0, 0.0);
    let t0 = std::time::Instant::now();
    let rn = fly_stored(&nom);
    println!(
        "nominal: {:?} t={:.1} s, range {:.1} km, ({:?})",
        rn.summary.termination,
        rn.summary.flight_time_s,
        rn.summary.range_angle_rad * 6378.137,
        t0.elapsed()
    );
    let point = end_point(&rn);
    let total = rn.summary.flown_range_angle_rad;
    let mode = match std::env::var("MODE").as_deref() { Ok("chain") => PredictorMode::Chain, Ok("glide") => PredictorMode::Glide, _ => PredictorMode::Auto };
    let use_point = std::env::var("POINT").is_ok();
    let every: u16 = std::env::var("EVERY").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    let target = if use_point { RangeTarget::Point(point) } else { RangeTarget::FlownRangeAngle { total_rad: total } };
    let re = 6378.137;
    for (df, dg) in [(1.0, 0.0), (1.1, 0.0), (0.9, 0.0), (1.0, -0.2), (1.0, 0.1)] {
        let s = setup(df, dg);
        let rs = fly_stored(&s);
        let t0 = std::time::Instant::now();
        let (rr, lp) = fly_replanning(&s, replanning_config(target, every, mode));
        println!(
            "df {df} dg {dg}: stored miss {:.1} km / flown {:.1} km ({:?}), replan miss {:.1} km / flown {:.1} km ({:?}, {:?}) odo {:.1}",
            miss_m(&rs, &point) / 1e3,
            (rs.summary.flown_range_angle_rad - total) * re,
            rs.summary.termination,
            miss_m(&rr, &point) / 1e3,
            (rr.summary.flown_range_angle_rad - total) * re,
            rr.summary.termination,
            t0.elapsed(),
            (lp.guidance.flown_range_angle_rad() - rr.summary.flown_range_angle_rad) * re,
        );
        println!("  counts {:?}", lp.guidance.counts());
        for r in lp.reports.iter().step_by(10) {
            println!(
                "  t {:.0} E {:.3} rtg {:.1} km case {:?} calls {} bank {:.1} pred {:?} applied {}",
                r.time_s,
                r.normalized_energy,
                r.range_to_go_m / 1e3,
                r.case,
                r.predictor_calls,
                r.bank_rad / DEG,
                r.predicted_range_m.map(|x| (x / 1e3).round()),
                r.applied
            );
        }
    }
    let _ = ReplanCase::Converged;
    let _ = TerminationReason::Mach;
}
