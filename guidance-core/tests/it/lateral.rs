//! Lateral guidance: the corridor logic on crafted headings, and bank reversals flown through
//! the rate limiter (never a step), with a stored profile and with the re-planner.

use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{BankSign, Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::lateral::{BankReversalLogic, Corridor, CorridorAxis, LateralConfig};
use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
use guidance_core::replan::TargetPoint;
use guidance_core::{GuidanceError, NavState};
use proptest::prelude::*;

const DEG: f64 = core::f64::consts::PI / 180.0;

/// Target 20 deg east on the equator; corridor 10 deg at >= 6 km/s, 4 deg at <= 3 km/s.
fn config(max_reversals: u8, hysteresis_deg: f64) -> LateralConfig<f64> {
    LateralConfig {
        target: TargetPoint {
            latitude_rad: 0.0,
            longitude_rad: 20.0 * DEG,
        },
        corridor: Corridor {
            axis: CorridorAxis::Speed,
            x_high: 6000.0,
            width_high_rad: 10.0 * DEG,
            x_low: 3000.0,
            width_low_rad: 4.0 * DEG,
        },
        hysteresis_rad: hysteresis_deg * DEG,
        max_reversals,
        freeze_angle_rad: 0.5 * DEG,
    }
}

/// On the equator at longitude 0, heading `heading_deg` (target bearing 90 deg).
fn nav(t: f64, speed: f64, heading_deg: f64) -> NavState<f64> {
    NavState {
        time_s: t,
        radius_m: EARTH_RADIUS_M + 60_000.0,
        speed_m_s: speed,
        flight_path_angle_rad: -0.5 * DEG,
        heading_rad: heading_deg * DEG,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

#[test]
fn corridor_narrows_linearly_with_speed() {
    let c = config(4, 1.0).corridor;
    assert_eq!(c.width_rad(7000.0), 10.0 * DEG);
    assert_eq!(c.width_rad(2000.0), 4.0 * DEG);
    assert!((c.width_rad(4500.0) - 7.0 * DEG).abs() < 1e-12);
    assert_eq!(c.width_rad(f64::NAN), 4.0 * DEG);
    // Fuzz finding (seed 20261130, case 5268): end widths 5e-324 (at x_high) and 0.317 rad,
    // x_low = -1e300: t rounds to 1 and `0.317 + (5e-324 - 0.317)` is 0. The width stays
    // within the end widths, hence positive.
    let tiny = Corridor {
        x_high: 7997.45,
        width_high_rad: 5e-324,
        x_low: -1e300,
        width_low_rad: 0.317,
        ..c
    };
    assert!(tiny.width_rad(5832.2) >= 5e-324);
}

#[test]
fn reversal_logic_on_crafted_headings() {
    let mut l = BankReversalLogic::new(config(2, 2.0)).unwrap();
    // Heading 95 deg: 5 deg right of the target -> first sign turns left.
    let s = l.update(&nav(0.0, 7000.0, 95.0)).unwrap();
    assert_eq!(s.sign, BankSign::Negative);
    assert!((s.heading_error_rad - 5.0 * DEG).abs() < 1e-9);
    assert!(!s.reversed);
    // 8 deg left, inside the 10 deg corridor: negative bank diverges but no reversal yet.
    let s = l.update(&nav(2.0, 7000.0, 82.0)).unwrap();
    assert_eq!((s.sign, s.reversed), (BankSign::Negative, false));
    // 11 deg left: outside -> reverse to the right.
    let s = l.update(&nav(4.0, 7000.0, 79.0)).unwrap();
    assert_eq!(
        (s.sign, s.reversed, s.reversals),
        (BankSign::Positive, true, 1)
    );
    // 11 deg right straight away (no pass inside 10 - 2 deg): disarmed, no reversal.
    let s = l.update(&nav(6.0, 7000.0, 101.0)).unwrap();
    assert_eq!((s.sign, s.reversed), (BankSign::Positive, false));
    // Back inside 8 deg: re-armed; then 11 deg right at 4500 m/s (corridor 7 deg): reverse.
    l.update(&nav(8.0, 7000.0, 95.0)).unwrap();
    let s = l.update(&nav(10.0, 4500.0, 98.0)).unwrap();
    assert_eq!(
        (s.sign, s.reversed, s.reversals),
        (BankSign::Negative, true, 2)
    );
    // At most 2 reversals: a diverging error far outside the corridor keeps the sign.
    l.update(&nav(12.0, 4500.0, 90.0)).unwrap();
    let s = l.update(&nav(14.0, 2000.0, 60.0)).unwrap();
    assert_eq!(
        (s.sign, s.reversed, s.reversals),
        (BankSign::Negative, false, 2)
    );
}

#[test]
fn converging_sign_is_never_reversed_and_freeze_holds() {
    let mut l = BankReversalLogic::new(config(9, 0.0)).unwrap();
    l.update(&nav(0.0, 7000.0, 120.0)).unwrap(); // 30 deg right -> negative (converging)
    let s = l.update(&nav(2.0, 7000.0, 130.0)).unwrap();
    assert_eq!((s.sign, s.reversed), (BankSign::Negative, false));
    // On the target (inside the freeze angle): no reversal whatever the heading.
    let mut l = BankReversalLogic::new(LateralConfig {
        target: TargetPoint {
            latitude_rad: 0.0,
            longitude_rad: 0.1 * DEG,
        },
        ..config(9, 0.0)
    })
    .unwrap();
    l.update(&nav(0.0, 7000.0, 80.0)).unwrap();
    let s = l.update(&nav(2.0, 7000.0, 40.0)).unwrap();
    assert!(!s.reversed);
}

#[test]
fn lateral_rejects_bad_config_and_state() {
    let bad = [
        LateralConfig {
            hysteresis_rad: -1.0,
            ..config(1, 0.0)
        },
        LateralConfig {
            freeze_angle_rad: f64::NAN,
            ..config(1, 0.0)
        },
        LateralConfig {
            corridor: Corridor {
                x_low: 7000.0,
                ..config(1, 0.0).corridor
            },
            ..config(1, 0.0)
        },
        LateralConfig {
            corridor: Corridor {
                width_low_rad: 0.0,
                ..config(1, 0.0).corridor
            },
            ..config(1, 0.0)
        },
    ];
    for c in bad {
        assert_eq!(BankReversalLogic::new(c), Err(GuidanceError::InvalidConfig));
    }
    let mut l = BankReversalLogic::new(config(1, 0.0)).unwrap();
    let mut n = nav(0.0, 7000.0, 90.0);
    n.heading_rad = f64::NAN;
    assert!(l.update(&n).is_err());
    assert_eq!(l.sign(), None);
    // Energy axis.
    let e = EnergyNormalizer::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122e3,
        7435.5,
    )
    .unwrap();
    let c = Corridor {
        axis: CorridorAxis::NormalizedEnergy(e),
        x_high: 0.8,
        width_high_rad: 0.2,
        x_low: 0.2,
        width_low_rad: 0.05,
    };
    let mut l = BankReversalLogic::new(LateralConfig {
        corridor: c,
        ..config(1, 0.0)
    })
    .unwrap();
    let s = l.update(&nav(0.0, 7000.0, 90.0)).unwrap();
    assert!(s.corridor_rad > 0.05 && s.corridor_rad <= 0.2);
}

/// A time-indexed stored profile with two-sided bank bounds (-90..90 deg).
fn stored(bank_deg: &[f64]) -> Guidance<f64> {
    let rows: Vec<(f64, f64, f64)> = bank_deg
        .iter()
        .enumerate()
        .map(|(i, &b)| (i as f64 * 40.0, 30.0, b))
        .collect();
    let bounds = AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).unwrap();
    let table = NodeTable::from_deg(Independent::TimeS, &rows, bounds).unwrap();
    let e = EnergyNormalizer::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122e3,
        7435.5,
    )
    .unwrap();
    Guidance::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::Linear,
        e,
        Command::from_deg(30.0, 0.0).unwrap(),
    )
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Whatever the profile and whenever the sign flips, the commanded attitude sampled every
    /// 0.25 s never changes faster than the rate limits (15 deg/s bank, 5 deg/s alpha): a
    /// reversal is a ramp, never a step; and it stays inside the bounds.
    #[test]
    fn reversal_never_makes_the_attitude_jump(
        banks in prop::collection::vec(-90.0f64..=90.0, 3..8),
        flips in prop::collection::vec(any::<bool>(), 40..120),
    ) {
        let mut g = stored(&banks);
        let cfg = GuidanceConfig::<f64>::thesis_default();
        let (ra, rs) = (cfg.rates.alpha_rad_s, cfg.rates.sigma_rad_s);
        let mut sign = BankSign::Positive;
        let mut prev: Option<(f64, Command<f64>)> = None;
        for (k, &flip) in flips.iter().enumerate() {
            let t = k as f64 * 2.0;
            if flip {
                sign = sign.reversed();
            }
            g.set_bank_sign(Some(sign));
            let n = NavState { time_s: t, ..nav(t, 7000.0, 90.0) };
            let out = g.update(&n).unwrap();
            prop_assert!(out.ticked);
            let target_sign = if sign == BankSign::Positive { 1.0 } else { -1.0 };
            prop_assert!(g.target().sigma_rad * target_sign >= 0.0);
            for q in 0..8 {
                let tq = t + 0.25 * f64::from(q);
                let c = g.attitude_at(tq);
                prop_assert!(c.sigma_rad.abs() <= 90.0 * DEG + 1e-12);
                if let Some((tp, cp)) = prev {
                    let dt = tq - tp;
                    prop_assert!((c.sigma_rad - cp.sigma_rad).abs() <= rs * dt * (1.0 + 1e-9) + 1e-12,
                        "bank jump at t = {tq}: {} -> {}", cp.sigma_rad, c.sigma_rad);
                    prop_assert!((c.alpha_rad - cp.alpha_rad).abs() <= ra * dt * (1.0 + 1e-9) + 1e-12);
                }
                prev = Some((tq, c));
            }
        }
    }
}

#[test]
fn a_full_reversal_takes_the_rate_limited_time() {
    // 60 deg right -> 60 deg left at 15 deg/s: 120 deg in 8 s, i.e. 4 ticks of 30 deg.
    let mut g = stored(&[60.0, 60.0, 60.0, 60.0]);
    let mut banks = Vec::new();
    for k in 0..12 {
        let t = f64::from(k) * 2.0;
        if k == 5 {
            g.set_bank_sign(Some(BankSign::Negative));
        }
        g.update(&nav(t, 7000.0, 90.0)).unwrap();
        banks.push(g.command().sigma_rad / DEG);
    }
    // Reached +60 (from 0) at tick 2; reversal from tick 5 on.
    let expect = [
        30.0, 60.0, 60.0, 60.0, 60.0, 30.0, 0.0, -30.0, -60.0, -60.0, -60.0, -60.0,
    ];
    for (b, e) in banks.iter().zip(expect) {
        assert!((b - e).abs() < 1e-9, "{banks:?}");
    }
    assert_eq!(g.bank_sign(), Some(BankSign::Negative));
}
