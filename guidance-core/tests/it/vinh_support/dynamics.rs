//! Reference dynamics written from the governing equations, independently of the library:
//! dimensional planar equations of motion (thesis eq. 3.14, planar, non-rotating, central
//! gravity, exponential atmosphere), the exact non-dimensional system (eq. 3.29-3.31), the
//! simplified one (3.33-3.35), its second-order form (3.49), and two-body motion in Cartesian
//! coordinates.

use super::ode::{Settings, integrate, sampled_max};
use super::vehicles::{H_S, MU, R_EARTH, RHO0, Vehicle};

pub const C_STAR: f64 = 1.1097e8;
pub const VC: f64 = 7905.4;

pub fn density(r: f64) -> f64 {
    RHO0 * (-(r - R_EARTH) / H_S).exp()
}

pub fn chapman(rn: f64, rho: f64, v: f64) -> f64 {
    C_STAR / rn.sqrt() * (rho / 1.225).sqrt() * (v / VC).powf(3.15)
}

/// Lift setting: total lambda and cos(bank).
#[derive(Clone, Copy, Debug)]
pub struct Lift {
    pub lambda: f64,
    pub cos_bank: f64,
}

/// Summary of a skip (reference or closed form), dimensional.
#[derive(Clone, Copy, Debug, Default)]
pub struct SkipSummary {
    pub exit_speed: f64,
    pub exit_fpa: f64,
    pub exit_range_angle: f64,
    pub min_radius: f64,
    pub peak_heat_flux: f64,
    pub peak_g_load: f64,
}

/// Dimensional planar EOM, state [r, V, gamma, theta], time t.
pub fn eom_dim(veh: &Vehicle, lift: Lift) -> impl Fn(f64, &[f64; 4]) -> [f64; 4] + '_ {
    move |_t, y| {
        let [r, v, g, _] = *y;
        let rho = density(r);
        let cl = lift.lambda * veh.cl_star();
        let cd = veh.cd0 + veh.k * cl * cl;
        let q = 0.5 * rho * v * v * veh.area_m2 / veh.mass_kg;
        let d = q * cd;
        let l = q * cl * lift.cos_bank;
        let grav = MU / (r * r);
        [
            v * g.sin(),
            -d - grav * g.sin(),
            (l - grav * g.cos()) / v + v * g.cos() / r,
            v * g.cos() / r,
        ]
    }
}

/// Integrate the dimensional EOM from the entry state until the vehicle climbs back through the
/// entry radius. `None` if it does not (captured or hits the surface within `t_max`).
pub fn skip_dim(veh: &Vehicle, lift: Lift, r_e: f64, v_e: f64, g_e: f64) -> Option<SkipSummary> {
    let f = eom_dim(veh, lift);
    let sol = integrate(
        f,
        0.0,
        [r_e, v_e, g_e, 0.0],
        20_000.0,
        Settings::tight(2.0),
        |_t, y| {
            if y[0] < R_EARTH {
                -1.0
            } else if y[2] > 0.0 {
                r_e - y[0]
            } else {
                1.0
            }
        },
    );
    let (_, ye) = sol.event?;
    if ye[0] < R_EARTH + 1.0 {
        return None;
    }
    let min_radius = sol
        .samples
        .iter()
        .map(|(_, y)| y[0])
        .fold(f64::INFINITY, f64::min);
    let (_, q) = sampled_max(&sol.samples, |_t, y| {
        chapman(veh.nose_radius_m, density(y[0]), y[1]).ln()
    });
    let (_, gl) = sampled_max(&sol.samples, |_t, y| {
        let rho = density(y[0]);
        let cl = lift.lambda * veh.cl_star();
        let cd = veh.cd0 + veh.k * cl * cl;
        let qd = 0.5 * rho * y[1] * y[1] * veh.area_m2 / veh.mass_kg;
        (qd * (cd * cd + cl * cl).sqrt() / 9.806_65).ln()
    });
    Some(SkipSummary {
        exit_speed: ye[1],
        exit_fpa: ye[2],
        exit_range_angle: ye[3],
        min_radius: refine_min_radius(&sol.samples),
        peak_heat_flux: q.exp(),
        peak_g_load: gl.exp(),
    })
    .map(|mut s| {
        s.min_radius = s.min_radius.min(min_radius);
        s
    })
}

fn refine_min_radius(samples: &[(f64, [f64; 4])]) -> f64 {
    let (_, negr) = sampled_max(samples, |_t, y| -y[0]);
    -negr
}

/// Non-dimensional constants computed here from the raw data (test-side re-implementation of
/// eq. 3.18-3.28, used to check the library's set-up and to drive eq. 3.29-3.35/3.49).
#[derive(Clone, Copy, Debug)]
pub struct RefConsts {
    pub e_star: f64,
    pub b: f64,
    pub lambda: f64,
    pub k1: f64,
    pub eta: f64,
    pub k: f64,
    pub alpha: f64,
    pub s: f64,
    pub c: f64,
    pub r_e: f64,
    pub v_e: f64,
    pub rho_e: f64,
}

