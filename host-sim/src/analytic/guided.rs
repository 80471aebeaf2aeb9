//! Node-guided glide: the glide closed form flown segment by segment along an energy-indexed
//! node table (the analytical SRM design problem, thesis sec. 9.2).
//!
//! The closed form flies one constant lift setting from a state it imposes (eq. 3.78/3.79), so
//! a guidance profile is a chain of glides:
//!
//! * **Segments.** Node `k` of the table `[E-hat, alpha, sigma]` sets the bank flown from its
//!   normalised energy down to node `k + 1`'s (zero-order hold on energy: the thesis'
//!   analytical simulator "sets a value at the start of a trajectory segment", sec. 1). The
//!   last node's bank is held to the end (as the closed loop holds its last command; with the
//!   presets' last node at `E-hat = 0` it is never reached). The vehicle must be steered by bank only (a trim-only
//!   vehicle such as the SRM capsule, thesis sec. 4.2.1): `C_L = C_L,trim`, bank `sigma`.
//! * **Entry.** The first segment starts at the entry altitude with the speed and flight-path
//!   angle that the closed form imposes for the first node's lift (thesis sec. 9.2: 100 km
//!   gives 7658.34 m/s and -0.056 deg for the SRM lift up); that state is `E-hat = 1`
//!   (`E-hat = (E - E_0)/(E_entry - E_0)`, `E = V^2/2 - mu/r`, `E_0 = -mu/R`, ERRATA sec. 3.7;
//!   `E_entry` of the first sample, the second-order point at `u_E`, which lies a few metres
//!   off the first-order imposed state).
//! * **Segment joins conserve energy.** A later segment starts where its own glide's imposed
//!   state has the energy reached at the node: the reference altitude is found by bisection
//!   (the imposed energy rises with the altitude). The closed form has no transient, so the
//!   altitude and speed jump along the energy level to the new equilibrium (the vehicle's
//!   phugoid is not modelled); time and range angle are continuous. Keeping the altitude
//!   instead would make the speed jump up (thesis sec. 8.1.5), creating energy.
//! * **End.** At the termination altitude (in any segment); a join whose new equilibrium lies
//!   below the termination altitude ends the glide at the join.
//! * **Peaks and rates.** Peak heat flux and g-load are the closed forms' own maximisations per
//!   segment; the g-load rate is the largest finite difference between samples *within* a
//!   segment: the jumps at the joins take no time in the model and are not rates (a real
//!   vehicle's g-rate is therefore under-estimated, as the module documentation says of the
//!   smooth closed forms in general).

use guidance_core::vinh::{GlideSolution, VinhError};

use super::glide::u_at_radius;
use super::samples::{Ctx, Planar};
use super::{
    AnalyticError, AnalyticRun, AnalyticVehicle, LiftSetting, Phase, Placement, evenly_spaced,
    planet, setting, vinh_atmosphere, vinh_planet,
};
use crate::dynamics::SphericalState;
use crate::env::{ExponentialAtmosphere, Planet};
use crate::sim::TerminationReason;

/// Samples per segment of a node-guided glide (both ends included).
pub const SEGMENT_POINTS: usize = 41;

/// Highest reference altitude \[m\] searched for a segment's start.
const MAX_JOIN_ALTITUDE_M: f64 = 200_000.0;

/// Decades of `u` below the segment start scanned for the termination altitude (a capsule's
/// equilibrium glide reaches 25 km only near 200 m/s, `u ~ 5e-4`).
const END_SCAN_DECADES: u32 = 6;

/// Bisection steps of the join altitude and the end speed (interval halved each step).
const BISECTIONS: usize = 80;

/// A node-guided glide's set-up.
#[derive(Clone, Copy, Debug)]
pub struct GuidedGlide<'a> {
    /// The vehicle (must be bank-only: trim coefficients).
    pub vehicle: &'a AnalyticVehicle,
    /// The closed forms' exponential atmosphere.
    pub atmosphere: &'a ExponentialAtmosphere,
    /// Entry altitude \[m\].
    pub entry_altitude_m: f64,
    /// Where the planar trajectory lies on the sphere.
    pub placement: Placement,
    /// Node table `[E-hat, alpha_rad, sigma_rad]`, strictly decreasing energies, at least 2
    /// nodes; the angle of attack is not used (bank-only vehicle).
    pub nodes: &'a [[f64; 3]],
    /// Termination altitude \[m\], below the entry altitude.
    pub end_altitude_m: f64,
}

struct Energy {
    mu: f64,
    e0: f64,
    span: f64,
}

impl Energy {
    fn of(&self, radius_m: f64, speed_m_s: f64) -> f64 {
        0.5 * speed_m_s * speed_m_s - self.mu / radius_m
    }

    fn at(&self, normalized: f64) -> f64 {
        self.e0 + normalized * self.span
    }
}

