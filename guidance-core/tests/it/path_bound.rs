//! `PathBound`: the heat-flux and g-load limits as a lower bound on the vertical lift fraction
//! at the current state (quasi-equilibrium glide at the limit density, plus a descent term),
//! and `ReplanningGuidance::with_path_bound`, which lowers the installed bank to it.

use crate::vinh_replan::{NO_LIMITS, glide_nav, glide_range_m, rcfg, replanning};
use crate::vinh_support::inputs::atmosphere;
use crate::vinh_support::inputs::srm;
use crate::vinh_support::inputs::{horus, planet};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::GuidanceError;
use guidance_core::monitor::{G0_M_S2, chapman_heat_flux_w_m2};
use guidance_core::nav::NavState;
use guidance_core::replan::{
    NumericalRun, PathBound, PredictorMode, RangeTarget, ReplanCase, ReplanLimits, ReplanSolver,
};
use guidance_core::vinh::{EntryState, LiftControl, PeakMode, Prediction, PredictorConfig};

const DEG: f64 = std::f64::consts::PI / 180.0;

pub(crate) fn nav(alt_km: f64, speed_m_s: f64, gamma_deg: f64) -> NavState<f64> {
    NavState {
        time_s: 0.0,
        radius_m: R_EARTH + alt_km * 1e3,
        speed_m_s,
        flight_path_angle_rad: gamma_deg * DEG,
        heading_rad: 90.0 * DEG,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

fn bound(q_w_m2: f64, g_load: f64, descent_time_s: f64) -> PathBound<f64> {
    PathBound {
        limits: ReplanLimits {
            heat_flux_w_m2: q_w_m2,
            g_load,
        },
        descent_time_s,
        barrier_frequency_rad_s: 0.0,
        barrier_damping: 0.0,
    }
}

/// Heat flux \[W/m^2\] and g-load \[-\] of the equilibrium glide with vertical lift fraction
/// `f` at `n`'s radius and speed, lift parameter `lambda` (computed here independently of the
/// bound: the equilibrium density, then the monitor's Chapman flux and the resultant).
fn equilibrium_loads(f: f64, lambda: f64, n: &NavState<f64>) -> (f64, f64) {
    let v = horus();
    let p = planet();
    let (r, s) = (n.radius_m, n.speed_m_s);
    let cl = lambda * (v.cd0 / v.k_polar).sqrt();
    let cd = v.cd0 * (1.0 + lambda * lambda);
    let need = p.mu_m3_s2 / (r * r) - s * s / r;
    // L f = need with L = rho s^2 S C_L / (2 m).
    let rho = 2.0 * v.mass_kg * need / (f * s * s * v.reference_area_m2 * cl);
    let q = chapman_heat_flux_w_m2(rho, s, v.nose_radius_m);
    let aero = rho * s * s * v.reference_area_m2 / (2.0 * v.mass_kg) * (cl * cl + cd * cd).sqrt();
    (q, aero / G0_M_S2)
}

/// On the equilibrium glide at the bound's fraction, the binding limit is met exactly and the
/// other is respected; which one binds changes with speed (heat flux fast, g-load slow).
#[test]
fn the_bound_is_the_equilibrium_glide_at_the_limit() {
    let lambda = 3.7;
    let b = bound(500e3, 2.5, 0.0);
    let mut binding = (0, 0);
    for &(alt, speed) in &[
        (70.0, 6500.0),
        (60.0, 5000.0),
        (45.0, 3000.0),
        (30.0, 1500.0),
    ] {
        let n = nav(alt, speed, 0.0);
        let f = b
            .min_vertical_fraction(&planet(), &horus(), lambda, &n)
            .unwrap();
        assert!(f > 0.0 && f < 1.0, "{speed} m/s: f {f}");
        let (q, g) = equilibrium_loads(f, lambda, &n);
        let (rq, rg) = (q / 500e3, g / 2.5);
        assert!(rq <= 1.0 + 1e-9 && rg <= 1.0 + 1e-9, "{speed}: {rq} {rg}");
        assert!(
            (rq.max(rg) - 1.0).abs() < 1e-9,
            "{speed}: one limit binds ({rq}, {rg})"
        );
        if rq > rg {
            binding.0 += 1;
        } else {
            binding.1 += 1;
        }
        // Less vertical lift: the equilibrium breaks the binding limit.
        let (q2, g2) = equilibrium_loads(0.9 * f, lambda, &n);
        assert!((q2 / 500e3).max(g2 / 2.5) > 1.0 + 1e-3, "{speed}");
    }
    assert!(binding.0 > 0 && binding.1 > 0, "{binding:?}");
}

/// Tighter limits, a steeper descent or a shorter descent time raise the bound; a climb, a
/// zero descent time or orbital speed do not; the output is in [0, 1].
#[test]
fn the_bound_is_monotone_in_limits_and_descent() {
    let (p, v) = (planet(), horus());
    let at =
        |b: &PathBound<f64>, n: &NavState<f64>| b.min_vertical_fraction(&p, &v, 3.0, n).unwrap();
    let n = nav(40.0, 2500.0, 0.0);
    let f = at(&bound(500e3, 2.5, 0.0), &n);
    assert!(at(&bound(500e3, 2.0, 0.0), &n) > f);
    assert!(at(&bound(100e3, 2.5, 0.0), &n) >= f);
    let dive = nav(40.0, 2500.0, -5.0);
    assert_eq!(at(&bound(500e3, 2.5, 0.0), &dive), f, "no descent term");
    let f30 = at(&bound(500e3, 2.5, 30.0), &dive);
    let f10 = at(&bound(500e3, 2.5, 10.0), &dive);
    assert!(f < f30 && f30 < f10, "{f} {f30} {f10}");
    assert_eq!(at(&bound(500e3, 2.5, 30.0), &nav(40.0, 2500.0, 3.0)), f);
    // Above circular speed the glide needs no lift: no bound.
    assert_eq!(at(&bound(500e3, 2.5, 0.0), &nav(100.0, 7900.0, 0.0)), 0.0);
    // Impossible limits: lift-up.
    assert_eq!(at(&bound(1.0, 1e-3, 0.0), &n), 1.0);
}

/// Invalid bounds and states give no bound (never NaN); a sweep of states stays in [0, 1].
#[test]
fn the_bound_is_finite_or_none() {
    let (p, v) = (planet(), horus());
    let ok = bound(500e3, 2.5, 20.0);
    assert!(ok.is_valid());
    for b in [
        bound(f64::NAN, 2.5, 0.0),
        bound(500e3, 0.0, 0.0),
        bound(-1.0, 2.5, 0.0),
        bound(500e3, 2.5, -1.0),
        bound(500e3, f64::INFINITY, 0.0),
    ] {
        assert!(!b.is_valid(), "{b:?}");
        assert_eq!(
            b.min_vertical_fraction(&p, &v, 3.0, &nav(40.0, 2500.0, 0.0)),
            None
        );
    }
    let mut bad_v = v;
    bad_v.cd0 = 0.0;
    assert_eq!(
        ok.min_vertical_fraction(&p, &bad_v, 3.0, &nav(40.0, 2500.0, 0.0)),
        None
    );
    assert_eq!(
        ok.min_vertical_fraction(&p, &v, f64::NAN, &nav(40.0, 2500.0, 0.0)),
        None
    );
    assert_eq!(
        ok.min_vertical_fraction(&p, &v, -1.0, &nav(40.0, 2500.0, 0.0)),
        None
    );
    assert_eq!(
        ok.min_vertical_fraction(&p, &v, 3.0, &nav(40.0, 0.0, 0.0)),
        None
    );
    assert_eq!(
        ok.min_vertical_fraction(&p, &v, 3.0, &nav(40.0, f64::NAN, 0.0)),
        None
    );
    // Zero lift: lift-up below circular speed.
    assert_eq!(
        ok.min_vertical_fraction(&p, &v, 0.0, &nav(40.0, 2500.0, 0.0)),
        Some(1.0)
    );
    for i in 0..200 {
        let x = f64::from(i);
        let n = nav(
            20.0 + (x * 7.0) % 80.0,
            300.0 + (x * 431.0) % 7800.0,
            -20.0 + (x * 3.3) % 25.0,
        );
        let f = ok
            .min_vertical_fraction(&p, &v, (x * 0.37) % 5.0, &n)
            .unwrap();
        assert!((0.0..=1.0).contains(&f), "{n:?}: {f}");
    }
}

/// `ReplanningGuidance::with_path_bound`: an invalid bound is refused; a binding bound installs
/// a smaller bank than the solved one (and says so); a loose one changes nothing.
#[test]
fn replanning_guidance_applies_the_bound() {
    let total = glide_range_m(0.6) / R_EARTH;
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Glide,
    );
    assert_eq!(
        replanning(cfg)
            .with_path_bound(bound(f64::NAN, 2.5, 0.0), false)
            .err(),
        Some(GuidanceError::InvalidConfig)
    );
    let mut free = replanning(cfg);
    let mut loose = replanning(cfg)
        .with_path_bound(bound(1e12, 1e6, 0.0), false)
        .unwrap();
    // The glide state is nearly circular: 1e-4 g of lift at the limit needs lift-up.
    let mut tight = replanning(cfg)
        .with_path_bound(bound(1e12, 1e-4, 0.0), false)
        .unwrap();
    let n = glide_nav(0.0);
    let rf = free.update(&n).unwrap().replan.unwrap();
    let rl = loose.update(&n).unwrap().replan.unwrap();
    let rt = tight.update(&n).unwrap().replan.unwrap();
    assert_eq!(rf.case, ReplanCase::Converged);
    assert_eq!(rl, rf);
    assert_eq!(free.guidance().table(), loose.guidance().table());
    assert!(!rf.path_bound_active);
    assert!(rt.applied && rt.path_bound_active, "{rt:?}");
    assert_eq!(rt.bank_rad, rf.bank_rad, "the report keeps the solved bank");
    assert_eq!(tight.counts().path_bound_active, 1);
    // Installed: the solver's max vertical fraction (1): bank 0 on the replanned nodes.
    let installed: Vec<f64> = tight
        .guidance()
        .table()
        .nodes()
        .iter()
        .zip(free.guidance().table().nodes())
        .filter(|(a, b)| a.sigma_rad != b.sigma_rad)
        .map(|(a, _)| a.sigma_rad.abs())
        .collect();
    assert!(!installed.is_empty());
    assert!(installed.iter().all(|s| *s < 1e-9), "{installed:?}");
}

/// A numerical prediction of HORUS-2B at a steep bank (f = 0.2) flying `bound` (if any).
pub(crate) fn predict(bound: Option<PathBound<f64>>) -> Prediction<f64> {
    let run = NumericalRun::new(
        &planet(),
        &atmosphere(),
        &horus(),
        &LiftControl {
            lambda: 3.7,
            vertical_fraction: 0.2,
        },
        &EntryState {
            radius_m: R_EARTH + 75e3,
            speed_m_s: 7000.0,
            flight_path_angle_rad: -0.2 * DEG,
        },
        &PredictorConfig {
            final_speed_m_s: 780.0,
            max_skips: 4,
        },
        PeakMode::Full,
    )
    .unwrap();
    let mut run = match bound {
        Some(b) => run.with_path_bound(b),
        None => run,
    };
    run.advance(u16::MAX).unwrap().unwrap()
}

/// `NumericalRun::with_path_bound`: a bound that never binds is the plain prediction bit for
/// bit, an invalid one is ignored; a binding g-load bound lowers the predicted peak g-load to
/// near its limit (the descent term holds it within 3 %) and flies farther.
#[test]
fn numerical_prediction_flies_the_bound() {
    let plain = predict(None);
    assert_eq!(predict(Some(bound(1e12, 1e6, 0.0))), plain);
    assert_eq!(predict(Some(bound(f64::NAN, 2.0, 0.0))), plain);
    let limit = 0.8 * plain.peak_g_load;
    let b = predict(Some(bound(1e12, limit, 20.0)));
    assert!(b.peak_g_load < plain.peak_g_load, "{b:?}");
    assert!(
        b.peak_g_load <= 1.03 * limit,
        "{} vs {limit}",
        b.peak_g_load
    );
    assert!(b.range_m > plain.range_m, "{} {}", b.range_m, plain.range_m);
}

/// A solve whose numerical predictions fly the bound, stepped one predictor call at a time,
/// gives the one-shot answer; the bound changes the solved bank (it binds in the predictions).
#[test]
fn stepped_solver_with_the_bound_equals_the_one_shot() {
    let srm_bound = bound(1e12, 0.6, 20.0);
    let total = glide_range_m(0.6) / R_EARTH;
    let target = RangeTarget::FlownRangeAngle { total_rad: total };
    let solver = |_: ()| {
        ReplanSolver::new(
            &planet(),
            &atmosphere(),
            &srm(),
            &glide_nav(0.0),
            total * R_EARTH,
            &NO_LIMITS,
            &rcfg(target, 1, PredictorMode::Numerical).solver,
        )
    };
    let plain = solver(()).run(u8::MAX).unwrap();
    let mut one = solver(()).with_path_bound(srm_bound);
    let one = one.run(u8::MAX).unwrap();
    let mut stepped = solver(()).with_path_bound(srm_bound);
    let mut n = 0;
    let r = loop {
        n += 1;
        assert!(n < 10_000);
        if let Some(r) = stepped.step() {
            break r;
        }
    };
    assert_eq!(r, one);
    assert!(one.bank_rad.is_finite());
    assert_ne!(one.bank_rad, plain.bank_rad, "{one:?} {plain:?}");
}
