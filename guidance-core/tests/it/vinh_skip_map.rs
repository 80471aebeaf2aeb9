//! Error maps of the skip closed form and of the predictor chain against numerical integration
//! of the planar equations of motion in the same environment (Dormand-Prince 5(4), rtol 1e-11;
//! the glide map's style, `vinh_error_map.rs`), over vehicles (max L/D 0.3 to 2.5: the SRM
//! capsule's mass, area and C_D0 with the polar factor K set for the L/D), entry states at
//! 122 km (6.5 to 10.5 km/s, -1 to -7 deg) and vertical lift fractions (0.5, 1).
//!
//! * Skip: exit speed, exit flight-path angle, range angle to the exit, peak heat flux and
//!   g-load of `SkipSolution` against the integration to the return to the entry radius.
//! * Chain: range angle of `predict` (skip -> arc -> ... -> glide) to 0.35 of the entry speed
//!   against one integration to that speed.
//!
//! `validate_dormand_prince_skip_map_validity_is_honest` and
//! `validate_dormand_prince_chain_map_validity_is_honest` check the typed validity against the
//! maps: every `InDomain` point is within the documented accuracy. `print_skip_error_map` and
//! `print_chain_error_map` (ignored) print the maps of docs/validation/vinh-numerical.md.

use crate::vinh_support::dynamics::{Lift, eom_dim, skip_dim};
use crate::vinh_support::inputs::{atmosphere, lift, params, planet};
use crate::vinh_support::ode::{Settings, integrate};
use crate::vinh_support::vehicles::{R_EARTH, srm_with_max_ld as vehicle};
use guidance_core::vinh::{
    EntryState, NonDim, PredictorConfig, SkipSolution, Validity, predict, skip_validity,
    validity_of,
};

const H_ENTRY: f64 = 122e3;
const LDS: [f64; 5] = [0.3, 0.72, 1.0, 1.5, 2.5];
const SPEEDS: [f64; 4] = [6_500.0, 7_400.0, 9_000.0, 10_500.0];
const FPAS_DEG: [f64; 4] = [-1.0, -2.0, -4.0, -7.0];
const FRACTIONS: [f64; 2] = [0.5, 1.0];

fn entry(v_e: f64, g_deg: f64) -> EntryState<f64> {
    EntryState {
        radius_m: R_EARTH + H_ENTRY,
        speed_m_s: v_e,
        flight_path_angle_rad: g_deg.to_radians(),
    }
}

/// Errors of one skip against the integration: exit speed [%], exit flight-path angle [deg],
/// range angle [%], peak heat flux [%], peak g-load [%].
#[derive(Clone, Copy, Debug)]
struct SkipErr {
    speed: f64,
    fpa_deg: f64,
    range: f64,
    heat: f64,
    g_load: f64,
}

/// Outcome of one skip case.
#[derive(Clone, Copy, Debug)]
enum SkipOutcome {
    Compared(SkipErr),
    /// The integration is captured (no return to the entry radius), the closed form exits.
    ClosedExitsExactCaptured,
    /// Both agree on capture (`NoAtmosphericExit`).
    BothCaptured,
    /// The closed form is captured, the integration exits.
    ClosedCapturedExactExits,
    /// Another closed-form domain error (typed; the validity carries it).
    OutOfDomain,
}

/// One skip map point: L/D, V_E, gamma_E [deg], vertical fraction, validity of the skip
/// (`skip_validity`), outcome.
type SkipPoint = (f64, f64, f64, f64, Validity, SkipOutcome);

fn skip_map() -> Vec<SkipPoint> {
    let mut out = Vec::new();
    for &ld in &LDS {
        let veh = vehicle(ld);
        let p = params(&veh);
        for &v_e in &SPEEDS {
            for &g in &FPAS_DEG {
                for &f in &FRACTIONS {
                    let e = entry(v_e, g);
                    let closed = NonDim::new(&planet(), &atmosphere(), &p, &lift(f), &e)
                        .and_then(|nd| SkipSolution::new(&nd));
                    let validity = match &closed {
                        Ok(s) => skip_validity(&e, s),
                        Err(err) => Validity::OutOfDomain(*err),
                    };
                    let reference = skip_dim(
                        &veh,
                        Lift {
                            lambda: 1.0,
                            cos_bank: f,
                        },
                        e.radius_m,
                        v_e,
                        e.flight_path_angle_rad,
                    );
                    use guidance_core::vinh::VinhError::NoAtmosphericExit;
                    let outcome = match (closed, reference) {
                        (Ok(s), Some(r)) => {
                            let x = s.exit();
                            let (q, n) = s.peaks().expect("peaks of an exiting skip");
                            SkipOutcome::Compared(SkipErr {
                                speed: 100.0 * (x.speed_m_s - r.exit_speed) / r.exit_speed,
                                fpa_deg: (x.flight_path_angle_rad - r.exit_fpa).to_degrees(),
                                range: 100.0 * (x.range_angle_rad - r.exit_range_angle)
                                    / r.exit_range_angle,
                                heat: 100.0 * (q.heat_flux_w_m2 - r.peak_heat_flux)
                                    / r.peak_heat_flux,
                                g_load: 100.0 * (n.g_load - r.peak_g_load) / r.peak_g_load,
                            })
                        }
                        (Ok(_), None) => SkipOutcome::ClosedExitsExactCaptured,
                        (Err(NoAtmosphericExit), None) => SkipOutcome::BothCaptured,
                        (Err(NoAtmosphericExit), Some(_)) => SkipOutcome::ClosedCapturedExactExits,
                        (Err(_), _) => SkipOutcome::OutOfDomain,
                    };
                    out.push((ld, v_e, g, f, validity, outcome));
                }
            }
        }
    }
    out
}

