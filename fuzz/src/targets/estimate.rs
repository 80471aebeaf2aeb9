//! Onboard aerodynamic estimation with hostile configurations, sensed and expected
//! accelerations and model states, in `f64` and `f32`. Checks: no panic; a bad configuration is
//! `InvalidConfig`; a non-finite or negative acceleration is a typed error that leaves the
//! estimate unchanged; the estimate is always finite and inside its configured bounds; the
//! model's expected accelerations are finite and non-negative or `None`; the scaled model is
//! finite and positive or `None`.

use guidance_core::estimate::{
    AeroEstimator, AeroScales, EstimatorConfig, SensedAero, expected_aero,
};
use guidance_core::scalar::Real;
use guidance_core::vinh::{ExpAtmosphere, VehicleParams};
use rand::Rng;

use crate::hostile::value;

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    let cfg: [f64; 7] = [
        value(rng, 0.0, 1.0, 0.05),
        value(rng, 0.0, 1.0, 0.05),
        value(rng, 0.05, 1.0, 0.05),
        value(rng, 1.0, 5.0, 0.05),
        value(rng, 0.05, 1.0, 0.05),
        value(rng, 1.0, 5.0, 0.05),
        value(rng, 0.0, 2.0, 0.05),
    ];
    let mut samples = Vec::new();
    for _ in 0..40 {
        samples.push([
            value(rng, 0.0, 100.0, 0.1),
            value(rng, 0.0, 100.0, 0.1),
            value(rng, 0.0, 100.0, 0.1),
            value(rng, 0.0, 100.0, 0.1),
            value(rng, 6.3e6, 6.6e6, 0.1),
            value(rng, 0.0, 8000.0, 0.1),
            value(rng, 0.0, 2.0, 0.1),
        ]);
    }
    check::<f64>(&cfg, &samples)?;
    check::<f32>(&cfg, &samples)
}

fn check<S: Real>(cfg: &[f64; 7], samples: &[[f64; 7]]) -> Result<(), String> {
    let c = |v: f64| S::from_f64(v);
    let config = EstimatorConfig {
        lift_to_drag_gain: c(cfg[0]),
        drag_gain: c(cfg[1]),
        lift_to_drag_bounds: (c(cfg[2]), c(cfg[3])),
        drag_bounds: (c(cfg[4]), c(cfg[5])),
        min_drag_m_s2: c(cfg[6]),
    };
    let mut est = match AeroEstimator::new(config) {
        Ok(e) => e,
        Err(guidance_core::GuidanceError::InvalidConfig) => return Ok(()),
        Err(e) => return Err(format!("unexpected config error {e:?}")),
    };
    let atm = ExpAtmosphere::<S>::earth();
    let veh = VehicleParams {
        mass_kg: c(1500.0),
        reference_area_m2: c(3.0),
        cd0: c(0.6),
        k_polar: c(0.9),
        nose_radius_m: c(0.5),
    };
    let in_bounds = |v: S, (lo, hi): (S, S)| v.is_finite() && v >= lo && v <= hi;
    for s in samples {
        let sensed = SensedAero {
            lift_m_s2: c(s[0]),
            drag_m_s2: c(s[1]),
        };
        let expected = match expected_aero(&atm, &veh, c(s[6]), c(s[4]), c(s[5])) {
            Some(e) => {
                if !(e.lift_m_s2.is_finite() && e.drag_m_s2.is_finite())
                    || e.lift_m_s2 < S::ZERO
                    || e.drag_m_s2 < S::ZERO
                {
                    return Err(format!("expected_aero gave {e:?}"));
                }
                e
            }
            None => SensedAero {
                lift_m_s2: c(s[2]),
                drag_m_s2: c(s[3]),
            },
        };
        let before = est.scales();
        if est.update(&sensed, &expected).is_err() && est.scales() != before {
            return Err("a rejected sample changed the estimate".into());
        }
        let a = est.scales();
        if !(in_bounds(a.lift_to_drag, config.lift_to_drag_bounds)
            && in_bounds(a.drag, config.drag_bounds))
        {
            return Err(format!("estimate out of bounds: {a:?} with {config:?}"));
        }
        if let Some((m, v)) = a.apply(&atm, &veh)
            && !(m.rho0_kg_m3.is_finite() && m.rho0_kg_m3 > S::ZERO && v.k_polar.is_finite())
        {
            return Err(format!("scaled model not finite: {m:?} {v:?}"));
        }
    }
    let _ = AeroScales::<S>::nominal();
    Ok(())
}
