//! The settings of the scenario's onboard layers beyond the stored profile (lateral corridor
//! and terminal law, re-planner, onboard estimation, path-limit bound): [`CampaignGuidance`]
//! with the documented defaults, written in the scenario's `[guidance.lateral]`,
//! `[guidance.replanning]`, `[guidance.estimator]` and `[guidance.barrier]` sections
//! (`resolve_layers`, key names in [`LAYER_KEYS`]) and validated with errors that
//! name the field.

use guidance_core::estimate::{AeroEstimator, EstimatorConfig};
use guidance_core::replan::PredictorMode;
use guidance_core::{estimate, lateral, replan};
use serde::{Deserialize, Serialize};

use crate::campaign::CampaignError;

/// The re-planner's predictor family in the re-planning campaign modes
/// (`[guidance.replanning] predictor`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CampaignPredictor {
    /// The closed forms: `PredictorMode::Auto`, or `AutoSink` with onboard estimation and
    /// `glide_sink` (`"closed-form"`).
    ClosedForm,
    /// Numerical integration of the predictor model from the navigated state:
    /// `PredictorMode::Numerical` in both re-planning modes (`"numerical"`).
    Numerical,
    /// The closed forms when the prediction to be flown is in their validated domain, else the
    /// numerical predictor: `PredictorMode::Hybrid`, or `HybridSink` with onboard estimation and
    /// `glide_sink` (`"hybrid"`, the default; the measured campaigns: docs/reference/campaigns.md,
    /// "Results").
    #[default]
    Hybrid,
}

impl CampaignPredictor {
    /// The re-planner's predictor mode, with (`sink = true`) or without the glide's sink to
    /// its equilibrium in its closed-form part (the numerical predictor has no such term).
    #[must_use]
    pub fn mode(self, sink: bool) -> PredictorMode {
        match (self, sink) {
            (Self::ClosedForm, false) => PredictorMode::Auto,
            (Self::ClosedForm, true) => PredictorMode::AutoSink,
            (Self::Numerical, _) => PredictorMode::Numerical,
            (Self::Hybrid, false) => PredictorMode::Hybrid,
            (Self::Hybrid, true) => PredictorMode::HybridSink,
        }
    }
}

