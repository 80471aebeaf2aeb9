//! Validation of the Vinh closed forms (`guidance_core::vinh`) against numerical integration of
//! the governing equations (reference: thesis eq. 3.14 planar / 3.29-3.31 / 3.33-3.35 / 3.49,
//! integrated test-side with an adaptive Dormand-Prince 5(4), rtol 1e-11), and of the Kepler arc
//! against two-body propagation in Cartesian coordinates.
//!
//! Environment of every comparison (the thesis' "simplified environment", sec. 8.1.3): spherical
//! non-rotating Earth (mu = 3.986004418e14 m^3/s^2, R = 6378137 m), inverse-square gravity,
//! exponential atmosphere rho0 = 1.225 kg/m^3, H_s = 7200 m. Vehicles: SRM capsule (thesis table
//! 2.3, polar back-derived, see `vinh_support::vehicles::srm`) and HORUS-2B (table 2.1 with the
//! table 8.1 polar read from shared/data/horus2b/drag_polar.csv).
//!
//! `print_vinh_error_table` (ignored) prints the measured errors as the Markdown tables of
//! docs/validation/vinh-numerical.md.

use crate::vinh_support::dynamics::{self, Lift, NdSystem, RefConsts, SkipSummary};
use crate::vinh_support::inputs::{atmosphere, params, planet};
use crate::vinh_support::ode::{Settings, integrate, sampled_max};
use crate::vinh_support::vehicles::{self, H_S, MU, R_EARTH, RHO0, Vehicle};
use guidance_core::vinh::{
    BallisticArc, EntryState, ExpAtmosphere, GlideSolution, LiftControl, NonDim, Planet,
    PredictorConfig, SkipSolution, VehicleParams, VinhError, predict,
};

pub fn lift_control(l: Lift) -> LiftControl<f64> {
    LiftControl {
        lambda: l.lambda,
        vertical_fraction: l.cos_bank,
    }
}
pub fn nondim(
    v: &Vehicle,
    lift: Lift,
    r: f64,
    speed: f64,
    fpa: f64,
) -> Result<NonDim<f64>, VinhError> {
    NonDim::new(
        &planet(),
        &atmosphere(),
        &params(v),
        &lift_control(lift),
        &EntryState {
            radius_m: r,
            speed_m_s: speed,
            flight_path_angle_rad: fpa,
        },
    )
}

fn closed_skip(sol: &SkipSolution<f64>) -> SkipSummary {
    let e = sol.exit();
    let d = sol.deepest_point().unwrap();
    SkipSummary {
        exit_speed: e.speed_m_s,
        exit_fpa: e.flight_path_angle_rad,
        exit_range_angle: e.range_angle_rad,
        min_radius: d.radius_m,
        peak_heat_flux: sol.peak_heat_flux().unwrap().heat_flux_w_m2,
        peak_g_load: sol.peak_g_load().unwrap().g_load,
    }
}

/// Entry interface of the thesis (table 2.1): 122 km.
const H_ENTRY: f64 = 122_000.0;
const SKIP_SPEEDS: [f64; 4] = [7435.5, 7800.0, 9000.0, 10500.0];
const SKIP_FPAS_DEG: [f64; 4] = [-2.0, -3.0, -5.0, -7.0];
const SKIP_LAMBDAS: [f64; 2] = [0.5, 1.0];

/// One skip case compared with the exact integration.
#[derive(Clone, Copy, Debug)]
pub struct SkipRow {
    pub v_e: f64,
    pub fpa_deg: f64,
    pub lambda: f64,
    pub eta_v_exit: f64,
    pub reference: SkipSummary,
    pub closed: SkipSummary,
}

impl SkipRow {
    pub fn exit_speed_rel(&self) -> f64 {
        (self.closed.exit_speed - self.reference.exit_speed) / self.reference.exit_speed
    }
    pub fn exit_fpa_abs_deg(&self) -> f64 {
        (self.closed.exit_fpa - self.reference.exit_fpa).to_degrees()
    }
    pub fn range_rel(&self) -> f64 {
        (self.closed.exit_range_angle - self.reference.exit_range_angle)
            / self.reference.exit_range_angle
    }
    pub fn depth_abs_km(&self) -> f64 {
        (self.closed.min_radius - self.reference.min_radius) / 1000.0
    }
    pub fn heat_rel(&self) -> f64 {
        (self.closed.peak_heat_flux - self.reference.peak_heat_flux) / self.reference.peak_heat_flux
    }
    pub fn g_rel(&self) -> f64 {
        (self.closed.peak_g_load - self.reference.peak_g_load) / self.reference.peak_g_load
    }
}

/// Outcome counts of a skip grid.
#[derive(Clone, Copy, Debug, Default)]
pub struct SkipCounts {
    /// Both exit: compared.
    pub compared: usize,
    /// Exact captured, closed form reports `NoAtmosphericExit` (agree).
    pub both_captured: usize,
    /// Exact captured, closed form exits (disagree).
    pub closed_exits_exact_captured: usize,
    /// Exact exits, closed form reports no exit (disagree).
    pub closed_captured_exact_exits: usize,
    /// Closed form returned another domain error.
    pub other_errors: usize,
}

/// Run the skip grid for one vehicle against the integration of `sys`.
pub fn skip_grid(veh: &Vehicle, sys: NdSystem) -> (Vec<SkipRow>, SkipCounts) {
    let r_e = R_EARTH + H_ENTRY;
    let mut rows = Vec::new();
    let mut n = SkipCounts::default();
    for &v_e in &SKIP_SPEEDS {
        for &g_deg in &SKIP_FPAS_DEG {
            for &lam in &SKIP_LAMBDAS {
                let lift = Lift {
                    lambda: lam,
                    cos_bank: 1.0,
                };
                let g_e = g_deg.to_radians();
                let reference = match sys {
                    NdSystem::Exact => dynamics::skip_dim(veh, lift, r_e, v_e, g_e),
                    _ => dynamics::skip_nd(veh, RefConsts::new(veh, lift, r_e, v_e, g_e), sys),
                };
                let nd = nondim(veh, lift, r_e, v_e, g_e).unwrap();
                match (SkipSolution::new(&nd), reference) {
                    (Ok(s), Some(reference)) => {
                        n.compared += 1;
                        rows.push(SkipRow {
                            v_e,
                            fpa_deg: g_deg,
                            lambda: lam,
                            eta_v_exit: s.exit().eta_v,
                            reference,
                            closed: closed_skip(&s),
                        });
                    }
                    (Ok(_), None) => n.closed_exits_exact_captured += 1,
                    (Err(VinhError::NoAtmosphericExit), None) => n.both_captured += 1,
                    (Err(VinhError::NoAtmosphericExit), Some(_)) => {
                        n.closed_captured_exact_exits += 1
                    }
                    (Err(_), _) => n.other_errors += 1,
                }
            }
        }
    }
    (rows, n)
}

