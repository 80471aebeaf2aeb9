//! A small dispersion campaign through the library API: the SRM glide, 40 dispersed flights
//! (seeded) in the stored-profile and re-planning modes, nothing written to disk:
//! `host_sim::campaign::{CampaignSetup, run_campaign}`.
//!
//! ```sh
//! cargo run --release -p host-sim --example dispersion_campaign -- 200   # flights (default 40)
//! ```

use host_sim::campaign::run::RunOptions;
use host_sim::campaign::{CampaignSetup, DispersionSettings, Mode, run_campaign};
use host_sim::scenario::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cases: u32 = match std::env::args().nth(1) {
        Some(n) => n.parse()?,
        None => 40,
    };
    // The terminal interface at 2500 m/s, as `host-sim dispersions --interface-speed 2500`.
    let setup = CampaignSetup::new(&Scenario::srm_glide(), "(built-in srm-glide)", Some(2500.0))?;
    let settings = DispersionSettings {
        cases,
        ..DispersionSettings::default()
    };
    let opts = RunOptions {
        modes: vec![Mode::StoredReversals, Mode::ReplanEstimation],
        out_dir: None,
        threads: None,
        progress: false,
    };
    let out = run_campaign(&setup, &settings, &opts)?;
    for s in &out.stats {
        println!(
            "{:?}: {} flights, miss mean {:.1} km, p95 {:.1} km, worst {:.1} km; peak heat flux {:.2} of the limit",
            s.mode,
            s.cases,
            s.miss_km.mean,
            s.miss_km.p95,
            s.miss_km.worst,
            s.heat_flux_ratio.worst
        );
    }
    Ok(())
}
