//! The bank shape of numerical predictions (`BankShape`, `ReplanningGuidance::with_bank_shape`):
//! the stored magnitudes interpolated and held in the bank interval, bad tables refused, a flat
//! shape predicting what the constant bank predicts, a shape with more bank ahead flying less
//! range, and a re-plan installing one offset on the stored magnitudes so that the command at
//! the current E-hat is the solved bank.

use crate::vinh_replan::{glide_nav, normalizer, rcfg, replanning};
use crate::vinh_support::inputs::{atmosphere, lift, planet, srm};
use crate::vinh_support::vehicles::R_EARTH;
use guidance_core::GuidanceError;
use guidance_core::replan::numerical::MAX_STEPS;
use guidance_core::replan::{
    BankShape, NumericalRun, PredictorMode, RangeTarget, ReplanCase, SHAPE_CAPACITY,
};
use guidance_core::vinh::{EntryState, PeakMode, PredictorConfig};

const DEG: f64 = std::f64::consts::PI / 180.0;

fn shape(nodes: &[(f64, f64)], f_min: f64, f_max: f64) -> Result<BankShape<f64>, GuidanceError> {
    BankShape::new(
        normalizer(),
        nodes.iter().map(|&(e, s)| (e, s * DEG)),
        f_min,
        f_max,
    )
}

#[test]
fn bank_shape_interpolates_clamps_and_refuses_bad_tables() {
    let s = shape(&[(1.0, 0.0), (0.8, -40.0), (0.4, 60.0)], 0.05, 0.9).unwrap();
    // Linear in E-hat between the nodes (the sign dropped), the end nodes' beyond them.
    assert!((s.sigma_at(0.9) - 20.0 * DEG).abs() < 1e-12);
    assert!((s.sigma_at(0.6) - 50.0 * DEG).abs() < 1e-12);
    assert_eq!(s.sigma_at(1.2), 0.0);
    assert!((s.sigma_at(0.1) - 60.0 * DEG).abs() < 1e-12);
    // Held in [acos(0.9), acos(0.05)].
    assert!((s.clamp(0.0) - 0.9_f64.acos()).abs() < 1e-15);
    assert!((s.clamp(1.6) - 0.05_f64.acos()).abs() < 1e-15);
    // The offset that flies f at E-hat 0.6, and the fraction it then flies there.
    let f = 0.5;
    let offset = s.offset_for(0.6, f);
    assert!((offset - 10.0 * DEG).abs() < 1e-12);
    let e_hat = 0.6;
    let (r, v) = state_at(e_hat);
    assert!((s.fraction(r, v, offset).unwrap() - f).abs() < 1e-9);
    // A non-finite state has no E-hat, so no fraction.
    assert_eq!(s.fraction(f64::NAN, v, offset), None);

    let bad = GuidanceError::InvalidConfig;
    assert_eq!(shape(&[], 0.05, 0.9), Err(bad));
    assert_eq!(shape(&[(0.5, 10.0), (0.8, 20.0)], 0.05, 0.9), Err(bad));
    assert_eq!(shape(&[(0.5, 10.0), (0.5, 20.0)], 0.05, 0.9), Err(bad));
    assert_eq!(shape(&[(0.5, f64::NAN)], 0.05, 0.9), Err(bad));
    assert_eq!(shape(&[(0.5, 10.0)], 0.9, 0.05), Err(bad));
    assert_eq!(shape(&[(0.5, 10.0)], 0.05, 1.5), Err(bad));
    let many: Vec<(f64, f64)> = (0..=SHAPE_CAPACITY)
        .map(|i| (1.0 - 0.01 * i as f64, 30.0))
        .collect();
    assert_eq!(shape(&many, 0.05, 0.9), Err(bad));
    assert!(shape(&many[..SHAPE_CAPACITY], 0.05, 0.9).is_ok());
}

