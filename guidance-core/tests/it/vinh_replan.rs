//! Tests of the onboard re-planner (`guidance_core::replan`) built on the Vinh predictor.

use crate::vinh_support::inputs::{atmosphere, lift, planet, srm};
use crate::vinh_support::vehicles::{self, H_S, MU, R_EARTH, RHO0};
use guidance_core::NavState;
use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Command, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, HostNodeTable, Independent, NodeTable};
use guidance_core::replan::{
    HostReplanningGuidance, MAX_PREDICTOR_CALLS, PredictorMode, PredictorModel, RangeTarget,
    ReplanCase, ReplanConfig, ReplanFallBack, ReplanLimits, ReplanningConfig, ReplanningGuidance,
    TargetPoint, predict_glide, predict_glide_with_sink, range_to_go_m, replan,
};
use guidance_core::vinh::{
    EntryState, ExpAtmosphere, LiftControl, PeakMode, Planet, PredictorConfig, VehicleParams,
    VinhError, predict,
};
use proptest::prelude::*;

pub(crate) fn nav(v: f64, g_deg: f64) -> NavState<f64> {
    NavState {
        time_s: 0.0,
        radius_m: R_EARTH + 122e3,
        speed_m_s: v,
        flight_path_angle_rad: g_deg.to_radians(),
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}
pub(crate) fn config() -> ReplanConfig<f64> {
    ReplanConfig {
        lambda: 1.0,
        min_vertical_fraction: 0.3,
        max_vertical_fraction: 1.0,
        tolerance_m: 1000.0,
        max_iterations: 40,
        predictor: PredictorConfig {
            final_speed_m_s: 2500.0,
            max_skips: 4,
        },
        mode: PredictorMode::Chain,
    }
}
pub(crate) fn range_at(n: &NavState<f64>, f: f64) -> guidance_core::vinh::Prediction<f64> {
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    };
    let s = EntryState {
        radius_m: n.radius_m,
        speed_m_s: n.speed_m_s,
        flight_path_angle_rad: n.flight_path_angle_rad,
    };
    predict(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    )
    .unwrap()
}
pub(crate) const NO_LIMITS: ReplanLimits<f64> = ReplanLimits {
    heat_flux_w_m2: 1e12,
    g_load: 1e6,
};

/// A target produced by the predictor at a known fraction is met within tolerance, with a
/// bounded number of predictor calls.
#[test]
fn replan_converges_on_a_reachable_target() {
    let n = nav(7000.0, -4.0);
    for &f_true in &[0.45, 0.7, 0.9] {
        let target = range_at(&n, f_true).range_m;
        let r = replan(
            &planet(),
            &atmosphere(),
            &srm(),
            &n,
            target,
            &NO_LIMITS,
            &config(),
        );
        assert_eq!(r.case, ReplanCase::Converged, "{r:?}");
        let p = r.prediction.unwrap();
        assert!(
            (p.range_m - target).abs() <= 1000.0,
            "{} vs {target}",
            p.range_m
        );
        assert!(r.predictor_calls <= 40 + 2 + 16);
        assert!((r.bank_rad.cos() - r.vertical_fraction).abs() < 1e-12);
    }
}

/// Targets beyond the reachable interval return the nearest end.
#[test]
fn replan_reports_target_out_of_reach() {
    let n = nav(7000.0, -4.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e9,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::TargetOutOfReach);
    assert_eq!(r.vertical_fraction, 1.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1.0,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::TargetOutOfReach);
    assert_eq!(r.vertical_fraction, 0.3);
}

/// A heat-flux limit below the peak at the range solution makes the limits bind: the returned
/// fraction satisfies the limit. An unreachable limit falls back.
#[test]
fn replan_limits_bind() {
    let n = nav(7000.0, -4.0);
    let target = range_at(&n, 1.0).range_m;
    let free = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &NO_LIMITS,
        &config(),
    );
    let q_free = free.prediction.unwrap().peak_heat_flux_w_m2;
    let q_min = (0..16)
        .map(|i| range_at(&n, 0.3 + 0.7 * f64::from(i) / 15.0).peak_heat_flux_w_m2)
        .fold(f64::INFINITY, f64::min);
    assert!(q_min < q_free, "{q_min} vs {q_free}");
    let lim = ReplanLimits {
        heat_flux_w_m2: 0.5 * (q_free + q_min),
        g_load: 1e6,
    };
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &lim,
        &config(),
    );
    assert_eq!(r.case, ReplanCase::LimitsBind, "{r:?}");
    assert!(r.prediction.unwrap().peak_heat_flux_w_m2 <= lim.heat_flux_w_m2);
    let lim = ReplanLimits {
        heat_flux_w_m2: 0.5 * q_min,
        g_load: 1e6,
    };
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        target,
        &lim,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::LimitsInfeasible)
    );
}

