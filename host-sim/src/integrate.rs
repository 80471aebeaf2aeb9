//! Numerical integrators: Runge-Kutta-Fehlberg 4(5) with error control (thesis sec. 5.3,
//! table 5.1) and the classical fixed-step RK4.
//!
//! The state is a fixed-size array `[f64; N]`. Problems implement [`OdeProblem`]: a
//! right-hand side, optional event functions (zero crossings located to a time tolerance) and
//! an observer called after every accepted step. [`Rkf45::advance_to`] integrates up to a
//! breakpoint and lands on it exactly (the last step is shortened), which is how the
//! closed loop lands on every guidance tick.
//!
//! Step-size control: the local error estimate is the difference between the fifth- and
//! fourth-order solutions (eq. 5.18); the fifth-order solution is propagated (local
//! extrapolation, as eq. 5.15 writes `x_{n+1}`). The weighted error norm is
//! `max_i |err_i| / (atol_i + rtol * max(|y0_i|, |y1_i|))`; a step is accepted when it is
//! <= 1 and the next step is `h * clamp(0.9 * err^(-1/5), 0.2, 5)`. The exponent 1/5 is that
//! of the O(h^5) local error of the embedded fourth-order solution; the thesis' eq. 5.19 uses
//! 1/4, which is only more conservative.
//!
//! Short landing steps: a step that lands on a breakpoint and is much shorter than the
//! controller's step (at most [`SHORT_STEP_FRACTION`] of it; in the closed loop, the few
//! milliseconds from a guidance tick to the end of the attitude ramp it starts) is first tried
//! with the Bogacki-Shampine 3(2) pair (four stages, the last one the derivative at the step
//! end, which the next step reuses as its first stage): it is accepted under the same error
//! test (the third-order solution propagated, the error of the embedded second-order one
//! estimated, so the test is conservative), and on failure the Fehlberg step of the same
//! length is taken. Such a step leaves the controller's step as it was.
//!
//! Derivative reuse: the first stage `f(t, y)` of a step is kept and reused by a retry after
//! a rejection and by every trial step of an event search from the same point; across
//! [`Rkf45::advance_to`] calls only while the problem's [`OdeProblem::rhs_generation`] says
//! its right-hand side has not changed.
//!
//! Events: after each accepted step every event function is compared at both ends; on a
//! sign change in the requested direction the crossing time is located by the Illinois
//! (modified regula falsi) method on the step's dense output, the cubic Hermite interpolant
//! of the two end states and derivatives (one right-hand-side evaluation for the end
//! derivative, none per iteration), until the bracket is at most
//! [`Tolerances::event_time_tol_s`] wide and short enough that no state component changes
//! across it by more than its integration tolerance (`atol_i + rtol * |y_i|`): the state at
//! an event is then as accurate as the integration and follows `rtol`. Both ends of that
//! bracket are checked with fresh Fehlberg steps from the step start (so the states have the
//! full integrator order, not that of the interpolant): the upper end must be past the
//! crossing, the lower end not. The state at the upper end is returned, so integration
//! resumed from it does not see the same crossing again. Should a check fail (the
//! interpolant's error exceeding the bracket: long steps, fast-changing forces, tight
//! tolerances), fresh trial points step away from the failed end, the first offset twice the
//! time its event value takes at the step's mean event rate, each next one four times longer,
//! until one is on the other side; the Illinois method then narrows that bracket with a fresh
//! Fehlberg step per trial.

use std::fmt;

/// Fehlberg's coefficients (thesis table 5.1; Fehlberg 1969).
mod fehlberg {
    pub const A: [f64; 6] = [0.0, 1.0 / 4.0, 3.0 / 8.0, 12.0 / 13.0, 1.0, 1.0 / 2.0];
    pub const B: [[f64; 5]; 6] = [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0 / 4.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 32.0, 9.0 / 32.0, 0.0, 0.0, 0.0],
        [1932.0 / 2197.0, -7200.0 / 2197.0, 7296.0 / 2197.0, 0.0, 0.0],
        [439.0 / 216.0, -8.0, 3680.0 / 513.0, -845.0 / 4104.0, 0.0],
        [
            -8.0 / 27.0,
            2.0,
            -3544.0 / 2565.0,
            1859.0 / 4104.0,
            -11.0 / 40.0,
        ],
    ];
    /// Fifth-order weights c_i.
    pub const C5: [f64; 6] = [
        16.0 / 135.0,
        0.0,
        6656.0 / 12825.0,
        28561.0 / 56430.0,
        -9.0 / 50.0,
        2.0 / 55.0,
    ];
    /// Fourth-order weights c_i^*.
    pub const C4: [f64; 6] = [
        25.0 / 216.0,
        0.0,
        1408.0 / 2565.0,
        2197.0 / 4104.0,
        -1.0 / 5.0,
        0.0,
    ];
}

