//! [`TerminalLateral`]: the last reversals from the predicted crossrange at the interface
//! instead of the heading-error corridor (opt-in, [`super::BankReversalLogic::with_terminal`]).
//!
//! Near the target a vehicle that flies a large bank (the corrector losing range in the
//! terminal dive) turns fast, and its heading error swings through the corridor in a few
//! seconds: with the corridor and a freeze distance `f` the last reversal comes at or before
//! `f`, and the constant-sign turn after it displaces the end point sideways by about
//! `kappa f^2 / 2` (`kappa` the path's curvature). The terminal law instead predicts the
//! crossrange at the end for both signs and reverses when the other sign would end within the
//! tolerance of the target: at most one reversal per turn, timed so the last turn ends on the
//! target.
//!
//! # Prediction (small angles, flat over the remaining arc)
//! With `s` the great-circle angle to the target \[rad\], `dpsi` the heading error \[rad\],
//! `kappa` the measured turn of the heading per angle flown \[rad/rad\] (from the previous call:
//! twice the angle between the heading and the chord from the previous position, over the
//! chord) and `c = +1` for a positive bank, `-1` for a negative one, the lateral offset at the
//! end (positive: right of the target, in angle \[rad\]) is
//!
//! * keeping the sign: `y_keep = s sin(dpsi) + c |kappa| s^2 / 2`;
//! * reversing now: `y_rev = s sin(dpsi) + c |kappa| (d s - d^2 / 2) - c |kappa| (s - d)^2 / 2`,
//!   where `d = min(lead V cos(gamma) / r, s)` is the angle flown during the first half of the
//!   reversal (`lead` = [`TerminalLateral::reversal_lead_s`]), over which the old turn goes on.
//!
//! Keeping the sign leaves `y_keep` unchanged while `y_rev = y_keep - c |kappa| (s - d)^2`
//! moves towards it as `s` shrinks, so one reversal at the right moment ends on the target.
//! The logic is called once per guidance tick, a step `h` apart (the angle flown since the
//! previous call), so the moment is the tick whose `y_rev` is nearest zero: a reversal when
//! `c y_keep > tol` (keeping the sign ends more than the tolerance off on the side of the
//! turn) and either `c y_rev >= -tol` (reversing now does not end more than `tol` off on the
//! other side) or `|y_rev| <= |y_rev(s - h)|` (waiting a tick would end farther off), the
//! target is ahead (`|dpsi| <= pi/2`: once passed, a reversal only lofts the vehicle), the
//! measured turn has the sign of the bank (`c kappa > 0`: the last
//! reversal is over), at least `2 lead` seconds after the last reversal, and the usual limits
//! hold (fewer than `max_reversals`, farther than `freeze_angle_rad`).
//!
//! # Cost
//! Inside the terminal range one more central angle and bearing per call (about 15 trig
//! functions); no loops, no allocation, no panics.

use crate::error::GuidanceError;
use crate::scalar::Real;

/// Settings of the terminal crossrange law (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TerminalLateral<S> {
    /// The law replaces the corridor once the great-circle angle to the target is below this
    /// \[rad\], `> 0`.
    pub start_angle_rad: S,
    /// Accepted predicted crossrange at the end \[rad\] (great-circle angle), `> 0`.
    pub tolerance_rad: S,
    /// Time from the start of a reversal to the middle of its bank ramp \[s\], `>= 0` (half
    /// the reversal's duration: 85 deg to -85 deg at 15 deg/s, about 5.7 s).
    pub reversal_lead_s: S,
}

impl<S: Real> TerminalLateral<S> {
    /// Check the settings: finite, `start_angle_rad` in `(0, pi]`, `tolerance_rad > 0`,
    /// `reversal_lead_s >= 0`.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] otherwise.
    pub fn validate(&self) -> Result<(), GuidanceError> {
        let ok = self.start_angle_rad.is_finite()
            && self.start_angle_rad > S::ZERO
            && self.start_angle_rad <= S::PI
            && self.tolerance_rad.is_finite()
            && self.tolerance_rad > S::ZERO
            && self.reversal_lead_s.is_finite()
            && self.reversal_lead_s >= S::ZERO;
        if ok {
            Ok(())
        } else {
            Err(GuidanceError::InvalidConfig)
        }
    }
}

/// Whether to reverse now (module docs): `s`, `dpsi`, `kappa`, `c` and `d` as in
/// [`predicted_offsets`], `h` the angle flown per call \[rad\], `tol` the tolerance \[rad\].
#[must_use]
pub fn reverse_now<S: Real>(s: S, dpsi: S, kappa: S, c: S, d: S, h: S, tol: S) -> bool {
    let (keep, rev) = predicted_offsets(s, dpsi, kappa, c, d);
    let (_, rev_next) = predicted_offsets(s - h, dpsi, kappa, c, d);
    // `predicted_offsets` at `s - h` with the same `dpsi` has another `y_keep`: shift it back.
    let (keep_next, _) = predicted_offsets(s - h, dpsi, kappa, c, d);
    let rev_next = rev_next + (keep - keep_next);
    c * keep > tol && (c * rev >= -tol || rev.abs() <= rev_next.abs())
}

/// The predicted lateral offsets at the end `(y_keep, y_rev)` \[rad\] (module docs), for
/// range angle `s` \[rad\], heading error `dpsi` \[rad\], measured turn `kappa` \[rad/rad\],
/// current sign `c` (`+1` or `-1`) and lead angle `d` \[rad\] (clamped into `[0, s]`).
#[must_use]
pub fn predicted_offsets<S: Real>(s: S, dpsi: S, kappa: S, c: S, d: S) -> (S, S) {
    let two = S::ONE + S::ONE;
    let d = d.max(S::ZERO).min(s);
    let k = c * kappa.abs();
    let y0 = s * dpsi.sin();
    let rest = s - d;
    let keep = y0 + k * s * s / two;
    let rev = y0 + k * (d * s - d * d / two) - k * rest * rest / two;
    (keep, rev)
}