/// Out of the predictor's domain: fall back to the stored profile with the reason.
#[test]
fn replan_falls_back_out_of_domain() {
    let mut n = nav(7000.0, -4.0);
    n.speed_m_s = f64::NAN;
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e6,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::OutOfDomain(VinhError::NonFiniteInput))
    );
    // Shallow entry above escape speed: the arc after the skip is hyperbolic.
    let n = nav(11_500.0, -2.0);
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &n,
        1e6,
        &NO_LIMITS,
        &config(),
    );
    assert_eq!(
        r.case,
        ReplanCase::FallBack(ReplanFallBack::OutOfDomain(VinhError::EscapeTrajectory)),
        "{r:?}"
    );
    assert!(r.prediction.is_none());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    #[test]
    fn replan_never_panics(v in 3000.0..11000.0f64, g in -0.2..0.05f64, target in -1e6..3e7f64, fmin in -0.2..1.2f64, q in 1e4..1e7f64) {
        let mut n = nav(v, 0.0);
        n.flight_path_angle_rad = g;
        let cfg = ReplanConfig { min_vertical_fraction: fmin, ..config() };
        let r = replan(&planet(), &atmosphere(), &srm(), &n, target, &ReplanLimits { heat_flux_w_m2: q, g_load: 5.0 }, &cfg);
        prop_assert!(r.vertical_fraction.is_finite() && r.bank_rad.is_finite());
        prop_assert!(r.predictor_calls <= 58);
        prop_assert!(r.predictor_calls <= MAX_PREDICTOR_CALLS);
        if let Some(p) = r.prediction {
            prop_assert!(p.range_m.is_finite() && p.peak_heat_flux_w_m2.is_finite() && p.peak_g_load.is_finite());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// ReplanningGuidance: the solver inside the guidance loop.
// ---------------------------------------------------------------------------------------------

pub(crate) const DEG: f64 = std::f64::consts::PI / 180.0;

/// SRM glide entry of thesis sec. 9.2 (100 km, 7658.34 m/s, -0.056 deg), on the equator
/// heading east.
pub(crate) fn glide_nav(t: f64) -> NavState<f64> {
    NavState {
        time_s: t,
        radius_m: R_EARTH + 100e3,
        speed_m_s: 7658.34,
        flight_path_angle_rad: -0.056 * DEG,
        heading_rad: 90.0 * DEG,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

/// The SRM on the equilibrium glide (the glide's imposed state, eq. 3.78-3.79) at `alt_m` above
/// `R_EARTH` for lambda = 1 and vertical lift fraction `f`: `glide_nav(0.0)` with that radius,
/// speed and flight-path angle.
pub(crate) fn srm_equilibrium_glide_nav(f: f64, alt_m: f64) -> NavState<f64> {
    let eq = guidance_core::vinh::GlideSolution::new(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift(f),
        R_EARTH + alt_m,
    )
    .unwrap()
    .imposed_entry();
    NavState {
        radius_m: eq.radius_m,
        speed_m_s: eq.speed_m_s,
        flight_path_angle_rad: eq.flight_path_angle_rad,
        ..glide_nav(0.0)
    }
}

pub(crate) fn model() -> PredictorModel<f64> {
    PredictorModel {
        planet: planet(),
        atmosphere: atmosphere(),
        vehicle: srm(),
        rotation_rate_rad_s: 0.0,
    }
}

pub(crate) fn glide_solver(mode: PredictorMode) -> ReplanConfig<f64> {
    ReplanConfig {
        min_vertical_fraction: 0.05,
        tolerance_m: 1000.0,
        max_iterations: 30,
        mode,
        ..config()
    }
}

pub(crate) fn rcfg(
    target: RangeTarget<f64>,
    every: u16,
    mode: PredictorMode,
) -> ReplanningConfig<f64> {
    ReplanningConfig {
        every_n_ticks: every,
        target,
        limits: NO_LIMITS,
        solver: glide_solver(mode),
        model: model(),
        apply_out_of_reach: false,
        steps_per_tick: 0,
    }
}

/// Energy table: E-hat 1.0 .. 0.0 with a negative bank on one node (sign convention kept).
pub(crate) fn energy_table() -> NodeTable<f64> {
    let rows = [
        (1.0, 5.0, 10.0),
        (0.8, 6.0, 40.0),
        (0.6, 7.0, -50.0),
        (0.4, 8.0, 60.0),
        (0.0, 9.0, 0.0),
    ];
    NodeTable::from_deg(
        Independent::NormalizedEnergy,
        &rows,
        AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).unwrap(),
    )
    .unwrap()
}

/// E-hat = 1 at 100 km and 7700 m/s: the glide entry state is at E-hat 0.99 (below node 0).
pub(crate) fn normalizer() -> EnergyNormalizer<f64> {
    EnergyNormalizer::new(MU, R_EARTH, R_EARTH + 100e3, 7700.0).unwrap()
}

pub(crate) fn replanning(cfg: ReplanningConfig<f64>) -> ReplanningGuidance<f64> {
    replanning_on(energy_table(), cfg)
}

/// [`replanning`] on the table `table` (any capacity).
fn replanning_on<const N: usize>(
    table: NodeTable<f64, N>,
    cfg: ReplanningConfig<f64>,
) -> ReplanningGuidance<f64, N> {
    ReplanningGuidance::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::Linear,
        normalizer(),
        Command::from_deg(5.0, 10.0).unwrap(),
        cfg,
    )
    .unwrap()
}

pub(crate) fn glide_range_m(f: f64) -> f64 {
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    };
    let n = glide_nav(0.0);
    let s = EntryState {
        radius_m: n.radius_m,
        speed_m_s: n.speed_m_s,
        flight_path_angle_rad: n.flight_path_angle_rad,
    };
    predict_glide(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    )
    .unwrap()
    .range_m
}

/// The first tick re-plans: with a target produced by the glide predictor at f = 0.6 the
/// solver converges to sigma = acos(0.6); every remaining node (E-hat below the current 1.0)
/// gets that magnitude with its own sign, the passed node and every angle of attack are kept.
#[test]
fn replanning_sets_the_remaining_nodes() {
    let total = glide_range_m(0.6) / R_EARTH;
    let mut g = replanning(rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Glide,
    ));
    let before = g.guidance().table().clone();
    let out = g.update(&glide_nav(0.0)).unwrap();
    assert!(out.guidance.ticked);
    let r = out.replan.expect("tick 0 re-plans");
    assert_eq!(r.case, ReplanCase::Converged, "{r:?}");
    assert!(r.applied);
    assert_eq!(r.nodes_replanned, 4);
    assert!((r.predicted_range_m.unwrap() - total * R_EARTH).abs() <= 1000.0);
    assert!(
        (r.bank_rad - 0.6f64.acos()).abs() < 0.5 * DEG,
        "{}",
        r.bank_rad / DEG
    );
    let after = g.guidance().table();
    let (n0, b0) = (after.nodes()[0], before.nodes()[0]);
    assert_eq!(n0, b0, "the passed node is kept");
    for (a, b) in after.nodes().iter().zip(before.nodes()).skip(1) {
        assert_eq!(a.x, b.x);
        assert_eq!(a.alpha_rad, b.alpha_rad);
        let want = if b.sigma_rad < 0.0 {
            -r.bank_rad
        } else {
            r.bank_rad
        };
        assert_eq!(a.sigma_rad, want);
    }
    assert_eq!(g.counts().converged, 1);
    assert_eq!(g.counts().applied, 1);
}