/// Bogacki-Shampine 3(2) coefficients (Bogacki & Shampine 1989), for short landing steps.
mod bogacki_shampine {
    pub const A: [f64; 4] = [0.0, 1.0 / 2.0, 3.0 / 4.0, 1.0];
    /// Third-order weights (the fourth stage is the derivative at the new state).
    pub const B3: [f64; 3] = [2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0];
    /// Third- minus second-order weights (second order: 7/24, 1/4, 1/3, 1/8).
    pub const E: [f64; 4] = [-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0];
}

/// A landing step at most this fraction of the controller's step is first tried with the
/// Bogacki-Shampine 3(2) pair (module documentation).
pub const SHORT_STEP_FRACTION: f64 = 0.02;

/// Direction of a zero crossing an event reacts to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// From negative to non-negative.
    Rising,
    /// From positive to non-positive.
    Falling,
    /// Either way.
    Either,
}

/// Largest number of event functions a problem may declare.
pub const MAX_EVENTS: usize = 8;

/// An initial-value problem `dy/dt = f(t, y)` with optional events and a step observer.
pub trait OdeProblem<const N: usize> {
    /// Right-hand side `f(t, y)`.
    fn rhs(&mut self, t: f64, y: &[f64; N]) -> [f64; N];
    /// Number of event functions (at most [`MAX_EVENTS`]).
    fn event_count(&self) -> usize {
        0
    }
    /// Event function values at `(t, y)` written into `out[..event_count()]`.
    fn events(&mut self, _t: f64, _y: &[f64; N], _out: &mut [f64]) {}
    /// Crossing direction that triggers event `index`.
    fn event_direction(&self, _index: usize) -> Direction {
        Direction::Either
    }
    /// Called after every accepted step with the new time and state.
    fn on_step(&mut self, _t: f64, _y: &[f64; N]) {}
    /// A count the problem changes whenever its right-hand side changes between
    /// [`Rkf45::advance_to`] calls (the closed loop: at every guidance tick), so a derivative
    /// computed in one call may be reused in the next at the same time and state. `None`
    /// (the default): no reuse across calls.
    fn rhs_generation(&self) -> Option<u64> {
        None
    }
}

/// Step-size control and event settings of [`Rkf45`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance [-].
    pub rtol: f64,
    /// Initial step \[s\] (or unit of the independent variable).
    pub h_init: f64,
    /// Smallest step allowed; needing a smaller one is an error (the landing step on a
    /// breakpoint may be shorter).
    pub h_min: f64,
    /// Largest step allowed.
    pub h_max: f64,
    /// Maximum number of step attempts over the life of the integrator.
    pub max_steps: u64,
    /// Largest width of the final bracket of an event crossing \[s\]; the bracket is also
    /// narrowed until the state changes across it by less than the integration tolerance.
    pub event_time_tol_s: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            rtol: 1e-9,
            h_init: 1e-2,
            h_min: 1e-9,
            h_max: 100.0,
            max_steps: 5_000_000,
            event_time_tol_s: 1e-6,
        }
    }
}

impl Tolerances {
    /// Check that every setting is finite and consistent.
    ///
    /// # Errors
    /// A message naming the offending setting and its value.
    pub fn validate(&self) -> Result<(), ToleranceError> {
        let pos = [
            ("rtol", self.rtol),
            ("h_init", self.h_init),
            ("h_min", self.h_min),
            ("h_max", self.h_max),
            ("event_time_tol_s", self.event_time_tol_s),
        ];
        for (field, value) in pos {
            if !(value.is_finite() && value > 0.0) {
                return Err(ToleranceError {
                    field,
                    value,
                    reason: "must be finite and > 0",
                });
            }
        }
        if self.h_min > self.h_max {
            return Err(ToleranceError {
                field: "h_min",
                value: self.h_min,
                reason: "must be <= h_max",
            });
        }
        if self.max_steps == 0 {
            return Err(ToleranceError {
                field: "max_steps",
                value: 0.0,
                reason: "must be > 0",
            });
        }
        Ok(())
    }
}