fn max_abs(rows: &[SkipRow], f: impl Fn(&SkipRow) -> f64) -> f64 {
    rows.iter().map(|r| f(r).abs()).fold(0.0, f64::max)
}

/// The library's non-dimensional constants equal the thesis definitions (eq. 3.18-3.28)
/// re-computed test-side, and the exact non-dimensional system 3.29-3.31 (integrated with those
/// constants) reproduces the dimensional equations of motion: the reference for everything else.
#[test]
fn validate_vinh_skip_nondim_setup_and_exact_equations() {
    let r_e = R_EARTH + H_ENTRY;
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        for &(v_e, g_deg, lam, cb) in &[(7800.0, -3.0, 1.0, 1.0), (9000.0, -5.0, 0.5, 0.6)] {
            let lift = Lift {
                lambda: lam,
                cos_bank: cb,
            };
            let g_e = f64::to_radians(g_deg);
            let rc = RefConsts::new(&veh, lift, r_e, v_e, g_e);
            let c = nondim(&veh, lift, r_e, v_e, g_e).unwrap().constants();
            for (name, lib, refv) in [
                ("E*", c.e_star, rc.e_star),
                ("B", c.b, rc.b),
                ("k1", c.k1, rc.k1),
                ("eta", c.eta, rc.eta),
                ("k", c.k, rc.k),
                ("alpha", c.alpha, rc.alpha),
                ("s", c.s, rc.s),
                ("c", c.c, rc.c),
            ] {
                assert!(
                    (lib - refv).abs() <= 1e-12 * refv.abs(),
                    "{name}: {lib} vs {refv}"
                );
            }
            // E = actual vertical L/D (ERRATA): C_L cos(sigma) / C_D.
            let cl = lam * veh.cl_star();
            let e_v = cl * cb / (veh.cd0 + veh.k * cl * cl);
            assert!((c.e_vertical - e_v).abs() < 1e-12 * e_v);
            let dim = dynamics::skip_dim(&veh, lift, r_e, v_e, g_e).unwrap();
            let nd = dynamics::skip_nd(&veh, rc, NdSystem::Exact).unwrap();
            assert!((dim.exit_speed - nd.exit_speed).abs() < 1e-6 * dim.exit_speed);
            assert!((dim.exit_fpa - nd.exit_fpa).abs() < 1e-7);
            assert!((dim.exit_range_angle - nd.exit_range_angle).abs() < 1e-7);
            assert!((dim.min_radius - nd.min_radius).abs() < 1.0);
            assert!((dim.peak_heat_flux - nd.peak_heat_flux).abs() < 1e-5 * dim.peak_heat_flux);
        }
    }
}

/// Second-order skip (eq. 3.39-3.61, ERRATA) against the exact equations of motion, SRM capsule,
/// entry at 122 km, V_E in {7435.5, 7800, 9000, 10500} m/s, gamma_E in {-2, -3, -5, -7} deg,
/// lambda in {0.5, 1}. The thesis states no number for the skip (sec. 8.2.1: "minimal
/// deviations", deviations "near the atmospheric exit"); the bounds are the measured maxima
/// (docs/validation/vinh-numerical.md) rounded up, so that a regression in any term fails.
#[test]
fn validate_vinh_skip_srm_against_exact_integration() {
    let (rows, n) = skip_grid(&vehicles::srm(), NdSystem::Exact);
    assert!(n.compared >= 20, "{n:?}");
    assert_eq!(n.other_errors, 0, "{n:?}");
    // Measured maxima: 0.52 %, 0.356 deg, 11.2 %, 0.247 km, 1.65 %, 3.31 %.
    assert!(
        max_abs(&rows, SkipRow::exit_speed_rel) < 0.006,
        "exit speed"
    );
    assert!(max_abs(&rows, SkipRow::exit_fpa_abs_deg) < 0.4, "exit fpa");
    assert!(max_abs(&rows, SkipRow::range_rel) < 0.12, "range angle");
    assert!(
        max_abs(&rows, SkipRow::depth_abs_km) < 0.3,
        "deepest altitude"
    );
    assert!(max_abs(&rows, SkipRow::heat_rel) < 0.02, "peak heat flux");
    assert!(max_abs(&rows, SkipRow::g_rel) < 0.035, "peak g-load");
}

/// As the SRM test, HORUS-2B with the Mach-20 polar of thesis table 8.1.
#[test]
fn validate_vinh_skip_horus_against_exact_integration() {
    let (rows, n) = skip_grid(&vehicles::horus(20.0), NdSystem::Exact);
    assert!(n.compared >= 20, "{n:?}");
    assert_eq!(n.other_errors, 0, "{n:?}");
    // Measured maxima: 0.80 %, 1.12 deg (lambda 0.5, 7435.5 m/s, -5 deg: shallow, marginal
    // exit), 10.5 %, 0.244 km, 1.58 %, 3.27 %.
    assert!(
        max_abs(&rows, SkipRow::exit_speed_rel) < 0.009,
        "exit speed"
    );
    assert!(max_abs(&rows, SkipRow::exit_fpa_abs_deg) < 1.2, "exit fpa");
    assert!(max_abs(&rows, SkipRow::range_rel) < 0.12, "range angle");
    assert!(
        max_abs(&rows, SkipRow::depth_abs_km) < 0.3,
        "deepest altitude"
    );
    assert!(max_abs(&rows, SkipRow::heat_rel) < 0.02, "peak heat flux");
    assert!(max_abs(&rows, SkipRow::g_rel) < 0.035, "peak g-load");
}

/// The closed form approximates the second-order system 3.49 (the equations it was derived
/// from): against its integration the deepest altitude agrees to 0.05 km (measured 0.045 km) and
/// the exit speed to 0.9 % (measured 0.84 %); the range angle keeps the error of the quadratic
/// fit of eq. 3.42 (measured up to 14.6 %, bound 15 %).
#[test]
fn validate_vinh_skip_against_second_order_system() {
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        let (rows, n) = skip_grid(&veh, NdSystem::SecondOrder);
        assert!(n.compared >= 20, "{n:?}");
        assert!(
            max_abs(&rows, SkipRow::depth_abs_km) < 0.05,
            "{} depth",
            veh.name
        );
        assert!(
            max_abs(&rows, SkipRow::exit_speed_rel) < 0.009,
            "{} speed",
            veh.name
        );
        assert!(
            max_abs(&rows, SkipRow::range_rel) < 0.15,
            "{} range",
            veh.name
        );
    }
}

