//! What every case of a campaign shares: the nominal world, the terminal interface, the
//! target point, the stored profile (energy-indexed, two-sided bank bounds) and the settings of
//! the lateral logic and of the re-planner. Built once from a scenario by flying it nominally
//! ([`CampaignSetup::new`], defined with the flights it needs in the private `build` module).

use guidance_core::geo::central_angle;
use guidance_core::nodes::{AngleBounds, HostNodeTable, Independent, Node};
use guidance_core::replan::{LiftSchedule, RangeTarget, SCHEDULE_NODES, ScheduleNode, TargetPoint};
use guidance_core::stack::HostStackConfig;

use super::CampaignError;
use crate::dynamics::SphericalState;
use crate::scenario::Scenario;
use crate::scenario::guidance_layers::CampaignGuidance;
use crate::sim::SimResult;

pub(super) const DEG: f64 = std::f64::consts::PI / 180.0;

/// Mach number of the polar the predictor uses (as the closed-loop re-planning tests).
pub const PREDICTOR_POLAR_MACH: f64 = 20.0;

/// Nominal flights used to place the target (module docs of [`CampaignSetup::new`]).
pub const RETARGET_ITERATIONS: usize = 6;

/// The shared part of a campaign.
#[derive(Clone, Debug)]
pub struct CampaignSetup {
    /// The scenario (nominal entry, vehicle, environment, guidance).
    pub scenario: Scenario,
    /// Name of the scenario file (for messages).
    pub file: String,
    /// Terminal interface: specific energy `V^2/2 - mu/r` \[J/kg\] of the nominal flight where
    /// it crosses [`CampaignSetup::interface`] (or of its end); every case ends on it.
    pub interface_energy_j_kg: f64,
    /// Speed of the nominal flight there \[m/s\] (the closed-form predictions' final speed).
    pub interface_speed_m_s: f64,
    /// The terminal interface as given (`None`: the nominal end), the one the two above
    /// derive from.
    pub interface: Option<crate::scenario::TerminalInterface>,
    /// Altitude floor of every case \[m\] (an end there is reported: interface not reached).
    pub floor_altitude_m: f64,
    /// Planet radius \[m\].
    pub planet_radius_m: f64,
    /// Downrange of the target along the nominal entry great circle \[rad\].
    pub target_downrange_rad: f64,
    /// The full onboard stack (every layer a mode may fly; [`CampaignSetup::stack_of`] masks
    /// it): the energy-indexed stored profile with two-sided bank bounds, the re-planner, the
    /// lateral logic, the estimator, the path bound, and the target point.
    pub stack: HostStackConfig<f64>,
    /// The guidance settings these were built from.
    pub guidance: CampaignGuidance,
}

/// The entry great circle's second point: `downrange` \[rad\] from the entry along its heading.
pub(super) fn along_heading(e: &SphericalState, downrange_rad: f64) -> TargetPoint<f64> {
    let (lat1, lon1, b, d) = (
        e.latitude_rad,
        e.longitude_rad,
        e.heading_rad,
        downrange_rad,
    );
    let lat2 = (lat1.sin() * d.cos() + lat1.cos() * d.sin() * b.cos()).asin();
    let lon2 = lon1 + (b.sin() * d.sin() * lat1.cos()).atan2(d.cos() - lat1.sin() * lat2.sin());
    TargetPoint {
        latitude_rad: lat2,
        longitude_rad: lon2,
    }
}

/// The point `downrange_rad` along the entry heading's great circle from the entry point `e`
/// and `crossrange_rad` off it, to the right of the direction of flight (great-circle angles).
#[must_use]
pub fn downrange_crossrange(
    e: &SphericalState,
    downrange_rad: f64,
    crossrange_rad: f64,
) -> TargetPoint<f64> {
    let p = along_heading(e, downrange_rad);
    // The course at `p`: the reverse of the bearing from `p` back to the entry.
    let back = guidance_core::geo::initial_bearing(
        p.latitude_rad,
        p.longitude_rad,
        e.latitude_rad,
        e.longitude_rad,
    )
    .unwrap_or(f64::NAN);
    let course = back + std::f64::consts::PI;
    let at_p = SphericalState {
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        heading_rad: course + std::f64::consts::FRAC_PI_2,
        ..*e
    };
    along_heading(&at_p, crossrange_rad)
}

