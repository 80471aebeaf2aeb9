//! Lateral guidance: bank reversals that keep the vehicle heading to a target point.
//!
//! The longitudinal channel (stored profile, or the predictor-corrector of [`crate::replan`])
//! sets the bank-angle *magnitude*; the lateral channel sets its *sign* (Apollo, Shuttle,
//! FNPEG, MSL). A constant-sign bank turns the heading steadily away from the target; the
//! [`BankReversalLogic`] reverses the sign whenever the heading error to the target leaves a
//! corridor that narrows as the vehicle slows down, so the path zig-zags about the great
//! circle to the target and arrives with a small crossrange.
//!
//! # Heading error and reversal rule
//! `dpsi = wrap(heading - bearing to target)` \[rad\], in `[-pi, pi]`, positive when the
//! velocity points to the right of the target. A positive bank turns the heading clockwise
//! (increases `dpsi`), a negative bank decreases it. At each call:
//!
//! 1. first call: the sign that reduces the error (`dpsi > 0` -> negative, else positive);
//! 2. the current sign is *diverging* when it increases `|dpsi|` (positive with `dpsi > 0`,
//!    negative with `dpsi < 0`). A reversal happens when the sign is diverging,
//!    `|dpsi| > w(x)` (the corridor half-width at the corridor variable `x`, [`Corridor`]), the
//!    logic is *armed*, fewer than [`LateralConfig::max_reversals`] reversals were made and the
//!    target is farther than [`LateralConfig::freeze_angle_rad`];
//! 3. hysteresis: a reversal disarms the logic; it re-arms only once `|dpsi|` has come back
//!    below `w(x) - hysteresis_rad`. So an error that hovers about the corridor edge, or jumps
//!    across the target bearing (a navigation glitch), cannot make the bank chatter; a corridor
//!    narrower than the hysteresis ends the reversals.
//!
//! # Terminal law (opt-in)
//! With [`BankReversalLogic::with_terminal`] the reversals inside a set range of the target
//! come from the predicted crossrange at the end instead of the corridor ([`TerminalLateral`]:
//! the turn measured between calls, a reversal at the tick whose reversed path ends nearest
//! the target). Without it the corridor decides to the freeze distance, as before.
//!
//! # Rate limits
//! The sign is applied to the interpolated bank target by [`Guidance::set_bank_sign`] /
//! [`ReplanningGuidance::set_bank_sign`] *before* the rate limiter: a reversal from `+s` to
//! `-s` is flown as a ramp at the bank-rate limit (60 deg at 15 deg/s: 8 s, 4 ticks), never as
//! a step. The table's angle bounds must allow negative bank (e.g. -90..90 deg); with the
//! thesis bounds (0..90 deg) the reversed target is clamped to 0.
//!
//! # Use
//! At every guidance tick, before the guidance update:
//! `let s = logic.update(&nav)?; guidance.set_bank_sign(Some(s.sign)); guidance.update(&nav)`.
//! With [`Guidance`] the magnitude is the stored profile's (sign logic only); with
//! [`ReplanningGuidance`] aimed at a [`crate::replan::RangeTarget::Point`] (the same target
//! point) the corrector sets the magnitude from the great-circle range to go.
//!
//! # Cost
//! One central angle and one bearing (about 15 trig functions) and a few comparisons per
//! call; no loops, no allocation, no panics. Generic over [`Real`](crate::scalar::Real) (`f32`, `f64`).
//!
//! [`Guidance::set_bank_sign`]: crate::guidance::Guidance::set_bank_sign
//! [`Guidance`]: crate::guidance::Guidance
//! [`ReplanningGuidance::set_bank_sign`]: crate::replan::ReplanningGuidance::set_bank_sign
//! [`ReplanningGuidance`]: crate::replan::ReplanningGuidance

mod corridor;
mod logic;
mod terminal;

pub use corridor::{
    Corridor, CorridorAxis, DEFAULT_LOW_SPEED_FRACTION, DEFAULT_WIDTH_ENTRY_DEG,
    DEFAULT_WIDTH_FINAL_DEG,
};
pub use logic::{
    BankReversalLogic, DEFAULT_FREEZE_DISTANCE_M, DEFAULT_HYSTERESIS_DEG, DEFAULT_MAX_REVERSALS,
    LateralConfig, LateralStatus,
};
pub use terminal::{TerminalLateral, predicted_offsets, reverse_now};
