//! Closed-loop trajectory simulation: dynamics + RKF4(5) + an attitude source (guidance).
//!
//! The attitude source is called at every guidance tick with the navigation state
//! (planet-relative spherical quantities); the integrator lands on every tick exactly, and
//! between ticks the right-hand side uses the source's continuous attitude
//! ([`AttitudeSource::attitude_at`], the rate-limited ramp towards the held command).
//!
//! Events located inside steps: atmosphere exit and re-entry at the interface altitude
//! (100 km), and termination on altitude, Mach number or normalised energy (all falling),
//! plus ground impact. A skip is an exit followed by a re-entry.
//!
//! Outputs: trajectory samples at the output interval, at ticks when no interval is set,
//! and at every event; a [`Summary`] with range angle, heat load (integrated as a state),
//! peak heat flux, g-load and g-load rate (from every accepted step), flight time, skips,
//! constraint violations (eq. 4.9-4.11) and the termination reason.

use guidance_core::NavState;
use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::{Command, Guidance};
use guidance_core::monitor::GLoadRateMonitor;
use serde::Serialize;

use crate::dynamics::{Dynamics, FlightConditions, STATE_LEN, SphericalState};
use crate::integrate::{Direction, IntegrateError, OdeProblem, Rkf45, Stats, Tolerances};

/// A source of commanded attitude: the guidance seam of the closed loop.
pub trait AttitudeSource {
    /// Called at every guidance tick (first at t = 0) with the navigation state.
    ///
    /// # Errors
    /// A message when the guidance rejects the state.
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), String>;
    /// Command<f64> at time `time_s` [s] between ticks (continuous).
    fn attitude_at(&self, time_s: f64) -> Command<f64>;
    /// Time of the next tick [s]; `f64::INFINITY` for none.
    fn next_tick_s(&self) -> f64;
    /// The next time after `time_s` at which [`AttitudeSource::attitude_at`] has a kink (a
    /// rate-limited ramp reaching the held command) [s]; `f64::INFINITY` for none. The loop
    /// makes these breakpoints, so no integration step straddles a kink (which would cost
    /// rejected steps and accuracy).
    fn next_kink_s(&self, time_s: f64) -> f64 {
        let _ = time_s;
        f64::INFINITY
    }
}

/// Constant attitude, never ticks (open loop).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedAttitude(pub Command<f64>);

impl AttitudeSource for FixedAttitude {
    fn tick(&mut self, _nav: &NavState<f64>) -> Result<(), String> {
        Ok(())
    }
    fn attitude_at(&self, _time_s: f64) -> Command<f64> {
        self.0
    }
    fn next_tick_s(&self) -> f64 {
        f64::INFINITY
    }
}

/// `guidance-core`'s flight [`Guidance`] as the attitude source of the closed loop: called
/// at every tick with the navigation state; the attitude between ticks is its rate-limited
/// ramp ([`Guidance::attitude_at`]).
#[derive(Clone, Debug)]
pub struct CoreGuidance(pub Guidance<f64>);

fn attitude_of(c: Command<f64>) -> Command<f64> {
    Command {
        alpha_rad: c.alpha_rad,
        sigma_rad: c.sigma_rad,
    }
}

impl AttitudeSource for CoreGuidance {
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), String> {
        let out = self.0.update(nav).map_err(|e| e.to_string())?;
        if out.ticked {
            Ok(())
        } else {
            Err(format!(
                "guidance did not tick at t = {} s (next tick {} s)",
                nav.time_s,
                self.0.next_tick_s()
            ))
        }
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        attitude_of(self.0.attitude_at(time_s))
    }
    fn next_tick_s(&self) -> f64 {
        self.0.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        let Some(t_k) = self.0.ramp_start_s() else {
            return f64::INFINITY;
        };
        let rates = self.0.config().rates;
        ramp_kink(
            time_s,
            t_k,
            attitude_of(self.0.attitude_at(t_k)),
            attitude_of(self.0.command()),
            (rates.alpha_rad_s, rates.sigma_rad_s),
        )
    }
}

