//! Typed validity of predictor outputs (issue 10 item 6): in domain inside the validated grids
//! of docs/validation/vinh-numerical.md, extrapolated (with the reason) outside them, out of domain with the error.

use crate::vinh_replan::glide_nav;
use crate::vinh_support::inputs::{atmosphere, lift, planet, srm};
use crate::vinh_support::vehicles::{MU, R_EARTH};
use guidance_core::replan::predict_glide;
use guidance_core::vinh::{
    EntryState, Extrapolation, Planet, PredictorConfig, Validity, VehicleParams, predict,
    validity_of,
};

/// 2700 m/s: 0.35 of the SRM glide entry speed (7658 m/s), inside the glide's final-speed
/// ratio bound (`GLIDE_MIN_FINAL_SPEED_RATIO`).
const TO_2700: PredictorConfig<f64> = PredictorConfig {
    final_speed_m_s: 2700.0,
    max_skips: 4,
};

fn glide_from(h: f64, v: f64, veh: &VehicleParams<f64>, f: f64) -> Validity {
    let s = EntryState {
        radius_m: R_EARTH + h,
        speed_m_s: v,
        flight_path_angle_rad: 0.0,
    };
    validity_of(&predict_glide(
        &planet(),
        &atmosphere(),
        veh,
        &lift(f),
        &s,
        &TO_2700,
    ))
}

/// Glide mode from the SRM glide entry: in domain at the equilibrium start (validated +0.56 %),
/// extrapolated when the start is far above the equilibrium of the bank (cos(sigma) = 0.4,
/// vertical L/D 0.91: 6.6 km above it) and for a vehicle of vertical L/D 0.3; out of domain with the error for a
/// final speed above the current speed.
#[test]
fn glide_predictions_carry_their_validity() {
    let n = glide_nav(0.0);
    let h = n.radius_m - R_EARTH;
    assert_eq!(glide_from(h, n.speed_m_s, &srm(), 1.0), Validity::InDomain);
    assert_eq!(
        glide_from(h, n.speed_m_s, &srm(), 0.4),
        Validity::Extrapolated(Extrapolation::GlideStartOffset)
    );
    // Same polar shape, L/D 0.3 (K raised: E* = 1/(2 sqrt(K C_D0))).
    let mut low = srm();
    low.k_polar = 1.0 / (4.0 * 0.3 * 0.3 * low.cd0);
    let v = glide_from(60e3, 5000.0, &low, 1.0);
    assert!(
        matches!(
            v,
            Validity::Extrapolated(
                Extrapolation::GlideVerticalLiftToDrag | Extrapolation::GlideAltitude
            )
        ),
        "{v:?}"
    );
    let s = EntryState {
        radius_m: n.radius_m,
        speed_m_s: 2000.0,
        flight_path_angle_rad: 0.0,
    };
    let r = predict_glide(&planet(), &atmosphere(), &srm(), &lift(1.0), &s, &TO_2700);
    assert!(matches!(validity_of(&r), Validity::OutOfDomain(_)), "{r:?}");
}

/// Chain: the grid of validated skip entries (SRM, 122 km, 7435.5-9000 m/s, -5/-7 deg) at
/// four vertical lift fractions. Only chains whose every skip starts inside the validated
/// grid and whose glide starts at 70-110 km are in domain; the later skips of a multi-skip
/// chain re-enter below 7.4 km/s, outside the grid, so those chains are extrapolated
/// (`SkipEntrySpeed`). An entry at 11.5 km/s is never in domain.
#[test]
fn chain_predictions_carry_their_validity() {
    let (mut in_domain, mut extrapolated) = (0, 0);
    for &f in &[0.3, 0.5, 0.7, 1.0] {
        for &(v, g) in &[
            (7435.5, -7.0),
            (7800.0, -7.0),
            (7800.0, -5.0),
            (9000.0, -7.0),
        ] {
            let s = EntryState {
                radius_m: R_EARTH + 122e3,
                speed_m_s: v,
                flight_path_angle_rad: f64::to_radians(g),
            };
            let r = predict(&planet(), &atmosphere(), &srm(), &lift(f), &s, &TO_2700);
            let val = validity_of(&r);
            println!(
                "f {f} {v} m/s {g} deg: {val:?}, {:?}",
                r.map(|p| (p.skips, p.glide_start_radius_m - R_EARTH))
            );
            if let Ok(p) = r {
                let later_skips = p.skips > 1;
                let h_g = p.glide_start_radius_m - R_EARTH;
                let glide_ok = (70e3..=110e3).contains(&h_g);
                match val {
                    Validity::InDomain => {
                        assert!(!later_skips && glide_ok, "{p:?}");
                        in_domain += 1;
                    }
                    Validity::Extrapolated(_) => extrapolated += 1,
                    Validity::OutOfDomain(_) => unreachable!(),
                }
            }
        }
    }
    println!("in domain {in_domain}, extrapolated {extrapolated}");
    assert!(extrapolated > 0);
    let s = EntryState {
        radius_m: R_EARTH + 122e3,
        speed_m_s: 11_500.0,
        flight_path_angle_rad: f64::to_radians(-7.0),
    };
    let r = predict(&planet(), &atmosphere(), &srm(), &lift(1.0), &s, &TO_2700);
    assert_ne!(validity_of(&r), Validity::InDomain, "{r:?}");
}