fn check(g: &GuidedGlide<'_>) -> Result<f64, AnalyticError> {
    let Some(trim) = g.vehicle.trim_cl else {
        return Err(AnalyticError::NotBankOnly {
            vehicle: g.vehicle.name.clone(),
        });
    };
    if g.nodes.len() < 2 {
        return Err(setting(
            "nodes",
            g.nodes.len() as f64,
            "give at least 2 nodes (first and last)",
        ));
    }
    for w in g.nodes.windows(2) {
        if let [a, b] = w
            && b[0].partial_cmp(&a[0]) != Some(std::cmp::Ordering::Less)
        {
            return Err(setting(
                "nodes.energy",
                b[0],
                "node energies must be finite and strictly decreasing",
            ));
        }
    }
    for n in g.nodes {
        if !(n.iter().all(|v| v.is_finite())) {
            return Err(setting("nodes", f64::NAN, "node values must be finite"));
        }
    }
    if !(g.entry_altitude_m.is_finite() && g.entry_altitude_m > 0.0) {
        return Err(setting(
            "entry_altitude_m",
            g.entry_altitude_m,
            "must be finite and positive",
        ));
    }
    if !(g.end_altitude_m.is_finite()
        && g.end_altitude_m >= 0.0
        && g.end_altitude_m < g.entry_altitude_m)
    {
        return Err(setting(
            "end_altitude_m",
            g.end_altitude_m,
            "must be finite, >= 0 and below the entry altitude",
        ));
    }
    Ok(trim)
}

/// The glide of `lift` from reference radius `radius_m`.
fn glide_at(
    g: &GuidedGlide<'_>,
    planet: &Planet,
    lift: &LiftSetting,
    radius_m: f64,
) -> Result<GlideSolution<f64>, AnalyticError> {
    GlideSolution::new(
        &vinh_planet(planet),
        &vinh_atmosphere(g.atmosphere, planet),
        &g.vehicle.params(),
        &g.vehicle.lift_control(lift)?,
        radius_m,
    )
    .map_err(|error| AnalyticError::Domain {
        phase: "glide",
        error,
    })
}

/// Energy \[J/kg\] of a glide's first point (`u = u_E` on the second-order solution, a few
/// metres off the first-order imposed state), where its samples start.
fn start_energy(en: &Energy, glide: &GlideSolution<f64>) -> f64 {
    glide
        .point_at_u(glide.u_entry())
        .map_or(f64::INFINITY, |p| en.of(p.radius_m, p.speed_m_s))
}

/// The glide of `lift` whose first point has energy `target` \[J/kg\]: bisection on the
/// reference altitude between the termination altitude and [`MAX_JOIN_ALTITUDE_M`] (a domain
/// error counts as "too high": the closed form fails towards circular speed). `None`: the
/// glide ends at the join (the new equilibrium at that energy lies below the termination
/// altitude).
fn join(
    g: &GuidedGlide<'_>,
    planet: &Planet,
    en: &Energy,
    lift: &LiftSetting,
    target: f64,
) -> Result<Option<GlideSolution<f64>>, AnalyticError> {
    let r = planet.radius_m;
    let low = glide_at(g, planet, lift, r + g.end_altitude_m)?;
    if start_energy(en, &low) >= target {
        return Ok(None);
    }
    let (mut lo, mut hi) = (g.end_altitude_m, MAX_JOIN_ALTITUDE_M);
    let mut best = low;
    let mut last_err = None;
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        match glide_at(g, planet, lift, r + mid) {
            Ok(gl) if start_energy(en, &gl) < target => {
                lo = mid;
                best = gl;
            }
            Ok(_) => hi = mid,
            Err(e) => {
                hi = mid;
                last_err = Some(e);
            }
        }
    }
    // The bisection converges on the target unless the closed form's domain ends below it.
    let miss = (target - start_energy(en, &best)) / en.span;
    if miss > 1e-9 {
        return Err(last_err.unwrap_or(AnalyticError::Domain {
            phase: "glide",
            error: VinhError::GlideNearCircular,
        }));
    }
    Ok(Some(best))
}