/// Energy-indexed version of the scenario's table (a time-indexed table is mapped through the
/// nominal flight's E-hat at the node times), with two-sided bank bounds `[-max, max]`.
pub(super) fn energy_table(
    sc: &Scenario,
    nominal: &SimResult,
    file: &str,
) -> Result<HostNodeTable<f64>, CampaignError> {
    let g = &sc.guidance;
    let e_at = |t: f64| -> f64 {
        let s = &nominal.samples;
        let i = s.partition_point(|p| p.time_s < t);
        match (i.checked_sub(1).and_then(|j| s.get(j)), s.get(i)) {
            (Some(a), Some(b)) if b.time_s > a.time_s => {
                let w = (t - a.time_s) / (b.time_s - a.time_s);
                a.normalized_energy + w * (b.normalized_energy - a.normalized_energy)
            }
            (_, Some(b)) => b.normalized_energy,
            (Some(a), None) => a.normalized_energy,
            (None, None) => 1.0,
        }
    };
    let mut nodes: Vec<Node<f64>> = Vec::new();
    for n in &g.nodes {
        let x = match g.independent {
            Independent::NormalizedEnergy => n[0],
            Independent::TimeS => e_at(n[0]),
        };
        // Strictly decreasing E-hat (drop nodes past the nominal end).
        if nodes.last().is_some_and(|p| x >= p.x) {
            continue;
        }
        nodes.push(Node {
            x,
            alpha_rad: n[1],
            sigma_rad: n[2].abs(),
        });
    }
    // Close the table below the interface with the last node's attitude.
    if let Some(last) = nodes.last().copied()
        && last.x > 0.0
    {
        nodes.push(Node { x: 0.0, ..last });
    }
    let b = g.bounds;
    let smax = b.sigma_max_rad.abs().max(b.sigma_min_rad.abs());
    let bounds = AngleBounds {
        alpha_min_rad: b.alpha_min_rad,
        alpha_max_rad: b.alpha_max_rad,
        sigma_min_rad: -smax,
        sigma_max_rad: smax,
    };
    HostNodeTable::new(Independent::NormalizedEnergy, &nodes, bounds).map_err(|e| {
        CampaignError::Guidance {
            file: file.into(),
            field: "guidance.nodes",
            source: e.into(),
        }
    })
}

/// The predictor's lift parameter `lambda = C_L / C_L*` of the stored profile (a value for
/// `[dispersions.guidance] predictor_lift_parameter`, docs/reference/campaigns.md): the mean over
/// the nominal flight `nominal`, weighted by the range flown, of `C_L(alpha)` at
/// [`PREDICTOR_POLAR_MACH`] and the flown angle of attack, over the model polar's `C_L* =
/// sqrt(C_D0/K)` (the lift coefficient of maximum L/D). A vehicle without angle-of-attack
/// control (trim only, as the SRM capsule) gives 1: its model polar has the trim point at
/// maximum L/D. With `lambda = 1` the predictor of HORUS-2B (alpha 40 deg for 85 % of the
/// range: `C_L` 0.77 against `C_L*` 0.21, L/D 1.1 against 2.1) flew a vehicle that needs 3.7
/// times the density to hold its glide (heat flux ~1.9x) and has twice the L/D.
///
/// # Errors
/// [`CampaignError::Setting`] (`dispersions.guidance.predictor_lift_parameter`) if the result
/// is not finite and positive (a nominal flight without range, a polar without lift).
pub fn profile_lift_parameter(
    vehicle: &crate::vehicle::Vehicle,
    model: &guidance_core::replan::PredictorModel<f64>,
    nominal: &SimResult,
    file: &str,
) -> Result<f64, CampaignError> {
    if !vehicle.aero.controls_alpha() {
        return Ok(1.0);
    }
    let cl_star = (model.vehicle.cd0 / model.vehicle.k_polar).sqrt();
    let lambda_at =
        |alpha: f64| vehicle.aero.coefficients(PREDICTOR_POLAR_MACH, alpha).cl / cl_star;
    let (mut sum, mut range) = (0.0, 0.0);
    for w in nominal.samples.windows(2) {
        if let [a, b] = w {
            let d = b.flown_range_rad - a.flown_range_rad;
            sum += d * 0.5 * (lambda_at(a.attitude.alpha_rad) + lambda_at(b.attitude.alpha_rad));
            range += d;
        }
    }
    let l = sum / range;
    if l.is_finite() && l > 0.0 {
        Ok(l)
    } else {
        Err(CampaignError::Setting {
            file: file.into(),
            field: "dispersions.guidance.predictor_lift_parameter".into(),
            value: l.to_string(),
            reason: "the stored profile gives no finite positive lift parameter (set it)".into(),
        })
    }
}