/// A node at most `NODE_EDGE_E_HAT` above the current E-hat counts as remaining: a re-plan sets
/// it; a node further above is passed and kept. (Without the margin a node at the current
/// E-hat was replaced or kept by the last bit of E-hat, which f64, f32 and fixed point round
/// differently.)
#[test]
fn a_node_within_the_edge_above_e_hat_is_replanned() {
    use guidance_core::replan::NODE_EDGE_E_HAT;
    let e_now = normalizer()
        .normalized(glide_nav(0.0).radius_m, glide_nav(0.0).speed_m_s)
        .unwrap();
    let total = glide_range_m(0.6) / R_EARTH;
    for (above, replanned) in [(0.5 * NODE_EDGE_E_HAT, 5), (2.0 * NODE_EDGE_E_HAT, 4)] {
        let rows = [
            (e_now + above, 5.0, 10.0),
            (0.8, 6.0, 40.0),
            (0.6, 7.0, -50.0),
            (0.4, 8.0, 60.0),
            (0.0, 9.0, 0.0),
        ];
        let table = NodeTable::from_deg(
            Independent::NormalizedEnergy,
            &rows,
            AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).unwrap(),
        )
        .unwrap();
        let mut g: ReplanningGuidance<f64> = replanning_on(
            table,
            rcfg(
                RangeTarget::FlownRangeAngle { total_rad: total },
                3,
                PredictorMode::Glide,
            ),
        );
        let r = g
            .update(&glide_nav(0.0))
            .unwrap()
            .replan
            .expect("tick 0 re-plans");
        assert!(r.applied, "{r:?}");
        assert_eq!(r.nodes_replanned, replanned, "node {above} above E-hat");
        let first = g.guidance().table().nodes()[0].sigma_rad;
        if replanned == 5 {
            assert_eq!(first, r.bank_rad);
        } else {
            assert_eq!(first, 10.0 * DEG);
        }
    }
}

/// Re-planning works on a host-sized table (256 energy nodes): every node below the current
/// E-hat gets the solved bank magnitude with its own sign (far more than the 16 the firmware
/// table holds).
#[test]
fn replanning_with_a_host_sized_table() {
    let rows: Vec<(f64, f64, f64)> = (0..256)
        .map(|i| {
            let e = 1.0 - f64::from(i) / 255.0;
            let sign = if i % 7 == 3 { -1.0 } else { 1.0 };
            (e, 5.0 + 4.0 * (1.0 - e), sign * (10.0 + 50.0 * (1.0 - e)))
        })
        .collect();
    let table: HostNodeTable<f64> = NodeTable::from_deg(
        Independent::NormalizedEnergy,
        &rows,
        AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).unwrap(),
    )
    .unwrap();
    let total = glide_range_m(0.6) / R_EARTH;
    let mut g: HostReplanningGuidance<f64> = replanning_on(
        table.clone(),
        rcfg(
            RangeTarget::FlownRangeAngle { total_rad: total },
            3,
            PredictorMode::Glide,
        ),
    );
    let out = g.update(&glide_nav(0.0)).unwrap();
    let r = out.replan.expect("tick 0 re-plans");
    assert_eq!(r.case, ReplanCase::Converged, "{r:?}");
    let e_hat = out.guidance.independent_value;
    let below = table.nodes().iter().filter(|n| n.x < e_hat).count();
    assert!(below > 200, "{below}");
    assert_eq!(usize::from(r.nodes_replanned), below);
    for (a, b) in g.guidance().table().nodes().iter().zip(table.nodes()) {
        let want = if b.x >= e_hat {
            b.sigma_rad
        } else if b.sigma_rad < 0.0 {
            -r.bank_rad
        } else {
            r.bank_rad
        };
        assert_eq!(a.sigma_rad, want);
        assert_eq!((a.x, a.alpha_rad), (b.x, b.alpha_rad));
    }
}

