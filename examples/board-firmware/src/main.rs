//! A minimal board firmware flying `guidance-core`'s re-planning guidance at its 2 s period.
//!
//! Everything it configures comes from the core: the SRM capsule's glide mission and vehicle
//! (`guidance_core::missions`), the re-planner's defaults (`ReplanningConfig::new`), the
//! predictor model (`PredictorModel::earth`), the onboard estimator
//! (`EstimatorConfig::default`) and the path-limit barrier (`PathBound::barrier`).
//!
//! The loop, once per guidance period (2 s, timed by SysTick):
//! 1. read the navigation state and the sensed lift and drag accelerations (here from a small
//!    onboard stand-in for the vehicle, [`Vehicle`]; on a real board: the navigation filter
//!    and the IMU);
//! 2. `sense` then `update` the guidance;
//! 3. send the command (angle of attack, bank) to the actuators (here: print it).
//!
//! It flies [`TICKS`] ticks, checks that every command is finite and within the table's
//! bounds and that the first tick re-planned, and exits through semihosting with status 0 (1
//! on any failure, a panic or a HardFault). Run: `cargo run --release` (QEMU `mps2-an386`).
#![no_std]
#![no_main]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use core::f32::consts::FRAC_PI_2;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::{ExceptionFrame, entry, exception};
use cortex_m_semihosting::{debug, hprintln};

use guidance_core::NavState;
use guidance_core::estimate::{AeroEstimator, EstimatorConfig, SensedAero};
use guidance_core::missions::{SRM_LIMITS, srm_glide, srm_vehicle};
use guidance_core::replan::{
    PathBound, PredictorModel, RangeTarget, ReplanningConfig, ReplanningGuidance,
};
use guidance_core::vinh::nondim::VehicleParams;

/// Guidance ticks flown (2 s each: 6 s of wall time in QEMU).
const TICKS: u32 = 3;

/// Core clock of the board \[Hz\] (QEMU `mps2-an386`: 25 MHz).
const CORE_CLOCK_HZ: u32 = 25_000_000;

/// Earth's radius and gravitational parameter \[m\], \[m^3/s^2\] (the core's constants).
const R_E: f32 = guidance_core::energy::EARTH_RADIUS_M as f32;
const MU: f32 = guidance_core::energy::EARTH_MU_M3_S2 as f32;

/// The flown range to aim at from the entry \[m\].
const TARGET_RANGE_M: f32 = 8.0e6;

/// Terminal interface speed \[m/s\]: where the predictions end.
const FINAL_SPEED_M_S: f32 = 2500.0;

/// Integration step of the stand-in vehicle \[s\].
const STEP_S: f32 = 0.05;

/// Stand-in for the vehicle and its sensors: planar point-mass flight on a spherical,
/// non-rotating Earth in an exponential atmosphere (1.225 kg/m^3, 7.2 km), with the SRM's
/// trim aerodynamics. On a real board this is the navigation filter and the IMU.
struct Vehicle {
    /// Radius \[m\], speed \[m/s\], flight-path angle \[rad\], range angle \[rad\].
    r: f32,
    v: f32,
    gamma: f32,
    theta: f32,
    /// Integration steps flown (the time is `steps * STEP_S`).
    steps: u32,
    params: VehicleParams<f32>,
}

impl Vehicle {
    /// Lift and drag accelerations \[m/s^2\] at the current state (lambda = 1: the trim point).
    fn aero(&self) -> SensedAero<f32> {
        let p = &self.params;
        let rho = 1.225 * libm::expf(-(self.r - R_E) / 7200.0);
        let q_s_m = 0.5 * rho * self.v * self.v * p.reference_area_m2 / p.mass_kg;
        let cl = libm::sqrtf(p.cd0 / p.k_polar);
        SensedAero {
            lift_m_s2: q_s_m * cl,
            drag_m_s2: q_s_m * 2.0 * p.cd0,
        }
    }

    /// Fly `dt` seconds at bank `sigma_rad` (explicit Euler, [`STEP_S`] steps).
    fn fly(&mut self, sigma_rad: f32, dt: f32) {
        let h = STEP_S;
        for _ in 0..libm::roundf(dt / h) as u32 {
            let a = self.aero();
            let g = MU / (self.r * self.r);
            let (sg, cg) = (libm::sinf(self.gamma), libm::cosf(self.gamma));
            let dr = self.v * sg;
            let dv = -a.drag_m_s2 - g * sg;
            let dgamma = (a.lift_m_s2 * libm::cosf(sigma_rad)
                - (g - self.v * self.v / self.r) * cg)
                / self.v;
            let dtheta = self.v * cg / self.r;
            self.r += h * dr;
            self.v += h * dv;
            self.gamma += h * dgamma;
            self.theta += h * dtheta;
            self.steps += 1;
        }
    }

