//! Analytical simulator (guidance-core's Vinh closed forms through `host_sim::analytic`) against
//! the numerical simulator, and the comparison grid of `host_sim::compare`.

use host_sim::analytic::{self, AnalyticVehicle, GlideEnd, Placement};
use host_sim::compare::{
    self, CompareConfig, Fidelity, GridKind, NumericalSettings,
};
use host_sim::vehicle;

fn srm() -> AnalyticVehicle {
    AnalyticVehicle::from_vehicle(&vehicle::srm::vehicle(), analytic::DEFAULT_POLAR_MACH).unwrap()
}

fn fitted() -> host_sim::env::ExponentialAtmosphere {
    let (a, b) = analytic::DEFAULT_FIT_ALTITUDES_M;
    analytic::fit_us76(a, b).unwrap()
}

#[test]
#[ignore = "exploration: prints a grid"]
fn explore_grid() {
    let kind = match std::env::var("KIND").as_deref() {
        Ok("skip") => GridKind::Skip {
            entry_altitude_m: 100_000.0,
            flight_path_angle_rad: (-3.0f64).to_radians(),
            entry_speeds_m_s: vec![7000.0, 7500.0, 8000.0, 9000.0, 10000.0],
        },
        _ => GridKind::Glide {
            entry_altitudes_m: vec![70e3, 80e3, 90e3, 100e3, 110e3],
            end: match std::env::var("END").as_deref() {
                Ok("alt") => GlideEnd::Altitude { altitude_m: 40e3 },
                _ => GlideEnd::SpeedFraction { fraction: 0.5 },
            },
        },
    };
    let cfg = CompareConfig {
        vehicle: srm(),
        kind,
        cl_vertical: vec![0.4, 0.6, 0.8, 1.0, 1.2786],
        atmosphere: fitted(),
        placement: Placement::default(),
        fidelities: vec![Fidelity::Simplified, Fidelity::Full],
        numerical: NumericalSettings::default(),
        points: 201,
    };
    let t0 = std::time::Instant::now();
    let g = compare::run_grid(&cfg, &mut |_, _| {}).unwrap();
    println!("{:?}", t0.elapsed());
    println!("{}", compare::grid_csv(&g));
    for (i, m) in g.metrics.iter().enumerate() {
        println!(
            "{} max|err| simplified {:?} full {:?}",
            m.name,
            g.max_abs_error(i, Fidelity::Simplified),
            g.max_abs_error(i, Fidelity::Full)
        );
    }
}
