//! The terminal crossrange law of the lateral logic (`TerminalLateral`): its prediction against
//! a numerical integration, its settings, that it leaves the corridor alone outside its range,
//! and a kinematic closed loop (a vehicle turning hard near the target, as HORUS-2B does in its
//! terminal dive) in which it ends on the target where the corridor with a freeze does not.

use guidance_core::energy::EARTH_RADIUS_M;
use guidance_core::guidance::BankSign;
use guidance_core::lateral::{
    BankReversalLogic, Corridor, CorridorAxis, LateralConfig, TerminalLateral, predicted_offsets,
};
use guidance_core::replan::TargetPoint;
use guidance_core::{GuidanceError, NavState};

const DEG: f64 = core::f64::consts::PI / 180.0;
const R: f64 = EARTH_RADIUS_M;

/// Target on the equator at longitude 0; corridor 4 deg below 3 km/s; freeze `freeze_km`.
fn config(freeze_km: f64) -> LateralConfig<f64> {
    LateralConfig {
        target: TargetPoint {
            latitude_rad: 0.0,
            longitude_rad: 0.0,
        },
        corridor: Corridor {
            axis: CorridorAxis::Speed,
            x_high: 6000.0,
            width_high_rad: 10.0 * DEG,
            x_low: 3000.0,
            width_low_rad: 4.0 * DEG,
        },
        hysteresis_rad: 1.0 * DEG,
        max_reversals: 20,
        freeze_angle_rad: freeze_km * 1e3 / R,
    }
}

fn terminal(start_km: f64) -> TerminalLateral<f64> {
    TerminalLateral {
        start_angle_rad: start_km * 1e3 / R,
        tolerance_rad: 0.5e3 / R,
        reversal_lead_s: 4.0,
    }
}

/// The offsets of `predicted_offsets` against a fine integration of `y'' = kappa(x)` (flat,
/// small angles: heading error 2 deg, turn radius 40 km, 60 km to go): keep the turn, or keep
/// it for the lead angle `d` and turn the other way after.
#[test]
fn predicted_offsets_match_an_integrated_path() {
    let (s, dpsi, kappa, d) = (60e3, 2.0 * DEG, 1.0 / 40e3, 8e3);
    for c in [1.0, -1.0] {
        let integrate = |switch_at: f64| {
            let (mut y, mut slope, dx) = (0.0, dpsi.sin(), 1.0);
            let mut x = 0.0;
            while x < s {
                let k = if x < switch_at { c * kappa } else { -c * kappa };
                y += slope * dx + 0.5 * k * dx * dx;
                slope += k * dx;
                x += dx;
            }
            y
        };
        let (keep, rev) = predicted_offsets(s, dpsi, kappa, c, d);
        assert!((keep - integrate(s)).abs() < 1.0, "{keep} {}", integrate(s));
        assert!((rev - integrate(d)).abs() < 1.0, "{rev} {}", integrate(d));
        // The sign of a turn decides the side: kappa s^2 / 2 = 45 km.
        assert!(c * keep > 40e3 && c * rev < -10e3, "{c}: {keep} {rev}");
    }
    // No turn: both are the straight line's offset; a lead beyond the target is the target.
    let (keep, rev) = predicted_offsets(60e3, 2.0 * DEG, 0.0, 1.0, 8e3);
    assert_eq!(keep, rev);
    let (keep, rev) = predicted_offsets(60e3, 2.0 * DEG, 1.0 / 40e3, 1.0, 1e9);
    assert!((keep - rev).abs() < 1e-9);
}

#[test]
fn terminal_settings_are_checked() {
    let l = BankReversalLogic::new(config(5.0)).unwrap();
    let bad = [
        TerminalLateral {
            start_angle_rad: 0.0,
            ..terminal(100.0)
        },
        TerminalLateral {
            start_angle_rad: 4.0,
            ..terminal(100.0)
        },
        TerminalLateral {
            tolerance_rad: 0.0,
            ..terminal(100.0)
        },
        TerminalLateral {
            tolerance_rad: f64::NAN,
            ..terminal(100.0)
        },
        TerminalLateral {
            reversal_lead_s: -1.0,
            ..terminal(100.0)
        },
        TerminalLateral {
            reversal_lead_s: f64::INFINITY,
            ..terminal(100.0)
        },
    ];
    for t in bad {
        assert_eq!(
            l.with_terminal(t),
            Err(GuidanceError::InvalidConfig),
            "{t:?}"
        );
    }
    let l = l.with_terminal(terminal(100.0)).unwrap();
    assert_eq!(l.terminal(), Some(&terminal(100.0)));
}