/// An integrator setting out of range.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("invalid integrator setting `{field}` = {}: {reason}", crate::num_fmt::Compact(*value))]
pub struct ToleranceError {
    /// Setting name.
    pub field: &'static str,
    /// Its value.
    pub value: f64,
    /// What is required.
    pub reason: &'static str,
}

/// Work counters of an integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
}

/// Integration failures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IntegrateError {
    /// The error control asked for a step below `h_min`.
    StepTooSmall {
        /// Time \[s\] where it happened.
        t: f64,
        /// The step that was asked for.
        h: f64,
    },
    /// More than `max_steps` step attempts.
    MaxSteps {
        /// Time \[s\] reached.
        t: f64,
    },
    /// The right-hand side or the state became NaN or infinite.
    NonFinite {
        /// Time \[s\] of the step start.
        t: f64,
    },
    /// The problem declared more than [`MAX_EVENTS`] events.
    TooManyEvents,
    /// The target time is not finite or lies before the current time.
    BadTarget {
        /// Current time.
        t: f64,
        /// Requested target.
        target: f64,
    },
}

impl fmt::Display for IntegrateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StepTooSmall { t, h } => {
                write!(f, "step size {h:e} below h_min at t = {t} s")
            }
            Self::MaxSteps { t } => write!(f, "maximum number of steps exceeded at t = {t} s"),
            Self::NonFinite { t } => write!(f, "state became non-finite near t = {t} s"),
            Self::TooManyEvents => write!(f, "more than {MAX_EVENTS} event functions"),
            Self::BadTarget { t, target } => {
                write!(f, "integration target {target} s is invalid from t = {t} s")
            }
        }
    }
}

impl std::error::Error for IntegrateError {}

/// An event crossing located inside a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventHit {
    /// Index of the event function.
    pub index: usize,
    /// Upper end of the final bracket (just past the crossing) \[s\].
    pub time: f64,
    /// Width of the final bracket \[s\].
    pub bracket: f64,
}

fn all_finite<const N: usize>(y: &[f64; N]) -> bool {
    y.iter().all(|v| v.is_finite())
}

/// One Fehlberg step of length `h` from `(t, y)`: returns the fifth-order solution and the
/// error estimate (fifth minus fourth order). Six RHS evaluations, counted in `stats`.
pub fn fehlberg_step<const N: usize, P: OdeProblem<N> + ?Sized>(
    p: &mut P,
    t: f64,
    y: &[f64; N],
    h: f64,
    stats: &mut Stats,
) -> ([f64; N], [f64; N]) {
    let k1 = p.rhs(t, y);
    stats.rhs_evals += 1;
    fehlberg_step_from(p, t, y, h, &k1, stats)
}

/// [`fehlberg_step`] with its first stage `k1 = f(t, y)` given (five RHS evaluations).
fn fehlberg_step_from<const N: usize, P: OdeProblem<N> + ?Sized>(
    p: &mut P,
    t: f64,
    y: &[f64; N],
    h: f64,
    k1: &[f64; N],
    stats: &mut Stats,
) -> ([f64; N], [f64; N]) {
    let mut k = [[0.0; N]; 6];
    k[0] = *k1;
    for s in 1..6 {
        let mut ys = *y;
        for (j, kj) in k.iter().enumerate().take(s) {
            let b = fehlberg::B[s][j];
            if b != 0.0 {
                for i in 0..N {
                    ys[i] += h * b * kj[i];
                }
            }
        }
        k[s] = p.rhs(t + fehlberg::A[s] * h, &ys);
        stats.rhs_evals += 1;
    }
    let mut y5 = *y;
    let mut err = [0.0; N];
    for (s, ks) in k.iter().enumerate() {
        let c5 = fehlberg::C5[s];
        let dc = c5 - fehlberg::C4[s];
        for i in 0..N {
            y5[i] += h * c5 * ks[i];
            err[i] += h * dc * ks[i];
        }
    }
    (y5, err)
}