/// The stored profile's lift parameter against speed, for a profile that holds one angle of
/// attack and then ramps to another (HORUS-2B: 40 deg, then from E-hat 0.31 a ramp to 11.5
/// deg): `lambda = C_L(alpha)/C_L*` at [`PREDICTOR_POLAR_MACH`] at the first and last sample
/// of the nominal flight `nominal` (up to the interface speed `interface_speed_m_s` \[m/s\]),
/// `speed_high_m_s` the speed where it first departs from the entry value by more than 1 %,
/// `speed_low_m_s` where it first comes within 1 % of the final value. `None` for a trim vehicle
/// or a profile whose lift parameter does not change by more than 1 %.
#[must_use]
pub fn profile_lift_schedule(
    vehicle: &crate::vehicle::Vehicle,
    model: &guidance_core::replan::PredictorModel<f64>,
    nominal: &SimResult,
    interface_speed_m_s: f64,
) -> Option<LiftSchedule<f64>> {
    if !vehicle.aero.controls_alpha() {
        return None;
    }
    let cl_star = (model.vehicle.cd0 / model.vehicle.k_polar).sqrt();
    let lambda_at =
        |alpha: f64| vehicle.aero.coefficients(PREDICTOR_POLAR_MACH, alpha).cl / cl_star;
    let flown: Vec<(f64, f64)> = nominal
        .samples
        .iter()
        .take_while(|s| s.state.speed_m_s >= interface_speed_m_s)
        .map(|s| (s.state.speed_m_s, lambda_at(s.attitude.alpha_rad)))
        .collect();
    let (&(_, high), &(_, low)) = (flown.first()?, flown.last()?);
    let near = |a: f64, b: f64| (a - b).abs() <= 0.01 * b.abs();
    if near(low, high) {
        return None;
    }
    let i = flown.iter().position(|&(_, l)| !near(l, high))?;
    let speed_high_m_s = flown.get(i.checked_sub(1)?)?.0;
    let speed_low_m_s = flown.iter().skip(i).find(|&&(_, l)| near(l, low))?.0;
    let s = LiftSchedule::linear(speed_high_m_s, high, speed_low_m_s, low);
    s.is_valid().then_some(s)
}

/// The stored profile's aerodynamics against speed, Mach included: [`SCHEDULE_NODES`] nodes
/// evenly spaced in speed from the entry speed of the nominal flight `nominal` to the
/// interface speed `interface_speed_m_s` \[m/s\]; at each, the first nominal sample at or
/// below the node's speed gives the angle of attack and the Mach number (its speed over the
/// US76 speed of sound at its altitude), and the vehicle's tables `C_L`, `C_D` there give
/// `lambda = C_L / C_L*` and the drag scale `C_D / (C_D0 (1 + lambda^2))` of the model polar
/// (`C_D0`, `K` at [`PREDICTOR_POLAR_MACH`]). HORUS-2B: `C_L` 0.77 at Mach 20 and 40 deg; at
/// Mach 5 the tables give more lift and drag than that polar. `None` for a trim vehicle or if
/// the nodes are not a valid schedule (a nominal flight too short).
#[must_use]
pub fn profile_aero_schedule(
    vehicle: &crate::vehicle::Vehicle,
    model: &guidance_core::replan::PredictorModel<f64>,
    nominal: &SimResult,
    interface_speed_m_s: f64,
) -> Option<LiftSchedule<f64>> {
    if !vehicle.aero.controls_alpha() {
        return None;
    }
    let (cd0, k) = (model.vehicle.cd0, model.vehicle.k_polar);
    let cl_star = (cd0 / k).sqrt();
    let flown: Vec<&crate::sim::results::Sample> = nominal
        .samples
        .iter()
        .take_while(|s| s.state.speed_m_s >= interface_speed_m_s)
        .collect();
    let v_hi = flown.first()?.state.speed_m_s;
    let v_lo = flown.last()?.state.speed_m_s;
    let last = SCHEDULE_NODES.checked_sub(1)?;
    let nodes: Vec<ScheduleNode<f64>> = (0..SCHEDULE_NODES)
        .map(|i| {
            let v = v_hi + (v_lo - v_hi) * i as f64 / last as f64;
            let s = if i == last {
                flown.last()
            } else {
                flown
                    .iter()
                    .find(|s| s.state.speed_m_s <= v)
                    .or(flown.last())
            }?;
            let c = vehicle
                .aero
                .coefficients(s.conditions.mach, s.attitude.alpha_rad);
            let lambda = c.cl / cl_star;
            Some(ScheduleNode {
                speed_m_s: v,
                lambda,
                drag_scale: c.cd / (cd0 * (1.0 + lambda * lambda)),
            })
        })
        .collect::<Option<_>>()?;
    LiftSchedule::from_nodes(&nodes).ok()
}