/// What the nodes of a [`HostSchedule`] are indexed by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ScheduleIndex {
    /// Mission time [s].
    Time,
    /// Normalised energy E-hat [-] (1 at entry).
    NormalizedEnergy,
}

/// A host-side reference implementation of node guidance: linear interpolation between
/// nodes (clamped outside), zero-order hold at a fixed period, the change per tick limited
/// to `rate * period`, and between ticks a ramp from the attitude at the tick towards the
/// held command at the rate limits. It mirrors the contract of `guidance-core`'s `Guidance`
/// (docs/guidance-api.md) for linear interpolation and serves as an independent
/// cross-check of it.
#[derive(Clone, Debug)]
pub struct HostSchedule {
    index: ScheduleIndex,
    nodes: Vec<[f64; 3]>,
    period_s: f64,
    alpha_rate: f64,
    sigma_rate: f64,
    energy: EnergyNormalizer<f64>,
    command: Command<f64>,
    at_tick: Command<f64>,
    tick_time: f64,
    ticks: u64,
}

impl HostSchedule {
    /// `nodes`: `[x, alpha_rad, sigma_rad]` in flight order (time increasing or energy
    /// decreasing); `initial`: attitude at t = 0.
    ///
    /// # Errors
    /// A message for fewer than one node, non-finite values or a non-positive period/rate.
    pub fn new(
        index: ScheduleIndex,
        nodes: Vec<[f64; 3]>,
        period_s: f64,
        rates_rad_s: (f64, f64),
        energy: EnergyNormalizer<f64>,
        initial: Command<f64>,
    ) -> Result<Self, String> {
        if nodes.is_empty() || nodes.iter().flatten().any(|v| !v.is_finite()) {
            return Err("node table must be non-empty and finite".into());
        }
        for (i, v) in [
            ("period_s", period_s),
            ("alpha_rate", rates_rad_s.0),
            ("sigma_rate", rates_rad_s.1),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{i} = {v}: must be finite and > 0"));
            }
        }
        Ok(Self {
            index,
            nodes,
            period_s,
            alpha_rate: rates_rad_s.0,
            sigma_rate: rates_rad_s.1,
            energy,
            command: initial,
            at_tick: initial,
            tick_time: 0.0,
            ticks: 0,
        })
    }

    fn interpolate(&self, x: f64) -> Command<f64> {
        // Work on an increasing abscissa.
        let key = |n: &[f64; 3]| match self.index {
            ScheduleIndex::Time => n[0],
            ScheduleIndex::NormalizedEnergy => -n[0],
        };
        let xk = match self.index {
            ScheduleIndex::Time => x,
            ScheduleIndex::NormalizedEnergy => -x,
        };
        let first = self.nodes[0];
        let last = self.nodes[self.nodes.len() - 1];
        let pick = |n: [f64; 3]| Command {
            alpha_rad: n[1],
            sigma_rad: n[2],
        };
        if xk <= key(&first) {
            return pick(first);
        }
        if xk >= key(&last) {
            return pick(last);
        }
        for w in self.nodes.windows(2) {
            let (a, b) = (w[0], w[1]);
            if xk <= key(&b) {
                let f = (xk - key(&a)) / (key(&b) - key(&a));
                return Command {
                    alpha_rad: a[1] + f * (b[1] - a[1]),
                    sigma_rad: a[2] + f * (b[2] - a[2]),
                };
            }
        }
        pick(last)
    }
}

fn step_towards(from: f64, to: f64, max_step: f64) -> f64 {
    from + (to - from).clamp(-max_step, max_step)
}