/// A radius and speed at `e_hat` of [`normalizer`] (100 km altitude).
fn state_at(e_hat: f64) -> (f64, f64) {
    let r = R_EARTH + 100e3;
    // Bisect the speed: E-hat grows with it.
    let (mut lo, mut hi) = (0.0, 12_000.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if normalizer().normalized(r, mid).unwrap() < e_hat {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (r, 0.5 * (lo + hi))
}

/// The range of a numerical prediction from the SRM glide entry at fraction `f`, with `shape`.
fn range_m(f: f64, shape: Option<BankShape<f64>>) -> f64 {
    let n = glide_nav(0.0);
    let run = NumericalRun::new(
        &planet(),
        &atmosphere(),
        &srm(),
        &lift(f),
        &EntryState {
            radius_m: n.radius_m,
            speed_m_s: n.speed_m_s,
            flight_path_angle_rad: n.flight_path_angle_rad,
        },
        &PredictorConfig {
            final_speed_m_s: 2700.0,
            max_skips: 4,
        },
        PeakMode::RangeOnly,
    )
    .unwrap();
    match shape {
        Some(s) => {
            let mut run = run.with_bank_shape(&s);
            run.advance_shaped(MAX_STEPS, Some(&s))
                .unwrap()
                .unwrap()
                .range_m
        }
        None => {
            let mut run = run;
            run.advance(MAX_STEPS).unwrap().unwrap().range_m
        }
    }
}

#[test]
fn a_flat_shape_predicts_the_constant_bank_and_more_bank_ahead_flies_less() {
    let f = 0.6_f64;
    let bank = f.acos() / DEG;
    let constant = range_m(f, None);
    let flat = range_m(
        f,
        Some(shape(&[(1.0, bank), (0.5, bank), (0.0, bank)], 0.05, 1.0).unwrap()),
    );
    assert!(
        ((flat - constant) / constant).abs() < 1e-9,
        "{flat} {constant}"
    );
    // The same bank at the start (the glide entry is at E-hat 0.99), 20 deg more below 0.5.
    let rising = range_m(
        f,
        Some(shape(&[(1.0, bank), (0.5, bank), (0.4, bank + 20.0)], 0.05, 1.0).unwrap()),
    );
    assert!(rising < constant - 100e3, "{rising} {constant}");
}

/// With the shape the first re-plan installs one offset on every stored magnitude (held in
/// the bank interval, signs kept), the node above the current E-hat included, and the command
/// the table gives at that E-hat is the solved bank: what is flown is what was predicted.
#[test]
fn a_shaped_replan_installs_one_offset_on_the_stored_magnitudes() {
    // The target: the constant-bank numerical range at f = 0.6 from the glide entry.
    let total = range_m(0.6, None) / R_EARTH;
    let cfg = rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Numerical,
    );
    let mut g = replanning(cfg).with_bank_shape().unwrap();
    let before = g.guidance().table().clone();
    let out = g.update(&glide_nav(0.0)).unwrap();
    let r = out.replan.expect("tick 0 re-plans");
    assert_eq!(r.case, ReplanCase::Converged, "{r:?}");
    assert!(r.applied);
    assert!((r.predicted_range_m.unwrap() - total * R_EARTH).abs() <= 1000.0);
    // Every node is replaced: the glide entry (E-hat 0.99) is inside the first segment.
    assert_eq!(usize::from(r.nodes_replanned), before.len());
    let e = r.normalized_energy;
    let stored = shape(
        &before
            .nodes()
            .iter()
            .map(|n| (n.x, n.sigma_rad / DEG))
            .collect::<Vec<_>>(),
        0.05,
        1.0,
    )
    .unwrap();
    let offset = r.bank_rad - stored.sigma_at(e);
    let after = g.guidance().table();
    for (a, b) in after.nodes().iter().zip(before.nodes()) {
        assert_eq!((a.x, a.alpha_rad), (b.x, b.alpha_rad));
        let want = stored.clamp(b.sigma_rad.abs() + offset);
        assert!((a.sigma_rad.abs() - want).abs() < 1e-12, "{a:?} {b:?}");
        assert_eq!(a.sigma_rad < 0.0, b.sigma_rad < 0.0, "the sign is kept");
    }
    // The table at the current E-hat (linear between the first two nodes) is the solved bank.
    let (n0, n1) = (after.nodes()[0], after.nodes()[1]);
    let w = (n0.x - e) / (n0.x - n1.x);
    let here = n0.sigma_rad.abs() + w * (n1.sigma_rad.abs() - n0.sigma_rad.abs());
    assert!((here - r.bank_rad).abs() < 1e-9, "{here} {}", r.bank_rad);
    // Without a shape the same solve flattens the remaining nodes to its bank.
    let mut flat = replanning(rcfg(
        RangeTarget::FlownRangeAngle { total_rad: total },
        3,
        PredictorMode::Numerical,
    ));
    let rf = flat.update(&glide_nav(0.0)).unwrap().replan.unwrap();
    assert!(rf.applied);
    assert!(
        flat.guidance()
            .table()
            .nodes()
            .iter()
            .skip(1)
            .all(|n| n.sigma_rad.abs() == rf.bank_rad)
    );
}
