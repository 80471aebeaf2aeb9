//! Stack measurement firmware: the maximum stack depth (stack painting, `onboard_demo::stack`)
//! of one guidance tick (HORUS-2B reference mission: `f32` on the Cortex-M4F, fixed point on
//! the Cortex-M3), of the onboard navigation conversion (`f32`), and of a re-planning solve
//! (`f32`: hardware float on the M4F, soft float on the M3; a converging solve and the
//! solver's worst case). Prints one `stack NAME: N bytes` line each and exits 0; `cargo xtask
//! stack` (a step of `cargo xtask test`) reads them and checks static RAM plus the largest
//! against `onboard-demo/size-budget.toml`.
//!
//! Firmware only: built for the host this binary is a stub that exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!("stack-bench: Cortex-M firmware, not a host program (see README)");
    std::process::exit(2);
}

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use cortex_m_semihosting::hprintln;
    use guidance_core::missions::horus2b_reference;
    use guidance_core::navconv::{CartesianNav, InertialFrame, from_inertial};
    use guidance_core::replan::{PredictorMode, ReplanConfig, ReplanLimits, replan};
    use guidance_core::vinh::nondim::{
        EntryState, ExpAtmosphere, LiftControl, Planet, VehicleParams,
    };
    use guidance_core::vinh::predict::{PredictorConfig, predict};
    use guidance_core::{NavState, Scalar};
    use nalgebra::Vector3;
    use onboard_demo::stack::{StackDepth, max_stack_bytes, report};

    #[cfg(target_abi = "eabihf")]
    type Num = f32;
    #[cfg(not(target_abi = "eabihf"))]
    type Num = guidance_core::Fixed;

    fn tick() -> Result<StackDepth, &'static str> {
        let mission = horus2b_reference::<Num>().map_err(|_| "mission")?;
        let energy = mission.earth_energy_normalizer().map_err(|_| "energy")?;
        let mut g = mission.guidance(energy).map_err(|_| "guidance")?;
        let nav = NavState {
            time_s: Num::from_f64(0.0),
            radius_m: Num::from_f64(6_478_137.0),
            speed_m_s: Num::from_f64(7_400.0),
            flight_path_angle_rad: Num::from_f64(-0.02),
            heading_rad: Num::from_f64(1.0),
            latitude_rad: Num::from_f64(0.1),
            longitude_rad: Num::from_f64(0.2),
        };
        let (d, r) = max_stack_bytes(|| g.update(core::hint::black_box(&nav)).is_ok());
        if r {
            Ok(d)
        } else {
            Err("guidance tick failed")
        }
    }

    fn navconv() -> Result<StackDepth, &'static str> {
        let nav = CartesianNav {
            time_s: 100.0f32,
            position_m: Vector3::new(6.4e6f32, 1.0e6, 0.5e6),
            velocity_m_s: Vector3::new(-500.0f32, 7_000.0, 1_000.0),
        };
        let frame = InertialFrame {
            rotation_rate_rad_s: 7.292_115e-5f32,
            angle_at_zero_rad: 0.0,
        };
        let (d, r) = max_stack_bytes(|| from_inertial(core::hint::black_box(&nav), &frame).is_ok());
        if r { Ok(d) } else { Err("navconv failed") }
    }

    /// A converging re-plan and the worst case (heat-flux limit below every prediction).
    fn replans() -> Result<(StackDepth, StackDepth), &'static str> {
        let planet = Planet::<f32>::earth();
        let atm = ExpAtmosphere::<f32>::earth();
        let veh = VehicleParams {
            mass_kg: 38.77f32,
            reference_area_m2: 0.441,
            cd0: 0.2576,
            k_polar: 0.1879,
            nose_radius_m: 0.9,
        };
        let predictor = PredictorConfig {
            final_speed_m_s: 2_500.0f32,
            max_skips: 4,
        };
        let solver = ReplanConfig {
            lambda: 1.0f32,
            min_vertical_fraction: 0.3,
            max_vertical_fraction: 1.0,
            tolerance_m: 1_000.0,
            max_iterations: 40,
            predictor,
            mode: PredictorMode::Chain,
        };
        let deg = core::f32::consts::PI / 180.0;
        let start = NavState {
            time_s: 0.0f32,
            radius_m: 6_378_137.0 + 122e3,
            speed_m_s: 7_000.0,
            flight_path_angle_rad: -4.0 * deg,
            heading_rad: 0.0,
            latitude_rad: 0.0,
            longitude_rad: 0.0,
        };
        let state = EntryState {
            radius_m: start.radius_m,
            speed_m_s: start.speed_m_s,
            flight_path_angle_rad: start.flight_path_angle_rad,
        };
        let lift = LiftControl {
            lambda: 1.0f32,
            vertical_fraction: 0.7,
        };
        let target = predict(&planet, &atm, &veh, &lift, &state, &predictor)
            .map(|p| p.range_m)
            .map_err(|_| "prediction failed")?;
        let limits = ReplanLimits {
            heat_flux_w_m2: 1e9f32,
            g_load: 1e3,
        };
        let (conv, _) = max_stack_bytes(|| {
            replan(
                &planet,
                &atm,
                &veh,
                &core::hint::black_box(start),
                target,
                &limits,
                &solver,
            )
        });
        let worst_limits = ReplanLimits {
            heat_flux_w_m2: 1.0f32,
            g_load: 1e3,
        };
        let worst_solver = ReplanConfig {
            tolerance_m: 1e-3,
            ..solver
        };
        let (worst, _) = max_stack_bytes(|| {
            replan(
                &planet,
                &atm,
                &veh,
                &core::hint::black_box(start),
                target,
                &worst_limits,
                &worst_solver,
            )
        });
        Ok((conv, worst))
    }

    fn run() -> Result<bool, &'static str> {
        let mut ok = report("guidance_tick", tick()?);
        ok &= report("navconv_f32", navconv()?);
        let (conv, worst) = replans()?;
        ok &= report("replan_converged_f32", conv);
        ok &= report("replan_worst_case_f32", worst);
        Ok(ok)
    }

    #[entry]
    fn main() -> ! {
        match run() {
            Ok(ok) => onboard_demo::exit(ok),
            Err(e) => {
                hprintln!("stack-bench: FAIL: {}", e);
                onboard_demo::exit(false)
            }
        }
    }

    #[exception]
    #[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        hprintln!("stack-bench: HardFault");
        onboard_demo::exit(false)
    }
}
