//! Dispersion-campaign throughput.
//! * `campaign_16_flights`: 16 dispersed flights of the SRM glide (terminal interface
//!   2.5 km/s) per iteration, per guidance mode, on 1 and on 2 rayon threads. Flights per
//!   second = 16 / time per iteration (docs/reference/performance.md, docs/reference/campaigns.md).
//! * `campaign_per_core`: flights per second on one core for every campaign mode of both
//!   vehicles: the SRM glide as above, and HORUS-2B (the built-in reference scenario with
//!   its built-in stack, examples/horus-2b-stack.toml: numerical predictor, path-limit
//!   barrier, terminal crossrange law) to its scenario's end, [`PER_CORE_FLIGHTS`] flights per
//!   iteration on one rayon thread. Flights per second per core = that count / time per
//!   iteration (docs/reference/campaign-throughput.md).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::campaign::run::RunOptions;
use host_sim::campaign::{CampaignSetup, DispersionSettings, Mode, run_campaign};
use host_sim::scenario::Scenario;

const FLIGHTS: u32 = 16;

/// Flights per iteration of `campaign_per_core`.
const PER_CORE_FLIGHTS: u32 = 8;

fn bench(c: &mut Criterion) {
    let setup = CampaignSetup::new(&Scenario::srm_glide(), "builtin:srm-glide", Some(2500.0))
        .expect("SRM campaign set-up");
    let settings = DispersionSettings {
        cases: FLIGHTS,
        interface_speed_m_s: Some(2500.0),
        ..DispersionSettings::default()
    };
    let mut g = c.benchmark_group("campaign_16_flights");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for mode in [
        Mode::StoredReversals,
        Mode::ReplanReversals,
        Mode::ReplanEstimation,
    ] {
        for threads in [1, 2] {
            let opts = RunOptions {
                modes: vec![mode],
                out_dir: None,
                threads: Some(threads),
                progress: false,
            };
            g.bench_function(format!("{}/{threads}-threads", mode.name()), |b| {
                b.iter(|| black_box(run_campaign(&setup, &settings, &opts).expect("campaign")))
            });
        }
    }
    g.finish();
}

fn per_core(c: &mut Criterion) {
    let horus = DispersionSettings::default();
    let srm = DispersionSettings {
        interface_speed_m_s: Some(2500.0),
        ..DispersionSettings::default()
    };
    let vehicles = [
        ("srm", Scenario::srm_glide(), "builtin:srm-glide", srm),
        (
            "horus-2b",
            Scenario::default(),
            "builtin:horus-2b-reference",
            horus,
        ),
    ];
    let mut g = c.benchmark_group("campaign_per_core");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for (name, sc, file, settings) in vehicles {
        let settings = DispersionSettings {
            cases: PER_CORE_FLIGHTS,
            ..settings
        };
        let setup =
            CampaignSetup::new(&sc, file, settings.interface_speed_m_s).expect("campaign set-up");
        for mode in setup.modes() {
            let opts = RunOptions {
                modes: vec![mode],
                out_dir: None,
                threads: Some(1),
                progress: false,
            };
            g.bench_function(format!("{name}/{}", mode.name()), |b| {
                b.iter(|| black_box(run_campaign(&setup, &settings, &opts).expect("campaign")))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench, per_core);
criterion_main!(benches);