impl CampaignSetup {
    /// The modes this campaign's stack can fly ([`super::Mode::flies_with`]), in report order.
    #[must_use]
    pub fn modes(&self) -> Vec<super::Mode> {
        let l = self.stack.layers();
        super::Mode::ALL
            .into_iter()
            .filter(|m| m.flies_with(l))
            .collect()
    }

    /// The mode flying the most of the scenario's stack: the last of
    /// [`CampaignSetup::modes`] (the barrier rides with the re-planning modes where the
    /// scenario has it). `host-sim simulate` of a scenario with guidance layers flies the
    /// nominal case in it (`crate::scenario::fly`).
    #[must_use]
    pub fn full_mode(&self) -> super::Mode {
        self.modes().last().copied().unwrap_or(super::Mode::Stored)
    }

    /// Check that the stack can fly every mode of `modes`.
    ///
    /// # Errors
    /// [`CampaignError::Setting`] naming the first mode whose layers the scenario does not
    /// define.
    pub fn check_modes(&self, modes: &[super::Mode]) -> Result<(), CampaignError> {
        let l = self.stack.layers();
        match modes.iter().find(|m| !m.flies_with(l)) {
            None => Ok(()),
            Some(m) => Err(CampaignError::Setting {
                file: self.file.clone(),
                field: "modes".into(),
                value: m.name().into(),
                reason: format!(
                    "the scenario's guidance has no layer for it (it defines {l:?}; add the \
                     [guidance.lateral] / [guidance.replanning] / [guidance.estimator] sections)"
                ),
            }),
        }
    }

    /// Radius \[m\] of the terminal interface: where its speed has its energy
    /// (`mu / (V^2/2 - E)`).
    fn interface_radius_m(&self) -> f64 {
        let mu = self.scenario.environment.planet.mu_m3_s2;
        let v = self.interface_speed_m_s;
        mu / (0.5 * v * v - self.interface_energy_j_kg)
    }

    /// Altitude \[m\] of the nominal flight at the terminal interface.
    #[must_use]
    pub fn interface_altitude_m(&self) -> f64 {
        self.interface_radius_m() - self.planet_radius_m
    }

    /// E-hat \[-\] of the nominal flight at the terminal interface (the stored profile's
    /// normaliser: the nominal entry's; NaN for a state it refuses).
    #[must_use]
    pub fn interface_normalized_energy(&self) -> f64 {
        self.stack
            .profile
            .energy
            .normalized(self.interface_radius_m(), self.interface_speed_m_s)
            .unwrap_or(f64::NAN)
    }

    /// The guidance settings as stored with each case: `None` for the defaults.
    #[must_use]
    pub fn guidance_key(&self) -> Option<CampaignGuidance> {
        (self.guidance != CampaignGuidance::default()).then(|| self.guidance.clone())
    }

    /// Aim at `target` (the scenario's own target; the downrange for the errors is its
    /// great-circle angle from the entry point).
    pub fn aim_at(&mut self, target: TargetPoint<f64>) {
        let e = &self.scenario.entry;
        self.stack.target = Some(RangeTarget::Point(target));
        self.target_downrange_rad = central_angle(
            e.latitude_rad,
            e.longitude_rad,
            target.latitude_rad,
            target.longitude_rad,
        )
        .unwrap_or(f64::NAN);
    }

    /// Put the target `downrange_rad` along the entry great circle.
    pub fn retarget(&mut self, downrange_rad: f64) {
        self.stack.target = Some(RangeTarget::Point(along_heading(
            &self.scenario.entry,
            downrange_rad,
        )));
        self.target_downrange_rad = downrange_rad;
    }

    /// The target point at the terminal interface (the stack's; NaN if it had none, which a
    /// setup this module built always has).
    #[must_use]
    pub fn target(&self) -> TargetPoint<f64> {
        match self.stack.target {
            Some(RangeTarget::Point(p)) => p,
            _ => TargetPoint {
                latitude_rad: f64::NAN,
                longitude_rad: f64::NAN,
            },
        }
    }

    /// The stack `mode` flies: the full stack with the layers off that the mode leaves out
    /// ([`super::Mode::layers`],
    /// [`StackConfig::masked`](guidance_core::stack::StackConfig::masked)).
    #[must_use]
    pub fn stack_of(&self, mode: super::Mode) -> HostStackConfig<f64> {
        self.stack.masked(mode.layers())
    }

    /// Great-circle distance \[m\] from (lat, lon) to the target.
    #[must_use]
    pub fn distance_to_target_m(&self, lat: f64, lon: f64, radius_m: f64) -> f64 {
        let t = self.target();
        central_angle(lat, lon, t.latitude_rad, t.longitude_rad)
            .map_or(f64::INFINITY, |a| a * radius_m)
    }
}