impl RefConsts {
    pub fn new(veh: &Vehicle, lift: Lift, r_e: f64, v_e: f64, g_e: f64) -> Self {
        let rho_e = density(r_e);
        let e_star = 1.0 / (2.0 * (veh.k * veh.cd0).sqrt());
        let b = rho_e * veh.area_m2 * r_e / (2.0 * veh.mass_kg) * (veh.cd0 / veh.k).sqrt();
        let s = r_e / H_S;
        let eta = rho_e * veh.area_m2 * veh.cd0 / veh.mass_kg * (H_S * r_e).sqrt();
        let k = 2.0 * e_star / (s.sqrt() * b);
        let alpha = MU / r_e / (v_e * v_e);
        Self {
            e_star,
            b,
            lambda: lift.lambda,
            k1: b * lift.lambda * lift.cos_bank,
            eta,
            k,
            alpha,
            s,
            c: -s.sqrt() * g_e.sin(),
            r_e,
            v_e,
            rho_e,
        }
    }
}

/// Which non-dimensional system to integrate, state [x, w = eta v, phi], independent tau.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NdSystem {
    /// Eq. 3.29-3.31.
    Exact,
    /// Eq. 3.33-3.35.
    Simplified,
    /// Eq. 3.49.
    SecondOrder,
}

pub fn eom_nd(c: RefConsts, sys: NdSystem) -> impl Fn(f64, &[f64; 3]) -> [f64; 3] {
    move |_tau, y| {
        let [x, w, phi] = *y;
        let l = 1.0 + c.lambda * c.lambda;
        let ey = x.exp();
        match sys {
            NdSystem::Exact => {
                let h1 = 1.0 - x / c.s; // 1 + h, h = -x H_s / r_E
                let cg = (1.0 - phi * phi / c.s).sqrt();
                let ew = w.exp();
                [
                    h1 * phi / cg,
                    c.eta * (h1 * l * ey / cg - c.k * c.alpha * phi * ew / (h1 * cg)),
                    -h1 * c.k1 * ey + cg * c.alpha * ew / h1 - cg,
                ]
            }
            NdSystem::Simplified => {
                let ew = w.exp();
                [
                    phi,
                    c.eta * (l * ey - c.k * c.alpha * phi * ew),
                    -c.k1 * ey - (1.0 - c.alpha * ew),
                ]
            }
            NdSystem::SecondOrder => [
                phi,
                c.eta * (l * ey - c.k * c.alpha * phi * (1.0 + w)),
                -c.k1 * ey - (1.0 - c.alpha) + c.alpha * w,
            ],
        }
    }
}

/// Skip of a non-dimensional system from `x = 0, w = 0, phi = c` to the return to `x = 0`.
/// Dimensionalised with eq. 3.59-3.61 and the test-side constants.
pub fn skip_nd(veh: &Vehicle, c: RefConsts, sys: NdSystem) -> Option<SkipSummary> {
    let f = eom_nd(c, sys);
    let x_surf = (c.r_e - R_EARTH) / H_S;
    let sol = integrate(
        f,
        0.0,
        [0.0, 0.0, c.c],
        1.0e4,
        Settings::tight(0.01),
        |_t, y| {
            if y[0] > x_surf {
                -1.0
            } else if y[2] < 0.0 {
                y[0]
            } else {
                1.0
            }
        },
    );
    let (tau_e, ye) = sol.event?;
    if ye[0] > 0.5 * x_surf {
        return None;
    }
    let (_, xmax) = sampled_max(&sol.samples, |_t, y| y[0]);
    let q_e = chapman(veh.nose_radius_m, c.rho_e, c.v_e);
    let (_, lq) = sampled_max(&sol.samples, |_t, y| 0.5 * y[0] - 1.575 * y[1]);
    let (_, lg) = sampled_max(&sol.samples, |_t, y| y[0] - y[1]);
    let cl = c.lambda * veh.cl_star();
    let cd = veh.cd0 + veh.k * cl * cl;
    let g_e0 = 0.5 * c.rho_e * c.v_e * c.v_e * veh.area_m2 / veh.mass_kg
        * (cd * cd + cl * cl).sqrt()
        / 9.806_65;
    Some(SkipSummary {
        exit_speed: c.v_e * (-0.5 * ye[1]).exp(),
        exit_fpa: (-ye[2] / c.s.sqrt()).asin(),
        exit_range_angle: tau_e / c.s.sqrt(),
        min_radius: c.r_e - H_S * xmax,
        peak_heat_flux: q_e * lq.exp(),
        peak_g_load: g_e0 * lg.exp(),
    })
}

/// Two-body motion, planar Cartesian state [x, y, vx, vy].
pub fn two_body(_t: f64, s: &[f64; 4]) -> [f64; 4] {
    let r = (s[0] * s[0] + s[1] * s[1]).sqrt();
    let a = -MU / (r * r * r);
    [s[2], s[3], a * s[0], a * s[1]]
}
