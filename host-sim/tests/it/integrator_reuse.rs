//! The integrator's work savings (issue 11 item 9): short landing steps with the
//! Bogacki-Shampine 3(2) pair, derivatives reused only under an unchanged right-hand side,
//! and events located on the dense output. Each test checks the accuracy against a closed
//! form and the work against the count the saving implies.

use host_sim::integrate::{Direction, OdeProblem, Rkf45, Tolerances};

/// Angular frequency of [`Oscillator`] \[rad/s\]: slow enough that the 1 s breakpoints, not
/// the tolerance, limit the steps (as in the closed loop).
const W: f64 = 0.01;

/// y'' = -W^2 y with a right-hand side that never changes (generation 0).
struct Oscillator;

impl OdeProblem<2> for Oscillator {
    fn rhs(&mut self, _t: f64, y: &[f64; 2]) -> [f64; 2] {
        [y[1], -W * W * y[0]]
    }
    fn rhs_generation(&self) -> Option<u64> {
        Some(0)
    }
}

/// Breakpoints as the closed loop makes them: every second, and a few milliseconds after
/// each (a guidance tick and the end of the attitude ramp it starts).
#[test]
fn short_landing_steps_keep_the_tolerance_at_fewer_evaluations() {
    let tol = Tolerances {
        rtol: 1e-10,
        h_init: 0.5,
        ..Tolerances::default()
    };
    let mut integ = Rkf45::new(tol, [1e-12, 1e-12]);
    let (mut t, mut y) = (0.0, [1.0, 0.0]);
    let n = 40;
    for k in 0..n {
        let tk = f64::from(k);
        integ
            .advance_to(&mut Oscillator, &mut t, &mut y, tk + 0.004)
            .unwrap();
        integ
            .advance_to(&mut Oscillator, &mut t, &mut y, tk + 1.0)
            .unwrap();
    }
    let err = ((y[0] - (W * t).cos()).powi(2) + (y[1] + W * (W * t).sin()).powi(2)).sqrt();
    // 80 steps at rtol 1e-10 on a unit state: a global error of a few 1e-10 (measured
    // below 1e-10); the bound is 1e-9.
    assert!(err < 1e-9, "error {err:e}");
    // The 0.004-long steps are far below `SHORT_STEP_FRACTION` of the controller's step once it
    // has grown, so each second costs the short step's first stage and its three further
    // stages (the last the derivative at its end) and the five further stages of the
    // Fehlberg step that starts there: 9, against 12 with two Fehlberg steps.
    let per_second = integ.stats.rhs_evals as f64 / f64::from(n);
    assert!(
        per_second < 9.5,
        "{per_second} RHS per second ({:?})",
        integ.stats
    );
}

/// y' = c, with c changed between calls: the derivative kept from the end of a short step
/// must not be reused once the generation changes.
struct Slope {
    c: f64,
    generation: u64,
}

impl OdeProblem<1> for Slope {
    fn rhs(&mut self, _t: f64, _y: &[f64; 1]) -> [f64; 1] {
        [self.c]
    }
    fn rhs_generation(&self) -> Option<u64> {
        Some(self.generation)
    }
}

#[test]
fn kept_derivative_is_dropped_when_the_rhs_changes() {
    let tol = Tolerances {
        h_init: 5.0,
        ..Tolerances::default()
    };
    let mut integ = Rkf45::new(tol, [1e-9]);
    let mut p = Slope {
        c: 1.0,
        generation: 0,
    };
    let (mut t, mut y) = (0.0, [0.0]);
    integ.advance_to(&mut p, &mut t, &mut y, 10.0).unwrap();
    // A short landing step (Bogacki-Shampine), ending with the derivative kept at t = 10.01.
    integ.advance_to(&mut p, &mut t, &mut y, 10.01).unwrap();
    assert!((y[0] - 10.01).abs() < 1e-12, "{}", y[0]);
    p.c = 2.0;
    p.generation = 1;
    integ.advance_to(&mut p, &mut t, &mut y, 12.0).unwrap();
    // With the stale derivative (c = 1) as first stage the Fehlberg step would end at
    // 10.01 + 1.99 * (2 - 16/135) = 13.75...
    assert!((y[0] - (10.01 + 2.0 * 1.99)).abs() < 1e-12, "{}", y[0]);
}

/// Free fall from 100 m (y = [height, vertical speed]), the ground as a falling event.
struct Drop;

const G: f64 = 9.80665;

impl OdeProblem<2> for Drop {
    fn rhs(&mut self, _t: f64, y: &[f64; 2]) -> [f64; 2] {
        [y[1], -G]
    }
    fn event_count(&self) -> usize {
        1
    }
    fn events(&mut self, _t: f64, y: &[f64; 2], out: &mut [f64]) {
        out[0] = y[0];
    }
    fn event_direction(&self, _i: usize) -> Direction {
        Direction::Falling
    }
}

#[test]
fn events_are_located_on_the_dense_output() {
    let tol = Tolerances {
        h_init: 1.0,
        event_time_tol_s: 1e-9,
        ..Tolerances::default()
    };
    let mut integ = Rkf45::new(tol, [1e-9, 1e-9]);
    let (mut t, mut y) = (0.0, [100.0, 0.0]);
    let hit = integ
        .advance_to(&mut Drop, &mut t, &mut y, 100.0)
        .unwrap()
        .unwrap();
    let exact = (2.0 * 100.0 / G).sqrt();
    // The motion is a parabola, which the cubic interpolant holds exactly: the crossing is
    // bracketed to the tolerance around the exact time, and the fresh state is past it.
    assert!(hit.bracket <= 1e-9);
    assert!((hit.time - exact).abs() <= 2e-9, "{} vs {exact}", hit.time);
    assert!(y[0] <= 0.0 && y[0] > -1e-6, "{}", y[0]);
    // Work: per step start one first stage (kept for a retry after a rejection) and five
    // more per attempt; for the crossing, one end derivative and the five further stages of
    // the two fresh steps checking the bracket's ends; no evaluation per search iteration.
    let s = integ.stats;
    assert_eq!(s.rhs_evals, 6 * s.accepted + 5 * s.rejected + 11, "{s:?}");
}