/// One chain map point: L/D, V_E, gamma_E [deg], vertical fraction, validity, range error [%]
/// (`None`: the predictor is out of domain or the integration does not reach the final speed).
type ChainPoint = (f64, f64, f64, f64, Validity, Option<f64>);

fn chain_map() -> Vec<ChainPoint> {
    let mut out = Vec::new();
    for &ld in &LDS {
        let veh = vehicle(ld);
        let p = params(&veh);
        for &v_e in &SPEEDS {
            for &g in &FPAS_DEG {
                for &f in &FRACTIONS {
                    let e = entry(v_e, g);
                    let v_f = 0.35 * v_e;
                    let r = predict(
                        &planet(),
                        &atmosphere(),
                        &p,
                        &lift(f),
                        &e,
                        &PredictorConfig {
                            final_speed_m_s: v_f,
                            max_skips: 8,
                        },
                    );
                    let validity = validity_of(&r);
                    let err = r.ok().and_then(|pred| {
                        let sol = integrate(
                            eom_dim(
                                &veh,
                                Lift {
                                    lambda: 1.0,
                                    cos_bank: f,
                                },
                            ),
                            0.0,
                            [e.radius_m, v_e, e.flight_path_angle_rad, 0.0],
                            200_000.0,
                            Settings::tight(5.0),
                            |_t, y| (y[1] - v_f).min(y[0] - R_EARTH),
                        );
                        let (_, ye) = sol.event?;
                        if ye[0] < R_EARTH + 1.0 {
                            return None;
                        }
                        Some(100.0 * (pred.range_angle_rad - ye[3]) / ye[3])
                    });
                    out.push((ld, v_e, g, f, validity, err));
                }
            }
        }
    }
    out
}

/// Every skip the validity calls `InDomain` and that both the closed form and the integration
/// exit is within the documented skip accuracy (the validation grids' bounds: exit speed
/// 0.9 %, exit flight-path angle 1.2 deg, range angle 12 %, peak heat flux 2 %, peak g-load
/// 3.5 %), and an `InDomain` skip agrees with the integration on capture; the map has
/// compared points both in and out of domain.
#[test]
fn validate_dormand_prince_skip_map_validity_is_honest() {
    let (mut n_in, mut n_out) = (0, 0);
    for (ld, v, g, f, val, o) in skip_map() {
        let case = format!("L/D {ld}, {v} m/s, {g} deg, f {f}: {o:?}");
        match (val, o) {
            (Validity::InDomain, SkipOutcome::Compared(e)) => {
                assert!(
                    e.speed.abs() < 0.9
                        && e.fpa_deg.abs() < 1.2
                        && e.range.abs() < 12.0
                        && e.heat.abs() < 2.0
                        && e.g_load.abs() < 3.5,
                    "{case}"
                );
                n_in += 1;
            }
            (Validity::InDomain, SkipOutcome::ClosedExitsExactCaptured) => panic!("{case}"),
            (Validity::Extrapolated(_), SkipOutcome::Compared(_)) => n_out += 1,
            _ => {}
        }
    }
    assert!(
        n_in >= 2 && n_out >= 10,
        "{n_in} in domain, {n_out} extrapolated"
    );
}

/// Every chain prediction classed `InDomain` is within the glide's bound (3.2 %) of the
/// integration. The capture transition after a skip or an arc is not modelled
/// (`CaptureTransition`: the map's chains that the phase limits alone accepted were off by -8.9
/// to +409 %); a chain captured in its first skip is the glide from the state and is classed by
/// the glide-start checks, which every chain of this map (entries at 1-7 deg, far from the
/// glide's flight-path angle) fails: measured 0 in domain. Every chain the predictor computes
/// is compared.
#[test]
fn validate_dormand_prince_chain_map_validity_is_honest() {
    let mut compared = 0;
    for (ld, v, g, f, val, err) in chain_map() {
        if matches!(val, Validity::InDomain) {
            assert!(
                err.is_some_and(|e| e.abs() <= 3.2),
                "L/D {ld}, {v} m/s, {g} deg, f {f}: {err:?}"
            );
        }
        compared += usize::from(err.is_some());
    }
    assert!(compared >= 60, "{compared}");
}

#[test]
#[ignore = "prints the skip error map of docs/validation/vinh-numerical.md"]
fn print_skip_error_map() {
    println!(
        "| L/D | V_E [m/s] | gamma_E [deg] | cos(sigma) | validity | exit V [%] | exit gamma [deg] | range [%] | peak q [%] | peak n [%] |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (ld, v, g, f, val, o) in skip_map() {
        match o {
            SkipOutcome::Compared(e) => println!(
                "| {ld} | {v:.0} | {g} | {f} | {val:?} | {:+.2} | {:+.3} | {:+.2} | {:+.2} | {:+.2} |",
                e.speed, e.fpa_deg, e.range, e.heat, e.g_load
            ),
            other => println!("| {ld} | {v:.0} | {g} | {f} | {val:?} | {other:?} | | | | |"),
        }
    }
}

#[test]
#[ignore = "prints the chain error map of docs/validation/vinh-numerical.md"]
fn print_chain_error_map() {
    println!("| L/D | V_E [m/s] | gamma_E [deg] | cos(sigma) | validity | range error [%] |");
    println!("|---|---|---|---|---|---|");
    for (ld, v, g, f, val, err) in chain_map() {
        let e = err.map_or("-".to_string(), |e| format!("{e:+.2}"));
        println!("| {ld} | {v:.0} | {g} | {f} | {val:?} | {e} |");
    }
}