/// Re-plans run on ticks 0, N, 2N, ... of the 2 s clock, never between ticks.
#[test]
fn replanning_runs_every_n_ticks() {
    let total = glide_range_m(0.6) / R_EARTH;
    for every in [1_u16, 3, 4] {
        let mut g = replanning(rcfg(
            RangeTarget::FlownRangeAngle { total_rad: total },
            every,
            PredictorMode::Glide,
        ));
        let mut replan_ticks = vec![];
        // Samples every 0.5 s for 30 s: ticks at 0, 2, ..., 30 s.
        for k in 0..=60 {
            let t = 0.5 * f64::from(k);
            let out = g.update(&glide_nav(t)).unwrap();
            if let Some(r) = out.replan {
                assert!(out.guidance.ticked, "re-plan off a tick at {t}");
                assert_eq!(r.time_s, t);
                replan_ticks.push(r.tick);
            }
        }
        let want: Vec<u32> = (0..16).filter(|k| k % u32::from(every) == 0).collect();
        assert_eq!(replan_ticks, want, "every {every}");
        assert_eq!(g.ticks(), 16);
        assert_eq!(g.counts().replans as usize, want.len());
    }
}

/// Out of the predictor's domain (final speed above the current speed: no glide reaches it):
/// every re-plan is a reported fall-back and the stored table stays in use.
#[test]
fn replanning_falls_back_to_the_stored_profile() {
    let mut cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: 1.0 },
        1,
        PredictorMode::Auto,
    );
    cfg.solver.predictor.final_speed_m_s = 9000.0;
    let mut g = replanning(cfg);
    let stored = g.guidance().table().clone();
    for k in 0..5 {
        let out = g.update(&glide_nav(2.0 * f64::from(k))).unwrap();
        let r = out.replan.unwrap();
        assert!(
            matches!(r.case, ReplanCase::FallBack(ReplanFallBack::OutOfDomain(_))),
            "{r:?}"
        );
        assert!(!r.applied);
        assert_eq!(r.nodes_replanned, 0);
        assert!(r.predicted_range_m.is_none());
    }
    assert_eq!(g.guidance().table(), &stored);
    assert_eq!(g.counts().fall_backs, 5);
    assert_eq!(g.counts().applied, 0);
}

/// Mid-glide (the equilibrium-glide state at 70 km for cos(sigma) = 0.3) the skip closed form
/// of the chain is out of domain; the chain mode falls back, the automatic mode switches to the
/// glide prediction and converges.
#[test]
fn auto_mode_switches_to_the_glide_when_the_chain_is_out_of_domain() {
    let n = srm_equilibrium_glide_nav(0.3, 70e3);
    let s = EntryState {
        radius_m: n.radius_m,
        speed_m_s: n.speed_m_s,
        flight_path_angle_rad: n.flight_path_angle_rad,
    };
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: 0.5,
    };
    let chain = predict(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    );
    assert!(chain.is_err(), "{chain:?}");
    let target = predict_glide(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    )
    .unwrap()
    .range_m;
    let run = |mode| {
        replan(
            &planet(),
            &atmosphere(),
            &srm(),
            &n,
            target,
            &NO_LIMITS,
            &glide_solver(mode),
        )
    };
    let c = run(PredictorMode::Chain);
    assert!(matches!(
        c.case,
        ReplanCase::FallBack(ReplanFallBack::OutOfDomain(_))
    ));
    let a = run(PredictorMode::Auto);
    assert_eq!(a.case, ReplanCase::Converged, "{a:?}");
    assert!((a.prediction.unwrap().range_m - target).abs() <= 1000.0);
    assert!(a.predictor_calls <= MAX_PREDICTOR_CALLS);
    let g = run(PredictorMode::Glide);
    assert_eq!(g.case, ReplanCase::Converged);
    assert_eq!(g.vertical_fraction, a.vertical_fraction);
    assert_eq!(a.predictor_calls, g.predictor_calls + 2);
}

