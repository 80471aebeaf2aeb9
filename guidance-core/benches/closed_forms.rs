//! Host timings of the Vinh closed forms and the re-planner, in `f64` and `f32`:
//! one skip (set-up, exit state, peak heat flux and g-load), one glide (set-up, point at the
//! final speed, peaks), one predictor chain (skip -> Kepler arc -> ... -> final glide), one
//! re-planning solve (chain mode, bisection to 1 km), the solver's worst case (58 chain calls)
//! and one glide-mode re-planning solve.
//!
//! `cargo bench -p guidance-core --bench closed_forms` (numbers in docs/reference/vinh.md).
//! Inputs: SRM capsule (polar C_D0 = 0.2576, K = 0.1879 from the thesis' sec. 9.2 glide entry,
//! docs/reference/vinh.md), Earth, exponential atmosphere (1.225 kg/m^3, H_s = 7.2 km).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use guidance_core::NavState;
use guidance_core::Real;
use guidance_core::replan::{PredictorMode, ReplanConfig, ReplanLimits, replan};
use guidance_core::vinh::{
    EntryState, ExpAtmosphere, GlideSolution, LiftControl, NonDim, Planet, PredictorConfig,
    SkipSolution, VehicleParams, predict,
};

struct Case<S> {
    planet: Planet<S>,
    atmosphere: ExpAtmosphere<S>,
    vehicle: VehicleParams<S>,
    lift: LiftControl<S>,
    skip_state: EntryState<S>,
    predictor: PredictorConfig<S>,
    nav: NavState<S>,
    glide_nav: NavState<S>,
    solver: ReplanConfig<S>,
    limits: ReplanLimits<S>,
}

fn case<S: Real>() -> Case<S> {
    let k = S::from_f64;
    let deg = std::f64::consts::PI / 180.0;
    let re = 6_378_137.0;
    let nav = |h: f64, v: f64, g_deg: f64| NavState {
        time_s: S::ZERO,
        radius_m: k(re + h),
        speed_m_s: k(v),
        flight_path_angle_rad: k(g_deg * deg),
        heading_rad: S::ZERO,
        latitude_rad: S::ZERO,
        longitude_rad: S::ZERO,
    };
    Case {
        planet: Planet::earth(),
        atmosphere: ExpAtmosphere::earth(),
        vehicle: VehicleParams {
            mass_kg: k(38.77),
            reference_area_m2: k(0.441),
            cd0: k(0.2576),
            k_polar: k(0.1879),
            nose_radius_m: k(0.9),
        },
        lift: LiftControl {
            lambda: S::ONE,
            vertical_fraction: S::ONE,
        },
        skip_state: EntryState {
            radius_m: k(re + 122e3),
            speed_m_s: k(7800.0),
            flight_path_angle_rad: k(-3.0 * deg),
        },
        predictor: PredictorConfig {
            final_speed_m_s: k(2500.0),
            max_skips: 4,
        },
        nav: nav(122e3, 7000.0, -4.0),
        glide_nav: nav(100e3, 7658.34, -0.056),
        solver: ReplanConfig {
            lambda: S::ONE,
            min_vertical_fraction: k(0.3),
            max_vertical_fraction: S::ONE,
            tolerance_m: k(1000.0),
            max_iterations: 40,
            predictor: PredictorConfig {
                final_speed_m_s: k(2500.0),
                max_skips: 4,
            },
            mode: PredictorMode::Chain,
        },
        limits: ReplanLimits {
            heat_flux_w_m2: k(1e9),
            g_load: k(1e3),
        },
    }
}

