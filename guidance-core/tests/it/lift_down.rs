//! Lift-down banks (|sigma| > 90 deg, issue 24 item 3) through the core: the guidance and its
//! bank reversals with -180..180 deg bounds, in f64, f32 and fixed point; the Vinh closed
//! forms with a negative vertical lift fraction (finite predictions or typed errors; the
//! property test `vinh_props::predictor_never_nan_never_panics` draws vertical fractions in
//! [-1, 1] too).

use guidance_core::NavState;
use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{BankSign, Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
use guidance_core::scalar::{Fixed, Scalar};
use guidance_core::vinh::{
    EntryState, ExpAtmosphere, LiftControl, Planet, PredictorConfig, VehicleParams, predict,
};

const DEG: f64 = core::f64::consts::PI / 180.0;

fn nav<S: Scalar>(t: f64) -> NavState<S> {
    NavState {
        time_s: S::from_f64(t),
        radius_m: S::from_f64(EARTH_RADIUS_M + 60_000.0),
        speed_m_s: S::from_f64(7000.0),
        flight_path_angle_rad: S::from_f64(-0.01),
        heading_rad: S::from_f64(90.0 * DEG),
        latitude_rad: S::ZERO,
        longitude_rad: S::ZERO,
    }
}

/// A lift-down profile (150 deg) reversed to -150 deg: the command ramps at the rate limit
/// (15 deg/s, through 0 deg: 300 deg in 20 s) and holds -150 deg, inside the bounds.
fn reversal<S: Scalar>() -> Vec<f64> {
    let bounds = AngleBounds::<S>::from_deg(0.0, 45.0, -180.0, 180.0).unwrap();
    let rows = [(0.0, 0.0, 150.0), (1000.0, 0.0, 150.0)];
    let table = NodeTable::<S>::from_deg(Independent::TimeS, &rows, bounds).unwrap();
    let e = EnergyNormalizer::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122e3,
        7435.5,
    )
    .unwrap();
    let mut g = Guidance::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::Linear,
        e,
        Command::from_deg(0.0, 150.0).unwrap(),
    )
    .unwrap();
    let mut banks = Vec::new();
    for k in 0..20 {
        let t = f64::from(k) * 2.0;
        if k == 2 {
            g.set_bank_sign(Some(BankSign::Negative));
        }
        let out = g.update(&nav::<S>(t)).unwrap();
        banks.push(out.command.sigma_rad.to_f64() / DEG);
    }
    banks
}

#[test]
fn lift_down_banks_reverse_through_the_rate_limiter_in_every_scalar() {
    for banks in [reversal::<f64>(), reversal::<f32>(), reversal::<Fixed>()] {
        assert!((banks[1] - 150.0).abs() < 1e-3, "{banks:?}");
        // 30 deg per 2 s tick, never a step.
        for w in banks.windows(2) {
            assert!((w[1] - w[0]).abs() <= 30.0 + 1e-3, "{banks:?}");
        }
        assert!((banks[2] - 120.0).abs() < 1e-3, "{banks:?}");
        assert!((banks[12] + 150.0).abs() < 1e-3, "{banks:?}");
        assert!((banks[19] + 150.0).abs() < 1e-3, "{banks:?}");
    }
}

#[test]
fn vinh_predictions_with_lift_down_are_finite_or_typed_errors() {
    let planet = Planet::<f64>::earth();
    let atm = ExpAtmosphere::<f64>::earth();
    let veh = VehicleParams {
        mass_kg: 5000.0,
        reference_area_m2: 12.0,
        cd0: 1.2,
        k_polar: 0.5,
        nose_radius_m: 2.0,
    };
    let entry = EntryState {
        radius_m: EARTH_RADIUS_M + 120e3,
        speed_m_s: 7800.0,
        flight_path_angle_rad: -1.5 * DEG,
    };
    let config = PredictorConfig {
        final_speed_m_s: 2000.0,
        max_skips: 4,
    };
    let mut outcomes = Vec::new();
    for bank in [91.0, 120.0, 150.0, 180.0, -120.0] {
        let lift = LiftControl::from_lift_coefficient(&veh, 0.3, f64::to_radians(bank)).unwrap();
        assert!(lift.vertical_fraction < 0.0);
        match predict(&planet, &atm, &veh, &lift, &entry, &config) {
            Ok(p) => {
                for v in [
                    p.range_angle_rad,
                    p.range_m,
                    p.peak_heat_flux_w_m2,
                    p.peak_g_load,
                ] {
                    assert!(v.is_finite(), "{bank}: {p:?}");
                }
                outcomes.push(format!("{bank}: range {:.0} km", p.range_m / 1e3));
            }
            Err(e) => outcomes.push(format!("{bank}: {e:?}")),
        }
    }
    println!("{outcomes:?}");
}