/// Range to go to a point: quarter great circle along the equator, the sign flips when the
/// target is behind, and a point target drives the solver like the equivalent range.
#[test]
fn range_to_go_to_a_point() {
    let t = TargetPoint {
        latitude_rad: 0.0,
        longitude_rad: 90.0 * DEG,
    };
    let n = glide_nav(0.0);
    let r = range_to_go_m(&n, &t, R_EARTH).unwrap();
    assert!(
        (r - R_EARTH * std::f64::consts::FRAC_PI_2).abs() < 1e-6,
        "{r}"
    );
    let back = NavState {
        heading_rad: 270.0 * DEG,
        ..n
    };
    assert!((range_to_go_m(&back, &t, R_EARTH).unwrap() + r).abs() < 1e-6);
    // North pole from the equator: pi/2 whatever the longitude; 45 deg off the heading.
    let pole = TargetPoint {
        latitude_rad: 90.0 * DEG,
        longitude_rad: 123.0 * DEG,
    };
    let ne = NavState {
        heading_rad: 45.0 * DEG,
        ..n
    };
    let rp = range_to_go_m(&ne, &pole, R_EARTH).unwrap();
    assert!((rp - R_EARTH * std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    assert!(
        range_to_go_m(
            &NavState {
                latitude_rad: f64::NAN,
                ..n
            },
            &t,
            R_EARTH
        )
        .is_none()
    );
    // A point target at the glide range along the heading gives the same solution as the
    // equivalent flown-range target.
    let theta = glide_range_m(0.6) / R_EARTH;
    let point = TargetPoint {
        latitude_rad: 0.0,
        longitude_rad: theta,
    };
    let mut gp = replanning(rcfg(RangeTarget::Point(point), 1, PredictorMode::Glide));
    let mut gr = replanning(rcfg(
        RangeTarget::FlownRangeAngle { total_rad: theta },
        1,
        PredictorMode::Glide,
    ));
    let rp = gp.update(&glide_nav(0.0)).unwrap().replan.unwrap();
    let rr = gr.update(&glide_nav(0.0)).unwrap().replan.unwrap();
    assert!((rp.range_to_go_m - rr.range_to_go_m).abs() < 1e-3);
    assert_eq!(rp.case, ReplanCase::Converged);
    assert!((rp.bank_rad - rr.bank_rad).abs() < 1e-9);
}

/// The onboard odometer sums the great-circle steps between samples, and the range to go of a
/// flown-range target shrinks by what was flown.
#[test]
fn odometer_accumulates_flown_range() {
    let total = 0.5;
    let mut g = replanning(rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        1,
        PredictorMode::Glide,
    ));
    // Along the equator 0.001 rad per 2 s, then north 0.002 rad.
    let mut lon = 0.0;
    let mut lat = 0.0;
    for k in 0..10 {
        let n = NavState {
            longitude_rad: lon,
            latitude_rad: lat,
            ..glide_nav(2.0 * f64::from(k))
        };
        let out = g.update(&n).unwrap();
        let r = out.replan.unwrap();
        let want = (total - g.flown_range_angle_rad()) * R_EARTH;
        assert!((r.range_to_go_m - want).abs() < 1e-3);
        if k < 5 {
            lon += 0.001;
        } else {
            lat += 0.002;
        }
    }
    let flown = g.flown_range_angle_rad();
    assert!(
        (flown - (5.0 * 0.001 + 4.0 * 0.002)).abs() < 1e-9,
        "{flown}"
    );
}

#[test]
fn replanning_rejects_bad_config() {
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: 1.0 },
        0,
        PredictorMode::Glide,
    );
    let mk = |table: NodeTable<f64>, cfg| {
        ReplanningGuidance::new(
            GuidanceConfig::thesis_default(),
            table,
            Interpolation::Linear,
            normalizer(),
            Command::from_deg(5.0, 10.0).unwrap(),
            cfg,
        )
    };
    assert!(mk(energy_table(), cfg).is_err());
    let ok = ReplanningConfig {
        every_n_ticks: 1,
        ..cfg
    };
    assert!(mk(energy_table(), ok).is_ok());
    assert!(
        mk(
            guidance_core::missions::horus2b_reference().unwrap().table,
            ok
        )
        .is_err()
    );
    let nan = ReplanningConfig {
        target: RangeTarget::Point(TargetPoint {
            latitude_rad: f64::NAN,
            longitude_rad: 0.0,
        }),
        ..ok
    };
    assert!(mk(energy_table(), nan).is_err());
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -1e7..1e7f64,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(0.0),
    ]
}

fn nav_strategy() -> impl Strategy<Value = (f64, f64, f64, f64, f64, f64, f64)> {
    (
        prop_oneof![4 => 0.0..1e4f64, 1 => any_f64()],
        prop_oneof![4 => (R_EARTH + 20e3)..(R_EARTH + 130e3), 1 => any_f64()],
        prop_oneof![4 => 1000.0..11000.0f64, 1 => any_f64()],
        prop_oneof![4 => -0.3..0.1f64, 1 => any_f64()],
        prop_oneof![4 => -7.0..7.0f64, 1 => any_f64()],
        prop_oneof![4 => -1.6..1.6f64, 1 => any_f64()],
        prop_oneof![4 => -4.0..4.0f64, 1 => any_f64()],
    )
}