/// The layers' settings (one flat set; the scenario's key for each field: [`LAYER_KEYS`]).
/// Units are those of the field name (deg, km, m/s^2, ticks).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CampaignGuidance {
    /// Corridor half-width at the entry speed \[deg\] (default 15).
    pub corridor_width_entry_deg: f64,
    /// Corridor half-width from `V_f + corridor_low_speed_fraction (V_e - V_f)` down \[deg\]
    /// (default 3).
    pub corridor_width_final_deg: f64,
    /// Where the corridor reaches its final width, as a fraction of the speed span from the
    /// interface speed `V_f` to the entry speed `V_e` \[-\], in `[0, 1)` (default 0.05; how it
    /// was chosen: CHANGELOG.md, issue 12).
    pub corridor_low_speed_fraction: f64,
    /// Corridor hysteresis \[deg\] (default 1).
    pub hysteresis_deg: f64,
    /// Most bank reversals per flight (default 12).
    pub max_reversals: u8,
    /// No reversal closer than this to the target \[km\] (default 30).
    pub freeze_km: f64,
    /// Re-plan on every N-th 2 s guidance tick, `>= 1` (default 5).
    pub replan_every_n_ticks: u16,
    /// Most solver steps of a re-plan per guidance tick, `[0, 255]` (default 0: a re-plan's
    /// whole solve inside its tick; `k >= 1`: the solve spread over ticks, at most `k` solver
    /// steps per tick; `guidance_core::replan::ReplanningConfig::steps_per_tick`).
    #[serde(skip_serializing_if = "is_zero_u8")]
    pub replan_solver_steps_per_tick: u8,
    /// Accepted range miss of a re-plan \[km\] (default 1).
    pub replan_tolerance_km: f64,
    /// Smallest vertical lift fraction `cos(sigma)` the corrector may command \[-\]
    /// (default 0.05).
    pub min_vertical_fraction: f64,
    /// Largest vertical lift fraction \[-\] (default 1).
    pub max_vertical_fraction: f64,
    /// In mode `replan-estimation` the re-planner's glide predicts the sink from the current
    /// radius to the glide's equilibrium (`PredictorMode::AutoSink`; `false`:
    /// `PredictorMode::Auto`, as the other re-planning mode always does) (default true).
    /// With `predictor = "hybrid"` the same choice between `HybridSink` and `Hybrid`.
    pub glide_sink: bool,
    /// The re-planner's predictor in both re-planning modes: `"closed-form"`, `"numerical"` or
    /// `"hybrid"` (default) ([`CampaignPredictor`]).
    pub predictor: CampaignPredictor,
    /// Lift parameter `lambda = C_L / C_L*` of the re-planner's predictor \[-\] (constant over
    /// a prediction), in `(0, 20]`. Default (absent): 1, the polar's maximum L/D (the trim
    /// point of a trim vehicle such as the SRM capsule). The value of a vehicle flying an
    /// angle-of-attack profile: [`crate::campaign::setup::profile_lift_parameter`] (HORUS-2B: 3.58).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub predictor_lift_parameter: Option<f64>,
    /// The predictor flies the lift of the stored angle-of-attack profile (default false):
    /// the constant lift parameter (closed forms) becomes
    /// [`crate::campaign::setup::profile_lift_parameter`] unless `predictor_lift_parameter` is set, and
    /// numerical predictions and the onboard estimator's model follow
    /// [`crate::campaign::setup::profile_lift_schedule`] against speed. No effect on a trim vehicle.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub predictor_lift_profile: bool,
    /// With `predictor_lift_profile`: the schedule carries the lift AND drag of the stored
    /// profile's angle of attack at the Mach number of the nominal flight at each speed
    /// ([`crate::campaign::setup::profile_aero_schedule`]) instead of the lift at the polar's Mach 20
    /// (default false).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub predictor_aero_mach: bool,
    /// No re-plan starts while E-hat is above this \[-\] (default absent: from the entry): the
    /// stored profile flies the entry pull-out. In `(0, 1]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replan_start_normalized_energy: Option<f64>,
    /// The re-planner's heat-flux and g-load limits as multiples of the vehicle's `[heat flux,
    /// g-load]` \[-\] (default `[1, 1]`; the campaign still counts flights over the vehicle's
    /// own limits). Each in `(0, 100]`.
    #[serde(skip_serializing_if = "is_unit_scale")]
    pub replan_limit_scale: [f64; 2],
    /// Bound the re-planned bank magnitude by heat-flux and g-load limits at the state where
    /// it is installed ([`guidance_core::replan::PathBound`], docs/reference/path-limits.md): the bound's limits as multiples of the vehicle's `[heat flux,
    /// g-load]` \[-\], each in `(0, 100]` (below 1: a margin; 100 leaves that limit out).
    /// Default (absent): no bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_bound_limit_scale: Option<[f64; 2]>,
    /// The bound's time to stop a descent \[s\], in `[0, 1000]` (default 0: the plain
    /// quasi-equilibrium-glide bound). Only with `path_bound_limit_scale`.
    #[serde(skip_serializing_if = "is_zero")]
    pub path_bound_descent_time_s: f64,
    /// The bound's barrier law `[omega, zeta]`: natural frequency \[rad/s\] in `(0, 1]` and
    /// damping ratio \[-\] in `[0, 10]` (`guidance_core::replan::PathBound`, module docs:
    /// the distance to each limit may not close faster than a damped second-order response;
    /// applied at every guidance tick; replaces the descent term). Default (absent): the
    /// equilibrium bound. Only with `path_bound_limit_scale`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_bound_barrier: Option<[f64; 2]>,
    /// The re-planner's numerical predictions fly the bound too (default false): the range is
    /// solved for the bounded flight. Only with `path_bound_limit_scale`.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub path_bound_predicted: bool,
    /// The re-planner's numerical predictions model the planet's rotation in their equations
    /// of motion, latitude and heading of the re-plan's start held, on the planet's own `mu`
    /// (`ReplanningGuidance::with_numerical_rotation`; docs/reference/campaigns.md, "The Earth's
    /// rotation in the numerical predictor"); default false: the effective planet of the
    /// closed forms. Not with `predictor = "closed-form"` (no numerical predictions).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub predictor_rotation: bool,
    /// The re-planner's numerical predictions fly the stored profile's bank magnitudes against
    /// E-hat shifted by one offset, and each re-plan installs that offset on the nodes it
    /// replaces (`ReplanningGuidance::with_bank_shape`; docs/reference/guidance-stack.md, "Bank
    /// shape"); default false: a constant bank. Only with `predictor = "numerical"` (the
    /// closed forms fly a constant bank) and a profile of at most 16 nodes.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub bank_shape: bool,
    /// The last reversals from the predicted crossrange at the interface once the target is
    /// closer than this \[km\] (`guidance_core::lateral::TerminalLateral`; CHANGELOG.md,
    /// "The crossrange of HORUS-2B"), in `(freeze_km, 2000]`. Default (absent): the corridor to
    /// the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub terminal_lateral_km: Option<f64>,
    /// The terminal law's accepted predicted crossrange \[km\], `> 0` and at most 100
    /// (default 1). Only with `terminal_lateral_km`.
    #[serde(skip_serializing_if = "is_one")]
    pub terminal_tolerance_km: f64,
    /// The terminal law's time from the start of a reversal to the middle of its bank ramp
    /// \[s\], in `[0, 60]` (default 5). Only with `terminal_lateral_km`.
    #[serde(skip_serializing_if = "is_five")]
    pub terminal_reversal_lead_s: f64,
    /// Fading-memory gain of the onboard L/D-scale estimate per tick \[-\] (default 0.1).
    pub estimator_lift_to_drag_gain: f64,
    /// Fading-memory gain of the onboard drag-scale estimate per tick \[-\] (default 0.2).
    pub estimator_drag_gain: f64,
    /// Bounds of the L/D-scale estimate `[min, max]` \[-\] (default `[0.5, 2]`).
    pub estimator_lift_to_drag_bounds: [f64; 2],
    /// Bounds of the drag-scale estimate `[min, max]` \[-\] (default `[0.3, 3]`).
    pub estimator_drag_bounds: [f64; 2],
    /// Smallest sensed drag acceleration that updates the estimate \[m/s^2\] (default 0.5,
    /// about 0.05 g).
    pub estimator_min_drag_m_s2: f64,
}

