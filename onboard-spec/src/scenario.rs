//! The smoke scenario flown by the firmware and, identically, on the host (by `cargo xtask
//! golden` to produce the golden commands, and by the workspace tests to check them).
//!
//! Two guidance sequences, each `SAMPLES` navigation samples 1 s apart (so the 2 s clock ticks
//! on every other sample and holds in between):
//! 1. the HORUS-2B reference mission (`guidance_core::missions::horus2b_reference`: thesis
//!    eq. 2.3, time-indexed, linear interpolation),
//!    sampled across the bank-angle step between 264 s and 290 s;
//! 2. an energy-indexed table with a cardinal Hermite spline on a synthetic fast deceleration,
//!    so that the bank-rate limit binds.
//!
//! One sample in each sequence is non-finite: guidance must reject it and keep its command.

use guidance_core::energy::EARTH_RADIUS_M;
use guidance_core::guidance::Guidance;
use guidance_core::interp::Interpolation;
use guidance_core::missions::{HORUS2B_ENTRY, horus2b_reference};
use guidance_core::nodes::{Independent, Node, NodeTable};
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
        flight_path_angle_rad: S::from_f64(HORUS2B_ENTRY.flight_path_angle_rad),
        heading_rad: S::from_f64(HORUS2B_ENTRY.heading_rad),
        latitude_rad: S::from_f64(HORUS2B_ENTRY.latitude_rad),
        longitude_rad: S::from_f64(HORUS2B_ENTRY.longitude_rad),
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
            HORUS2B_ENTRY.altitude_m - 150.0 * k,
            HORUS2B_ENTRY.speed_m_s - speed_step_m_s * k,
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
    // Sequence 1: the HORUS-2B reference mission as the firmware flies it (thesis eq. 2.3).
    let mission = horus2b_reference::<S>()?;
    let energy = mission.earth_energy_normalizer()?;
    let [first, second] = out;
    sequence(mission.guidance(energy)?, 250.0, 2.0, first)?;

    // Sequence 2: energy-indexed, cardinal Hermite, fast synthetic deceleration; the mission's
    // period, rates, bounds, initial attitude and entry (E-hat = 1).
    let energy_nodes = [
        node::<S>(1.0, 40.0, 0.0),
        node(0.9, 38.0, 75.0),
        node(0.7, 30.0, 20.0),
        node(0.5, 20.0, 60.0),
        node(0.1, 11.5, 54.0),
    ];
    let bounds = mission.table.bounds();
    let table = NodeTable::new(Independent::NormalizedEnergy, &energy_nodes, bounds)?;
    let kind = Interpolation::CardinalHermite {
        tension: S::from_f64(0.5),
    };
    sequence(
        Guidance::new(mission.config, table, kind, energy, mission.initial)?,
        0.0,
        90.0,
        second,
    )?;
    Ok(())
}