impl AttitudeSource for HostSchedule {
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), String> {
        nav.validate().map_err(|e| e.to_string())?;
        let x = match self.index {
            ScheduleIndex::Time => nav.time_s,
            ScheduleIndex::NormalizedEnergy => self
                .energy
                .normalized(nav.radius_m, nav.speed_m_s)
                .map_err(|e| e.to_string())?,
        };
        let target = self.interpolate(x);
        let now = self.attitude_at(nav.time_s);
        self.command = Command {
            alpha_rad: step_towards(
                self.command.alpha_rad,
                target.alpha_rad,
                self.alpha_rate * self.period_s,
            ),
            sigma_rad: step_towards(
                self.command.sigma_rad,
                target.sigma_rad,
                self.sigma_rate * self.period_s,
            ),
        };
        self.at_tick = now;
        self.tick_time = nav.time_s;
        self.ticks += 1;
        Ok(())
    }

    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        let dt = (time_s - self.tick_time).max(0.0);
        Command {
            alpha_rad: step_towards(
                self.at_tick.alpha_rad,
                self.command.alpha_rad,
                self.alpha_rate * dt,
            ),
            sigma_rad: step_towards(
                self.at_tick.sigma_rad,
                self.command.sigma_rad,
                self.sigma_rate * dt,
            ),
        }
    }

    fn next_tick_s(&self) -> f64 {
        // t0 = 0: tick k at k * period exactly.
        self.ticks as f64 * self.period_s
    }

    fn next_kink_s(&self, time_s: f64) -> f64 {
        ramp_kink(
            time_s,
            self.tick_time,
            self.at_tick,
            self.command,
            (self.alpha_rate, self.sigma_rate),
        )
    }
}

/// Next ramp end after `time_s` for ramps that started at `tick_time` from `at_tick`
/// towards `command` at `rates` [rad/s]; `f64::INFINITY` if none.
#[must_use]
pub fn ramp_kink(
    time_s: f64,
    tick_time: f64,
    at_tick: Command<f64>,
    command: Command<f64>,
    rates: (f64, f64),
) -> f64 {
    let ta = tick_time + (command.alpha_rad - at_tick.alpha_rad).abs() / rates.0;
    let ts = tick_time + (command.sigma_rad - at_tick.sigma_rad).abs() / rates.1;
    let mut best = f64::INFINITY;
    for k in [ta, ts] {
        if k > time_s && k.is_finite() {
            best = best.min(k);
        }
    }
    best
}

/// Termination conditions (each optional except the time limit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Termination {
    /// Stop when the altitude falls below this [m].
    pub altitude_m: Option<f64>,
    /// Stop when the Mach number falls below this [-].
    pub mach: Option<f64>,
    /// Stop when the normalised energy falls below this [-].
    pub normalized_energy: Option<f64>,
    /// Stop at this mission time [s].
    pub max_time_s: f64,
}

impl Default for Termination {
    fn default() -> Self {
        Self {
            altitude_m: Some(25_000.0),
            mach: None,
            normalized_energy: None,
            max_time_s: 4000.0,
        }
    }
}

/// Simulation settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimConfig {
    /// Entry state (planet-relative) at t = 0.
    pub entry: SphericalState,
    /// Termination conditions.
    pub termination: Termination,
    /// Integrator settings.
    pub tolerances: Tolerances,
    /// Trajectory output interval [s]; 0 records at guidance ticks (and events) only.
    pub output_interval_s: f64,
    /// Atmospheric interface altitude for exit/re-entry events [m] (thesis: 100 km).
    pub interface_altitude_m: f64,
    /// Minimum window for the finite-difference g-load rate [s].
    pub g_rate_window_s: f64,
}

impl SimConfig {
    /// Defaults around an entry state: 25 km / 4000 s termination, rtol 1e-9, output at
    /// ticks, interface at 100 km, 0.1 s g-rate window.
    #[must_use]
    pub fn new(entry: SphericalState) -> Self {
        Self {
            entry,
            termination: Termination::default(),
            tolerances: Tolerances {
                rtol: 1e-9,
                h_init: 0.1,
                h_min: 1e-9,
                h_max: 20.0,
                max_steps: 2_000_000,
                event_time_tol_s: 1e-6,
            },
            output_interval_s: 0.0,
            interface_altitude_m: 100_000.0,
            g_rate_window_s: 0.1,
        }
    }
}

/// Why the simulation stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TerminationReason {
    /// Altitude fell below the termination altitude.
    Altitude,
    /// Mach number fell below the termination Mach.
    Mach,
    /// Normalised energy fell below the termination value.
    NormalizedEnergy,
    /// The time limit was reached.
    MaxTime,
    /// The vehicle reached the surface (altitude 0).
    Ground,
}

