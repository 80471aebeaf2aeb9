//! Validation of the Vinh closed forms against numerical integration.

use crate::vinh_support::dynamics::{self, Lift, NdSystem, RefConsts, SkipSummary};
use crate::vinh_support::vehicles::{self, H_S, MU, R_EARTH, RHO0, Vehicle};
use guidance_core::vinh::{
    EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, SkipSolution, VehicleParams,
};

fn planet() -> Planet<f64> {
    Planet {
        mu_m3_s2: MU,
        radius_m: R_EARTH,
    }
}
fn atmosphere() -> ExpAtmosphere<f64> {
    ExpAtmosphere {
        rho0_kg_m3: RHO0,
        scale_height_m: H_S,
        ref_radius_m: R_EARTH,
    }
}
fn params(v: &Vehicle) -> VehicleParams<f64> {
    VehicleParams {
        mass_kg: v.mass_kg,
        reference_area_m2: v.area_m2,
        cd0: v.cd0,
        k_polar: v.k,
        nose_radius_m: v.nose_radius_m,
    }
}
fn nondim(
    v: &Vehicle,
    lift: Lift,
    r: f64,
    speed: f64,
    fpa: f64,
) -> Result<NonDim<f64>, guidance_core::vinh::VinhError> {
    NonDim::new(
        &planet(),
        &atmosphere(),
        &params(v),
        &LiftControl {
            lambda: lift.lambda,
            vertical_fraction: lift.cos_bank,
        },
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

#[test]
#[ignore]
fn explore_skip() {
    let h_e = 122_000.0;
    let r_e = R_EARTH + h_e;
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        println!(
            "{} cd0 {} k {} E* {}",
            veh.name,
            veh.cd0,
            veh.k,
            veh.e_star()
        );
        for &v_e in &[7435.5, 7800.0, 9000.0, 10500.0] {
            for &g_deg in &[-1.43, -3.0, -5.0, -7.0] {
                for &lam in &[0.5, 1.0] {
                    let lift = Lift {
                        lambda: lam,
                        cos_bank: 1.0,
                    };
                    let g_e = f64::to_radians(g_deg);
                    let rc = RefConsts::new(&veh, lift, r_e, v_e, g_e);
                    let dim = dynamics::skip_dim(&veh, lift, r_e, v_e, g_e);
                    let ex = dynamics::skip_nd(&veh, rc, NdSystem::Exact);
                    let so = dynamics::skip_nd(&veh, rc, NdSystem::SecondOrder);
                    let nd = nondim(&veh, lift, r_e, v_e, g_e).unwrap();
                    let cf = SkipSolution::new(&nd).map(|s| {
                        (
                            closed_skip(&s),
                            s.x1(),
                            s.x1_first_order(),
                            s.low_ld_remedy_used(),
                        )
                    });
                    println!(
                        "V {v_e} g {g_deg} lam {lam} k1 {:.3e} eta {:.3e} k {:.3e} alpha {:.4}",
                        rc.k1, rc.eta, rc.k, rc.alpha
                    );
                    println!("  dim {:?}", dim.map(fmt));
                    println!("  ex  {:?}", ex.map(fmt));
                    println!("  so  {:?}", so.map(fmt));
                    match cf {
                        Ok((s, x1, x1f, rem)) => {
                            println!("  cf  {:?} x1 {x1:.4} x1f {x1f:.4} rem {rem}", fmt(s))
                        }
                        Err(e) => println!("  cf  ERR {e:?}"),
                    }
                }
            }
        }
    }
}

fn fmt(s: SkipSummary) -> String {
    format!(
        "V {:.2} g {:.4} th {:.5} hmin {:.1} q {:.4e} n {:.4}",
        s.exit_speed,
        s.exit_fpa.to_degrees(),
        s.exit_range_angle.to_degrees(),
        (s.min_radius - R_EARTH) / 1000.0,
        s.peak_heat_flux,
        s.peak_g_load
    )
}

#[test]
#[ignore]
fn explore_skip_consistency() {
    use guidance_core::vinh::SkipOptions;
    let r_e = R_EARTH + 122_000.0;
    for veh in [vehicles::srm(), vehicles::horus(20.0)] {
        for &v_e in &[11500.0, 12500.0, 14000.0] {
            for &g_deg in &[-1.43, -2.0, -3.0, -5.0, -7.0, -10.0] {
                for &lam in &[0.3, 1.0] {
                    let lift = Lift {
                        lambda: lam,
                        cos_bank: 1.0,
                    };
                    let g_e = f64::to_radians(g_deg);
                    let nd = nondim(&veh, lift, r_e, v_e, g_e).unwrap();
                    let rc = RefConsts::new(&veh, lift, r_e, v_e, g_e);
                    let ex = dynamics::skip_nd(&veh, rc, NdSystem::Exact);
                    for refine in [0u8, 3] {
                        let sol = SkipSolution::with_options(
                            &nd,
                            SkipOptions {
                                deepest_point_refinements: refine,
                            },
                        );
                        match sol {
                            Err(e) => println!(
                                "{} V {v_e} g {g_deg} lam {lam} r{refine}: ERR {e:?} ex {:?}",
                                veh.name,
                                ex.map(|s| s.exit_fpa.to_degrees())
                            ),
                            Ok(s) => {
                                let mut min_rel: f64 = 1e9;
                                let mut errs = 0;
                                for i in 0..=400 {
                                    let t = (s.tau_exit() * i as f64 / 400.0).min(s.tau_exit());
                                    let p2 = s.phi_squared_at_tau(t).unwrap();
                                    min_rel = min_rel.min(p2 / (rc.c * rc.c));
                                    if s.point_at_tau(t).is_err() {
                                        errs += 1;
                                    }
                                }
                                let pb =
                                    s.phi_squared_at_tau(s.tau_bottom()).unwrap() / (rc.c * rc.c);
                                let e = s.exit();
                                let (ev, eg, eth) = ex
                                    .map(|x| (x.exit_speed, x.exit_fpa, x.exit_range_angle))
                                    .unwrap_or((f64::NAN, f64::NAN, f64::NAN));
                                println!(
                                    "{} V {v_e} g {g_deg} lam {lam} r{refine}: x1 {:.4} x1f {:.4} rem {} minphi2 {min_rel:.3e} bottom {pb:.3e} errs {errs} etav_exit {:.3} dV {:.2e} dg {:.2e} dth {:.2e}",
                                    veh.name,
                                    s.x1(),
                                    s.x1_first_order(),
                                    s.low_ld_remedy_used(),
                                    e.eta_v,
                                    (e.speed_m_s - ev) / ev,
                                    (e.flight_path_angle_rad - eg) / eg,
                                    (e.range_angle_rad - eth) / eth
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}