fn mode_strategy() -> impl Strategy<Value = PredictorMode> {
    prop_oneof![
        Just(PredictorMode::Chain),
        Just(PredictorMode::Glide),
        Just(PredictorMode::Auto)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    /// Random (also non-finite) navigation states through `ReplanningGuidance` in f64 and f32:
    /// never a panic, every command finite and inside the table's bounds, at most
    /// `MAX_PREDICTOR_CALLS` predictor calls per re-plan, every reported number finite.
    #[test]
    fn replanning_guidance_never_panics_never_nan(
        navs in proptest::collection::vec(nav_strategy(), 1..6),
        mode in mode_strategy(),
        every in 1u16..3,
        total in prop_oneof![4 => -1.0..3.0f64, 1 => Just(1e30)],
        point in any::<bool>(),
        steps in 0u8..3,
    ) {
        let target = if point {
            RangeTarget::Point(TargetPoint { latitude_rad: 0.3, longitude_rad: total })
        } else {
            RangeTarget::FlownRangeAngle { total_rad: total }
        };
        let mut g = replanning(rcfg(target, every, mode));
        let mut g32 = ReplanningGuidance::<f32>::new(
            GuidanceConfig::thesis_default(),
            NodeTable::from_deg(Independent::NormalizedEnergy, &[(1.0, 5.0, 10.0), (0.6, 7.0, -50.0), (0.0, 9.0, 0.0)],
                AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).unwrap()).unwrap(),
            Interpolation::NaturalCubic,
            EnergyNormalizer::new(MU, R_EARTH, R_EARTH + 100e3, 7658.34).unwrap(),
            Command::from_deg(5.0, 10.0).unwrap(),
            ReplanningConfig {
                every_n_ticks: every,
                target: match target {
                    RangeTarget::Point(p) => RangeTarget::Point(TargetPoint { latitude_rad: p.latitude_rad as f32, longitude_rad: p.longitude_rad as f32 }),
                    RangeTarget::FlownRangeAngle { total_rad } => RangeTarget::FlownRangeAngle { total_rad: total_rad as f32 },
                },
                limits: ReplanLimits { heat_flux_w_m2: 1e9, g_load: 1e3 },
                solver: ReplanConfig {
                    lambda: 1.0, min_vertical_fraction: 0.05, max_vertical_fraction: 1.0,
                    tolerance_m: 1000.0, max_iterations: 30,
                    predictor: PredictorConfig { final_speed_m_s: 2500.0, max_skips: 4 }, mode,
                },
                model: PredictorModel {
                    planet: Planet { mu_m3_s2: MU as f32, radius_m: R_EARTH as f32 },
                    atmosphere: ExpAtmosphere { rho0_kg_m3: RHO0 as f32, scale_height_m: H_S as f32, ref_radius_m: R_EARTH as f32 },
                    vehicle: { let v = srm(); VehicleParams { mass_kg: v.mass_kg as f32, reference_area_m2: v.reference_area_m2 as f32, cd0: v.cd0 as f32, k_polar: v.k_polar as f32, nose_radius_m: v.nose_radius_m as f32 } },
                    rotation_rate_rad_s: if point { 7.292_115e-5 } else { 0.0 },
                },
                apply_out_of_reach: true,
                steps_per_tick: steps,
            },
        ).unwrap();
        let bounds = g.guidance().table().bounds();
        for (t, r, v, gam, h, lat, lon) in navs {
            let n = NavState { time_s: t, radius_m: r, speed_m_s: v, flight_path_angle_rad: gam, heading_rad: h, latitude_rad: lat, longitude_rad: lon };
            if let Ok(out) = g.update(&n) {
                let c = out.guidance.command;
                prop_assert!(c.is_finite());
                prop_assert!(bounds.alpha_ok(c.alpha_rad) && bounds.sigma_ok(c.sigma_rad));
                if let Some(rep) = out.replan {
                    prop_assert!(rep.predictor_calls <= MAX_PREDICTOR_CALLS);
                    prop_assert!(rep.bank_rad.is_finite() && rep.range_to_go_m.is_finite());
                    prop_assert!(rep.predicted_range_m.is_none_or(f64::is_finite));
                }
            }
            let a = g.guidance().attitude_at(t);
            prop_assert!(a.is_finite());
            let n32 = NavState { time_s: t as f32, radius_m: r as f32, speed_m_s: v as f32, flight_path_angle_rad: gam as f32, heading_rad: h as f32, latitude_rad: lat as f32, longitude_rad: lon as f32 };
            if let Ok(out) = g32.update(&n32) {
                prop_assert!(out.guidance.command.is_finite());
                prop_assert!(steps == 0 || out.predictor_calls <= steps);
                if let Some(rep) = out.replan {
                    prop_assert!(rep.predictor_calls <= MAX_PREDICTOR_CALLS);
                    prop_assert!(rep.bank_rad.is_finite() && rep.range_to_go_m.is_finite());
                }
            }
            prop_assert!(g32.guidance().attitude_at(t as f32).is_finite());
            for tab in [g.guidance().table()] {
                for node in tab.nodes() {
                    prop_assert!(node.sigma_rad.is_finite() && bounds.sigma_ok(node.sigma_rad));
                }
            }
        }
    }
}