/// One Bogacki-Shampine 3(2) step of length `h` from `(t, y)` with first stage `k1`: the
/// third-order solution, the error estimate and the derivative at the new state (three RHS
/// evaluations).
fn bs3_step<const N: usize, P: OdeProblem<N> + ?Sized>(
    p: &mut P,
    t: f64,
    y: &[f64; N],
    h: f64,
    k1: &[f64; N],
    stats: &mut Stats,
) -> ([f64; N], [f64; N], [f64; N]) {
    use bogacki_shampine::{A, B3, E};
    let mut ys = *y;
    for i in 0..N {
        ys[i] += h * A[1] * k1[i];
    }
    let k2 = p.rhs(t + A[1] * h, &ys);
    let mut ys = *y;
    for i in 0..N {
        ys[i] += h * A[2] * k2[i];
    }
    let k3 = p.rhs(t + A[2] * h, &ys);
    let mut y3 = *y;
    for i in 0..N {
        y3[i] += h * (B3[0] * k1[i] + B3[1] * k2[i] + B3[2] * k3[i]);
    }
    let k4 = p.rhs(t + h, &y3);
    stats.rhs_evals += 3;
    let mut err = [0.0; N];
    for i in 0..N {
        err[i] = h * (E[0] * k1[i] + E[1] * k2[i] + E[2] * k3[i] + E[3] * k4[i]);
    }
    (y3, err, k4)
}

/// The cubic Hermite interpolant of a step `(y0, f0) -> (y1, f1)` of length `h` at fraction
/// `th` of it.
fn hermite<const N: usize>(
    y0: &[f64; N],
    f0: &[f64; N],
    y1: &[f64; N],
    f1: &[f64; N],
    h: f64,
    th: f64,
) -> [f64; N] {
    let (t2, t3) = (th * th, th * th * th);
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + th;
    let h01 = 3.0 * t2 - 2.0 * t3;
    let h11 = t3 - t2;
    let mut out = [0.0; N];
    for i in 0..N {
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i];
    }
    out
}

/// A derivative `f(t, y)` kept for reuse (see the module documentation).
#[derive(Clone, Copy, Debug)]
struct KeptDerivative<const N: usize> {
    generation: Option<u64>,
    t: f64,
    y: [f64; N],
    f: [f64; N],
}

fn same_point<const N: usize>(t0: f64, y0: &[f64; N], t1: f64, y1: &[f64; N]) -> bool {
    t0.to_bits() == t1.to_bits() && y0.iter().zip(y1).all(|(a, b)| a.to_bits() == b.to_bits())
}

/// Adaptive Runge-Kutta-Fehlberg 4(5) integrator with per-component absolute tolerances.
#[derive(Clone, Debug)]
pub struct Rkf45<const N: usize> {
    tol: Tolerances,
    atol: [f64; N],
    /// Suggested next step (kept across breakpoints).
    h: f64,
    /// The last derivative computed at a step start or end, for reuse.
    kept: Option<KeptDerivative<N>>,
    /// Work counters.
    pub stats: Stats,
}

impl<const N: usize> Rkf45<N> {
    /// New integrator with tolerances `tol` and absolute tolerance `atol[i]` per component.
    #[must_use]
    pub fn new(tol: Tolerances, atol: [f64; N]) -> Self {
        Self {
            tol,
            atol,
            h: tol.h_init,
            kept: None,
            stats: Stats::default(),
        }
    }

    /// The tolerances in use.
    #[must_use]
    pub fn tolerances(&self) -> &Tolerances {
        &self.tol
    }

    fn error_norm(&self, y0: &[f64; N], y1: &[f64; N], err: &[f64; N]) -> f64 {
        let mut e: f64 = 0.0;
        for i in 0..N {
            let sc = self.atol[i] + self.tol.rtol * y0[i].abs().max(y1[i].abs());
            e = e.max(err[i].abs() / sc);
        }
        e
    }