/// The thesis (sec. 8.2.1) reports complex numbers for entry speeds above 11 km/s. The
/// corrected closed form stays real and close to the exact integration up to the validated
/// 14 km/s; the failure near 11 km/s is the hyperbolic arc after the exit (see
/// `vinh_domain_errors_are_typed`). Bounds: exit speed 2 %, range angle 14 %, deepest altitude
/// 0.3 km (measured during development: 1.7 %, 12.8 %).
#[test]
fn validate_vinh_skip_above_11_km_s() {
    let r_e = R_EARTH + H_ENTRY;
    let mut n = 0;
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        for &v_e in &[11_500.0, 12_500.0, 14_000.0] {
            for &g_deg in &[-3.0, -7.0, -10.0] {
                let lift = Lift {
                    lambda: 1.0,
                    cos_bank: 1.0,
                };
                let g_e = f64::to_radians(g_deg);
                let s = SkipSolution::new(&nondim(&veh, lift, r_e, v_e, g_e).unwrap()).unwrap();
                let ex = dynamics::skip_dim(&veh, lift, r_e, v_e, g_e).unwrap();
                let c = closed_skip(&s);
                assert!(
                    (c.exit_speed - ex.exit_speed).abs() < 0.02 * ex.exit_speed,
                    "{v_e} {g_deg}"
                );
                assert!(
                    (c.exit_range_angle - ex.exit_range_angle).abs() < 0.14 * ex.exit_range_angle
                );
                assert!((c.min_radius - ex.min_radius).abs() < 300.0);
                n += 1;
            }
        }
    }
    assert_eq!(n, 18);
}

/// Vinh's low-L/D remedy is exercised: for a steep low-lift entry the second-order root lies
/// beyond the first-order one (frozen `I`), and the result still matches the integration.
#[test]
fn validate_vinh_skip_low_ld_remedy() {
    let veh = vehicles::srm();
    let lift = Lift {
        lambda: 0.3,
        cos_bank: 1.0,
    };
    let (r_e, v_e, g_e) = (R_EARTH + H_ENTRY, 9000.0, f64::to_radians(-7.0));
    let s = SkipSolution::new(&nondim(&veh, lift, r_e, v_e, g_e).unwrap()).unwrap();
    assert!(s.low_ld_remedy_used());
    assert!(s.x1() > s.x1_first_order());
    let ex = dynamics::skip_dim(&veh, lift, r_e, v_e, g_e).unwrap();
    let d = s.deepest_point().unwrap();
    assert!((d.radius_m - ex.min_radius).abs() < 300.0);
    assert!((s.exit().speed_m_s - ex.exit_speed).abs() < 0.01 * ex.exit_speed);
}

/// Range of a SRM glide against the numerical solution (dimensional EOM, simplified
/// environment) from the imposed entry state (eq. 3.78/3.79) to the final speed.
fn glide_dim(veh: &Vehicle, lift: Lift, e: EntryState<f64>, v_f: f64) -> Option<(f64, f64, f64)> {
    let f = dynamics::eom_dim(veh, lift);
    let sol = integrate(
        f,
        0.0,
        [e.radius_m, e.speed_m_s, e.flight_path_angle_rad, 0.0],
        1.0e5,
        Settings::tight(2.0),
        |_t, y| if y[0] < R_EARTH { -1.0 } else { y[1] - v_f },
    );
    let (_, ye) = sol.event?;
    if ye[0] < R_EARTH + 1.0 {
        return None;
    }
    let (_, lq) = sampled_max(&sol.samples, |_t, y| {
        dynamics::chapman(veh.nose_radius_m, dynamics::density(y[0]), y[1]).ln()
    });
    let cl = lift.lambda * veh.cl_star();
    let cd = veh.cd0 + veh.k * cl * cl;
    let (_, lg) = sampled_max(&sol.samples, |_t, y| {
        (0.5 * dynamics::density(y[0]) * y[1] * y[1] * veh.area_m2 / veh.mass_kg
            * (cd * cd + cl * cl).sqrt()
            / 9.806_65)
            .ln()
    });
    Some((ye[3], lq.exp(), lg.exp()))
}

/// One glide case.
#[derive(Clone, Copy, Debug)]
pub struct GlideRow {
    pub h_km: f64,
    pub cos_bank: f64,
    pub one_minus_ue: f64,
    pub final_fraction: f64,
    pub theta_closed: f64,
    pub theta_num: f64,
    pub q_rel: f64,
    pub g_rel: f64,
}

/// Glide grid: reference altitudes [km], vertical fractions cos(sigma) (lambda = 1), final speed
/// as a fraction of the imposed entry speed. Out-of-domain cases (near circular) are counted.
pub fn glide_grid(
    veh: &Vehicle,
    h_km: &[f64],
    cbs: &[f64],
    fracs: &[f64],
) -> (Vec<GlideRow>, usize) {
    let mut rows = Vec::new();
    let mut rejected = 0;
    for &h in h_km {
        for &cb in cbs {
            let lift = Lift {
                lambda: 1.0,
                cos_bank: cb,
            };
            let sol = match GlideSolution::new(
                &planet(),
                &atmosphere(),
                &params(veh),
                &lift_control(lift),
                R_EARTH + h * 1e3,
            ) {
                Ok(s) => s,
                Err(VinhError::GlideNearCircular) => {
                    rejected += 1;
                    continue;
                }
                Err(e) => panic!("{} h {h} cb {cb}: {e:?}", veh.name),
            };
            let e = sol.imposed_entry();
            for &frac in fracs {
                let v_f = e.speed_m_s * frac;
                let p = sol.point_at_speed(v_f).unwrap();
                let q = sol.peak_heat_flux(v_f).unwrap().heat_flux_w_m2;
                let g = sol.peak_g_load(v_f).unwrap().g_load;
                let (th, qn, gn) =
                    glide_dim(veh, lift, e, v_f).expect("numerical glide ends at v_f");
                rows.push(GlideRow {
                    h_km: h,
                    cos_bank: cb,
                    one_minus_ue: 1.0 - sol.u_entry(),
                    final_fraction: frac,
                    theta_closed: p.range_angle_rad,
                    theta_num: th,
                    q_rel: (q - qn) / qn,
                    g_rel: (g - gn) / gn,
                });
            }
        }
    }
    (rows, rejected)
}

impl GlideRow {
    pub fn theta_rel(&self) -> f64 {
        (self.theta_closed - self.theta_num) / self.theta_num
    }
}

