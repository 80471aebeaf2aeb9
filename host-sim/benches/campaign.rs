//! Dispersion-campaign throughput: 16 dispersed flights of the SRM glide (terminal interface
//! 2.5 km/s) per iteration, per guidance mode, on 1 and on 2 rayon threads. Flights per second
//! = 16 / time per iteration (docs/reference/performance.md, docs/reference/campaigns.md).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use host_sim::campaign::run::RunOptions;
use host_sim::campaign::{CampaignSetup, DispersionSettings, Mode, run_campaign};
use host_sim::scenario::Scenario;

const FLIGHTS: u32 = 16;

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

criterion_group!(benches, bench);
criterion_main!(benches);