/// The scenario key of every field of [`CampaignGuidance`]: `(field, layer section, key)`,
/// the key written as `[guidance.<section>] <key>` (the one list of these names: the parser,
/// the template and the docs' key table are checked against it).
pub const LAYER_KEYS: [(&str, &str, &str); 33] = [
    (
        "corridor_width_entry_deg",
        "lateral",
        "corridor_width_entry_deg",
    ),
    (
        "corridor_width_final_deg",
        "lateral",
        "corridor_width_final_deg",
    ),
    (
        "corridor_low_speed_fraction",
        "lateral",
        "corridor_low_speed_fraction",
    ),
    ("hysteresis_deg", "lateral", "hysteresis_deg"),
    ("max_reversals", "lateral", "max_reversals"),
    ("freeze_km", "lateral", "freeze_km"),
    ("terminal_lateral_km", "lateral", "terminal_start_km"),
    ("terminal_tolerance_km", "lateral", "terminal_tolerance_km"),
    (
        "terminal_reversal_lead_s",
        "lateral",
        "terminal_reversal_lead_s",
    ),
    ("replan_every_n_ticks", "replanning", "every_n_ticks"),
    (
        "replan_solver_steps_per_tick",
        "replanning",
        "solver_steps_per_tick",
    ),
    ("replan_tolerance_km", "replanning", "tolerance_km"),
    (
        "min_vertical_fraction",
        "replanning",
        "min_vertical_fraction",
    ),
    (
        "max_vertical_fraction",
        "replanning",
        "max_vertical_fraction",
    ),
    ("glide_sink", "replanning", "glide_sink"),
    ("predictor", "replanning", "predictor"),
    ("predictor_lift_parameter", "replanning", "lift_parameter"),
    ("predictor_lift_profile", "replanning", "lift_profile"),
    ("predictor_aero_mach", "replanning", "lift_profile_mach"),
    (
        "replan_start_normalized_energy",
        "replanning",
        "start_normalized_energy",
    ),
    ("replan_limit_scale", "replanning", "limit_scale"),
    ("predictor_rotation", "replanning", "numerical_rotation"),
    ("bank_shape", "replanning", "bank_shape"),
    ("path_bound_limit_scale", "barrier", "limit_scale"),
    ("path_bound_descent_time_s", "barrier", "descent_time_s"),
    ("path_bound_barrier", "barrier", "frequency_rad_s"),
    ("path_bound_barrier", "barrier", "damping"),
    ("path_bound_predicted", "barrier", "predicted"),
    (
        "estimator_lift_to_drag_gain",
        "estimator",
        "lift_to_drag_gain",
    ),
    ("estimator_drag_gain", "estimator", "drag_gain"),
    (
        "estimator_lift_to_drag_bounds",
        "estimator",
        "lift_to_drag_bounds",
    ),
    ("estimator_drag_bounds", "estimator", "drag_bounds"),
    ("estimator_min_drag_m_s2", "estimator", "min_drag_m_s2"),
];