/// Thesis sec. 8.1.4 / fig. 8.5: "errors in the final range angle not exceeding 3.0 %" for the
/// SRM glide against the simplified numerical model, altitudes up to 110 km. Region here: 70-110
/// km, cos(sigma) in {0.3, 0.5, 0.7, 1}, final speed 0.8 and 0.5 of the entry speed. Measured
/// max 2.5 % (docs/validation/vinh-numerical.md); asserted: the thesis' 3 %. Heat flux and g-load peaks within 2 %
/// and 3 % (measured 0.9 % and 2.0 %).
#[test]
fn validate_vinh_glide_srm_range_angle_fig_8_5_region() {
    let (rows, rejected) = glide_grid(
        &vehicles::srm(),
        &[70.0, 80.0, 90.0, 100.0, 110.0],
        &[0.3, 0.5, 0.7, 1.0],
        &[0.8, 0.5],
    );
    assert!(rows.len() >= 30, "{} rows, {rejected} rejected", rows.len());
    for r in &rows {
        assert!(r.theta_rel().abs() <= 0.03, "{r:?}");
        assert!(r.q_rel.abs() <= 0.02, "{r:?}");
        assert!(r.g_rel.abs() <= 0.03, "{r:?}");
    }
}

/// At lower final speeds (0.3 V_E) the error grows past the thesis' 3 %: measured max 3.2 % for
/// the SRM at 70 km and cos(sigma) = 0.3 (recorded in docs/validation/vinh-numerical.md, not hidden). Bound 4 %.
#[test]
fn validate_vinh_glide_srm_low_final_speed() {
    let (rows, _) = glide_grid(&vehicles::srm(), &[70.0, 90.0, 110.0], &[0.3, 1.0], &[0.3]);
    assert!(rows.len() >= 5);
    let worst = rows.iter().map(|r| r.theta_rel().abs()).fold(0.0, f64::max);
    assert!(worst <= 0.04, "{worst}");
    assert!(
        worst > 0.01,
        "the error at low final speed is expected to be visible: {worst}"
    );
}

/// HORUS-2B (Mach-20 polar): at 122 km (thesis entry) the glide entry is near circular
/// (1 - u_E ~ 1e-4) and rejected as the thesis found (sec. 8.1.6); lower reference altitudes are
/// in domain and within 3 %.
#[test]
fn validate_vinh_glide_horus() {
    let veh = vehicles::horus(20.0);
    let err = GlideSolution::new(
        &planet(),
        &atmosphere(),
        &params(&veh),
        &LiftControl::max_ld_lift_up(),
        R_EARTH + 122e3,
    );
    assert_eq!(err.unwrap_err(), VinhError::GlideNearCircular);
    let (rows, _) = glide_grid(&veh, &[50.0, 70.0, 90.0], &[0.5, 1.0], &[0.8, 0.5]);
    assert!(rows.len() >= 8);
    for r in &rows {
        assert!(r.theta_rel().abs() <= 0.03, "{r:?}");
    }
}

/// `phi1` computed by the library from the defining relation (3.64) with the analytic `y1'`
/// against the printed closed form eq. 3.73/3.74. Also checks the library against a centred
/// finite difference of `y1` (so the analytic derivative is right). Records (docs/validation/vinh-numerical.md) how
/// far the printed 3.74 is from the defining relation.
#[test]
fn validate_vinh_glide_phi1_defining_relation() {
    let veh = vehicles::srm();
    let lift = Lift {
        lambda: 1.0,
        cos_bank: 0.7,
    };
    let sol = GlideSolution::new(
        &planet(),
        &atmosphere(),
        &params(&veh),
        &lift_control(lift),
        R_EARTH + 90e3,
    )
    .unwrap();
    let c = sol.nondim().constants();
    let (k1, e, s) = (c.k1, c.e_vertical, c.s);
    for &f in &[0.95, 0.8, 0.5, 0.3] {
        let u = sol.u_entry() * f;
        let p = sol.point_at_u(u).unwrap();
        // Finite-difference check of 3.64 with the library's y1.
        let h = 1e-6 * u;
        let y_p = sol.point_at_u(u + h).unwrap().density_ratio;
        let y_m = sol.point_at_u(u - h).unwrap().density_ratio;
        let dy = (y_p - y_m) / (2.0 * h);
        let phi_fd = 2.0 * k1 * u / (e * s.sqrt()) / (2.0 / (s * p.density_ratio) - 1.0 / dy);
        assert!(
            (p.phi - phi_fd).abs() < 1e-6 * p.phi.abs(),
            "u {u}: {} vs {phi_fd}",
            p.phi
        );
        // First-order phi0 (3.68) is close to phi1 for a slowly varying glide.
        let phi0 = 2.0 * (1.0 - u) / (e * s.sqrt() * (2.0 / s + u * (1.0 - u)));
        assert!(
            (p.phi - phi0).abs() < 0.5 * phi0,
            "u {u}: phi1 {} phi0 {phi0}",
            p.phi
        );
    }
}