/// Simulation failures.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// An invalid setting.
    #[error("invalid setting `{field}` = {value}: {reason}")]
    Config {
        /// Setting name.
        field: String,
        /// Its value.
        value: String,
        /// Why it is rejected.
        reason: String,
    },
    /// The integrator failed.
    #[error("integration failed: {0}")]
    Integration(#[from] IntegrateError),
    /// The guidance rejected a state.
    #[error("guidance failed at t = {time_s} s: {message}")]
    Guidance {
        /// Mission time [s].
        time_s: f64,
        /// Guidance message.
        message: String,
    },
}

/// One trajectory sample (SI units, radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Mission time [s].
    pub time_s: f64,
    /// Planet-relative spherical state.
    pub state: SphericalState,
    /// Command<f64> [rad].
    pub attitude: Command<f64>,
    /// Flight conditions (altitude, density, Mach, forces, heat flux, g-load).
    pub conditions: FlightConditions,
    /// Heat load so far [J/m^2].
    pub heat_load_j_m2: f64,
    /// Flown range angle so far [rad].
    pub flown_range_rad: f64,
    /// Normalised energy [-].
    pub normalized_energy: f64,
    /// Why this sample was taken.
    pub kind: SampleKind,
}

/// Why a sample was recorded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SampleKind {
    /// Initial state.
    Start,
    /// Output interval or guidance tick.
    Output,
    /// Atmosphere exit (rising through the interface).
    Exit,
    /// Re-entry (falling through the interface).
    Entry,
    /// Final state.
    End,
}

/// A value with the time it occurred.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Peak {
    /// The peak value.
    pub value: f64,
    /// When [s].
    pub time_s: f64,
}

impl Peak {
    fn update(&mut self, v: f64, t: f64) {
        if v > self.value {
            self.value = v;
            self.time_s = t;
        }
    }
}

/// Run summary.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Why the run stopped.
    pub termination: TerminationReason,
    /// Flight time [s].
    pub flight_time_s: f64,
    /// Great-circle angle between entry and final position (planet-fixed) [rad].
    pub range_angle_rad: f64,
    /// Integral of V cos(gamma) / r dt (eq. 3.15) [rad].
    pub flown_range_angle_rad: f64,
    /// Heat load, integral of the Chapman heat flux [J/m^2].
    pub heat_load_j_m2: f64,
    /// Peak heat flux [W/m^2].
    pub peak_heat_flux_w_m2: Peak,
    /// Peak g-load [-].
    pub peak_g_load: Peak,
    /// Peak |g-load rate| [1/s]: finite differences (core `GLoadRateMonitor`) of the g-load
    /// at accepted steps at least [`SimConfig::g_rate_window_s`] apart. Steps end on every
    /// tick and ramp end, so the short attitude ramps after each tick are resolved.
    pub peak_g_load_rate_per_s: Peak,
    /// Atmosphere exits (rising through the interface).
    pub exits: u32,
    /// Skips: exits followed by a re-entry.
    pub skips: u32,
    /// Times of exits and re-entries [s].
    pub interface_crossings_s: Vec<(f64, SampleKind)>,
    /// Constraint violations (eq. 4.9-4.11): 0 if within the limit, else peak / limit.
    pub violations: Violations,
    /// Integrator work.
    pub rhs_evals: u64,
    /// Accepted integrator steps.
    pub accepted_steps: u64,
    /// Rejected integrator steps.
    pub rejected_steps: u64,
    /// Guidance ticks.
    pub ticks: u64,
}

/// Constraint violations, eq. 4.9-4.11.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Violations {
    /// Heat flux p_q.
    pub heat_flux: f64,
    /// g-load p_g.
    pub g_load: f64,
    /// g-load rate p_gdot.
    pub g_load_rate: f64,
}

/// Eq. 4.9-4.11: 0 if `peak <= limit`, else `peak / limit` (`guidance-core`'s monitor).
#[must_use]
pub fn violation(peak: f64, limit: f64) -> f64 {
    guidance_core::monitor::violation(peak, limit)
}

/// Result of a run.
#[derive(Clone, Debug)]
pub struct SimResult {
    /// Trajectory samples.
    pub samples: Vec<Sample>,
    /// Summary.
    pub summary: Summary,
}