/// `u` of `glide` where the energy falls to `target` \[J/kg\], in `[u_low, u_E]` (the energy
/// rises with `u` along a glide).
fn u_at_energy(
    glide: &GlideSolution<f64>,
    en: &Energy,
    target: f64,
    u_low: f64,
) -> Result<f64, VinhError> {
    let energy = |u: f64| glide.point_at_u(u).map(|p| en.of(p.radius_m, p.speed_m_s));
    let (mut lo, mut hi) = (u_low, glide.u_entry());
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if energy(mid)? < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Fly the node table with the glide closed form (module documentation), [`SEGMENT_POINTS`]
/// samples per segment.
///
/// # Errors
/// [`AnalyticError::NotBankOnly`] for a vehicle steered by the angle of attack,
/// [`AnalyticError::Setting`] for a bad table or altitude (naming the field),
/// [`AnalyticError::Domain`] when a segment leaves the closed form's domain (e.g. a bank
/// near 90 deg: [`VinhError::GlideNoLift`], or a join near circular speed).
pub fn guided_glide(g: &GuidedGlide<'_>) -> Result<AnalyticRun, AnalyticError> {
    let trim = check(g)?;
    let planet = planet();
    let dom = |error| AnalyticError::Domain {
        phase: "glide",
        error,
    };
    let lifts: Vec<LiftSetting> = g
        .nodes
        .iter()
        .map(|n| LiftSetting {
            cl: trim,
            bank_rad: n[2],
        })
        .collect();
    let first_lift = lifts.first().copied().unwrap_or(LiftSetting {
        cl: trim,
        bank_rad: 0.0,
    });
    let mut glide = glide_at(
        g,
        &planet,
        &first_lift,
        planet.radius_m + g.entry_altitude_m,
    )?;
    let entry = glide.imposed_entry();
    let mu = planet.mu_m3_s2;
    let e0 = -mu / planet.radius_m;
    let mut en = Energy { mu, e0, span: 1.0 };
    // E-hat = 1 at the first sample (the second-order point at u_E).
    let e_entry = start_energy(&en, &glide);
    en.span = e_entry - e0;
    if !(en.span.is_finite() && en.span > 0.0) {
        return Err(dom(VinhError::NonFiniteResult));
    }
    let end_radius = planet.radius_m + g.end_altitude_m;
    let mut rows: Vec<Planar> = Vec::new();
    let mut theta0 = 0.0;
    let (mut peak_q, mut peak_g): (Option<Planar>, Option<Planar>) = (None, None);
    // The last node's bank is held to the end, as the closed loop holds the last command.
    let next_energies = g
        .nodes
        .iter()
        .skip(1)
        .map(|n| n[0])
        .chain(std::iter::once(f64::NEG_INFINITY));
    for (seg, (lift, next_energy)) in lifts.iter().zip(next_energies).enumerate() {
        if seg > 0 {
            let start = rows
                .last()
                .map_or(e_entry, |p: &Planar| en.of(p.radius, p.speed));
            match join(g, &planet, &en, lift, start)? {
                Some(next) => glide = next,
                None => break,
            }
        }
        let u_e = glide.u_entry();
        let u_alt = u_at_radius(&glide, end_radius, END_SCAN_DECADES).map_err(dom)?;
        let target = en.at(next_energy);
        let alt_end = glide.point_at_u(u_alt).map_err(dom)?;
        let (u_end, ends_here) = if en.of(alt_end.radius_m, alt_end.speed_m_s) >= target {
            (u_alt, true)
        } else {
            (u_at_energy(&glide, &en, target, u_alt).map_err(dom)?, false)
        };
        for i in 0..SEGMENT_POINTS {
            let p = glide
                .point_at_u(evenly_spaced(u_e, u_end, i, SEGMENT_POINTS))
                .map_err(dom)?;
            let mut q = Planar::from(p);
            q.theta += theta0;
            q.segment = seg;
            rows.push(q);
        }
        let v_end = rows.last().map_or(entry.speed_m_s, |p| p.speed);
        let shift = |p: Planar| Planar {
            theta: p.theta + theta0,
            segment: seg,
            ..p
        };
        let q = shift(Planar::from(glide.peak_heat_flux(v_end).map_err(dom)?));
        let n = shift(Planar::from(glide.peak_g_load(v_end).map_err(dom)?));
        if peak_q.is_none_or(|b| q.heat_flux > b.heat_flux) {
            peak_q = Some(q);
        }
        if peak_g.is_none_or(|b| n.g_load > b.g_load) {
            peak_g = Some(n);
        }
        theta0 = rows.last().map_or(theta0, |p| p.theta);
        if ends_here {
            break;
        }
    }
    let (Some(peak_q), Some(peak_g)) = (peak_q, peak_g) else {
        return Err(setting("nodes", 0.0, "no segment was flown"));
    };
    let ctx = Ctx {
        vehicle: g.vehicle,
        lifts: &lifts,
        atmosphere: g.atmosphere,
        planet,
        placement: g.placement,
    };
    let result = ctx.assemble(&rows, peak_q, peak_g, TerminationReason::Altitude);
    let deepest = rows.iter().map(|p| p.radius).fold(f64::INFINITY, f64::min) - planet.radius_m;
    Ok(AnalyticRun {
        result,
        phase: Phase::Glide,
        entry: SphericalState {
            radius_m: entry.radius_m,
            longitude_rad: g.placement.longitude_rad,
            latitude_rad: g.placement.latitude_rad,
            speed_m_s: entry.speed_m_s,
            flight_path_angle_rad: entry.flight_path_angle_rad,
            heading_rad: g.placement.heading_rad,
        },
        deepest_altitude_m: deepest,
        lift: first_lift,
        atmosphere: *g.atmosphere,
    })
}