/// Kepler arc against two-body propagation in Cartesian coordinates (rtol 1e-12): range angle,
/// flight time, re-entry speed and flight-path angle, and the Kepler-equation state at mid-arc.
/// Exit at 122 km; speeds 6-10.5 km/s; flight-path angles 0.5-89 deg (the thesis verified at
/// +90 deg, a degenerate rectilinear conic that is a domain error here); re-entry at the exit
/// radius and 10 km below/above it.
#[test]
fn validate_kepler_ballistic_against_cartesian_two_body() {
    let r0 = R_EARTH + H_ENTRY;
    let mut cases = 0;
    for &v0 in &[6000.0, 7000.0, 7800.0, 9000.0, 10500.0] {
        for &g_deg in &[0.5, 2.0, 5.0, 20.0, 60.0, 89.0] {
            for &dr in &[0.0, -10e3, 10e3] {
                let g0 = f64::to_radians(g_deg);
                let exit = EntryState {
                    radius_m: r0,
                    speed_m_s: v0,
                    flight_path_angle_rad: g0,
                };
                let arc = match BallisticArc::new(&planet(), &exit, r0 + dr) {
                    Ok(a) => a,
                    Err(VinhError::NoReentry) => {
                        // Apoapsis below r0 + dr or periapsis above it: check that it really is.
                        let eps = v0 * v0 / 2.0 - MU / r0;
                        let h = r0 * v0 * g0.cos();
                        let e = (1.0 + 2.0 * eps * h * h / (MU * MU)).sqrt();
                        let ra = h * h / MU / (1.0 - e);
                        let rp = h * h / MU / (1.0 + e);
                        assert!(ra < r0 + dr || rp > r0 + dr, "v {v0} g {g_deg} dr {dr}");
                        continue;
                    }
                    Err(e) => panic!("v {v0} g {g_deg}: {e:?}"),
                };
                let y0 = [r0, 0.0, v0 * g0.sin(), v0 * g0.cos()];
                let r1 = r0 + dr;
                let set = Settings {
                    rtol: 1e-12,
                    atol: 1e-6,
                    h_init: 0.1,
                    h_max: 10.0,
                    max_steps: 2_000_000,
                };
                let sol = integrate(dynamics::two_body, 0.0, y0, 1e6, set, |t, y| {
                    let r = (y[0] * y[0] + y[1] * y[1]).sqrt();
                    let vr = (y[0] * y[2] + y[1] * y[3]) / r;
                    if t > 0.0 && vr < 0.0 { r - r1 } else { 1.0 }
                });
                let (t1, y1) = sol
                    .event
                    .unwrap_or_else(|| panic!("re-entry v {v0} g {g_deg} dr {dr}"));
                let theta = y1[1].atan2(y1[0]).rem_euclid(2.0 * std::f64::consts::PI);
                let v1 = (y1[2] * y1[2] + y1[3] * y1[3]).sqrt();
                let rr = (y1[0] * y1[0] + y1[1] * y1[1]).sqrt();
                let g1 = ((y1[0] * y1[2] + y1[1] * y1[3]) / (rr * v1)).asin();
                let re = arc.reentry();
                assert!(
                    (arc.range_angle_rad() - theta).abs() < 1e-8,
                    "v {v0} g {g_deg} dr {dr}: {} vs {theta}",
                    arc.range_angle_rad()
                );
                assert!(
                    (arc.flight_time_s() - t1).abs() < 1e-8 * t1 + 1e-6,
                    "time {} vs {t1}",
                    arc.flight_time_s()
                );
                assert!((re.speed_m_s - v1).abs() < 1e-8 * v1);
                assert!((re.flight_path_angle_rad - g1).abs() < 1e-8);
                // Mid-arc state from Kepler's equation.
                let tm = 0.5 * t1;
                let sol_m = integrate(dynamics::two_body, 0.0, y0, tm, set, |_t, _y| 1.0);
                let (_, ym) = *sol_m.samples.last().unwrap();
                let pm = arc.state_at_time(tm).unwrap();
                let rm = (ym[0] * ym[0] + ym[1] * ym[1]).sqrt();
                let thm = ym[1].atan2(ym[0]).rem_euclid(2.0 * std::f64::consts::PI);
                assert!(
                    (pm.radius_m - rm).abs() < 1e-8 * rm,
                    "mid r {} vs {rm}",
                    pm.radius_m
                );
                assert!(
                    (pm.range_angle_rad - thm).abs() < 1e-8,
                    "mid theta {} vs {thm}",
                    pm.range_angle_rad
                );
                cases += 1;
            }
        }
    }
    assert!(cases >= 60, "{cases}");
}

/// ERRATA on eq. 3.81: the printed conic with the true anomaly taken as zero at the exit does
/// not follow the two-body motion (wrong by kilometres), the phased one does.
#[test]
fn validate_kepler_ballistic_eq_3_81_needs_exit_phase() {
    let r0 = R_EARTH + H_ENTRY;
    let (v0, g0) = (7500.0, f64::to_radians(3.0));
    let exit = EntryState {
        radius_m: r0,
        speed_m_s: v0,
        flight_path_angle_rad: g0,
    };
    let arc = BallisticArc::new(&planet(), &exit, r0).unwrap();
    let theta = 0.3 * arc.range_angle_rad();
    let phased = arc.radius_at_range_angle(theta).unwrap();
    // Printed eq. 3.81 (nu = theta): r = S0^2 cos^2 g / (1 + sqrt(1 - S0^2 cos^2 g (2 - S0^2)) cos theta) r0.
    let s02 = v0 * v0 * r0 / MU;
    let p_r0 = s02 * g0.cos().powi(2);
    let printed = r0 * p_r0 / (1.0 + (1.0 - p_r0 * (2.0 - s02)).sqrt() * theta.cos());
    // Reference by propagation to that range angle.
    let y0 = [r0, 0.0, v0 * g0.sin(), v0 * g0.cos()];
    let set = Settings {
        rtol: 1e-12,
        atol: 1e-6,
        h_init: 0.1,
        h_max: 10.0,
        max_steps: 2_000_000,
    };
    let sol = integrate(dynamics::two_body, 0.0, y0, 1e6, set, |_t, y| {
        theta - y[1].atan2(y[0])
    });
    let (_, y) = sol.event.unwrap();
    let r_ref = (y[0] * y[0] + y[1] * y[1]).sqrt();
    assert!((phased - r_ref).abs() < 1e-3, "{phased} vs {r_ref}");
    assert!(
        (printed - r_ref).abs() > 1e4,
        "printed {printed} vs {r_ref}"
    );
    assert!(arc.exit_true_anomaly_rad() > 0.1);
}

/// The predictor's first skip + arc against one integration of the exact equations through the
/// skip, the near-vacuum arc (exponential atmosphere continued above 122 km, density < 1e-11
/// kg/m^3 above 250 km) and back down to 122 km. The range error is dominated by the exit
/// flight-path-angle error of the skip amplified by the arc (measured, docs/validation/vinh-numerical.md).
#[test]
fn validate_vinh_predictor_skip_and_arc_against_integration() {
    // Measured: 7800 m/s -3 deg: -4.1 %, 9000 m/s -5 deg: see docs/validation/vinh-numerical.md.
    for &(v_e, g_deg, bound) in &[
        (7800.0, -3.0, 0.05),
        (9000.0, -5.0, 0.06),
        (10500.0, -7.0, 0.07),
    ] {
        let (predicted, reference) = skip_arc_case(v_e, g_deg);
        let rel = (predicted - reference) / reference;
        assert!(
            rel.abs() < bound,
            "V {v_e} g {g_deg}: predicted {predicted} vs {reference} ({rel})"
        );
    }
}