const EV_EXIT: usize = 0;
const EV_ENTRY: usize = 1;
const EV_ALT: usize = 2;
const EV_MACH: usize = 3;
const EV_ENERGY: usize = 4;
const EV_GROUND: usize = 5;

struct Loop<'a, A> {
    dynm: Dynamics<'a>,
    source: A,
    term: Termination,
    interface_m: f64,
    energy: EnergyNormalizer<f64>,
    g_rate_window_s: f64,
    peak_q: Peak,
    peak_g: Peak,
    peak_gdot: Peak,
    g_rate: GLoadRateMonitor<f64>,
    g_rate_last_s: Option<f64>,
}

impl<A: AttitudeSource> Loop<'_, A> {
    fn observe(&mut self, t: f64, y: &[f64; STATE_LEN]) {
        let fc = self.dynm.conditions_at(y, self.source.attitude_at(t));
        self.peak_q.update(fc.heat_flux_w_m2, t);
        self.peak_g.update(fc.g_load, t);
        // g-load rate from successive samples at least one window apart (core monitor).
        if self
            .g_rate_last_s
            .is_none_or(|t0| t - t0 >= self.g_rate_window_s)
        {
            if let Ok(Some(rate)) = self.g_rate.update(t, fc.g_load) {
                self.peak_gdot.update(rate.abs(), t);
            }
            self.g_rate_last_s = Some(t);
        }
    }

    fn sample(&self, t: f64, y: &[f64; STATE_LEN], kind: SampleKind) -> Sample {
        let state = self.dynm.spherical_of(y, t);
        let attitude = self.source.attitude_at(t);
        Sample {
            time_s: t,
            state,
            attitude,
            conditions: self.dynm.conditions_at(y, attitude),
            heat_load_j_m2: y[6],
            flown_range_rad: y[7],
            normalized_energy: self
                .energy
                .normalized(state.radius_m, state.speed_m_s)
                .unwrap_or(f64::NAN),
            kind,
        }
    }
}

impl<A: AttitudeSource> OdeProblem<STATE_LEN> for Loop<'_, A> {
    fn rhs(&mut self, t: f64, y: &[f64; STATE_LEN]) -> [f64; STATE_LEN] {
        self.dynm.cartesian_rhs(y, self.source.attitude_at(t)).0
    }
    fn event_count(&self) -> usize {
        6
    }
    fn events(&mut self, t: f64, y: &[f64; STATE_LEN], out: &mut [f64]) {
        let r = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
        let h = r - self.dynm.planet.radius_m;
        out[EV_EXIT] = h - self.interface_m;
        out[EV_ENTRY] = h - self.interface_m;
        out[EV_ALT] = self.term.altitude_m.map_or(1.0, |ht| h - ht);
        out[EV_GROUND] = h;
        let need_fc = self.term.mach.is_some() || self.term.normalized_energy.is_some();
        if need_fc {
            let fc = self.dynm.conditions_at(y, self.source.attitude_at(t));
            out[EV_MACH] = match self.term.mach {
                Some(m) if fc.mach > 0.0 => fc.mach - m,
                _ => 1.0,
            };
            out[EV_ENERGY] = match self.term.normalized_energy {
                Some(e) => self
                    .energy
                    .normalized(r, fc.airspeed_m_s)
                    .map_or(1.0, |v| v - e),
                None => 1.0,
            };
        } else {
            out[EV_MACH] = 1.0;
            out[EV_ENERGY] = 1.0;
        }
    }
    fn event_direction(&self, i: usize) -> Direction {
        if i == EV_EXIT {
            Direction::Rising
        } else {
            Direction::Falling
        }
    }
    fn on_step(&mut self, t: f64, y: &[f64; STATE_LEN]) {
        self.observe(t, y);
    }
}

fn nav_of(t: f64, s: &SphericalState) -> NavState<f64> {
    NavState {
        time_s: t,
        radius_m: s.radius_m,
        speed_m_s: s.speed_m_s,
        flight_path_angle_rad: s.flight_path_angle_rad,
        heading_rad: s.heading_rad,
        latitude_rad: s.latitude_rad,
        longitude_rad: s.longitude_rad,
    }
}