/// Far from the target the law does nothing: the same decisions as the corridor alone on a
/// zig-zag of crafted headings 1000 km out.
#[test]
fn terminal_law_leaves_the_corridor_alone_outside_its_range() {
    let mut plain = BankReversalLogic::new(config(5.0)).unwrap();
    let mut with = BankReversalLogic::new(config(5.0))
        .unwrap()
        .with_terminal(terminal(200.0))
        .unwrap();
    for i in 0..60 {
        let t = f64::from(i) * 2.0;
        let heading = 90.0 + 12.0 * (t / 15.0).sin();
        let n = NavState {
            time_s: t,
            radius_m: R + 40e3,
            speed_m_s: 2000.0,
            flight_path_angle_rad: -DEG,
            heading_rad: heading * DEG,
            latitude_rad: 0.0,
            longitude_rad: -9.0 * DEG + t * 2000.0 / R,
        };
        assert_eq!(plain.update(&n).unwrap(), with.update(&n).unwrap(), "t {t}");
    }
    assert!(plain.reversals() > 2);
}

/// A vehicle on the equator flying east at 1.5 km/s towards the target, 150 km out,
/// `north_km` north with the heading `heading_deg`, turning on a 40 km radius in the direction of its bank
/// sign; a reversal swings the turn through zero at a constant rate in 8 s. The logic is
/// called every 2 s. Returns the offset \[m\] (north positive) when it passes the target's
/// longitude and the number of reversals.
fn fly(logic: &mut BankReversalLogic<f64>, north_km: f64, heading_deg: f64) -> (f64, u8) {
    let (v, radius, swing_s, dt) = (1500.0, 40e3, 8.0, 0.05);
    let (mut x, mut y, mut heading) = (-150e3, north_km * 1e3, heading_deg * DEG);
    let mut turn: f64 = 0.0; // current curvature [1/m], clockwise positive
    let mut t = 0.0;
    let mut next_tick = 0.0;
    let mut sign = BankSign::Positive;
    while x < 0.0 {
        if t >= next_tick {
            let n = NavState {
                time_s: t,
                radius_m: R + 30e3,
                speed_m_s: v,
                flight_path_angle_rad: 0.0,
                heading_rad: heading,
                latitude_rad: y / R,
                longitude_rad: x / R,
            };
            sign = logic.update(&n).unwrap().sign;
            next_tick += 2.0;
        }
        let wanted = match sign {
            BankSign::Positive => 1.0 / radius,
            BankSign::Negative => -1.0 / radius,
        };
        let step = 2.0 / radius / swing_s * dt;
        turn += (wanted - turn).clamp(-step, step);
        x += v * heading.sin() * dt;
        y += v * heading.cos() * dt;
        heading += turn * v * dt;
        t += dt;
    }
    (y, logic.reversals())
}

/// With the corridor and a 30 km freeze the last constant-sign turn carries the vehicle
/// kilometres to the side; the terminal law from 120 km (freeze 3 km) times its reversals on
/// the predicted crossrange and passes the target within 1.5 km (its 0.5 km tolerance plus the
/// granularity of 2 s ticks). Worst of 25 starts (-4..4 km north, heading 86..94 deg).
#[test]
fn terminal_law_ends_on_the_target_where_the_corridor_does_not() {
    let (mut worst_corridor, mut worst_terminal) = (0.0_f64, 0.0_f64);
    for i in 0..5 {
        for j in 0..5 {
            let (north, heading) = (-4.0 + 2.0 * f64::from(i), 86.0 + 2.0 * f64::from(j));
            let mut corridor = BankReversalLogic::new(config(30.0)).unwrap();
            let (y, _) = fly(&mut corridor, north, heading);
            worst_corridor = worst_corridor.max(y.abs());
            let mut term = BankReversalLogic::new(config(3.0))
                .unwrap()
                .with_terminal(terminal(120.0))
                .unwrap();
            let (y, reversals) = fly(&mut term, north, heading);
            worst_terminal = worst_terminal.max(y.abs());
            assert!(reversals >= 1);
        }
    }
    assert!(worst_corridor > 3e3, "corridor: {worst_corridor} m");
    // Measured: corridor 19.5 km, terminal 1.08 km (the tolerance plus a 2 s tick's worth of
    // timing: 3 km flown per tick late in the turn).
    assert!(worst_terminal < 1.5e3, "terminal: {worst_terminal} m");
}

