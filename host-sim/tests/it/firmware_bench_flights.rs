//! The recorded flights of the firmware's full-stack benchmarks (`onboard-demo/bench-data/`,
//! read by `insn-bench`, run by `cargo xtask bench-firmware`).
//!
//! Each file is one vehicle's campaign stack in its PIL mode (`Mode::ReplanEstimation`: the
//! re-planner with the estimator, bank reversals with the terminal law, the barrier where the
//! vehicle flies it) as the set-up image the host uploads in PIL
//! (`guidance_core::setup::image`), followed by every guidance tick of the nominal SIL
//! flight of that stack (`campaign::flight::fly_case_with`, the `f64` stack flying the
//! simulated vehicle): the navigation state and the sensed lift and drag accelerations the
//! stack was given at that tick. The firmware decodes the image in its scalars and replays
//! the ticks open loop, timing each one.
//!
//! Layout (little endian): `b"FSB1"`, image length `u32`, the image, tick count `u32`, then per
//! tick 9 `f32`: time \[s\], radius \[m\], speed \[m/s\], flight-path angle, heading, latitude,
//! longitude \[rad\], sensed lift and drag \[m/s^2\] (`NaN`: none). `f32` halves the file
//! (the M3's flash is 256 KiB); the M4F narrows to `f32` anyway.
//!
//! The test checks the committed files are what the current host flies; after a change to
//! the stack, the built-ins or the simulator, regenerate them with
//! `UPDATE_BENCH_FLIGHTS=1 cargo test --release -p host-sim --test it firmware_bench_flights`.

use std::path::PathBuf;

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;
use guidance_core::setup::image::{encode, image_capacity};
use guidance_core::stack::FlightStack;
use host_sim::campaign::flight::{CaseCounts, CaseSource, fly_case_with};
use host_sim::campaign::{CampaignSetup, Mode};
use host_sim::scenario::Scenario;
use host_sim::sim::AttitudeSource;
use host_sim::stack_loop::StackSource;

/// The campaign stack flown, recording every tick's inputs.
struct Recorder {
    inner: StackSource,
    sensed: Option<SensedAero<f64>>,
    ticks: Vec<(NavState<f64>, Option<SensedAero<f64>>)>,
}

impl AttitudeSource for Recorder {
    type Error = <StackSource as AttitudeSource>::Error;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), Self::Error> {
        self.ticks.push((*nav, self.sensed.take()));
        self.inner.tick(nav)
    }
    fn sense(&mut self, nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), Self::Error> {
        self.sensed = Some(*sensed);
        self.inner.sense(nav, sensed)
    }
    fn senses(&self) -> bool {
        self.inner.senses()
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        self.inner.attitude_at(time_s)
    }
    fn next_tick_s(&self) -> f64 {
        self.inner.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.inner.next_kink_s(time_s)
    }
}

impl CaseSource for Recorder {
    fn counts(&self) -> CaseCounts {
        self.inner.counts()
    }
}

/// The file of `vehicle` as the current host flies it.
fn record(vehicle: &str) -> Vec<u8> {
    let sc = Scenario::try_builtin(vehicle).unwrap();
    let setup = CampaignSetup::new(&sc, &format!("builtin:{vehicle}"), None).unwrap();
    let mode = Mode::ReplanEstimation;
    let config = setup.stack_of(mode);
    let mut image = vec![0u8; image_capacity(config.profile.table.len())];
    let n = encode(&config, &mut image).unwrap();
    image.truncate(n);
    let (result, rec, _) = fly_case_with(&setup, None, mode, 0.0, &mut |_| {}, |c| {
        Ok(Recorder {
            inner: StackSource::new(FlightStack::new(c).unwrap()),
            sensed: None,
            ticks: Vec::new(),
        })
    })
    .unwrap();
    assert!(
        result.reached_interface,
        "{vehicle}: {}",
        result.termination
    );
    let mut out = b"FSB1".to_vec();
    out.extend_from_slice(&u32::try_from(n).unwrap().to_le_bytes());
    out.extend_from_slice(&image);
    out.extend_from_slice(&u32::try_from(rec.ticks.len()).unwrap().to_le_bytes());
    for (nav, sensed) in &rec.ticks {
        let (lift, drag) = sensed.map_or((f64::NAN, f64::NAN), |s| (s.lift_m_s2, s.drag_m_s2));
        for x in [
            nav.time_s,
            nav.radius_m,
            nav.speed_m_s,
            nav.flight_path_angle_rad,
            nav.heading_rad,
            nav.latitude_rad,
            nav.longitude_rad,
            lift,
            drag,
        ] {
            #[allow(clippy::cast_possible_truncation)] // the file's f32 (module docs)
            out.extend_from_slice(&(x as f32).to_le_bytes());
        }
    }
    println!(
        "{vehicle}: image {n} B, {} ticks, {} reversals, {} re-plans, {} B",
        rec.ticks.len(),
        result.reversals,
        result.replans,
        out.len()
    );
    out
}

fn path(vehicle: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../onboard-demo/bench-data")
        .join(format!("{vehicle}.bin"))
}

#[test]
fn firmware_bench_flights_are_current() {
    let update = std::env::var_os("UPDATE_BENCH_FLIGHTS").is_some();
    for vehicle in ["horus-2b-reference", "srm-glide"] {
        let now = record(vehicle);
        let p = path(vehicle);
        if update {
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            let tmp = p.with_extension("bin.tmp");
            std::fs::write(&tmp, &now).unwrap();
            std::fs::rename(&tmp, &p).unwrap();
            continue;
        }
        let stored = std::fs::read(&p).unwrap_or_default();
        assert!(
            stored == now,
            "{}: not what the current host flies ({} B stored, {} B now); regenerate: \
             UPDATE_BENCH_FLIGHTS=1 cargo test --release -p host-sim --test it \
             firmware_bench_flights",
            p.display(),
            stored.len(),
            now.len()
        );
    }
}
