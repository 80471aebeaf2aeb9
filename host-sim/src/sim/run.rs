//! The run loop: integrate between breakpoints (ticks, output times, ramp ends), tick the
//! attitude source, locate events, record samples and peaks.

use guidance_core::NavState;
use guidance_core::energy::EnergyNormalizer;
use guidance_core::estimate::SensedAero;
use guidance_core::monitor::GLoadRateMonitor;
use guidance_core::navconv::{self, CartesianNav, InertialFrame};

use super::events::{Event, EventState};
use super::{
    AttitudeSource, Peak, Sample, SampleKind, SimConfig, SimError, SimResult, Summary, Termination,
    TerminationReason, great_circle, state_atol, validate_config, violations,
};
use crate::dynamics::{
    Dynamics, FLOWN_RANGE_SLOT, HEAT_LOAD_SLOT, RhsCache, STATE_LEN, cartesian_of,
};
use crate::integrate::{Direction, OdeProblem, Rkf45, Stats};

/// Progress of a run, reported at every guidance tick and output sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Mission time \[s\].
    pub time_s: f64,
    /// Altitude \[m\].
    pub altitude_m: f64,
}

struct Loop<'a, A> {
    dynm: Dynamics<'a>,
    rhs_cache: RhsCache,
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
    /// Guidance ticks so far: the attitude function changes only at ticks
    /// ([`OdeProblem::rhs_generation`]).
    ticks: u64,
}

impl<A: AttitudeSource> Loop<'_, A> {
    fn observe(&mut self, t: f64, y: &[f64; STATE_LEN]) {
        // The right-hand side's heat flux (within a few ulp of the core's) and the g-load.
        let (q, g_load) =
            self.dynm
                .heat_flux_and_g_load(y, self.source.attitude_at(t), &mut self.rhs_cache);
        self.peak_q.update(q, t);
        self.peak_g.update(g_load, t);
        // g-load rate from successive samples at least one window apart (core monitor).
        if self
            .g_rate_last_s
            .is_none_or(|t0| t - t0 >= self.g_rate_window_s)
        {
            if let Ok(Some(rate)) = self.g_rate.update(t, g_load) {
                self.peak_gdot.update(rate.abs(), t);
            }
            self.g_rate_last_s = Some(t);
        }
    }

    fn sample(&mut self, t: f64, y: &[f64; STATE_LEN], kind: SampleKind) -> Sample {
        let state = self.dynm.spherical_of(y, t);
        let attitude = self.source.attitude_at(t);
        Sample {
            time_s: t,
            state,
            attitude,
            conditions: self
                .dynm
                .conditions_at_cached(y, attitude, &mut self.rhs_cache),
            heat_load_j_m2: y[HEAT_LOAD_SLOT],
            flown_range_rad: y[FLOWN_RANGE_SLOT],
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
        let att = self.source.attitude_at(t);
        self.dynm.cartesian_derivative(y, att, &mut self.rhs_cache)
    }
    fn event_count(&self) -> usize {
        Event::ALL.len()
    }
    fn events(&mut self, t: f64, y: &[f64; STATE_LEN], out: &mut [f64]) {
        let r = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
        let mut state = EventState {
            altitude_m: r - self.dynm.planet.radius_m,
            mach: 0.0,
            normalized_energy: None,
        };
        if Event::needs_conditions(&self.term) {
            let att = self.source.attitude_at(t);
            let fc = self.dynm.conditions_at_cached(y, att, &mut self.rhs_cache);
            state.mach = fc.mach;
            state.normalized_energy = self.energy.normalized(r, fc.airspeed_m_s).ok();
        }
        for (o, e) in out.iter_mut().zip(Event::ALL) {
            *o = e.value(&state, self.interface_m, &self.term);
        }
    }
    fn event_direction(&self, i: usize) -> Direction {
        Event::from_index(i).map_or(Direction::Falling, Event::direction)
    }
    fn on_step(&mut self, t: f64, y: &[f64; STATE_LEN]) {
        self.observe(t, y);
    }
    fn rhs_generation(&self) -> Option<u64> {
        Some(self.ticks)
    }
}

/// The navigation state guidance sees, as flight computes it: the inertial Cartesian state
/// converted onboard by `guidance_core::navconv` (not the simulator's own spherical state).
fn nav_of(
    t: f64,
    y: &[f64; STATE_LEN],
    rotation_rate_rad_s: f64,
) -> Result<NavState<f64>, SimError> {
    let c = cartesian_of(y);
    navconv::from_inertial(
        &CartesianNav {
            time_s: t,
            position_m: c.position_m,
            velocity_m_s: c.velocity_m_s,
        },
        &InertialFrame {
            rotation_rate_rad_s,
            angle_at_zero_rad: 0.0,
        },
    )
    .map_err(|source| SimError::Navigation { time_s: t, source })
}