/// Glide-mode prediction (`predict_glide`) against numerical integration of the planar
/// equations of motion (Dormand-Prince 5(4), rtol 1e-11, `vinh_support`), constant bank, from
/// the SRM glide entry (100 km, 7658.34 m/s, -0.056 deg: the equilibrium for cos(sigma) = 1)
/// to 2.5 km/s. For cos(sigma) < 1 the start is above the equilibrium of that bank: the
/// vehicle sinks in a phugoid that the glide prediction (started at its equilibrium radius,
/// the descent to it not modelled: zero range) does not contain. Checked: the thesis' <= 3 %
/// at the equilibrium start; below it the prediction falls short (the missing descent) and the
/// shortfall grows as the start moves away from the equilibrium (smaller cos(sigma)).
/// Measured (docs/validation/vinh-numerical.md): -10.3 % at 0.3, -3.2 % at 0.5, -0.9 % at 0.7, +0.6 % at 1.
/// `predict_glide_with_sink` adds the sink (`sink_range_angle`): within 3 % at every bank.
#[test]
fn validate_dormand_prince_glide_predictor_range() {
    use crate::vinh_support::dynamics::{Lift, eom_dim};
    use crate::vinh_support::ode::{Settings, integrate};
    let veh = vehicles::srm();
    let n = glide_nav(0.0);
    let mut errs = vec![];
    for f in [0.3, 0.5, 0.7, 1.0] {
        let sol = integrate(
            eom_dim(
                &veh,
                Lift {
                    lambda: 1.0,
                    cos_bank: f,
                },
            ),
            0.0,
            [n.radius_m, n.speed_m_s, n.flight_path_angle_rad, 0.0],
            50_000.0,
            Settings::tight(5.0),
            |_t, y| y[1] - 2500.0,
        );
        let (_, ye) = sol.event.expect("reaches 2.5 km/s");
        let lift = LiftControl {
            lambda: 1.0,
            vertical_fraction: f,
        };
        let s = EntryState {
            radius_m: n.radius_m,
            speed_m_s: n.speed_m_s,
            flight_path_angle_rad: n.flight_path_angle_rad,
        };
        let p = predict_glide(
            &planet(),
            &atmosphere(),
            &srm(),
            &lift,
            &s,
            &config().predictor,
        )
        .unwrap();
        let err = (p.range_angle_rad - ye[3]) / ye[3];
        let ps = predict_glide_with_sink(
            &planet(),
            &atmosphere(),
            &srm(),
            &lift,
            &s,
            &config().predictor,
            PeakMode::RangeOnly,
        )
        .unwrap();
        let err_sink = (ps.range_angle_rad - ye[3]) / ye[3];
        println!(
            "cos(sigma) {f}: predicted {:.2} deg, with sink {:.2} deg, integrated {:.2} deg, \
             error {:+.2} %, with sink {:+.2} %",
            p.range_angle_rad.to_degrees(),
            ps.range_angle_rad.to_degrees(),
            ye[3].to_degrees(),
            100.0 * err,
            100.0 * err_sink
        );
        errs.push(err);
        // With the sink to the equilibrium of the bank modelled, the thesis' <= 3 % at every
        // bank (measured -0.90 % at 0.3, +1.16 % at 0.5, +1.05 % at 0.7, +0.56 % at 1).
        assert!(err_sink.abs() < 0.03, "cos(sigma) {f}: {err_sink}");
    }
    // The thesis' glide claim (<= 3 %) applies at the imposed entry (cos(sigma) = 1).
    assert!(errs[3].abs() < 0.03, "{errs:?}");
    for w in errs[..3].windows(2) {
        assert!(w[0] < 0.0 && w[0] < w[1], "{errs:?}");
    }
}

/// Near the end of the flight the sink has no time to pay out: from 2.6 km/s, 2 km above the
/// equilibrium of cos(sigma) = 0.5 (fpa 0), to 2.5 km/s (46 km flown), against Dormand-Prince
/// integration. `predict_glide_with_sink` lets the drag deficit act for at most the time to go
/// (`sink_range_angle_within`); the uncapped term (one radian of phugoid, `sink_range_angle`)
/// predicts more range than is flown. Measured: glide alone -25.5 %, capped sink -7.1 %,
/// uncapped +14.0 % (from 2.56 km/s: -24.6, -6.1, +41.6 %; from 2.7 km/s, where the cap no
/// longer binds, both -7.2 %: the one-radian term then falls short). The capped prediction is
/// the closest and within 10 %.
#[test]
fn validate_dormand_prince_sink_capped_by_the_time_to_go() {
    use crate::vinh_support::dynamics::{Lift, eom_dim};
    use crate::vinh_support::ode::{Settings, integrate};
    use guidance_core::replan::sink_range_angle;
    use guidance_core::vinh::predict::glide_start_radius;
    let f = 0.5;
    let lift = LiftControl {
        lambda: 1.0,
        vertical_fraction: f,
    };
    let v0 = 2600.0;
    let r_eq =
        glide_start_radius(&planet(), &atmosphere(), &srm(), &lift, v0, R_EARTH + 150e3).unwrap();
    let s = EntryState {
        radius_m: r_eq + 2000.0,
        speed_m_s: v0,
        flight_path_angle_rad: 0.0,
    };
    let sol = integrate(
        eom_dim(
            &vehicles::srm(),
            Lift {
                lambda: 1.0,
                cos_bank: f,
            },
        ),
        0.0,
        [s.radius_m, s.speed_m_s, s.flight_path_angle_rad, 0.0],
        5_000.0,
        Settings::tight(1.0),
        |_t, y| y[1] - 2500.0,
    );
    let (_, ye) = sol.event.expect("reaches 2.5 km/s");
    let plain = predict_glide(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
    )
    .unwrap()
    .range_angle_rad;
    let capped = predict_glide_with_sink(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift,
        &s,
        &config().predictor,
        PeakMode::RangeOnly,
    )
    .unwrap()
    .range_angle_rad;
    let uncapped = plain + sink_range_angle(&planet(), &atmosphere(), &s, r_eq);
    let err = |x: f64| (x - ye[3]) / ye[3];
    println!(
        "integrated {:.1} km; glide {:+.1} %, capped sink {:+.1} %, uncapped {:+.1} %",
        ye[3] * R_EARTH / 1e3,
        100.0 * err(plain),
        100.0 * err(capped),
        100.0 * err(uncapped)
    );
    assert!(capped < uncapped);
    assert!(err(capped).abs() < err(uncapped).abs());
    assert!(err(capped).abs() < err(plain).abs());
    assert!(err(capped).abs() < 0.10, "{}", err(capped));
}