fn bench_type<S: Real>(c: &mut Criterion, name: &str) {
    let cs = case::<S>();
    let skip = || {
        let nd = NonDim::new(
            &cs.planet,
            &cs.atmosphere,
            &cs.vehicle,
            &cs.lift,
            &cs.skip_state,
        )?;
        let s = SkipSolution::new(&nd)?;
        let q = s.peak_heat_flux()?;
        let g = s.peak_g_load()?;
        Ok::<_, guidance_core::vinh::VinhError>((s.exit(), q, g))
    };
    assert!(skip().is_ok(), "skip case out of domain");
    c.bench_function(&format!("{name}/skip"), |b| b.iter(|| black_box(skip())));

    let glide = || {
        let g = GlideSolution::new(
            &cs.planet,
            &cs.atmosphere,
            &cs.vehicle,
            &cs.lift,
            cs.glide_nav.radius_m,
        )?;
        let e = g.point_at_speed(cs.predictor.final_speed_m_s)?;
        let q = g.peak_heat_flux(cs.predictor.final_speed_m_s)?;
        let n = g.peak_g_load(cs.predictor.final_speed_m_s)?;
        Ok::<_, guidance_core::vinh::VinhError>((e, q, n))
    };
    assert!(glide().is_ok(), "glide case out of domain");
    c.bench_function(&format!("{name}/glide"), |b| b.iter(|| black_box(glide())));

    let chain = || {
        predict(
            &cs.planet,
            &cs.atmosphere,
            &cs.vehicle,
            &cs.lift,
            &cs.skip_state,
            &cs.predictor,
        )
    };
    let p = chain().expect("chain case in domain");
    println!("{name}: chain with {} skips, {} arcs", p.skips, p.arcs);
    c.bench_function(&format!("{name}/predictor_chain"), |b| {
        b.iter(|| black_box(chain()))
    });

    // Target: the chain's range at cos(sigma) = 0.7 from the re-planning state.
    let target = predict(
        &cs.planet,
        &cs.atmosphere,
        &cs.vehicle,
        &LiftControl {
            lambda: S::ONE,
            vertical_fraction: S::from_f64(0.7),
        },
        &EntryState {
            radius_m: cs.nav.radius_m,
            speed_m_s: cs.nav.speed_m_s,
            flight_path_angle_rad: cs.nav.flight_path_angle_rad,
        },
        &cs.solver.predictor,
    )
    .expect("target in domain")
    .range_m;
    let solve = |nav: &NavState<S>, target: S, solver: &ReplanConfig<S>| {
        replan(
            &cs.planet,
            &cs.atmosphere,
            &cs.vehicle,
            nav,
            target,
            &cs.limits,
            solver,
        )
    };
    let r = solve(&cs.nav, target, &cs.solver);
    println!(
        "{name}: re-planning solve (chain) {:?}, {} predictor calls",
        r.case, r.predictor_calls
    );
    c.bench_function(&format!("{name}/replan_chain"), |b| {
        b.iter(|| black_box(solve(black_box(&cs.nav), target, &cs.solver)))
    });
    // Worst case of the solver: a tolerance that is never met (all 40 halvings) and a heat-flux
    // limit below every prediction (the whole 16-point grid is scanned): 58 chain calls.
    let worst_solver = ReplanConfig {
        tolerance_m: S::from_f64(1e-6),
        ..cs.solver
    };
    let worst_limits = ReplanLimits {
        heat_flux_w_m2: S::ONE,
        g_load: S::from_f64(1e3),
    };
    let worst = || {
        replan(
            &cs.planet,
            &cs.atmosphere,
            &cs.vehicle,
            black_box(&cs.nav),
            target,
            &worst_limits,
            &worst_solver,
        )
    };
    let r = worst();
    println!(
        "{name}: worst-case re-planning solve {:?}, {} predictor calls",
        r.case, r.predictor_calls
    );
    c.bench_function(&format!("{name}/replan_chain_worst_case"), |b| {
        b.iter(|| black_box(worst()))
    });
    let glide_solver = ReplanConfig {
        mode: PredictorMode::Glide,
        min_vertical_fraction: S::from_f64(0.05),
        ..cs.solver
    };
    let glide_target = S::from_f64(12_000e3);
    let r = solve(&cs.glide_nav, glide_target, &glide_solver);
    println!(
        "{name}: re-planning solve (glide) {:?}, {} predictor calls",
        r.case, r.predictor_calls
    );
    c.bench_function(&format!("{name}/replan_glide"), |b| {
        b.iter(|| black_box(solve(black_box(&cs.glide_nav), glide_target, &glide_solver)))
    });
}

fn closed_forms(c: &mut Criterion) {
    bench_type::<f64>(c, "f64");
    bench_type::<f32>(c, "f32");
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    targets = closed_forms
}
criterion_main!(benches);
