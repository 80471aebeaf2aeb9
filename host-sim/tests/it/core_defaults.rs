//! One home for the reference vehicles and the guidance defaults: what `guidance_core` offers
//! a firmware (`missions`, the configurations' constructors) is what host-sim flies.

use guidance_core::estimate::EstimatorConfig;
use guidance_core::lateral::{
    DEFAULT_FREEZE_DISTANCE_M, DEFAULT_HYSTERESIS_DEG, DEFAULT_LOW_SPEED_FRACTION,
    DEFAULT_MAX_REVERSALS, DEFAULT_WIDTH_ENTRY_DEG, DEFAULT_WIDTH_FINAL_DEG,
};
use guidance_core::missions::{self, HORUS2B_LIMITS, SRM_LIMITS};
use guidance_core::replan::{DEFAULT_EVERY_N_TICKS, ReplanConfig};
use guidance_core::vinh::nondim::VehicleParams;
use host_sim::analytic::AnalyticVehicle;
use host_sim::campaign::{CampaignGuidance, CampaignSetup};
use host_sim::scenario::{Scenario, parse_scenario};
use host_sim::vehicle::{Vehicle, by_name as builtin};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-15 * a.abs().max(b.abs())
}

fn same_params(a: &VehicleParams<f64>, b: &VehicleParams<f64>) {
    assert!(close(a.mass_kg, b.mass_kg), "{a:?} {b:?}");
    assert!(
        close(a.reference_area_m2, b.reference_area_m2),
        "{a:?} {b:?}"
    );
    assert!(close(a.cd0, b.cd0), "{a:?} {b:?}");
    assert!(close(a.k_polar, b.k_polar), "{a:?} {b:?}");
    assert!(close(a.nose_radius_m, b.nose_radius_m), "{a:?} {b:?}");
}

fn same_limits(v: &Vehicle, core: &missions::VehicleLimits) {
    let l = &v.limits;
    assert_eq!(
        (
            l.heat_flux_w_m2,
            l.g_load,
            l.g_load_rate_per_s,
            l.alpha_rate_rad_s,
            l.sigma_rate_rad_s
        ),
        (
            core.heat_flux_w_m2,
            core.g_load,
            core.g_load_rate_per_s,
            core.alpha_rate_rad_s,
            core.sigma_rate_rad_s
        ),
        "{}",
        v.name
    );
}

#[test]
fn core_reference_vehicles_are_the_simulators() {
    let horus = builtin("horus-2b").unwrap();
    let srm = builtin("srm").unwrap();
    same_limits(&horus, &HORUS2B_LIMITS);
    same_limits(&srm, &SRM_LIMITS);
    for mach in [1.0, 1.2, 1.7, 2.0, 4.0, 10.0, 15.0, 20.0, 25.0] {
        let host = AnalyticVehicle::from_vehicle(&horus, mach)
            .unwrap()
            .params();
        same_params(&host, &missions::horus2b_vehicle_at_mach(mach));
    }
    let host = AnalyticVehicle::from_vehicle(&horus, 20.0)
        .unwrap()
        .params();
    same_params(&host, &missions::horus2b_vehicle());
    let host = AnalyticVehicle::from_vehicle(&srm, 20.0).unwrap().params();
    same_params(&host, &missions::srm_vehicle());
}