/// The glide-start checks derived from the re-planning domain (docs/validation/vinh-numerical.md): a glide-mode
/// prediction from the SRM glide entry is in domain at the glide's flight-path angle,
/// `GlideFlightPathAngle` 0.4 deg steeper, `GlideBelowEquilibrium` from 3 km below its glide start
/// radius (in domain from 0.5 km below).
#[test]
fn glide_start_checks_of_the_replanning_domain() {
    let n = glide_nav(0.0);
    let at = |dr: f64, gamma: f64| {
        let s = EntryState {
            radius_m: n.radius_m + dr,
            speed_m_s: n.speed_m_s,
            flight_path_angle_rad: gamma,
        };
        predict_glide(&planet(), &atmosphere(), &srm(), &lift(1.0), &s, &TO_2700).unwrap()
    };
    let p = at(0.0, n.flight_path_angle_rad);
    assert_eq!(p.validity, Validity::InDomain);
    let deg = std::f64::consts::PI / 180.0;
    assert_eq!(
        at(0.0, n.flight_path_angle_rad - 0.4 * deg).validity,
        Validity::Extrapolated(Extrapolation::GlideFlightPathAngle)
    );
    let below = p.glide_start_radius_m - n.radius_m;
    assert_eq!(
        at(below - 500.0, n.flight_path_angle_rad).validity,
        Validity::InDomain
    );
    assert_eq!(
        at(below - 3000.0, n.flight_path_angle_rad).validity,
        Validity::Extrapolated(Extrapolation::GlideBelowEquilibrium)
    );
}

/// A chain captured in its first skip from a descending state is the glide started from the
/// state: the same range (to 1e-9) and the same validity as the glide mode, never
/// `CaptureTransition`. States near the SRM glide entry with `mu` lowered as the rotation
/// correction lowers it (where the skip closed form is oscillatory and captures at once); at
/// least one such chain must be found and in domain.
#[test]
fn chain_captured_in_its_first_skip_is_the_glide_from_the_state() {
    let deg = std::f64::consts::PI / 180.0;
    let (mut found, mut in_domain) = (0, 0);
    for mu_factor in [1.0, 0.99, 0.98, 0.97] {
        let pl = Planet {
            mu_m3_s2: MU * mu_factor,
            radius_m: R_EARTH,
        };
        for h_km in [85.0, 90.0, 95.0, 100.0] {
            for v in [7400.0, 7550.0, 7650.0] {
                for g_deg in [-0.05, -0.15, -0.3] {
                    for f in [0.6, 0.8, 1.0] {
                        let s = EntryState {
                            radius_m: R_EARTH + h_km * 1e3,
                            speed_m_s: v,
                            flight_path_angle_rad: g_deg * deg,
                        };
                        let Ok(c) = predict(&pl, &atmosphere(), &srm(), &lift(f), &s, &TO_2700)
                        else {
                            continue;
                        };
                        if c.skips != 0 || c.arcs != 0 {
                            continue;
                        }
                        found += 1;
                        let g = predict_glide(&pl, &atmosphere(), &srm(), &lift(f), &s, &TO_2700)
                            .unwrap();
                        assert!(
                            (c.range_m - g.range_m).abs() <= 1e-9 * g.range_m,
                            "{h_km} km {v} m/s {g_deg} deg f {f}: {} vs {}",
                            c.range_m,
                            g.range_m
                        );
                        assert_eq!(c.validity, g.validity);
                        assert_ne!(
                            c.validity,
                            Validity::Extrapolated(Extrapolation::CaptureTransition)
                        );
                        in_domain += usize::from(c.validity == Validity::InDomain);
                    }
                }
            }
        }
    }
    println!("{found} first-capture chains, {in_domain} in domain");
    assert!(found > 0 && in_domain > 0, "{found} / {in_domain}");
}
