//! The numerical predictor's opt-in rotating-planet terms (`NumericalRun::with_rotation`).

use crate::vinh_support::inputs::{atmosphere, horus, planet};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::replan::NumericalRun;
use guidance_core::vinh::{EntryState, LiftControl, PeakMode, Prediction, PredictorConfig};

const OMEGA: f64 = 7.292_115e-5;

fn run() -> NumericalRun<f64> {
    NumericalRun::new(
        &planet(),
        &atmosphere(),
        &horus(),
        &LiftControl {
            lambda: 3.6,
            vertical_fraction: 0.6,
        },
        &EntryState {
            radius_m: R_EARTH + 60e3,
            speed_m_s: 5000.0,
            flight_path_angle_rad: -0.001,
        },
        &PredictorConfig {
            final_speed_m_s: 780.0,
            max_skips: 4,
        },
        PeakMode::Full,
    )
    .unwrap()
}

fn finish(mut r: NumericalRun<f64>) -> Prediction<f64> {
    r.advance(u16::MAX).unwrap().unwrap()
}

/// A zero or non-finite rotation rate, latitude or heading leaves the prediction the
/// non-rotating one bit for bit.
#[test]
fn zero_rotation_is_the_planar_prediction_bit_for_bit() {
    let base = finish(run());
    for (w, lat, psi) in [
        (0.0, 0.3, 1.2),
        (-0.0, -0.8, 4.0),
        (f64::NAN, 0.3, 1.2),
        (OMEGA, f64::NAN, 1.2),
        (OMEGA, 0.3, f64::INFINITY),
    ] {
        let p = finish(run().with_rotation(w, lat, psi));
        assert_eq!(p, base, "{w} {lat} {psi}");
        assert_eq!(
            p.range_angle_rad.to_bits(),
            base.range_angle_rad.to_bits(),
            "{w} {lat} {psi}"
        );
    }
}

/// Flying east at the equator the rotation adds lift (Coriolis and centrifugal) and the range
/// grows; flying west it shrinks; flying north from the equator only the centrifugal term acts
/// (small, positive); at the pole the rotation acts only through the tiny `Omega^2 r cos(phi)`
/// terms, which vanish.
#[test]
fn rotation_lengthens_eastward_and_shortens_westward_flight() {
    let base = finish(run()).range_m;
    let east = finish(run().with_rotation(OMEGA, 0.0, core::f64::consts::FRAC_PI_2)).range_m;
    let west = finish(run().with_rotation(OMEGA, 0.0, -core::f64::consts::FRAC_PI_2)).range_m;
    let north = finish(run().with_rotation(OMEGA, 0.0, 0.0)).range_m;
    let pole = finish(run().with_rotation(OMEGA, core::f64::consts::FRAC_PI_2, 1.0)).range_m;
    println!("base {base:.0} east {east:.0} west {west:.0} north {north:.0} pole {pole:.0}");
    assert!(east > 1.02 * base, "{east} {base}");
    assert!(west < 0.98 * base, "{west} {base}");
    assert!(north > base && north < east, "{north} {base} {east}");
    assert!(((pole - base) / base).abs() < 1e-6, "{pole} {base}");
}
