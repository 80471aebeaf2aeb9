//! Lateral guidance (bank reversals) with hostile configurations and navigation states, in
//! `f64` and `f32`, driving a guidance with two-sided bank bounds. Checks: no panic; a bad
//! configuration or state is a typed error; every status is finite (heading error in
//! `[-pi, pi]`, corridor width positive, reversals within the maximum); the guidance command
//! with the imposed sign is finite, in its bounds and has the imposed sign.

use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{BankSign, Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::lateral::{
    BankReversalLogic, Corridor, CorridorAxis, LateralConfig, TerminalLateral,
};
use guidance_core::nav::NavState;
use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
use guidance_core::replan::TargetPoint;
use guidance_core::scalar::Real;
use rand::{Rng, RngExt};

use crate::hostile::value;

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    let cfg: [f64; 9] = [
        value(rng, -1.6, 1.6, 0.05),
        value(rng, -3.2, 3.2, 0.05),
        value(rng, 3000.0, 8000.0, 0.05),
        value(rng, 0.0, 0.5, 0.05),
        value(rng, 0.0, 3000.0, 0.05),
        value(rng, 0.0, 0.5, 0.05),
        value(rng, 0.0, 0.1, 0.05),
        value(rng, 0.0, 0.05, 0.05),
        value(rng, 0.0, 1.0, 0.0),
    ];
    let max_rev = rng.random_range(0..12u8);
    // Half the cases with the terminal law (hostile settings: a rejected one is flown
    // without it).
    let terminal = rng.random_bool(0.5).then(|| {
        [
            value(rng, 0.0, 3.2, 0.05),
            value(rng, 0.0, 0.01, 0.05),
            value(rng, 0.0, 20.0, 0.05),
        ]
    });
    let mut navs = Vec::new();
    let mut t = 0.0;
    for _ in 0..60 {
        t += 2.0;
        let mut n = [
            t,
            EARTH_RADIUS_M + value(rng, 20e3, 120e3, 0.0),
            value(rng, 300.0, 7800.0, 0.0),
            value(rng, -0.1, 0.05, 0.0),
            value(rng, -7.0, 7.0, 0.0),
            value(rng, -1.6, 1.6, 0.0),
            value(rng, -3.2, 3.2, 0.0),
        ];
        if rng.random_bool(0.1) {
            let i = rng.random_range(1..7);
            n[i] = value(rng, -1e7, 1e7, 0.5);
        }
        navs.push(n);
    }
    fly::<f64>(&cfg, max_rev, terminal, &navs)?;
    fly::<f32>(&cfg, max_rev, terminal, &navs)
}

fn fly<S: Real>(
    cfg: &[f64; 9],
    max_rev: u8,
    terminal: Option<[f64; 3]>,
    navs: &[[f64; 7]],
) -> Result<(), String> {
    let c = |v: f64| S::from_f64(v);
    let energy = EnergyNormalizer::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122e3,
        7435.5,
    )
    .map_err(|e| format!("normaliser: {e:?}"))?;
    let axis = if cfg[8] < 0.5 {
        CorridorAxis::Speed
    } else {
        CorridorAxis::NormalizedEnergy(energy)
    };
    let config = LateralConfig {
        target: TargetPoint {
            latitude_rad: c(cfg[0]),
            longitude_rad: c(cfg[1]),
        },
        corridor: Corridor {
            axis,
            x_high: c(cfg[2]),
            width_high_rad: c(cfg[3]),
            x_low: c(cfg[4]),
            width_low_rad: c(cfg[5]),
        },
        hysteresis_rad: c(cfg[6]),
        max_reversals: max_rev,
        freeze_angle_rad: c(cfg[7]),
    };
    let Ok(mut logic) = BankReversalLogic::new(config) else {
        return Ok(()); // rejected with a typed error: fine
    };
    if let Some([start, tol, lead]) = terminal {
        let t = TerminalLateral {
            start_angle_rad: c(start),
            tolerance_rad: c(tol),
            reversal_lead_s: c(lead),
        };
        if let Ok(l) = logic.with_terminal(t) {
            logic = l;
        }
    }
    let bounds = AngleBounds::from_deg(0.0, 45.0, -90.0, 90.0).map_err(|e| format!("{e:?}"))?;
    let table = NodeTable::from_deg(
        Independent::TimeS,
        &[(0.0, 30.0, 60.0), (200.0, 20.0, 45.0)],
        bounds,
    )
    .map_err(|e| format!("{e:?}"))?;
    let mut g = Guidance::<S>::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::Linear,
        energy,
        Command {
            alpha_rad: S::ZERO,
            sigma_rad: S::ZERO,
        },
    )
    .map_err(|e| format!("guidance: {e:?}"))?;
    for n in navs {
        let nav = NavState {
            time_s: c(n[0]),
            radius_m: c(n[1]),
            speed_m_s: c(n[2]),
            flight_path_angle_rad: c(n[3]),
            heading_rad: c(n[4]),
            latitude_rad: c(n[5]),
            longitude_rad: c(n[6]),
        };
        let Ok(s) = logic.update(&nav) else {
            continue;
        };
        let e = s.heading_error_rad;
        if !(e.is_finite() && e.abs() <= S::PI + S::EPSILON * c(8.0)) {
            return Err(format!("heading error {e:?} at {n:?}"));
        }
        if !(s.corridor_rad.is_finite() && s.corridor_rad > S::ZERO) {
            return Err(format!(
                "corridor {:?} at {n:?}, config {cfg:?}",
                s.corridor_rad
            ));
        }
        if !s.range_angle_rad.is_finite() || s.reversals > max_rev {
            return Err(format!("status {s:?} at {n:?}"));
        }
        g.set_bank_sign(Some(s.sign));
        if g.update(&nav).is_ok() {
            let t = g.target();
            let ok_sign = match s.sign {
                BankSign::Positive => t.sigma_rad >= S::ZERO,
                BankSign::Negative => t.sigma_rad <= S::ZERO,
            };
            let cmd = g.command();
            if !(cmd.is_finite() && bounds_ok(&g, cmd) && ok_sign) {
                return Err(format!("command {cmd:?} target {t:?} sign {:?}", s.sign));
            }
        }
    }
    Ok(())
}

fn bounds_ok<S: Real>(g: &Guidance<S>, c: Command<S>) -> bool {
    let b = g.table().bounds();
    b.alpha_ok(c.alpha_rad) && b.sigma_ok(c.sigma_rad)
}