/// The keys of `[guidance.target]` (one form: latitude and longitude, downrange and
/// crossrange, or nominal; and the terminal interface: at most one of a speed, an altitude
/// and a normalised energy, [`TerminalInterface`](super::TerminalInterface)).
pub const TARGET_KEYS: [&str; 8] = [
    "latitude_deg",
    "longitude_deg",
    "downrange_km",
    "crossrange_km",
    "nominal",
    "interface_speed_m_s",
    "interface_altitude_m",
    "interface_normalized_energy",
];

/// The scenario key (`guidance.<section>.<key>`) of a [`CampaignGuidance`] field (the field
/// itself if it has none). `path_bound_barrier` is written as two keys, `frequency_rad_s` and
/// `damping`; its errors name the first.
#[must_use]
pub fn scenario_key(field: &str) -> String {
    LAYER_KEYS.iter().find(|(f, _, _)| *f == field).map_or_else(
        || field.to_string(),
        |(_, s, k)| format!("guidance.{s}.{k}"),
    )
}

/// Whether `x` is 0 (the default: not written).
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if signature
fn is_zero_u8(x: &u8) -> bool {
    *x == 0
}

/// Whether `x` is 1 (the default terminal tolerance: not written).
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_one(x: &f64) -> bool {
    *x == 1.0
}

/// Whether `x` is 5 (the default terminal reversal lead: not written).
#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_five(x: &f64) -> bool {
    *x == 5.0
}

/// Whether both limit scales are 1 (the default: not written).
fn is_unit_scale(s: &[f64; 2]) -> bool {
    *s == [1.0, 1.0]
}

