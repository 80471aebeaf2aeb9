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
//! Events: after each accepted step every event function is compared at both ends; on a
//! sign change in the requested direction the crossing time is located by the Illinois
//! (modified regula falsi) method, where the state inside the step is obtained by a fresh
//! Fehlberg step of the trial length from the step start (so the located state has the full
//! integrator order, not that of an interpolant). The root is bracketed until the bracket is
//! shorter than [`Tolerances::event_time_tol_s`]; the state returned is the one at the end of
//! the bracket *past* the crossing, so integration resumed from it does not see the same
//! crossing again.

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
    /// Width of the final bracket of an event crossing \[s\].
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
    let mut k = [[0.0; N]; 6];
    for s in 0..6 {
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

/// Adaptive Runge-Kutta-Fehlberg 4(5) integrator with per-component absolute tolerances.
#[derive(Clone, Debug)]
pub struct Rkf45<const N: usize> {
    tol: Tolerances,
    atol: [f64; N],
    /// Suggested next step (kept across breakpoints).
    h: f64,
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
            let (y1, err) = fehlberg_step(p, *t, y, h, &mut self.stats);
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
            // Accepted.
            self.stats.accepted += 1;
            let t1 = if landing { t_end } else { *t + h };
            // A shortened landing step says nothing about the controller's step: keep the
            // larger of the two suggestions.
            let h_next = (h * factor).min(self.tol.h_max);
            self.h = if landing { h_next.max(h_ctrl) } else { h_next };
            if m > 0 {
                p.events(t1, &y1, &mut g1[..m]);
                if let Some(hit) = self.locate(p, *t, y, h, &g0[..m], &g1[..m])? {
                    let (yh, _) = fehlberg_step(p, *t, y, hit.time - *t, &mut self.stats);
                    *y = yh;
                    *t = hit.time;
                    p.on_step(*t, y);
                    return Ok(Some(hit));
                }
                g0 = g1;
            }
            *y = y1;
            *t = t1;
            p.on_step(*t, y);
        }
        Ok(None)
    }

    /// Locate the earliest triggered crossing in the step `(t0, y0) + h`.
    fn locate<P: OdeProblem<N> + ?Sized>(
        &mut self,
        p: &mut P,
        t0: f64,
        y0: &[f64; N],
        h: f64,
        g0: &[f64],
        g1: &[f64],
    ) -> Result<Option<EventHit>, IntegrateError> {
        let mut best: Option<EventHit> = None;
        let mut buf = [0.0; MAX_EVENTS];
        let m = g0.len();
        for i in 0..m {
            let (a, b) = (g0[i], g1[i]);
            let triggered = match p.event_direction(i) {
                Direction::Rising => a < 0.0 && b >= 0.0,
                Direction::Falling => a > 0.0 && b <= 0.0,
                Direction::Either => (a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0),
            };
            if !triggered {
                continue;
            }
            // Illinois on theta in [0, h]; bracket [lo, hi] with g(lo) on the old side.
            let (mut lo, mut hi) = (0.0_f64, h);
            let (mut glo, mut ghi) = (a, b);
            let mut side = 0i8;
            let mut iter = 0;
            while hi - lo > self.tol.event_time_tol_s && iter < 200 {
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
                let (yt, _) = fehlberg_step(p, t0, y0, th, &mut self.stats);
                if !all_finite(&yt) {
                    return Err(IntegrateError::NonFinite { t: t0 });
                }
                p.events(t0 + th, &yt, &mut buf[..m]);
                let gt = buf[i];
                let past = if a < 0.0 { gt >= 0.0 } else { gt <= 0.0 };
                if past {
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
            let hit = EventHit {
                index: i,
                time: t0 + hi,
                bracket: hi - lo,
            };
            if best.is_none_or(|b| hit.time < b.time) {
                best = Some(hit);
            }
        }
        Ok(best)
    }
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