/// Inside its range, 44 km west of the target with the heading 2 deg left of it and the bank
/// negative (turning left: diverging, but inside the 4 deg corridor, which would keep it), the
/// law reverses when keeping the turn ends far left and reversing now ends within the
/// tolerance (a 300 km turn radius: keep -4.8 km, reverse +0.05 km), waits when reversing now
/// would overshoot to the right (100 km radius: keep -11.2 km, reverse +3.2 km), and never
/// reverses while the measured turn is against the bank sign (a reversal in progress) or once
/// the target is behind.
#[test]
fn terminal_law_reverses_on_the_predicted_crossrange() {
    let n = |t: f64, heading_deg: f64, x_km: f64, y_km: f64| NavState {
        time_s: t,
        radius_m: R + 30e3,
        speed_m_s: 1500.0,
        flight_path_angle_rad: 0.0,
        heading_rad: heading_deg * DEG,
        latitude_rad: y_km * 1e3 / R,
        longitude_rad: x_km * 1e3 / R,
    };
    // The last 3 km flown on a circle of `radius_km`, `left` (counter-clockwise) or not.
    let decide = |radius_km: f64, left: bool| {
        let mut l = BankReversalLogic::new(config(1.0))
            .unwrap()
            .with_terminal(terminal(100.0))
            .unwrap();
        let half = 1.5 / radius_km / DEG;
        let chord = if left { 88.0 + half } else { 88.0 - half };
        let (x0, y0) = (
            -44.0 - 3.0 * (chord * DEG).sin(),
            -3.0 * (chord * DEG).cos(),
        );
        let first = l.update(&n(0.0, 110.0, x0, y0)).unwrap();
        assert_eq!(first.sign, BankSign::Negative);
        let s = l.update(&n(2.0, 88.0, -44.0, 0.0)).unwrap();
        (s.sign, s.reversed)
    };
    assert_eq!(decide(300.0, true), (BankSign::Positive, true));
    assert_eq!(decide(100.0, true), (BankSign::Negative, false));
    assert_eq!(decide(300.0, false), (BankSign::Negative, false));
    // The target passed: 44 km east of it, heading 88 deg (away), bank positive, turning
    // right on a 500 km radius. Ahead of the target the same numbers would ask for a reversal
    // (keep +3.5 km, reverse +0.59 km, within the tolerance); behind it, none.
    let mut l = BankReversalLogic::new(config(1.0))
        .unwrap()
        .with_terminal(terminal(100.0))
        .unwrap();
    let chord = 88.0 - 1.5 / 500.0 / DEG;
    let (x0, y0) = (44.0 - 3.0 * (chord * DEG).sin(), -3.0 * (chord * DEG).cos());
    assert_eq!(
        l.update(&n(0.0, 100.0, x0, y0)).unwrap().sign,
        BankSign::Positive
    );
    let s = l.update(&n(2.0, 88.0, 44.0, 0.0)).unwrap();
    assert!(
        s.heading_error_rad.abs() > 90.0 * DEG && !s.reversed,
        "{s:?}"
    );
    let kappa = 2.0 * (1.5 / 500.0) / (3e3 / R);
    let (keep, rev) = predicted_offsets(44e3 / R, s.heading_error_rad, kappa, 1.0, 6e3 / R);
    assert!(keep * R > 3e3 && (rev * R).abs() < 1e3, "{keep} {rev}");
    // The corridor alone keeps the sign on the same states.
    let mut l = BankReversalLogic::new(config(1.0)).unwrap();
    l.update(&n(0.0, 110.0, -47.0, 0.0)).unwrap();
    assert!(!l.update(&n(2.0, 88.0, -44.0, 0.0)).unwrap().reversed);
}