fn cfg_err(field: &str, value: f64, reason: &str) -> SimError {
    SimError::Config {
        field: field.into(),
        value: value.to_string(),
        reason: reason.into(),
    }
}

/// Validate a configuration against a planet.
///
/// # Errors
/// [`SimError::Config`] naming the field and value.
pub fn validate_config(cfg: &SimConfig, planet_radius_m: f64) -> Result<(), SimError> {
    let e = &cfg.entry;
    if !(e.radius_m.is_finite() && e.radius_m > planet_radius_m) {
        return Err(cfg_err(
            "entry.altitude_m",
            e.radius_m - planet_radius_m,
            "must be finite and > 0",
        ));
    }
    if !(e.speed_m_s.is_finite() && e.speed_m_s > 0.0) {
        return Err(cfg_err(
            "entry.speed_m_s",
            e.speed_m_s,
            "must be finite and > 0",
        ));
    }
    if !(e.flight_path_angle_rad.is_finite()
        && e.flight_path_angle_rad.abs() <= std::f64::consts::FRAC_PI_2)
    {
        return Err(cfg_err(
            "entry.flight_path_angle_rad",
            e.flight_path_angle_rad,
            "must be within [-90, 90] deg",
        ));
    }
    if !(e.latitude_rad.is_finite() && e.latitude_rad.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(cfg_err(
            "entry.latitude_rad",
            e.latitude_rad,
            "must be within (-90, 90) deg",
        ));
    }
    for (f, v) in [
        ("entry.longitude_rad", e.longitude_rad),
        ("entry.heading_rad", e.heading_rad),
    ] {
        if !v.is_finite() {
            return Err(cfg_err(f, v, "must be finite"));
        }
    }
    let t = &cfg.termination;
    if !(t.max_time_s.is_finite() && t.max_time_s > 0.0) {
        return Err(cfg_err(
            "termination.max_time_s",
            t.max_time_s,
            "must be finite and > 0",
        ));
    }
    for (f, v) in [
        ("termination.altitude_m", t.altitude_m),
        ("termination.mach", t.mach),
        ("termination.normalized_energy", t.normalized_energy),
    ] {
        if let Some(v) = v
            && !v.is_finite()
        {
            return Err(cfg_err(f, v, "must be finite"));
        }
    }
    if !(cfg.output_interval_s.is_finite() && cfg.output_interval_s >= 0.0) {
        return Err(cfg_err(
            "output.interval_s",
            cfg.output_interval_s,
            "must be finite and >= 0",
        ));
    }
    if !(cfg.g_rate_window_s.is_finite() && cfg.g_rate_window_s > 0.0) {
        return Err(cfg_err(
            "g_rate_window_s",
            cfg.g_rate_window_s,
            "must be > 0",
        ));
    }
    if !cfg.interface_altitude_m.is_finite() {
        return Err(cfg_err(
            "interface_altitude_m",
            cfg.interface_altitude_m,
            "must be finite",
        ));
    }
    cfg.tolerances.validate().map_err(|m| SimError::Config {
        field: "integrator".into(),
        value: String::new(),
        reason: m,
    })?;
    Ok(())
}

/// Per-component absolute tolerances of the integrated state for relative tolerance
/// `rtol`: position 1e6 * rtol m, velocity 1e3 * rtol m/s, heat load 1e9 * rtol J/m^2,
/// range angle rtol rad (scales of the quantities during entry).
#[must_use]
pub fn state_atol(rtol: f64) -> [f64; STATE_LEN] {
    [
        1e6 * rtol,
        1e6 * rtol,
        1e6 * rtol,
        1e3 * rtol,
        1e3 * rtol,
        1e3 * rtol,
        1e9 * rtol,
        rtol,
    ]
}