impl Default for CampaignGuidance {
    fn default() -> Self {
        Self {
            corridor_width_entry_deg: lateral::DEFAULT_WIDTH_ENTRY_DEG,
            corridor_width_final_deg: lateral::DEFAULT_WIDTH_FINAL_DEG,
            corridor_low_speed_fraction: lateral::DEFAULT_LOW_SPEED_FRACTION,
            hysteresis_deg: lateral::DEFAULT_HYSTERESIS_DEG,
            max_reversals: lateral::DEFAULT_MAX_REVERSALS,
            freeze_km: lateral::DEFAULT_FREEZE_DISTANCE_M / 1e3,
            replan_every_n_ticks: replan::DEFAULT_EVERY_N_TICKS,
            replan_solver_steps_per_tick: 0,
            replan_tolerance_km: replan::DEFAULT_TOLERANCE_M / 1e3,
            min_vertical_fraction: replan::DEFAULT_MIN_VERTICAL_FRACTION,
            max_vertical_fraction: replan::DEFAULT_MAX_VERTICAL_FRACTION,
            glide_sink: true,
            predictor: CampaignPredictor::Hybrid,
            predictor_lift_parameter: None,
            predictor_lift_profile: false,
            predictor_aero_mach: false,
            replan_start_normalized_energy: None,
            replan_limit_scale: [1.0, 1.0],
            path_bound_limit_scale: None,
            path_bound_descent_time_s: 0.0,
            path_bound_barrier: None,
            path_bound_predicted: false,
            predictor_rotation: false,
            bank_shape: false,
            terminal_lateral_km: None,
            terminal_tolerance_km: 1.0,
            terminal_reversal_lead_s: 5.0,
            estimator_lift_to_drag_gain: estimate::DEFAULT_LIFT_TO_DRAG_GAIN,
            estimator_drag_gain: estimate::DEFAULT_DRAG_GAIN,
            estimator_lift_to_drag_bounds: [
                estimate::DEFAULT_LIFT_TO_DRAG_BOUNDS.0,
                estimate::DEFAULT_LIFT_TO_DRAG_BOUNDS.1,
            ],
            estimator_drag_bounds: [
                estimate::DEFAULT_DRAG_BOUNDS.0,
                estimate::DEFAULT_DRAG_BOUNDS.1,
            ],
            estimator_min_drag_m_s2: estimate::DEFAULT_MIN_DRAG_M_S2,
        }
    }
}

impl CampaignGuidance {
    /// Settings read only beside another: one set away from its default where nothing reads
    /// it is refused (a file states only what it flies). The default value is accepted (the
    /// printed template writes every key).
    ///
    /// # Errors
    /// [`CampaignError::Setting`] naming the setting's scenario key and what it needs.
    fn validate_read(&self, file: &str) -> Result<(), CampaignError> {
        let bad = |field: &str, value: String, reason: &str| CampaignError::Setting {
            file: file.to_string(),
            field: scenario_key(field),
            value,
            reason: reason.into(),
        };
        let t = self.path_bound_descent_time_s;
        if self.path_bound_barrier.is_some() && t != 0.0 {
            return Err(bad(
                "path_bound_descent_time_s",
                t.to_string(),
                "is read by nothing beside the barrier law (frequency_rad_s, damping), which \
                 replaces the descent term: remove one",
            ));
        }
        if self.predictor_aero_mach && !self.predictor_lift_profile {
            return Err(bad(
                "predictor_aero_mach",
                "true".into(),
                "is read only with lift_profile = true (the schedule it changes)",
            ));
        }
        if self.terminal_lateral_km.is_none() {
            for (field, v, default) in [
                ("terminal_tolerance_km", self.terminal_tolerance_km, 1.0),
                (
                    "terminal_reversal_lead_s",
                    self.terminal_reversal_lead_s,
                    5.0,
                ),
            ] {
                if v != default {
                    return Err(bad(
                        field,
                        v.to_string(),
                        "is read only by the terminal law: set terminal_start_km too",
                    ));
                }
            }
        }
        if self.predictor == CampaignPredictor::Numerical {
            if !self.glide_sink {
                return Err(bad(
                    "glide_sink",
                    "false".into(),
                    "is read only by the closed forms (predictor = \"closed-form\" or \
                     \"hybrid\"); the numerical predictor has no sink term",
                ));
            }
            if let Some(l) = self.predictor_lift_parameter
                && self.predictor_lift_profile
            {
                return Err(bad(
                    "predictor_lift_parameter",
                    l.to_string(),
                    "is read by nothing with predictor = \"numerical\" and lift_profile = \
                     true (the predictions fly the profile's lift schedule)",
                ));
            }
        }
        Ok(())
    }