    /// What navigation reports: heading east along the equator.
    fn nav(&self) -> NavState<f32> {
        NavState {
            time_s: self.steps as f32 * STEP_S,
            radius_m: self.r,
            speed_m_s: self.v,
            flight_path_angle_rad: self.gamma,
            heading_rad: FRAC_PI_2,
            latitude_rad: 0.0,
            longitude_rad: self.theta,
        }
    }
}

/// The firmware's work: set up the guidance, run the 2 s loop, check the commands.
fn run(syst: cortex_m::peripheral::SYST) -> Result<(), &'static str> {
    let mission = srm_glide::<f32>().map_err(|_| "mission")?;
    let vehicle = srm_vehicle::<f32>();
    let limits = SRM_LIMITS.load_limits();
    let mut model = PredictorModel::earth(vehicle);
    model.rotation_rate_rad_s = 0.0; // this stand-in Earth does not rotate
    let target = RangeTarget::FlownRangeAngle {
        total_rad: TARGET_RANGE_M / R_E,
    };
    let config = ReplanningConfig::new(target, FINAL_SPEED_M_S, limits, model);
    let energy = mission.earth_energy_normalizer().map_err(|_| "energy")?;
    let estimator = AeroEstimator::new(EstimatorConfig::default()).map_err(|_| "estimator")?;
    let mut guidance = ReplanningGuidance::new(
        mission.config,
        mission.table.clone(),
        mission.interpolation,
        energy,
        mission.initial,
        config,
    )
    .map_err(|_| "re-planning configuration")?
    .with_estimator(estimator)
    .with_path_bound(PathBound::barrier(limits), false)
    .map_err(|_| "path bound")?;

    let e = mission.entry;
    let mut plant = Vehicle {
        r: R_E + e.altitude_m as f32,
        v: e.speed_m_s as f32,
        gamma: e.flight_path_angle_rad as f32,
        theta: 0.0,
        steps: 0,
        params: vehicle,
    };
    let bounds = mission.table.bounds();
    let period_s = mission.config.period_s;
    let mut delay = cortex_m::delay::Delay::with_source(syst, CORE_CLOCK_HZ, SystClkSource::Core);
    let mut replanned = false;
    for tick in 0..TICKS {
        let nav = plant.nav();
        guidance
            .sense(&nav, &plant.aero())
            .map_err(|_| "sensed accelerations")?;
        let out = guidance.update(&nav).map_err(|_| "guidance update")?;
        let c = out.guidance.command;
        let in_bounds = c.alpha_rad >= bounds.alpha_min_rad
            && c.alpha_rad <= bounds.alpha_max_rad
            && c.sigma_rad >= bounds.sigma_min_rad
            && c.sigma_rad <= bounds.sigma_max_rad;
        if !(c.alpha_rad.is_finite() && c.sigma_rad.is_finite() && in_bounds) {
            return Err("command not finite or out of bounds");
        }
        if let Some(r) = out.replan {
            replanned |= tick == 0;
            hprintln!(
                "tick {}: re-plan {:?}, bank {} deg, {} predictor calls",
                tick,
                r.case,
                r.bank_rad.to_degrees(),
                r.predictor_calls
            );
        }
        hprintln!(
            "tick {}: t {} s, h {} km, V {} m/s -> alpha {} deg, bank {} deg",
            tick,
            nav.time_s,
            (nav.radius_m - R_E) / 1e3,
            nav.speed_m_s,
            c.alpha_rad.to_degrees(),
            c.sigma_rad.to_degrees()
        );
        // The actuators fly the held command until the next tick.
        plant.fly(c.sigma_rad, period_s);
        delay.delay_ms((period_s * 1000.0) as u32);
    }
    if !replanned {
        return Err("the first tick did not re-plan");
    }
    Ok(())
}

#[entry]
fn main() -> ! {
    let result = match cortex_m::Peripherals::take() {
        Some(p) => run(p.SYST),
        None => Err("peripherals taken"),
    };
    match result {
        Ok(()) => {
            hprintln!(
                "board-firmware: {} guidance ticks flown, every command in bounds",
                TICKS
            );
            exit(true)
        }
        Err(e) => {
            hprintln!("board-firmware: FAIL: {}", e);
            exit(false)
        }
    }
}

/// Exit QEMU through semihosting with status 0 (`success`) or 1.
fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::nop();
    }
}

#[exception]
#[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
    hprintln!("board-firmware: HardFault");
    exit(false)
}

#[panic_handler]
fn panic(_info: &core::panic::PanicInfo) -> ! {
    hprintln!("board-firmware: panic");
    exit(false)
}
