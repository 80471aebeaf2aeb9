//! The smoke scenario flown by the firmware and, identically, on the host (by `cargo xtask
//! golden` to produce the golden commands, and by the workspace tests to check them).
//!
//! Two guidance sequences, each `SAMPLES` navigation samples 1 s apart (so the 2 s clock ticks
//! on every other sample and holds in between):
//! 1. the HORUS-2B reference mission of thesis eq. 2.3 (time-indexed, linear interpolation),
//!    sampled across the bank-angle step between 264 s and 290 s;
//! 2. an energy-indexed table with a cardinal Hermite spline on a synthetic fast deceleration,
//!    so that the bank-rate limit binds.
//!
//! One sample in each sequence is non-finite: guidance must reject it and keep its command.

use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{Command, Guidance, GuidanceConfig};
use guidance_core::interp::Interpolation;
use guidance_core::nodes::{AngleBounds, Independent, Node, NodeTable};
use guidance_core::{GuidanceError, NavState, Scalar};

/// Navigation samples per sequence.
pub const SAMPLES: usize = 48;
/// Number of sequences.
pub const SEQUENCES: usize = 2;
/// Index of the non-finite sample in each sequence.
pub const BAD_SAMPLE: usize = 17;

/// One output row: attitude at the sample time (ramp) and held command [rad].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row<S> {
    /// Attitude angle of attack [rad].
    pub alpha_rad: S,
    /// Attitude bank angle [rad].
    pub sigma_rad: S,
    /// Held commanded angle of attack [rad].
    pub cmd_alpha_rad: S,
    /// Held commanded bank angle [rad].
    pub cmd_sigma_rad: S,
}

const DEG: f64 = core::f64::consts::PI / 180.0;
const ENTRY_ALTITUDE_M: f64 = 122_000.0;
const ENTRY_SPEED_M_S: f64 = 7435.5;

fn node<S: Scalar>(x: f64, alpha_deg: f64, sigma_deg: f64) -> Node<S> {
    Node {
        x: S::from_f64(x),
        alpha_rad: S::from_f64(alpha_deg * DEG),
        sigma_rad: S::from_f64(sigma_deg * DEG),
    }
}

fn nav<S: Scalar>(t: f64, altitude_m: f64, speed_m_s: f64) -> NavState<S> {
    NavState {
        time_s: S::from_f64(t),
        radius_m: S::from_f64(EARTH_RADIUS_M + altitude_m),
        speed_m_s: S::from_f64(speed_m_s),
        flight_path_angle_rad: S::from_f64(-1.43 * DEG),
        heading_rad: S::from_f64(70.75 * DEG),
        latitude_rad: S::from_f64(-22.3 * DEG),
        longitude_rad: S::from_f64(-106.7 * DEG),
    }
}

fn sequence<S: Scalar>(
    mut guidance: Guidance<S>,
    t0: f64,
    speed_step_m_s: f64,
    out: &mut [Row<S>; SAMPLES],
) -> Result<(), GuidanceError> {
    for (i, row) in out.iter_mut().enumerate() {
        let k = i as f64;
        let t = t0 + k;
        let mut state = nav::<S>(
            t,
            ENTRY_ALTITUDE_M - 150.0 * k,
            ENTRY_SPEED_M_S - speed_step_m_s * k,
        );
        if i == BAD_SAMPLE {
            // A corrupted sample: radius 0/0 is NaN in floating point and 0 in fixed point
            // (which has no NaN); either way guidance must reject it and hold its command.
            state.radius_m = S::ZERO / S::from_f64(0.0);
            if guidance.update(&state).is_ok() {
                return Err(GuidanceError::InvalidConfig);
            }
        } else {
            guidance.update(&state)?;
        }
        let a = guidance.attitude_at(S::from_f64(t));
        let c = guidance.command();
        *row = Row {
            alpha_rad: a.alpha_rad,
            sigma_rad: a.sigma_rad,
            cmd_alpha_rad: c.alpha_rad,
            cmd_sigma_rad: c.sigma_rad,
        };
    }
    Ok(())
}

/// Run both sequences in scalar type `S`, filling `out`.
///
/// # Errors
/// Any guidance error (none is expected: the test fails if one occurs), or
/// `InvalidConfig` if the corrupted sample was accepted.
pub fn run<S: Scalar>(out: &mut [[Row<S>; SAMPLES]; SEQUENCES]) -> Result<(), GuidanceError> {
    let bounds = AngleBounds::thesis_default();
    let energy = EnergyNormalizer::<S>::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + ENTRY_ALTITUDE_M,
        ENTRY_SPEED_M_S,
    )?;
    let config = GuidanceConfig::thesis_default();
    let initial = Command {
        alpha_rad: S::from_f64(40.0 * DEG),
        sigma_rad: S::ZERO,
    };

    // Sequence 1: HORUS-2B reference mission, thesis eq. 2.3.
    let reference = [
        node::<S>(0.0, 40.0, 0.0),
        node(264.0, 40.0, 0.0),
        node(290.0, 40.0, 79.6),
        node(554.0, 40.0, 59.8),
        node(686.0, 40.0, 59.8),
        node(924.0, 40.0, 59.8),
        node(1319.0, 11.5, 54.0),
    ];
    let table = NodeTable::new(Independent::TimeS, &reference, bounds)?;
    let [first, second] = out;
    sequence(
        Guidance::new(config, table, Interpolation::Linear, energy, initial)?,
        250.0,
        2.0,
        first,
    )?;

    // Sequence 2: energy-indexed, cardinal Hermite, fast synthetic deceleration.
    let energy_nodes = [
        node::<S>(1.0, 40.0, 0.0),
        node(0.9, 38.0, 75.0),
        node(0.7, 30.0, 20.0),
        node(0.5, 20.0, 60.0),
        node(0.1, 11.5, 54.0),
    ];
    let table = NodeTable::new(Independent::NormalizedEnergy, &energy_nodes, bounds)?;
    let kind = Interpolation::CardinalHermite {
        tension: S::from_f64(0.5),
    };
    sequence(
        Guidance::new(config, table, kind, energy, initial)?,
        0.0,
        90.0,
        second,
    )?;
    Ok(())
}