/// (closed-form skip + Kepler range angle, integrated range angle) to the second re-entry at
/// 122 km, SRM, lambda = 1.
pub fn skip_arc_case(v_e: f64, g_deg: f64) -> (f64, f64) {
    let veh = vehicles::srm();
    let lift = Lift {
        lambda: 1.0,
        cos_bank: 1.0,
    };
    let r_e = R_EARTH + H_ENTRY;
    let g_e = f64::to_radians(g_deg);
    let s = SkipSolution::new(&nondim(&veh, lift, r_e, v_e, g_e).unwrap()).unwrap();
    let ex = s.exit();
    let arc = BallisticArc::new(
        &planet(),
        &EntryState {
            radius_m: r_e,
            speed_m_s: ex.speed_m_s,
            flight_path_angle_rad: ex.flight_path_angle_rad,
        },
        r_e,
    )
    .unwrap();
    let predicted = ex.range_angle_rad + arc.range_angle_rad();
    let f = dynamics::eom_dim(&veh, lift);
    let sol = integrate(
        f,
        0.0,
        [r_e, v_e, g_e, 0.0],
        1e6,
        Settings::tight(5.0),
        |_t, y| {
            // Second descending crossing of r_e (well past the first exit).
            if y[2] < 0.0 && y[3] > 2.0 * ex.range_angle_rad {
                y[0] - r_e
            } else {
                1.0
            }
        },
    );
    let (_, y) = sol.event.expect("re-entry");
    (predicted, y[3])
}

/// The chain is the sum of its phases, bounded, and reports a glide after capture.
#[test]
fn vinh_predictor_chain_is_sum_of_phases() {
    let veh = vehicles::srm();
    let lift = LiftControl::max_ld_lift_up();
    let state = EntryState {
        radius_m: R_EARTH + H_ENTRY,
        speed_m_s: 7800.0,
        flight_path_angle_rad: f64::to_radians(-3.0),
    };
    let cfg = PredictorConfig {
        final_speed_m_s: 2500.0,
        max_skips: 8,
    };
    let p = predict(&planet(), &atmosphere(), &params(&veh), &lift, &state, &cfg).unwrap();
    assert!(p.skips >= 1 && p.arcs == p.skips, "{p:?}");
    // Recompute phase by phase.
    let mut cur = state;
    let mut theta = 0.0;
    let mut q: f64 = 0.0;
    for _ in 0..p.skips {
        let s = SkipSolution::new(
            &NonDim::new(&planet(), &atmosphere(), &params(&veh), &lift, &cur).unwrap(),
        )
        .unwrap();
        q = q.max(s.peak_heat_flux().unwrap().heat_flux_w_m2);
        let e = s.exit();
        let arc = BallisticArc::new(
            &planet(),
            &EntryState {
                radius_m: cur.radius_m,
                speed_m_s: e.speed_m_s,
                flight_path_angle_rad: e.flight_path_angle_rad,
            },
            cur.radius_m,
        )
        .unwrap();
        theta += e.range_angle_rad + arc.range_angle_rad();
        cur = EntryState {
            radius_m: cur.radius_m,
            speed_m_s: arc.reentry().speed_m_s,
            flight_path_angle_rad: arc.reentry().flight_path_angle_rad,
        };
    }
    let s = SkipSolution::new(
        &NonDim::new(&planet(), &atmosphere(), &params(&veh), &lift, &cur).unwrap(),
    );
    assert_eq!(s.unwrap_err(), VinhError::NoAtmosphericExit);
    let g = GlideSolution::new(
        &planet(),
        &atmosphere(),
        &params(&veh),
        &lift,
        p.glide_start_radius_m,
    )
    .unwrap();
    assert!((g.imposed_entry().speed_m_s - cur.speed_m_s).abs() < 1e-6 * cur.speed_m_s);
    theta += g.point_at_speed(2500.0).unwrap().range_angle_rad;
    q = q.max(g.peak_heat_flux(2500.0).unwrap().heat_flux_w_m2);
    assert!((p.range_angle_rad - theta).abs() < 1e-9 * theta);
    assert!((p.peak_heat_flux_w_m2 - q).abs() < 1e-9 * q);
    assert!((p.range_m - theta * R_EARTH).abs() < 1e-6 * p.range_m);
    // Budget of zero skips on a skipping entry: typed phase-limit error.
    let cfg0 = PredictorConfig {
        final_speed_m_s: 2500.0,
        max_skips: 0,
    };
    assert_eq!(
        predict(
            &planet(),
            &atmosphere(),
            &params(&veh),
            &lift,
            &state,
            &cfg0
        )
        .unwrap_err(),
        VinhError::PhaseLimit
    );
}

/// Every failure mode of thesis sec. 8.1.6 / 8.2.1 is a typed error, not NaN.
#[test]
fn vinh_domain_errors_are_typed() {
    let veh = vehicles::srm();
    let up = Lift {
        lambda: 1.0,
        cos_bank: 1.0,
    };
    let r_e = R_EARTH + H_ENTRY;
    // C_D0 <= 0.
    let mut bad = veh;
    bad.cd0 = 0.0;
    assert_eq!(
        nondim(&bad, up, r_e, 7800.0, -0.05).unwrap_err(),
        VinhError::NonPositiveZeroLiftDrag
    );
    bad.cd0 = -0.01;
    assert_eq!(
        nondim(&bad, up, r_e, 7800.0, -0.05).unwrap_err(),
        VinhError::NonPositiveZeroLiftDrag
    );
    // Entry speed above the validated range.
    assert_eq!(
        nondim(&veh, up, r_e, 14_500.0, -0.05).unwrap_err(),
        VinhError::EntrySpeedTooHigh
    );
    // Exit above escape speed (the thesis' > 11 km/s case): the arc is hyperbolic.
    let s = SkipSolution::new(&nondim(&veh, up, r_e, 11_500.0, f64::to_radians(-2.0)).unwrap())
        .unwrap();
    let e = s.exit();
    assert!(e.speed_m_s > (2.0 * MU / r_e).sqrt());
    let arc = BallisticArc::new(
        &planet(),
        &EntryState {
            radius_m: r_e,
            speed_m_s: e.speed_m_s,
            flight_path_angle_rad: e.flight_path_angle_rad,
        },
        r_e,
    );
    assert_eq!(arc.unwrap_err(), VinhError::EscapeTrajectory);
    // x beyond the deepest point.
    let s =
        SkipSolution::new(&nondim(&veh, up, r_e, 7800.0, f64::to_radians(-3.0)).unwrap()).unwrap();
    assert_eq!(
        s.point_at_depth(s.x1() * 1.01, guidance_core::vinh::Leg::Descending)
            .unwrap_err(),
        VinhError::BeyondDeepestPoint
    );
    assert!(
        s.point_at_depth(s.x1() * 0.99, guidance_core::vinh::Leg::Ascending)
            .is_ok()
    );
    assert_eq!(
        s.point_at_tau(s.tau_exit() * 1.01).unwrap_err(),
        VinhError::OutsideSkip
    );
    // No deepest point: lift down at sub-circular speed dives into the ground.
    let down = Lift {
        lambda: 1.0,
        cos_bank: -1.0,
    };
    let s = SkipSolution::new(&nondim(&veh, down, r_e, 7400.0, f64::to_radians(-3.0)).unwrap());
    assert_eq!(s.unwrap_err(), VinhError::NoDeepestPoint);
    // Captured (no exit).
    let s = SkipSolution::new(&nondim(&veh, up, r_e, 7435.5, f64::to_radians(-1.43)).unwrap());
    assert_eq!(s.unwrap_err(), VinhError::NoAtmosphericExit);
    // Ascending reference state is not a skip entry.
    let s = SkipSolution::new(&nondim(&veh, up, r_e, 7800.0, 0.01).unwrap());
    assert_eq!(s.unwrap_err(), VinhError::NotDescending);
    // Glide near circular (HORUS-2B at 122 km) and glide speed above the imposed one.
    let h = vehicles::horus(20.0);
    let g = GlideSolution::new(
        &planet(),
        &atmosphere(),
        &params(&h),
        &LiftControl::max_ld_lift_up(),
        r_e,
    );
    assert_eq!(g.unwrap_err(), VinhError::GlideNearCircular);
    let g = GlideSolution::new(
        &planet(),
        &atmosphere(),
        &params(&veh),
        &LiftControl::max_ld_lift_up(),
        R_EARTH + 90e3,
    )
    .unwrap();
    assert_eq!(
        g.point_at_speed(g.imposed_entry().speed_m_s + 1.0)
            .unwrap_err(),
        VinhError::GlideSpeedOutOfDomain
    );
    assert_eq!(
        g.point_at_u(0.0).unwrap_err(),
        VinhError::GlideSpeedOutOfDomain
    );
    // Non-finite input.
    assert_eq!(
        nondim(&veh, up, f64::NAN, 7800.0, -0.05).unwrap_err(),
        VinhError::NonFiniteInput
    );
    assert_eq!(s_point_nan(&veh), VinhError::NonFiniteInput);
}