/// Fly a trajectory closed-loop. `progress(t, altitude_m)` is called at every guidance tick
/// and output sample.
///
/// # Errors
/// [`SimError`] for bad settings, integrator failure or a guidance error.
pub fn simulate<A: AttitudeSource>(
    dynm: Dynamics<'_>,
    source: A,
    cfg: &SimConfig,
    progress: &mut dyn FnMut(f64, f64),
) -> Result<(SimResult, A), SimError> {
    validate_config(cfg, dynm.planet.radius_m)?;
    let energy = EnergyNormalizer::<f64>::new(
        dynm.planet.mu_m3_s2,
        dynm.planet.radius_m,
        cfg.entry.radius_m,
        cfg.entry.speed_m_s,
    )
    .map_err(|e| SimError::Config {
        field: "entry".into(),
        value: format!("{:?}", cfg.entry),
        reason: e.to_string(),
    })?;
    let mut lp = Loop {
        dynm,
        source,
        term: cfg.termination,
        interface_m: cfg.interface_altitude_m,
        energy,
        g_rate_window_s: cfg.g_rate_window_s,
        peak_q: Peak::default(),
        peak_g: Peak::default(),
        peak_gdot: Peak::default(),
        g_rate: GLoadRateMonitor::new(),
        g_rate_last_s: None,
    };
    let mut integ = Rkf45::new(cfg.tolerances, state_atol(cfg.tolerances.rtol));
    let mut t = 0.0_f64;
    let mut y = dynm.initial_state(&cfg.entry, 0.0);
    let mut ticks = 0u64;
    let tick = |lp: &mut Loop<'_, A>, t: f64, y: &[f64; STATE_LEN], ticks: &mut u64| {
        let s = lp.dynm.spherical_of(y, t);
        *ticks += 1;
        lp.source
            .tick(&nav_of(t, &s))
            .map_err(|message| SimError::Guidance { time_s: t, message })
    };
    tick(&mut lp, t, &y, &mut ticks)?;
    lp.observe(t, &y);
    let mut samples = vec![lp.sample(t, &y, SampleKind::Start)];
    let mut crossings = Vec::new();
    let (mut exits, mut skips, mut pending_exit) = (0u32, 0u32, false);
    let mut out_k = 1u64;
    let out_dt = cfg.output_interval_s;
    let next_out = |k: u64| {
        if out_dt > 0.0 {
            out_dt * k as f64
        } else {
            f64::INFINITY
        }
    };
    let reason = loop {
        let t_tick = lp.source.next_tick_s();
        let t_tick = if t_tick.is_finite() && t_tick > t {
            t_tick
        } else if t_tick.is_finite() {
            return Err(SimError::Guidance {
                time_s: t,
                message: format!("next tick {t_tick} s is not after the current time"),
            });
        } else {
            f64::INFINITY
        };
        let t_out = next_out(out_k);
        let t_kink = lp.source.next_kink_s(t);
        let t_break = t_tick
            .min(t_out)
            .min(t_kink)
            .min(cfg.termination.max_time_s);
        let hit = integ.advance_to(&mut lp, &mut t, &mut y, t_break)?;
        if let Some(hit) = hit {
            match hit.index {
                EV_EXIT => {
                    exits += 1;
                    pending_exit = true;
                    crossings.push((t, SampleKind::Exit));
                    samples.push(lp.sample(t, &y, SampleKind::Exit));
                    continue;
                }
                EV_ENTRY => {
                    if pending_exit {
                        skips += 1;
                        pending_exit = false;
                    }
                    crossings.push((t, SampleKind::Entry));
                    samples.push(lp.sample(t, &y, SampleKind::Entry));
                    continue;
                }
                EV_ALT => break TerminationReason::Altitude,
                EV_MACH => break TerminationReason::Mach,
                EV_ENERGY => break TerminationReason::NormalizedEnergy,
                _ => break TerminationReason::Ground,
            }
        }
        if t >= cfg.termination.max_time_s {
            break TerminationReason::MaxTime;
        }
        let mut record = false;
        if t >= t_tick {
            tick(&mut lp, t, &y, &mut ticks)?;
            record = out_dt == 0.0;
        }
        if t >= t_out {
            out_k += 1;
            record = true;
        }
        if record {
            samples.push(lp.sample(t, &y, SampleKind::Output));
            progress(t, samples.last().map_or(0.0, |s| s.conditions.altitude_m));
        }
    };
    samples.push(lp.sample(t, &y, SampleKind::End));
    let first = samples[0].state;
    let last = samples[samples.len() - 1].state;
    let range = great_circle(&first, &last);
    let lim = dynm.vehicle.limits;
    let stats: Stats = integ.stats;
    let summary = Summary {
        termination: reason,
        flight_time_s: t,
        range_angle_rad: range,
        flown_range_angle_rad: y[7],
        heat_load_j_m2: y[6],
        peak_heat_flux_w_m2: lp.peak_q,
        peak_g_load: lp.peak_g,
        peak_g_load_rate_per_s: lp.peak_gdot,
        exits,
        skips,
        interface_crossings_s: crossings,
        violations: Violations {
            heat_flux: violation(lp.peak_q.value, lim.heat_flux_w_m2),
            g_load: violation(lp.peak_g.value, lim.g_load),
            g_load_rate: violation(lp.peak_gdot.value, lim.g_load_rate_per_s),
        },
        rhs_evals: stats.rhs_evals,
        accepted_steps: stats.accepted,
        rejected_steps: stats.rejected,
        ticks,
    };
    Ok((SimResult { samples, summary }, lp.source))
}