/// Fly a trajectory closed-loop. `progress` is called at every guidance tick
/// and output sample.
///
/// # Errors
/// [`SimError`] for bad settings, integrator failure or a guidance error.
///
/// The closed loop by hand: the scenario's vehicle, environment and guidance, flown by
/// `guidance-core`'s `Guidance` as an [`AttitudeSource`] (what [`crate::scenario::fly`] does):
///
/// ```
/// use host_sim::dynamics::Dynamics;
/// use host_sim::scenario::{Scenario, build_guidance};
/// use host_sim::sim::{CoreGuidance, simulate};
/// let sc = Scenario::srm_glide();
/// let vehicle = sc.load_vehicle()?;
/// let env = sc.environment.build();
/// let guidance = CoreGuidance::new(build_guidance(&sc, &env.planet, "(built-in)")?);
/// let dynamics = Dynamics::from_environment(&env, &vehicle);
/// let (result, _guidance) = simulate(dynamics, guidance, &sc.sim_config(), &mut |_| {})?;
/// let last = result.samples.last().expect("samples");
/// assert!(result.summary.flight_time_s > 100.0 && last.state.speed_m_s < 7658.34);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simulate<A: AttitudeSource>(
    dynm: Dynamics<'_>,
    source: A,
    cfg: &SimConfig,
    progress: &mut dyn FnMut(Progress),
) -> Result<(SimResult, A), SimError> {
    validate_config(cfg, dynm.planet.radius_m)?;
    let _active = super::stop::ActiveRun::start();
    let energy = EnergyNormalizer::<f64>::new(
        dynm.planet.mu_m3_s2,
        dynm.planet.radius_m,
        cfg.entry.radius_m,
        cfg.entry.speed_m_s,
    )
    .map_err(SimError::Entry)?;
    let mut lp = Loop {
        dynm,
        rhs_cache: dynm.rhs_cache(),
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
        ticks: 0,
    };
    let mut integ = Rkf45::new(cfg.tolerances, state_atol(cfg.tolerances.rtol));
    let mut t = 0.0_f64;
    let mut y = dynm.initial_state(&cfg.entry, 0.0);
    let tick = |lp: &mut Loop<'_, A>, t: f64, y: &[f64; STATE_LEN]| {
        let nav = nav_of(t, y, lp.dynm.planet.rotation_rate_rad_s)?;
        lp.ticks += 1;
        let wrap = |e: A::Error| SimError::Guidance {
            time_s: t,
            source: Box::new(e),
        };
        // What an IMU senses at this instant: the aerodynamic accelerations at the attitude
        // flown now (before the tick's update), for a source that uses them.
        if lp.source.senses() {
            let (lift_m_s2, drag_m_s2) = lp.dynm.aero_accelerations_at(y, lp.source.attitude_at(t));
            let sensed = SensedAero {
                lift_m_s2,
                drag_m_s2,
            };
            lp.source.sense(&nav, &sensed).map_err(wrap)?;
        }
        lp.source.tick(&nav).map_err(wrap)
    };
    tick(&mut lp, t, &y)?;
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
        // A stop request (Ctrl-C) ends the run at the next breakpoint, where progress is
        // reported.
        if super::stop_requested() {
            return Err(SimError::Interrupted { time_s: t });
        }
        let t_tick = lp.source.next_tick_s();
        let t_tick = if t_tick.is_finite() && t_tick > t {
            t_tick
        } else if t_tick.is_finite() {
            return Err(SimError::TickNotAfter {
                time_s: t,
                next_tick_s: t_tick,
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
            match Event::from_index(hit.index).ok_or(SimError::UnknownEvent(hit.index))? {
                Event::Exit => {
                    exits += 1;
                    pending_exit = true;
                    crossings.push((t, SampleKind::Exit));
                    samples.push(lp.sample(t, &y, SampleKind::Exit));
                    continue;
                }
                Event::Entry => {
                    if pending_exit {
                        skips += 1;
                        pending_exit = false;
                    }
                    crossings.push((t, SampleKind::Entry));
                    samples.push(lp.sample(t, &y, SampleKind::Entry));
                    continue;
                }
                Event::Altitude => break TerminationReason::Altitude,
                Event::Mach => break TerminationReason::Mach,
                Event::NormalizedEnergy => break TerminationReason::NormalizedEnergy,
                Event::Ground => break TerminationReason::Ground,
            }
        }
        if t >= cfg.termination.max_time_s {
            break TerminationReason::MaxTime;
        }
        let mut record = false;
        if t >= t_tick {
            tick(&mut lp, t, &y)?;
            record = out_dt == 0.0;
        }
        if t >= t_out {
            out_k += 1;
            record = true;
        }
        if record {
            samples.push(lp.sample(t, &y, SampleKind::Output));
            progress(Progress {
                time_s: t,
                altitude_m: samples.last().map_or(0.0, |s| s.conditions.altitude_m),
            });
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
        flown_range_angle_rad: y[FLOWN_RANGE_SLOT],
        heat_load_j_m2: y[HEAT_LOAD_SLOT],
        peak_heat_flux_w_m2: lp.peak_q,
        peak_g_load: lp.peak_g,
        peak_g_load_rate_per_s: lp.peak_gdot,
        exits,
        skips,
        interface_crossings_s: crossings,
        violations: violations(lp.peak_q, lp.peak_g, lp.peak_gdot, &lim),
        rhs_evals: stats.rhs_evals,
        accepted_steps: stats.accepted,
        rejected_steps: stats.rejected,
        ticks: lp.ticks,
    };
    Ok((SimResult { samples, summary }, lp.source))
}