fn s_point_nan(veh: &Vehicle) -> VinhError {
    let s = SkipSolution::new(
        &nondim(
            veh,
            Lift {
                lambda: 1.0,
                cos_bank: 1.0,
            },
            R_EARTH + H_ENTRY,
            7800.0,
            f64::to_radians(-3.0),
        )
        .unwrap(),
    )
    .unwrap();
    s.point_at_tau(f64::NAN).unwrap_err()
}

/// f32 against f64 on the validation grid. Documented bounds (module docs of `guidance_core::vinh`):
/// skip exit speed 1e-5 relative, exit flight-path angle 1e-6 rad, range angle 1e-4 relative,
/// peak heat flux 5e-4 relative; glide range angle 1e-3 relative; Kepler range angle and flight
/// time 1e-4 relative.
#[test]
fn vinh_f32_agrees_with_f64() {
    let p32 = Planet::<f32>::earth();
    let a32 = ExpAtmosphere::<f32> {
        rho0_kg_m3: RHO0 as f32,
        scale_height_m: H_S as f32,
        ref_radius_m: R_EARTH as f32,
    };
    let r_e = R_EARTH + H_ENTRY;
    let mut worst = [0.0_f64; 4];
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        let v32 = VehicleParams::<f32> {
            mass_kg: veh.mass_kg as f32,
            reference_area_m2: veh.area_m2 as f32,
            cd0: veh.cd0 as f32,
            k_polar: veh.k as f32,
            nose_radius_m: veh.nose_radius_m as f32,
        };
        for &v_e in &SKIP_SPEEDS {
            for &g_deg in &SKIP_FPAS_DEG {
                for &lam in &SKIP_LAMBDAS {
                    let lift = Lift {
                        lambda: lam,
                        cos_bank: 1.0,
                    };
                    let g_e = f64::to_radians(g_deg);
                    let s64 = SkipSolution::new(&nondim(&veh, lift, r_e, v_e, g_e).unwrap());
                    let nd32 = NonDim::<f32>::new(
                        &p32,
                        &a32,
                        &v32,
                        &LiftControl {
                            lambda: lam as f32,
                            vertical_fraction: 1.0,
                        },
                        &EntryState {
                            radius_m: r_e as f32,
                            speed_m_s: v_e as f32,
                            flight_path_angle_rad: g_e as f32,
                        },
                    )
                    .unwrap();
                    let s32 = SkipSolution::new(&nd32);
                    let (Ok(s64), Ok(s32)) = (s64, s32) else {
                        continue;
                    };
                    let (e64, e32) = (s64.exit(), s32.exit());
                    worst[0] = worst[0]
                        .max(((f64::from(e32.speed_m_s) - e64.speed_m_s) / e64.speed_m_s).abs());
                    worst[1] = worst[1].max(
                        (f64::from(e32.flight_path_angle_rad) - e64.flight_path_angle_rad).abs(),
                    );
                    worst[2] = worst[2].max(
                        ((f64::from(e32.range_angle_rad) - e64.range_angle_rad)
                            / e64.range_angle_rad)
                            .abs(),
                    );
                    let q64 = s64.peak_heat_flux().unwrap().heat_flux_w_m2;
                    let q32 = f64::from(s32.peak_heat_flux().unwrap().heat_flux_w_m2);
                    worst[3] = worst[3].max(((q32 - q64) / q64).abs());
                }
            }
        }
    }
    // Measured: 1.1e-6, 6.2e-8 rad, 2.6e-5, 1.1e-4.
    assert!(worst[0] < 1e-5, "exit speed {worst:?}");
    assert!(worst[1] < 1e-6, "exit fpa {worst:?}");
    assert!(worst[2] < 1e-4, "range {worst:?}");
    assert!(worst[3] < 5e-4, "heat {worst:?}");
    // Glide.
    let veh = vehicles::srm();
    let v32 = VehicleParams::<f32> {
        mass_kg: 38.77,
        reference_area_m2: 0.441,
        cd0: veh.cd0 as f32,
        k_polar: veh.k as f32,
        nose_radius_m: 0.9,
    };
    for &h in &[70e3, 90e3, 110e3] {
        let g64 = GlideSolution::new(
            &planet(),
            &atmosphere(),
            &params(&veh),
            &LiftControl::max_ld_lift_up(),
            R_EARTH + h,
        )
        .unwrap();
        let g32 = GlideSolution::new(
            &p32,
            &a32,
            &v32,
            &LiftControl::max_ld_lift_up(),
            (R_EARTH + h) as f32,
        )
        .unwrap();
        let vf = 0.5 * g64.imposed_entry().speed_m_s;
        let t64 = g64.point_at_speed(vf).unwrap().range_angle_rad;
        let t32 = f64::from(g32.point_at_speed(vf as f32).unwrap().range_angle_rad);
        assert!(
            ((t32 - t64) / t64).abs() < 1e-3,
            "glide h {h}: {t32} vs {t64}"
        );
    }
    // Kepler arc.
    for &(v0, g_deg) in &[(7000.0, 2.0), (7800.0, 5.0), (10500.0, 20.0)] {
        let e64 = EntryState {
            radius_m: r_e,
            speed_m_s: v0,
            flight_path_angle_rad: f64::to_radians(g_deg),
        };
        let e32 = EntryState {
            radius_m: r_e as f32,
            speed_m_s: v0 as f32,
            flight_path_angle_rad: (g_deg as f32).to_radians(),
        };
        let a64 = BallisticArc::new(&planet(), &e64, r_e).unwrap();
        let a32 = BallisticArc::new(&p32, &e32, r_e as f32).unwrap();
        assert!(
            ((f64::from(a32.range_angle_rad()) - a64.range_angle_rad()) / a64.range_angle_rad())
                .abs()
                < 1e-4
        );
        assert!(
            ((f64::from(a32.flight_time_s()) - a64.flight_time_s()) / a64.flight_time_s()).abs()
                < 1e-4
        );
    }
}

