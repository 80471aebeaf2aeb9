//! Fly a scenario file (or the built-in HORUS-2B reference mission) with the library API and
//! print its summary: `host_sim::scenario::read_scenario`, `fly`.
//!
//! ```sh
//! cargo run --release -p host-sim --example fly_scenario                       # HORUS-2B
//! cargo run --release -p host-sim --example fly_scenario -- examples/betts-shuttle.toml
//! ```

use std::path::Path;

use host_sim::scenario::{Scenario, fly, read_scenario};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (sc, file) = match std::env::args().nth(1) {
        Some(p) => (read_scenario(Path::new(&p))?, p),
        None => (Scenario::default(), "(built-in horus-2b-reference)".into()),
    };
    let flight = fly(&sc, &file, &mut |_| {})?;
    let s = &flight.result.summary;
    println!("{} ({}, vehicle {})", sc.name, file, flight.vehicle.name);
    println!("  end: {:?} after {:.1} s", s.termination, s.flight_time_s);
    println!(
        "  range angle {:.2} deg ({:.0} km on the sphere)",
        s.range_angle_rad.to_degrees(),
        s.range_angle_rad * flight.environment.planet.radius_m / 1e3
    );
    println!(
        "  peak heat flux {:.1} kW/m^2 (limit {:.1}), peak g-load {:.2} (limit {:.2})",
        s.peak_heat_flux_w_m2.value / 1e3,
        flight.vehicle.limits.heat_flux_w_m2 / 1e3,
        s.peak_g_load.value,
        flight.vehicle.limits.g_load
    );
    if let Some(last) = flight.result.samples.last() {
        println!(
            "  final state: {:.2} km, {:.1} m/s",
            last.conditions.altitude_m / 1e3,
            last.state.speed_m_s
        );
    }
    Ok(())
}