    /// The onboard estimator's settings.
    #[must_use]
    pub fn estimator(&self) -> EstimatorConfig<f64> {
        let [a, b] = self.estimator_lift_to_drag_bounds;
        let [c, d] = self.estimator_drag_bounds;
        EstimatorConfig {
            lift_to_drag_gain: self.estimator_lift_to_drag_gain,
            drag_gain: self.estimator_drag_gain,
            lift_to_drag_bounds: (a, b),
            drag_bounds: (c, d),
            min_drag_m_s2: self.estimator_min_drag_m_s2,
        }
    }

    /// Check every field (the core checks the built configurations again).
    ///
    /// # Errors
    /// [`CampaignError::Setting`] naming the scenario key (`guidance.<layer>.<key>`,
    /// [`scenario_key`]) and the value.
    pub fn validate(&self, file: &str) -> Result<(), CampaignError> {
        let bad = |field: &str, value: String, reason: &str| CampaignError::Setting {
            file: file.to_string(),
            field: scenario_key(field),
            value,
            reason: reason.into(),
        };
        let positive = [
            ("corridor_width_entry_deg", self.corridor_width_entry_deg),
            ("corridor_width_final_deg", self.corridor_width_final_deg),
            ("replan_tolerance_km", self.replan_tolerance_km),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, v.to_string(), "must be finite and > 0"));
            }
        }
        let non_negative = [
            ("hysteresis_deg", self.hysteresis_deg),
            ("freeze_km", self.freeze_km),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(name, v.to_string(), "must be finite and >= 0"));
            }
        }
        let f = self.corridor_low_speed_fraction;
        if !(f.is_finite() && (0.0..1.0).contains(&f)) {
            return Err(bad(
                "corridor_low_speed_fraction",
                f.to_string(),
                "must be in [0, 1)",
            ));
        }
        if self.replan_every_n_ticks == 0 {
            return Err(bad("replan_every_n_ticks", "0".into(), "must be >= 1"));
        }
        let (lo, hi) = (self.min_vertical_fraction, self.max_vertical_fraction);
        if !(lo.is_finite() && lo > 0.0 && lo <= 1.0) {
            return Err(bad(
                "min_vertical_fraction",
                lo.to_string(),
                "must be in (0, 1]",
            ));
        }
        if !(hi.is_finite() && hi >= lo && hi <= 1.0) {
            return Err(bad(
                "max_vertical_fraction",
                hi.to_string(),
                "must be in [min_vertical_fraction, 1]",
            ));
        }
        for (name, g) in [
            (
                "estimator_lift_to_drag_gain",
                self.estimator_lift_to_drag_gain,
            ),
            ("estimator_drag_gain", self.estimator_drag_gain),
        ] {
            if !(g.is_finite() && g > 0.0 && g <= 1.0) {
                return Err(bad(name, g.to_string(), "must be in (0, 1]"));
            }
        }
        for (name, [l, h]) in [
            (
                "estimator_lift_to_drag_bounds",
                self.estimator_lift_to_drag_bounds,
            ),
            ("estimator_drag_bounds", self.estimator_drag_bounds),
        ] {
            if !(l.is_finite() && h.is_finite() && l > 0.0 && l <= 1.0 && h >= 1.0) {
                return Err(bad(
                    name,
                    format!("[{l}, {h}]"),
                    "must be [min, max] with 0 < min <= 1 <= max, finite",
                ));
            }
        }
        if let Some(l) = self.predictor_lift_parameter
            && !(l.is_finite() && l > 0.0 && l <= 20.0)
        {
            return Err(bad(
                "predictor_lift_parameter",
                l.to_string(),
                "must be in (0, 20]",
            ));
        }
        if self.predictor_rotation && self.predictor == CampaignPredictor::ClosedForm {
            return Err(bad(
                "predictor_rotation",
                "true".into(),
                "needs numerical predictions (predictor = \"numerical\" or \"hybrid\")",
            ));
        }
        if self.bank_shape && self.predictor != CampaignPredictor::Numerical {
            return Err(bad(
                "bank_shape",
                "true".into(),
                "needs predictor = \"numerical\" (the closed forms fly a constant bank)",
            ));
        }
        let [q, g] = self.replan_limit_scale;
        if !(q.is_finite() && g.is_finite() && q > 0.0 && g > 0.0 && q <= 100.0 && g <= 100.0) {
            return Err(bad(
                "replan_limit_scale",
                format!("[{q}, {g}]"),
                "must be [heat flux, g-load] scales in (0, 100]",
            ));
        }
        if let Some([q, g]) = self.path_bound_limit_scale
            && !(q.is_finite() && g.is_finite() && q > 0.0 && g > 0.0 && q <= 100.0 && g <= 100.0)
        {
            return Err(bad(
                "path_bound_limit_scale",
                format!("[{q}, {g}]"),
                "must be [heat flux, g-load] scales in (0, 100]",
            ));
        }
        let t = self.path_bound_descent_time_s;
        if !(t.is_finite() && (0.0..=1000.0).contains(&t)) {
            return Err(bad(
                "path_bound_descent_time_s",
                t.to_string(),
                "must be in [0, 1000] s",
            ));
        }
        if let Some([w, z]) = self.path_bound_barrier
            && !(w.is_finite() && w > 0.0 && w <= 1.0 && z.is_finite() && (0.0..=10.0).contains(&z))
        {
            return Err(bad(
                "path_bound_barrier",
                format!("[{w}, {z}]"),
                "must be [frequency in (0, 1] rad/s, damping in [0, 10]]",
            ));
        }
        if let Some(e) = self.replan_start_normalized_energy
            && !(e.is_finite() && e > 0.0 && e <= 1.0)
        {
            return Err(bad(
                "replan_start_normalized_energy",
                e.to_string(),
                "must be in (0, 1]",
            ));
        }
        if let Some(k) = self.terminal_lateral_km
            && !(k.is_finite() && k > self.freeze_km && k <= 2000.0)
        {
            return Err(bad(
                "terminal_lateral_km",
                k.to_string(),
                "must be in (freeze_km, 2000]",
            ));
        }
        let tol = self.terminal_tolerance_km;
        if !(tol.is_finite() && tol > 0.0 && tol <= 100.0) {
            return Err(bad(
                "terminal_tolerance_km",
                tol.to_string(),
                "must be in (0, 100]",
            ));
        }
        let lead = self.terminal_reversal_lead_s;
        if !(lead.is_finite() && (0.0..=60.0).contains(&lead)) {
            return Err(bad(
                "terminal_reversal_lead_s",
                lead.to_string(),
                "must be in [0, 60] s",
            ));
        }
        self.validate_read(file)?;
        let m = self.estimator_min_drag_m_s2;
        if !(m.is_finite() && m >= 0.0) {
            return Err(bad(
                "estimator_min_drag_m_s2",
                m.to_string(),
                "must be finite and >= 0",
            ));
        }
        // The core's own check (one home of the rule); unreachable after the above.
        AeroEstimator::new(self.estimator()).map_err(|_| {
            bad(
                "estimator",
                format!("{:?}", self.estimator()),
                "rejected by guidance-core",
            )
        })?;
        Ok(())
    }
}