/// Issue 8 item 6: the limit grid `f_min + (f_max - f_min) i / 15` rounds to one ulp above
/// `f_max` for `f_min = 0.06`, `f_max = 0.85` (f64), and `replan` returned that fraction. In the
/// glide the peak heat flux falls with more vertical lift, so a heat-flux limit between the
/// peaks of the last two grid points leaves only the last one feasible: the result must be
/// exactly `f_max`, never above.
#[test]
fn replan_output_is_clamped_exactly_into_its_bounds() {
    let (f_min, f_max) = (0.06_f64, 0.85_f64);
    let n = 15.0;
    let f14 = f_min + (f_max - f_min) * 14.0 / n;
    let f15 = f_min + (f_max - f_min) * 15.0 / n;
    assert!(f15 > f_max, "the rounding this test needs: {f15}");
    let s = glide_nav(0.0);
    let state = EntryState {
        radius_m: s.radius_m,
        speed_m_s: s.speed_m_s,
        flight_path_angle_rad: s.flight_path_angle_rad,
    };
    let q_at = |f: f64| {
        predict_glide(
            &planet(),
            &atmosphere(),
            &srm(),
            &LiftControl {
                lambda: 1.0,
                vertical_fraction: f,
            },
            &state,
            &config().predictor,
        )
        .unwrap()
        .peak_heat_flux_w_m2
    };
    let (q14, q15) = (q_at(f14), q_at(f15));
    assert!(q15 < q14, "{q15} {q14}");
    let limits = ReplanLimits {
        heat_flux_w_m2: 0.5 * (q14 + q15),
        g_load: 1e3,
    };
    let solver = ReplanConfig {
        min_vertical_fraction: f_min,
        max_vertical_fraction: f_max,
        mode: PredictorMode::Glide,
        ..config()
    };
    let r = replan(
        &planet(),
        &atmosphere(),
        &srm(),
        &s,
        glide_range_m(0.3),
        &limits,
        &solver,
    );
    assert_eq!(r.case, ReplanCase::LimitsBind, "{r:?}");
    assert!(
        r.vertical_fraction >= f_min && r.vertical_fraction <= f_max,
        "{}",
        r.vertical_fraction
    );
    assert_eq!(r.vertical_fraction, f_max);
}

/// `PredictorMode::AutoSink`: for a state lofted above its equilibrium (as after a bank
/// reversal) the sink adds range, so for the same target the solve commands less vertical lift
/// than `Auto`, mid-glide and near the end (no fall-back, and no root at almost full lift: the
/// sink term is never negative).
#[test]
fn auto_sink_commands_less_lift_when_lofted_and_never_falls_back_on_the_sink() {
    use guidance_core::vinh::predict::glide_start_radius;
    let solve = |v: f64, dh: f64, target_m: f64, mode| {
        let lift = LiftControl {
            lambda: 1.0,
            vertical_fraction: 0.5,
        };
        let r_eq = glide_start_radius(&planet(), &atmosphere(), &srm(), &lift, v, R_EARTH + 150e3)
            .unwrap();
        let nav = NavState {
            radius_m: r_eq + dh,
            speed_m_s: v,
            flight_path_angle_rad: 0.0,
            ..glide_nav(0.0)
        };
        let cfg = ReplanConfig {
            min_vertical_fraction: 0.05,
            mode,
            ..config()
        };
        replan(
            &planet(),
            &atmosphere(),
            &srm(),
            &nav,
            target_m,
            &ReplanLimits {
                heat_flux_w_m2: 1e9,
                g_load: 1e3,
            },
            &cfg,
        )
    };
    // Mid-glide, 2 km above the equilibrium of cos(sigma) = 0.5.
    let auto = solve(5000.0, 2000.0, 1.5e6, PredictorMode::Auto);
    let sink = solve(5000.0, 2000.0, 1.5e6, PredictorMode::AutoSink);
    println!("mid-glide: auto {auto:?}\nsink {sink:?}");
    assert_eq!(auto.case, ReplanCase::Converged);
    assert_eq!(sink.case, ReplanCase::Converged);
    assert!(sink.vertical_fraction < auto.vertical_fraction);
    // Near the end: no fall-back on the sink in any of these states.
    for (v, dh, target) in [
        (2600.0, 2000.0, 20e3),
        (2560.0, 1000.0, 10e3),
        (2700.0, 3000.0, 40e3),
    ] {
        let a = solve(v, dh, target, PredictorMode::Auto);
        let s = solve(v, dh, target, PredictorMode::AutoSink);
        assert!(!matches!(
            s.case,
            ReplanCase::FallBack(ReplanFallBack::NotMonotone)
        ));
        assert_eq!(a.case, ReplanCase::Converged);
        assert_eq!(s.case, ReplanCase::Converged);
        assert!(s.vertical_fraction < a.vertical_fraction);
        assert!(s.predictor_calls <= MAX_PREDICTOR_CALLS);
    }
}