#[test]
fn core_srm_glide_is_the_builtin_scenario() {
    let m = missions::srm_glide::<f64>().unwrap();
    let sc = Scenario::srm_glide();
    let g = &sc.guidance;
    let nodes: Vec<[f64; 3]> = m
        .table
        .nodes()
        .iter()
        .map(|n| [n.x, n.alpha_rad, n.sigma_rad])
        .collect();
    assert_eq!(g.nodes, nodes);
    assert_eq!(g.bounds, m.table.bounds());
    assert_eq!(g.independent, m.table.independent());
    assert_eq!(g.period_s, m.config.period_s);
    assert_eq!(
        (g.alpha_rate_rad_s, g.sigma_rate_rad_s),
        (m.config.rates.alpha_rad_s, m.config.rates.sigma_rad_s)
    );
    assert_eq!(g.initial, m.initial);
    let e = m.entry;
    let planet_radius = sc.environment.planet.radius_m;
    assert_eq!(sc.entry.radius_m, planet_radius + e.altitude_m);
    assert_eq!(sc.entry.speed_m_s, e.speed_m_s);
    assert_eq!(sc.entry.flight_path_angle_rad, e.flight_path_angle_rad);
    assert_eq!(sc.entry.heading_rad, e.heading_rad);
    assert_eq!(
        (sc.entry.latitude_rad, sc.entry.longitude_rad),
        (e.latitude_rad, e.longitude_rad)
    );
}

/// An empty `[guidance.replanning]` section (with `[guidance.lateral]` and a target) builds
/// the core's default re-planner: `ReplanConfig::new` at the interface speed, the vehicle's
/// limits, re-planning every `DEFAULT_EVERY_N_TICKS` ticks.
#[test]
fn scenario_replanning_defaults_are_the_cores() {
    let text = r#"
vehicle = "srm"
[environment]
preset = "simplified"
[entry]
altitude_km = 100.0
longitude_deg = 0.0
latitude_deg = 0.0
speed_m_s = 7500.0
flight_path_angle_deg = -1.0
heading_deg = 90.0
[guidance]
independent = "energy"
interpolation = "linear"
period_s = 2.0
alpha_rate_deg_s = 5.0
sigma_rate_deg_s = 15.0
initial_alpha_deg = 0.0
initial_sigma_deg = 0.0
nodes = [[1.0, 0.0, 0.0], [0.5, 0.0, 50.0], [0.0, 0.0, 0.0]]
[termination]
max_time_s = 3000.0
[guidance.replanning]
[guidance.lateral]
[guidance.target]
downrange_km = 8000.0
crossrange_km = 0.0
interface_speed_m_s = 2500.0
"#;
    let sc = parse_scenario(text, "test.toml", std::path::Path::new(".")).unwrap();
    let setup = CampaignSetup::new(&sc, "test.toml", None).unwrap();
    let got = setup.stack.replan.unwrap();
    assert_eq!(setup.interface_speed_m_s, 2500.0);
    assert_eq!(got.solver, ReplanConfig::new(2500.0));
    assert_eq!(got.limits, SRM_LIMITS.load_limits());
    assert_eq!(got.every_n_ticks, DEFAULT_EVERY_N_TICKS);
    assert!(got.apply_out_of_reach);
    assert_eq!(got.steps_per_tick, 0);
}

/// The campaigns' default lateral logic and estimator are the core's defaults.
#[test]
fn campaign_defaults_are_the_cores() {
    let gs = CampaignGuidance::default();
    assert_eq!(gs.corridor_width_entry_deg, DEFAULT_WIDTH_ENTRY_DEG);
    assert_eq!(gs.corridor_width_final_deg, DEFAULT_WIDTH_FINAL_DEG);
    assert_eq!(gs.corridor_low_speed_fraction, DEFAULT_LOW_SPEED_FRACTION);
    assert_eq!(gs.hysteresis_deg, DEFAULT_HYSTERESIS_DEG);
    assert_eq!(gs.max_reversals, DEFAULT_MAX_REVERSALS);
    assert_eq!(gs.freeze_km * 1e3, DEFAULT_FREEZE_DISTANCE_M);
    assert_eq!(gs.replan_every_n_ticks, DEFAULT_EVERY_N_TICKS);
    assert_eq!(gs.estimator(), EstimatorConfig::default());
    let core = ReplanConfig::<f64>::new(2500.0);
    assert_eq!(gs.replan_tolerance_km * 1e3, core.tolerance_m);
    assert_eq!(gs.min_vertical_fraction, core.min_vertical_fraction);
    assert_eq!(gs.max_vertical_fraction, core.max_vertical_fraction);
}