    /// `f(t, y)`: the kept derivative if it is at this point, else a fresh evaluation
    /// (counted), which is then kept.
    fn derivative_at<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        t: f64,
        y: &[f64; N],
    ) -> [f64; N] {
        if let Some(k) = &self.kept
            && same_point(k.t, &k.y, t, y)
        {
            return k.f;
        }
        let f = p.rhs(t, y);
        self.stats.rhs_evals += 1;
        self.keep(p, t, y, f);
        f
    }

    fn keep<P: OdeProblem<N> + ?Sized>(&mut self, p: &P, t: f64, y: &[f64; N], f: [f64; N]) {
        self.kept = Some(KeptDerivative {
            generation: p.rhs_generation(),
            t,
            y: *y,
            f,
        });
    }

    /// Integrate from `(*t, *y)` towards `t_end`, landing on it exactly.
    ///
    /// Returns `Ok(None)` when `t_end` is reached (then `*t == t_end`) or `Ok(Some(hit))`
    /// when an event crossing was located first (then `*t == hit.time` and `*y` is the
    /// state there, just past the crossing). `on_step` is called for every accepted step,
    /// including the partial step up to an event.
    ///
    /// # Errors
    /// [`IntegrateError`] on step-size underflow, step-count overflow, non-finite state or a
    /// bad target.
    pub fn advance_to<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        t: &mut f64,
        y: &mut [f64; N],
        t_end: f64,
    ) -> Result<Option<EventHit>, IntegrateError> {
        if !(t_end.is_finite() && t_end >= *t) {
            return Err(IntegrateError::BadTarget {
                t: *t,
                target: t_end,
            });
        }
        let m = p.event_count();
        if m > MAX_EVENTS {
            return Err(IntegrateError::TooManyEvents);
        }
        // A derivative from an earlier call is reused only under the same right-hand side.
        let generation = p.rhs_generation();
        if self
            .kept
            .is_some_and(|k| generation.is_none() || k.generation != generation)
        {
            self.kept = None;
        }
        let mut g0 = [0.0; MAX_EVENTS];
        let mut g1 = [0.0; MAX_EVENTS];
        if m > 0 {
            p.events(*t, y, &mut g0[..m]);
        }
        while *t < t_end {
            if self.stats.accepted + self.stats.rejected >= self.tol.max_steps {
                return Err(IntegrateError::MaxSteps { t: *t });
            }
            let remaining = t_end - *t;
            let h_ctrl = self.h.clamp(self.tol.h_min, self.tol.h_max);
            // Land when the remainder is within 10 % of the suggested step, rather than
            // leave a sliver step behind (the 0.9 safety factor covers the stretch).
            let landing = remaining <= 1.1 * h_ctrl;
            let h = if landing { remaining } else { h_ctrl };
            let k1 = self.derivative_at(p, *t, y);
            // A short landing step: the Bogacki-Shampine pair first (module documentation).
            let mut short = None;
            if landing && h <= SHORT_STEP_FRACTION * h_ctrl {
                let (y3, err, k4) = bs3_step(p, *t, y, h, &k1, &mut self.stats);
                let e = self.error_norm(y, &y3, &err);
                if e <= 1.0 && all_finite(&y3) {
                    short = Some((y3, k4));
                }
            }
            let (y1, f1, factor) = if let Some((y3, k4)) = short {
                (y3, Some(k4), None)
            } else {
                let (y1, err) = fehlberg_step_from(p, *t, y, h, &k1, &mut self.stats);
                let e = self.error_norm(y, &y1, &err);
                if !e.is_finite() || !all_finite(&y1) {
                    // Treat as a failed step: shrink hard, error out below h_min.
                    self.stats.rejected += 1;
                    let h_new = h * 0.1;
                    if h_new < self.tol.h_min {
                        return Err(IntegrateError::NonFinite { t: *t });
                    }
                    self.h = h_new;
                    continue;
                }
                let factor = if e == 0.0 {
                    5.0
                } else {
                    (0.9 * e.powf(-0.2)).clamp(0.2, 5.0)
                };
                if e > 1.0 {
                    self.stats.rejected += 1;
                    let h_new = h * factor;
                    if h_new < self.tol.h_min {
                        return Err(IntegrateError::StepTooSmall { t: *t, h: h_new });
                    }
                    self.h = h_new;
                    continue;
                }
                (y1, None, Some(factor))
            };
            // Accepted.
            self.stats.accepted += 1;
            let t1 = if landing { t_end } else { *t + h };
            if let Some(factor) = factor {
                // A shortened landing step says nothing about the controller's step: keep
                // the larger of the two suggestions.
                let h_next = (h * factor).min(self.tol.h_max);
                self.h = if landing { h_next.max(h_ctrl) } else { h_next };
            }
            if m > 0 {
                p.events(t1, &y1, &mut g1[..m]);
                if any_triggered(p, &g0[..m], &g1[..m]) {
                    let f1 = match f1 {
                        Some(f) => f,
                        None => self.derivative_at(p, t1, &y1),
                    };
                    let step = Step {
                        t0: *t,
                        y0: *y,
                        f0: k1,
                        h,
                        y1,
                        f1,
                    };
                    if let Some((hit, yh)) = self.locate(p, &step, &g0[..m], &g1[..m])? {
                        *y = yh;
                        *t = hit.time;
                        p.on_step(*t, y);
                        return Ok(Some(hit));
                    }
                }
                g0 = g1;
            }
            if let Some(k4) = f1 {
                self.keep(p, t1, &y1, k4);
            }
            *y = y1;
            *t = t1;
            p.on_step(*t, y);
        }
        Ok(None)
    }

    /// Locate the earliest triggered crossing in an accepted step: on its dense output
    /// first, then (if the fresh state there is not past the crossing) with fresh steps.
    /// Returns the hit and the state at its time.
    fn locate<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        step: &Step<N>,
        g0: &[f64],
        g1: &[f64],
    ) -> Result<Option<(EventHit, [f64; N])>, IntegrateError> {
        let dense = |_p: &mut P, _s: &mut Stats, th: f64| -> Option<[f64; N]> {
            Some(hermite(
                &step.y0,
                &step.f0,
                &step.y1,
                &step.f1,
                step.h,
                th / step.h,
            ))
        };
        let tol = self.event_bracket_tol(step);
        let Some(hit) = self.bracket(p, step, g0, g1, tol, dense)? else {
            return Ok(None);
        };
        // Check the bracket with fresh steps at both ends: the upper one past the crossing,
        // the lower one not (the step start is known not to be).
        let (i, a) = (hit.index, g0[hit.index]);
        let th_hi = hit.time - step.t0;
        let th_lo = th_hi - hit.bracket;
        let (yh, g_hi) = self.fresh_event(p, step, th_hi, i, g0.len())?;
        // The event's mean rate over the step, to turn an event value into a time offset.
        let rate = (g1[i] - a) / step.h;
        let fresh_bracket = if !past(a, g_hi) {
            // The crossing is later than the interpolant says.
            self.widen(p, step, i, a, (th_hi, g_hi), (step.h, g1[i]), rate, tol)?
        } else if th_lo <= 0.0 {
            return Ok(Some((hit, yh)));
        } else {
            let (_, g_lo) = self.fresh_event(p, step, th_lo, i, g0.len())?;
            if !past(a, g_lo) {
                return Ok(Some((hit, yh)));
            }
            // Earlier than the interpolant says.
            self.widen(p, step, i, a, (th_lo, g_lo), (0.0, a), rate, tol)?
        };
        // The interpolant was not close enough: the search goes on from the bracket the
        // checks left, with a fresh step for every trial.
        let f0 = step.f0;
        let mut fresh = |p: &mut P, s: &mut Stats, th: f64| -> Option<[f64; N]> {
            let (yt, _) = fehlberg_step_from(p, step.t0, &step.y0, th, &f0, s);
            all_finite(&yt).then_some(yt)
        };
        let (lo, hi) = fresh_bracket;
        let hit = self.illinois(p, step, i, a, lo, hi, tol, &mut fresh)?;
        let (yh, _) = self.fresh_event(p, step, hit.time - step.t0, i, g0.len())?;
        Ok(Some((hit, yh)))
    }

    /// A fresh bracket of event `i`'s crossing next to `from`, a checked end of the
    /// interpolant's bracket that is on the wrong side: trial points step away from it
    /// towards `limit` (the step's end on the other side of the crossing), the first offset
    /// twice the time `from`'s event value takes at the step's mean `rate`, each next one
    /// four times longer. Returns `(lo, hi)` (offsets with event values), `lo` before the
    /// crossing and `hi` past it, as short as the trials found.
    #[allow(clippy::too_many_arguments)]
    fn widen<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        step: &Step<N>,
        i: usize,
        a: f64,
        from: (f64, f64),
        limit: (f64, f64),
        rate: f64,
        tol: f64,
    ) -> Result<(Probe, Probe), IntegrateError> {
        let m = p.event_count().min(MAX_EVENTS);
        let later = limit.0 > from.0;
        let order =
            |near: (f64, f64), far: (f64, f64)| if later { (near, far) } else { (far, near) };
        let mut d = if rate != 0.0 && rate.is_finite() {
            (2.0 * from.1 / rate).abs().max(tol)
        } else {
            tol
        };
        let mut near = from;
        loop {
            let th = if later { near.0 + d } else { near.0 - d };
            if !(th > 0.0 && th < step.h) || (later && th >= limit.0) || (!later && th <= limit.0) {
                return Ok(order(near, limit));
            }
            let (_, g) = self.fresh_event(p, step, th, i, m)?;
            // Later: `near` is before the crossing; earlier: past it.
            if past(a, g) == later {
                return Ok(order(near, (th, g)));
            }
            near = (th, g);
            d *= 4.0;
        }
    }

    /// The width to which an event crossing in `step` is bracketed \[s\]: at most
    /// [`Tolerances::event_time_tol_s`], and short enough that no state component changes
    /// across it by more than its integration tolerance `atol_i + rtol * |y_i|` (the rate
    /// bounded by the larger of the step's end derivatives). The state returned at the
    /// bracket's upper end is then within the integration tolerance of the state at the
    /// crossing, so the final state's error follows `rtol`. Floored at a few rounding units
    /// of the time, below which the bracket cannot shrink.
    fn event_bracket_tol(&self, step: &Step<N>) -> f64 {
        let mut tol = self.tol.event_time_tol_s;
        for i in 0..N {
            let scale = self.atol[i] + self.tol.rtol * step.y0[i].abs().max(step.y1[i].abs());
            let rate = step.f0[i].abs().max(step.f1[i].abs());
            if rate * tol > scale {
                tol = scale / rate;
            }
        }
        tol.max(8.0 * f64::EPSILON * (step.t0.abs() + step.h))
    }

    /// The state a fresh Fehlberg step reaches at fraction `th` of the step and event `i`
    /// there (`m` events).
    fn fresh_event<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        step: &Step<N>,
        th: f64,
        i: usize,
        m: usize,
    ) -> Result<([f64; N], f64), IntegrateError> {
        let (y, _) = fehlberg_step_from(p, step.t0, &step.y0, th, &step.f0, &mut self.stats);
        if !all_finite(&y) {
            return Err(IntegrateError::NonFinite { t: step.t0 });
        }
        let mut buf = [0.0; MAX_EVENTS];
        p.events(step.t0 + th, &y, &mut buf[..m]);
        Ok((y, buf[i]))
    }

    /// Bracket the earliest triggered crossing of the step with the Illinois method, the
    /// state at a trial fraction `th` of the step coming from `state_at` (`None`: not
    /// finite).
    fn bracket<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        step: &Step<N>,
        g0: &[f64],
        g1: &[f64],
        tol: f64,
        mut state_at: impl FnMut(&mut P, &mut Stats, f64) -> Option<[f64; N]>,
    ) -> Result<Option<EventHit>, IntegrateError> {
        let mut best: Option<EventHit> = None;
        for i in 0..g0.len() {
            let (a, b) = (g0[i], g1[i]);
            if !triggered(p.event_direction(i), a, b) {
                continue;
            }
            let hit = self.illinois(p, step, i, a, (0.0, a), (step.h, b), tol, &mut state_at)?;
            if best.is_none_or(|b| hit.time < b.time) {
                best = Some(hit);
            }
        }
        Ok(best)
    }

    /// The Illinois method on event `i` (value `a` at the step start) from the bracket
    /// `[lo, hi]` (offsets into the step with their event values, `lo` on the old side)
    /// until it is at most `tol` wide.
    #[allow(clippy::too_many_arguments)]
    fn illinois<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        step: &Step<N>,
        i: usize,
        a: f64,
        (mut lo, mut glo): (f64, f64),
        (mut hi, mut ghi): (f64, f64),
        tol: f64,
        state_at: &mut impl FnMut(&mut P, &mut Stats, f64) -> Option<[f64; N]>,
    ) -> Result<EventHit, IntegrateError> {
        let m = p.event_count().min(MAX_EVENTS);
        let mut buf = [0.0; MAX_EVENTS];
        let mut side = 0i8;
        let mut iter = 0;
        while hi - lo > tol && iter < 200 {
            iter += 1;
            let mut th = if ghi != glo {
                hi - ghi * (hi - lo) / (ghi - glo)
            } else {
                0.5 * (lo + hi)
            };
            // Keep the trial strictly inside, away from the ends.
            let w = hi - lo;
            if !(th > lo + 1e-3 * w && th < hi - 1e-3 * w) {
                th = 0.5 * (lo + hi);
            }
            let Some(yt) = state_at(p, &mut self.stats, th) else {
                return Err(IntegrateError::NonFinite { t: step.t0 });
            };
            p.events(step.t0 + th, &yt, &mut buf[..m]);
            let gt = buf[i];
            if past(a, gt) {
                hi = th;
                ghi = gt;
                if side == 1 {
                    glo *= 0.5;
                }
                side = 1;
            } else {
                lo = th;
                glo = gt;
                if side == -1 {
                    ghi *= 0.5;
                }
                side = -1;
            }
        }
        Ok(EventHit {
            index: i,
            time: step.t0 + hi,
            bracket: hi - lo,
        })
    }
}

