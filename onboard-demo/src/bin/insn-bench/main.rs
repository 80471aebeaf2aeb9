//! Instruction counts of guidance-core on the target, under QEMU `-icount shift=0`
//! (run by `cargo xtask bench-firmware`; see `onboard_demo::insn` for the method).
//!
//! Prints one line per benchmark: `bench <name>: <instructions> insn/call`. The first line
//! is the calibration (10 000 `nop`s must count as 10 000 instructions); the binary exits 1 if
//! the calibration is off, so a wrong QEMU setting cannot produce plausible-looking numbers.
//!
//! Firmware only: built for the host (as `cargo test --workspace` and `cargo clippy
//! --workspace` do) this binary is a stub that says so and exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "insn-bench: Cortex-M firmware, not a host program: build it with \
         --target thumbv7em-none-eabihf or thumbv7m-none-eabi (see README)"
    );
    std::process::exit(2);
}

/// The re-planning and onboard-estimation benchmarks (firmware only).
#[cfg(target_os = "none")]
mod replanning;

/// The numerical-predictor benchmarks (firmware only).
#[cfg(target_os = "none")]
mod numerical;

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use cortex_m_semihosting::hprintln;
    use guidance_core::energy::EARTH_RADIUS_M;
    use guidance_core::guidance::{Command, Guidance, GuidanceConfig};
    use guidance_core::interp::Interpolation;
    use guidance_core::missions::horus2b_reference;
    use guidance_core::vinh::glide::GlideSolution;
    use guidance_core::vinh::nondim::{
        EntryState, ExpAtmosphere, LiftControl, NonDim, Planet, VehicleParams,
    };
    use guidance_core::vinh::predict::{PredictorConfig, predict};
    use guidance_core::vinh::skip::SkipSolution;
    use guidance_core::{NavState, Scalar};
    use onboard_demo::insn::InsnCounter;

    use crate::numerical::{bench_numerical, bench_numerical_tick};
    use crate::replanning::{bench_estimator, bench_replan, bench_replanning_tick};

    #[cfg(target_abi = "eabihf")]
    type Num = f32;
    #[cfg(not(target_abi = "eabihf"))]
    type Num = guidance_core::Fixed;

    pub(crate) use onboard_demo::insn::INSN_PER_TICK;

    /// Calls per measurement of the per-call benchmarks.
    pub(crate) const REPS: u32 = 100;

    fn nav(t: f64, speed: f64) -> NavState<Num> {
        NavState {
            time_s: Num::from_f64(t),
            radius_m: Num::from_f64(EARTH_RADIUS_M + 80_000.0),
            speed_m_s: Num::from_f64(speed),
            flight_path_angle_rad: Num::ZERO,
            heading_rad: Num::ZERO,
            latitude_rad: Num::ZERO,
            longitude_rad: Num::ZERO,
        }
    }

    fn bench_guidance(c: &mut InsnCounter, name: &str, kind: Interpolation<Num>) -> bool {
        let Ok(mission) = horus2b_reference::<Num>() else {
            return false;
        };
        let Ok(energy) = mission.earth_energy_normalizer() else {
            return false;
        };
        let table = mission.table;
        let initial = Command {
            alpha_rad: Num::from_f64(0.6981),
            sigma_rad: Num::ZERO,
        };
        let Ok(mut g) = Guidance::new(
            GuidanceConfig::thesis_default(),
            table,
            kind,
            energy,
            initial,
        ) else {
            return false;
        };
        let mut ok = true;
        // Every call is a tick: times 2 s apart, crossing the bank-angle step of the reference
        // mission. The samples are built before the measurement (f64 -> Num conversions are
        // soft float on the M3), so only the guidance updates are counted; subtracting a
        // separately measured construction loop was fragile to inlining.
        let mut samples = [nav(0.0, 0.0); REPS as usize];
        for (k, s) in (0u32..).zip(samples.iter_mut()) {
            *s = nav(250.0 + 2.0 * f64::from(k), 7000.0 - f64::from(k));
        }
        let ticks = c.ticks(|| {
            for s in &samples {
                ok &= g.update(core::hint::black_box(s)).is_ok();
            }
        });
        let overhead = c.ticks(|| {
            for s in &samples {
                core::hint::black_box(s);
            }
        });
        let per_call = (ticks.saturating_sub(overhead)) * INSN_PER_TICK / REPS;
        hprintln!("bench guidance_tick_{}: {} insn/call", name, per_call);
        ok
    }

    /// SRM capsule (thesis table 2.3) with the drag polar back-derived in docs/reference/vinh.md.
    pub(crate) fn srm() -> VehicleParams<f32> {
        VehicleParams {
            mass_kg: 38.77,
            reference_area_m2: 0.441,
            cd0: 0.2576,
            k_polar: 0.1879,
            nose_radius_m: 0.9,
        }
    }

    /// Closed forms in `f32` (hardware FPU on the M4F, soft float on the M3): one skip
    /// solution with its exit state, one glide point, one full predictor chain.
    fn bench_closed_forms(c: &mut InsnCounter) -> bool {
        let planet = Planet::<f32>::earth();
        let atm = ExpAtmosphere::<f32>::earth();
        let veh = srm();
        let lift = LiftControl::<f32>::max_ld_lift_up();
        let entry = EntryState {
            radius_m: 6_378_137.0 + 122_000.0,
            speed_m_s: 7_500.0,
            flight_path_angle_rad: -0.035,
        };
        let mut ok = true;
        let reps = 10u32;
        let skip = c.ticks(|| {
            for _ in 0..reps {
                let r = NonDim::new(&planet, &atm, &veh, &lift, &entry)
                    .and_then(|nd| SkipSolution::new(&nd));
                ok &= r.is_ok();
                core::hint::black_box(r.map(|s| s.exit()).ok());
            }
        });
        hprintln!(
            "bench vinh_skip_solution_f32: {} insn/call",
            skip * INSN_PER_TICK / reps
        );
        let skip_peaks = c.ticks(|| {
            for _ in 0..reps {
                let r = NonDim::new(&planet, &atm, &veh, &lift, &entry)
                    .and_then(|nd| SkipSolution::new(&nd))
                    .and_then(|s| Ok((s.exit(), s.peaks()?)));
                ok &= r.is_ok();
                core::hint::black_box(r.ok());
            }
        });
        hprintln!(
            "bench vinh_skip_with_peaks_f32: {} insn/call",
            skip_peaks * INSN_PER_TICK / reps
        );
        let glide = c.ticks(|| {
            for _ in 0..reps {
                let r = GlideSolution::new(&planet, &atm, &veh, &lift, 6_378_137.0 + 80_000.0)
                    .and_then(|g| g.point_at_u(core::hint::black_box(0.5)));
                ok &= r.is_ok();
                core::hint::black_box(r.ok());
            }
        });
        hprintln!(
            "bench vinh_glide_point_f32: {} insn/call",
            glide * INSN_PER_TICK / reps
        );
        let config = PredictorConfig {
            final_speed_m_s: 2_000.0,
            max_skips: 3,
        };
        let chain = c.ticks(|| {
            for _ in 0..reps {
                let r = predict(
                    &planet,
                    &atm,
                    &veh,
                    &lift,
                    &core::hint::black_box(entry),
                    &config,
                );
                ok &= r.is_ok();
                core::hint::black_box(r.ok());
            }
        });
        hprintln!(
            "bench vinh_predictor_chain_f32: {} insn/call",
            chain * INSN_PER_TICK / reps
        );
        ok
    }

    #[entry]
    fn main() -> ! {
        let Some(p) = cortex_m::Peripherals::take() else {
            onboard_demo::exit(false)
        };
        let mut c = InsnCounter::new(p.SYST);
        if !onboard_demo::insn::calibrate(&mut c) {
            onboard_demo::exit(false)
        }
        let mut ok = bench_guidance(&mut c, "linear", Interpolation::Linear);
        ok &= bench_guidance(&mut c, "natural_cubic", Interpolation::NaturalCubic);
        ok &= bench_guidance(
            &mut c,
            "cardinal_hermite",
            Interpolation::CardinalHermite {
                tension: Num::from_f64(0.5),
            },
        );
        ok &= bench_closed_forms(&mut c);
        ok &= bench_replan(&mut c);
        ok &= bench_replanning_tick(&mut c);
        ok &= bench_estimator(&mut c);
        ok &= bench_numerical(&mut c);
        ok &= bench_numerical_tick(&mut c);
        onboard_demo::exit(ok)
    }

    #[exception]
    #[allow(unsafe_code)]
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        onboard_demo::exit(false)
    }
}
