//! Trace the re-plans of a scenario's undispersed campaign flight (the nominal world) in the
//! best mode, against the stored profile with reversals.
//!
//! ```sh
//! cargo run --release -p host-sim --example replan_trace -- examples/validation/horus-2b-nominal.toml
//! ```
//!
//! `replan_trace SCENARIO [quiet] [CASE SEED]` flies dispersed case CASE of the default
//! dispersions with seed SEED instead (as `host-sim dispersions --seed SEED` draws it).

use std::path::Path;

use host_sim::campaign::flight::fly_case_logged;
use host_sim::campaign::{CampaignSetup, Mode};
use host_sim::scenario::read_scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: replan_trace SCENARIO [quiet]")?;
    let quiet = std::env::args().nth(2).is_some_and(|a| a == "quiet");
    let case: Option<(u32, u64)> = match (std::env::args().nth(3), std::env::args().nth(4)) {
        (Some(c), Some(s)) => Some((c.parse()?, s.parse()?)),
        _ => None,
    };
    let draw = case.map(|(i, seed)| {
        let settings = host_sim::campaign::DispersionSettings {
            seed,
            ..Default::default()
        };
        host_sim::campaign::draw::draw_case(&settings, i)
    });
    let sc = read_scenario(Path::new(&path))?;
    let setup = CampaignSetup::new(&sc, &path, None)?;
    let (stored, _) = fly_case_logged(&setup, draw.as_ref(), Mode::StoredReversals)?;
    let mode = setup.full_mode();
    let (guided, log) = fly_case_logged(&setup, draw.as_ref(), mode)?;
    println!(
        "{path}: stored+reversals miss {:.3} km ratios {:.3?}; {mode:?} miss {:.3} km ratios {:.3?} ({} re-plans)",
        stored.miss_m / 1e3,
        stored.limit_ratios,
        guided.miss_m / 1e3,
        guided.limit_ratios,
        log.len()
    );
    if quiet {
        return Ok(());
    }
    println!(
        "start_tick tick calls t_s e_hat alt_km v_m_s gamma_deg rtg_km case bank_deg pred_km pred-rtg_km applied bound est"
    );
    for (r, c) in &log {
        println!(
            "{} {} {} {:.0} {:.4} {:.2} {:.1} {:.3} {:.1} {:?} {:.2} {} {} {} {} {:?}",
            r.start_tick,
            r.tick,
            r.predictor_calls,
            r.time_s,
            r.normalized_energy,
            (c.nav.radius_m - setup.planet_radius_m) / 1e3,
            c.nav.speed_m_s,
            c.nav.flight_path_angle_rad.to_degrees(),
            r.range_to_go_m / 1e3,
            r.case,
            r.bank_rad.to_degrees(),
            r.predicted_range_m
                .map_or("-".into(), |p| format!("{:.1}", p / 1e3)),
            r.predicted_range_m.map_or("-".into(), |p| format!(
                "{:.1}",
                (p - r.range_to_go_m) / 1e3
            )),
            r.applied,
            r.path_bound_active,
            c.aero_scales.map(|a| (a.lift_to_drag, a.drag)),
        );
    }
    Ok(())
}