/// A trial point of an event search: its offset into the step \[s\] and the event value there.
type Probe = (f64, f64);

/// An accepted step: start, first stage, length, end and the derivative there.
struct Step<const N: usize> {
    t0: f64,
    y0: [f64; N],
    f0: [f64; N],
    h: f64,
    y1: [f64; N],
    f1: [f64; N],
}

/// Whether an event value `a` at a step start and `b` at its end cross in `dir`.
fn triggered(dir: Direction, a: f64, b: f64) -> bool {
    match dir {
        Direction::Rising => a < 0.0 && b >= 0.0,
        Direction::Falling => a > 0.0 && b <= 0.0,
        Direction::Either => (a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0),
    }
}

/// Whether `gt` lies past the crossing of an event that started at `a`.
fn past(a: f64, gt: f64) -> bool {
    if a < 0.0 { gt >= 0.0 } else { gt <= 0.0 }
}

fn any_triggered<const N: usize, P: OdeProblem<N> + ?Sized>(p: &P, g0: &[f64], g1: &[f64]) -> bool {
    g0.iter()
        .zip(g1)
        .enumerate()
        .any(|(i, (a, b))| triggered(p.event_direction(i), *a, *b))
}

/// One classical fourth-order Runge-Kutta step (four RHS evaluations, counted in `stats`).
pub fn rk4_step<const N: usize, P: OdeProblem<N> + ?Sized>(
    p: &mut P,
    t: f64,
    y: &[f64; N],
    h: f64,
    stats: &mut Stats,
) -> [f64; N] {
    let k1 = p.rhs(t, y);
    let mut tmp = *y;
    for i in 0..N {
        tmp[i] = y[i] + 0.5 * h * k1[i];
    }
    let k2 = p.rhs(t + 0.5 * h, &tmp);
    for i in 0..N {
        tmp[i] = y[i] + 0.5 * h * k2[i];
    }
    let k3 = p.rhs(t + 0.5 * h, &tmp);
    for i in 0..N {
        tmp[i] = y[i] + h * k3[i];
    }
    let k4 = p.rhs(t + h, &tmp);
    stats.rhs_evals += 4;
    let mut out = *y;
    for i in 0..N {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}

/// Integrate with fixed-step RK4 from `t0` to `t1` in `steps` equal steps (no events; the
/// observer is called after each step).
///
/// # Errors
/// [`IntegrateError::BadTarget`] for zero steps or a non-finite interval,
/// [`IntegrateError::NonFinite`] if the state stops being finite.
pub fn rk4_integrate<const N: usize, P: OdeProblem<N> + ?Sized>(
    p: &mut P,
    t0: f64,
    y0: [f64; N],
    t1: f64,
    steps: u64,
    stats: &mut Stats,
) -> Result<[f64; N], IntegrateError> {
    if steps == 0 || !(t0.is_finite() && t1.is_finite()) {
        return Err(IntegrateError::BadTarget { t: t0, target: t1 });
    }
    let h = (t1 - t0) / steps as f64;
    let mut y = y0;
    for k in 0..steps {
        let t = t0 + h * k as f64;
        y = rk4_step(p, t, &y, h, stats);
        if !all_finite(&y) {
            return Err(IntegrateError::NonFinite { t });
        }
        stats.accepted += 1;
        let tn = if k + 1 == steps {
            t1
        } else {
            t0 + h * (k + 1) as f64
        };
        p.on_step(tn, &y);
    }
    Ok(y)
}

/// An [`OdeProblem`] from a closure (no events).
pub struct FnProblem<F>(pub F);

impl<const N: usize, F: FnMut(f64, &[f64; N]) -> [f64; N]> OdeProblem<N> for FnProblem<F> {
    fn rhs(&mut self, t: f64, y: &[f64; N]) -> [f64; N] {
        (self.0)(t, y)
    }
}