/// Prints the measured errors as Markdown (docs/validation/vinh-numerical.md). Run with
/// `cargo test -p guidance-core --test it print_vinh_error_table -- --ignored --nocapture`.
#[test]
#[ignore]
fn print_vinh_error_table() {
    println!("### Skip (second order) vs exact equations of motion, entry 122 km\n");
    println!(
        "| vehicle | V_E [m/s] | gamma_E [deg] | lambda | eta v exit | exit V err [%] | exit gamma err [deg] | range err [%] | h_min err [km] | peak q err [%] | peak n err [%] |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut summaries = Vec::new();
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        let (rows, n) = skip_grid(&veh, NdSystem::Exact);
        for r in &rows {
            println!(
                "| {} | {} | {} | {} | {:.3} | {:+.3} | {:+.3} | {:+.2} | {:+.3} | {:+.2} | {:+.2} |",
                veh.name,
                r.v_e,
                r.fpa_deg,
                r.lambda,
                r.eta_v_exit,
                100.0 * r.exit_speed_rel(),
                r.exit_fpa_abs_deg(),
                100.0 * r.range_rel(),
                r.depth_abs_km(),
                100.0 * r.heat_rel(),
                100.0 * r.g_rel()
            );
        }
        summaries.push((veh.name, rows, n));
    }
    println!(
        "\n| vehicle | cases compared | max exit V err [%] | max exit gamma err [deg] | max range err [%] | max h_min err [km] | max q err [%] | max n err [%] | outcome counts |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, rows, n) in &summaries {
        println!(
            "| {name} | {} | {:.3} | {:.3} | {:.2} | {:.3} | {:.2} | {:.2} | both captured {}, closed exits/exact captured {}, closed captured/exact exits {}, other errors {} |",
            n.compared,
            100.0 * max_abs(rows, SkipRow::exit_speed_rel),
            max_abs(rows, SkipRow::exit_fpa_abs_deg),
            100.0 * max_abs(rows, SkipRow::range_rel),
            max_abs(rows, SkipRow::depth_abs_km),
            100.0 * max_abs(rows, SkipRow::heat_rel),
            100.0 * max_abs(rows, SkipRow::g_rel),
            n.both_captured,
            n.closed_exits_exact_captured,
            n.closed_captured_exact_exits,
            n.other_errors
        );
    }
    println!(
        "\n### Skip closed form vs the simplified (3.33-3.35) and second-order (3.49) systems\n"
    );
    println!(
        "| vehicle | reference system | max exit V err [%] | max exit gamma err [deg] | max range err [%] | max h_min err [km] |"
    );
    println!("|---|---|---|---|---|---|");
    for (veh, sys) in [
        (vehicles::srm(), NdSystem::Simplified),
        (vehicles::srm(), NdSystem::SecondOrder),
        (vehicles::horus(20.0), NdSystem::Simplified),
        (vehicles::horus(20.0), NdSystem::SecondOrder),
    ] {
        let (rows, _) = skip_grid(&veh, sys);
        println!(
            "| {} | {:?} | {:.3} | {:.3} | {:.2} | {:.3} |",
            veh.name,
            sys,
            100.0 * max_abs(&rows, SkipRow::exit_speed_rel),
            max_abs(&rows, SkipRow::exit_fpa_abs_deg),
            100.0 * max_abs(&rows, SkipRow::range_rel),
            max_abs(&rows, SkipRow::depth_abs_km)
        );
    }
    println!("\n### Skip + Kepler arc (SRM, lambda 1) vs one integration to the second re-entry\n");
    println!("| V_E [m/s] | gamma_E [deg] | predicted [deg] | integrated [deg] | err [%] |");
    println!("|---|---|---|---|---|");
    for &(v_e, g_deg) in &[(7800.0, -3.0), (9000.0, -5.0), (10500.0, -7.0)] {
        let (p, r) = skip_arc_case(v_e, g_deg);
        println!(
            "| {v_e} | {g_deg} | {:.2} | {:.2} | {:+.2} |",
            p.to_degrees(),
            r.to_degrees(),
            100.0 * (p - r) / r
        );
    }
    println!("\n### Glide (second order) vs numerical glide, simplified environment\n");
    println!(
        "| vehicle | h_E [km] | cos(sigma) | 1 - u_E | V_f / V_E | theta closed [deg] | theta numerical [deg] | theta err [%] | peak q err [%] | peak n err [%] |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (veh, hs) in [
        (vehicles::srm(), vec![50.0, 70.0, 90.0, 100.0, 105.0, 110.0]),
        (vehicles::horus(20.0), vec![50.0, 70.0, 85.0, 90.0]),
    ] {
        let (rows, rejected) = glide_grid(&veh, &hs, &[0.3, 0.5, 0.7, 1.0], &[0.8, 0.5, 0.3]);
        for r in &rows {
            println!(
                "| {} | {} | {} | {:.4} | {} | {:.2} | {:.2} | {:+.2} | {:+.2} | {:+.2} |",
                veh.name,
                r.h_km,
                r.cos_bank,
                r.one_minus_ue,
                r.final_fraction,
                r.theta_closed.to_degrees(),
                r.theta_num.to_degrees(),
                100.0 * r.theta_rel(),
                100.0 * r.q_rel,
                100.0 * r.g_rel
            );
        }
        println!(
            "| {} | rejected as near circular (GlideNearCircular): {rejected} | | | | | | | | |",
            veh.name
        );
    }
}