/// Great-circle angle between two positions [rad].
#[must_use]
pub fn great_circle(a: &SphericalState, b: &SphericalState) -> f64 {
    let (sa, ca) = a.latitude_rad.sin_cos();
    let (sb, cb) = b.latitude_rad.sin_cos();
    let dl = b.longitude_rad - a.longitude_rad;
    let x = sa * sb + ca * cb * dl.cos();
    let yv = ((cb * dl.sin()).powi(2) + (ca * sb - sa * cb * dl.cos()).powi(2)).sqrt();
    yv.atan2(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(lat_deg: f64, lon_deg: f64) -> SphericalState {
        SphericalState {
            radius_m: 1.0,
            longitude_rad: lon_deg.to_radians(),
            latitude_rad: lat_deg.to_radians(),
            speed_m_s: 0.0,
            flight_path_angle_rad: 0.0,
            heading_rad: 0.0,
        }
    }

    #[test]
    fn great_circle_angles() {
        let d = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(0.0, 90.0)),
            std::f64::consts::FRAC_PI_2
        ));
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(90.0, 0.0)),
            std::f64::consts::FRAC_PI_2
        ));
        assert!(d(great_circle(&at(10.0, 20.0), &at(10.0, 20.0)), 0.0));
        assert!(d(
            great_circle(&at(0.0, -170.0), &at(0.0, 170.0)),
            20f64.to_radians()
        ));
        assert!(d(
            great_circle(&at(0.0, 0.0), &at(0.0, 180.0)),
            std::f64::consts::PI
        ));
    }

    #[test]
    fn ramp_kinks() {
        let a = |x: f64, y: f64| Command {
            alpha_rad: x,
            sigma_rad: y,
        };
        // alpha needs 0.1/0.5 = 0.2 s, sigma 0.3/1.0 = 0.3 s from the tick at t = 10.
        let k = ramp_kink(10.0, 10.0, a(0.0, 0.0), a(0.1, -0.3), (0.5, 1.0));
        assert!((k - 10.2).abs() < 1e-12);
        let k = ramp_kink(10.25, 10.0, a(0.0, 0.0), a(0.1, -0.3), (0.5, 1.0));
        assert!((k - 10.3).abs() < 1e-12);
        assert!(ramp_kink(10.5, 10.0, a(0.0, 0.0), a(0.1, -0.3), (0.5, 1.0)).is_infinite());
    }

    #[test]
    fn config_validation_names_fields() {
        let mut c = SimConfig::new(at(0.0, 0.0));
        c.entry.radius_m = 7e6;
        c.entry.speed_m_s = 7000.0;
        assert!(validate_config(&c, 6.4e6).is_ok());
        let mut bad = c;
        bad.entry.speed_m_s = f64::NAN;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("entry.speed_m_s")
        );
        let mut bad = c;
        bad.termination.max_time_s = -1.0;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("max_time_s")
        );
        let mut bad = c;
        bad.tolerances.rtol = 0.0;
        assert!(
            validate_config(&bad, 6.4e6)
                .unwrap_err()
                .to_string()
                .contains("rtol")
        );
    }
}
