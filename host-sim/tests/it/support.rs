//! Small test-local environment and vehicle models shared by the dynamics and closed-loop
//! tests (written independently of `host_sim::env` so these tests check the integrators and
//! equations of motion, not the environment implementations), and [`HostSchedule`], the
//! host-side oracle of node guidance the closed-loop tests check the core against.

use guidance_core::energy::EnergyNormalizer;
use guidance_core::guidance::Command;
use guidance_core::nodes::Independent;
use guidance_core::{GuidanceError, NavState};
use host_sim::env::{Atmosphere, AtmosphereState, Gravity, Planet};
use host_sim::sim::AttitudeSource;
use host_sim::vehicle::{AeroCoefficients, Aerodynamics, Vehicle, VehicleLimits};
use nalgebra::Vector3;

pub const MU: f64 = 3.986_004_418e14;
pub const RE: f64 = 6_378_137.0;
pub const OMEGA_E: f64 = 7.292_115e-5;
pub const J2: f64 = 1.082_63e-3;

/// Exponential atmosphere rho0 exp(-h/H), isothermal speed of sound; zero above `top_m`.
pub struct ExpAtmo {
    pub rho0: f64,
    pub h_s: f64,
    pub top_m: f64,
}

impl Atmosphere for ExpAtmo {
    fn state(&self, h: f64) -> AtmosphereState {
        let rho = if h > self.top_m {
            0.0
        } else {
            self.rho0 * (-h.max(0.0) / self.h_s).exp()
        };
        AtmosphereState {
            temperature_k: 250.0,
            pressure_pa: rho * 287.05 * 250.0,
            density_kg_m3: rho,
            speed_of_sound_m_s: (1.4_f64 * 287.05 * 250.0).sqrt(),
        }
    }
}

pub struct Central;
impl Gravity for Central {
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        -r * (MU / r.norm().powi(3))
    }
}

/// J2 gravity from the gradient of U = -mu/r [1 - J2 (R/r)^2 P2(z/r)].
pub struct J2Grav;
impl Gravity for J2Grav {
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let rn = r.norm();
        let zr2 = (r.z / rn).powi(2);
        let k = 1.5 * J2 * (RE / rn).powi(2);
        let f = -MU / rn.powi(3);
        Vector3::new(
            f * r.x * (1.0 + k * (1.0 - 5.0 * zr2)),
            f * r.y * (1.0 + k * (1.0 - 5.0 * zr2)),
            f * r.z * (1.0 + k * (3.0 - 5.0 * zr2)),
        )
    }
}

#[derive(Debug)]
pub struct ConstAero {
    pub cl_per_rad: f64,
    pub cd: f64,
}
impl Aerodynamics for ConstAero {
    fn coefficients(&self, _mach: f64, alpha: f64) -> AeroCoefficients {
        AeroCoefficients {
            cl: self.cl_per_rad * alpha,
            cd: self.cd,
        }
    }
}

pub fn vehicle(mass: f64, area: f64, cl_per_rad: f64, cd: f64) -> Vehicle {
    Vehicle {
        name: "test".into(),
        mass_kg: mass,
        reference_area_m2: area,
        nose_radius_m: 0.8,
        limits: VehicleLimits {
            heat_flux_w_m2: 5e5,
            g_load: 3.0,
            g_load_rate_per_s: 0.5,
            alpha_rate_rad_s: 5f64.to_radians(),
            sigma_rate_rad_s: 15f64.to_radians(),
        },
        aero: Box::new(ConstAero { cl_per_rad, cd }),
    }
}

pub fn planet(rotating: bool) -> Planet {
    Planet {
        mu_m3_s2: MU,
        radius_m: RE,
        rotation_rate_rad_s: if rotating { OMEGA_E } else { 0.0 },
        j2: J2,
    }
}

/// A host-side reference implementation of node guidance: linear interpolation between
/// nodes (clamped outside), zero-order hold at a fixed period, the change per tick limited
/// to `rate * period`, and between ticks a ramp from the attitude at the tick towards the
/// held command at the rate limits. It mirrors the contract of `guidance-core`'s `Guidance`
/// (docs/reference/guidance-api.md) for linear interpolation and serves as an independent
/// cross-check of it.
#[derive(Clone, Debug)]
pub struct HostSchedule {
    index: Independent,
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
        index: Independent,
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
            Independent::TimeS => n[0],
            Independent::NormalizedEnergy => -n[0],
        };
        let xk = match self.index {
            Independent::TimeS => x,
            Independent::NormalizedEnergy => -x,
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
    type Error = GuidanceError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), GuidanceError> {
        nav.validate()?;
        let x = match self.index {
            Independent::TimeS => nav.time_s,
            Independent::NormalizedEnergy => self.energy.normalized(nav.radius_m, nav.speed_m_s)?,
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
/// towards `command` at `rates` \[rad/s\]; `f64::INFINITY` if none. Part of the
/// [`HostSchedule`] oracle, which re-derives the ramp independently of the core (the library
/// asks the core: `Guidance::next_ramp_kink_s`, `CommandFrame::ramp_end`).
pub fn ramp_kink(
    time_s: f64,
    tick_time: f64,
    at_tick: Command<f64>,
    command: Command<f64>,
    rates: (f64, f64),
) -> f64 {
    let ta = tick_time + (command.alpha_rad - at_tick.alpha_rad).abs() / rates.0;
    let ts = tick_time + (command.sigma_rad - at_tick.sigma_rad).abs() / rates.1;
    [ta, ts]
        .into_iter()
        .filter(|k| *k > time_s && k.is_finite())
        .fold(f64::INFINITY, f64::min)
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

/// A complete scenario file: the built-in HORUS-2B reference mission as printed by
/// `simulate --print-scenario` without its onboard layers (`[guidance.<layer>]`: the stored
/// profile alone), with the tables and keys of `snippet` merged over it (tables merged key by
/// key, other values replaced). Scenario files state what they fly; tests that change a few
/// keys start from this.
pub fn complete_scenario(snippet: &str) -> String {
    fn merge(base: &mut toml::Table, over: toml::Table) {
        for (k, v) in over {
            match (base.get_mut(&k), v) {
                (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
                (_, v) => {
                    base.insert(k, v);
                }
            }
        }
    }
    let printed = host_sim::scenario::scenario_to_toml(&host_sim::scenario::Scenario::default());
    let mut base: toml::Table = printed.parse().expect("the printed scenario parses");
    strip_layers(&mut base);
    let over: toml::Table = snippet.parse().expect("the snippet is valid TOML");
    merge(&mut base, over);
    toml::to_string(&base).expect("a TOML table serialises")
}

/// Remove the onboard layers (`[guidance.<layer>]` tables) from a scenario table.
pub fn strip_layers(t: &mut toml::Table) {
    if let Some(toml::Value::Table(g)) = t.get_mut("guidance") {
        g.retain(|_, v| !v.is_table());
    }
}
