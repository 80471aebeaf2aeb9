//! Issue 20, item 3 ("never worse than the stored profile"): on the undispersed flight of
//! every mission of the held-out set (docs/validation/held-out-set.md, `examples/validation/`),
//! the guided flight (the scenario's full stack, the campaigns' best mode) misses by no more
//! than the stored profile with bank reversals, and exceeds no limit the stored profile holds.
//!
//! Not met today on five HORUS-2B missions (docs/validation/held-out-results.md, "Why the
//! re-planner makes good nominal flights worse"). [`KNOWN_WORSE`] lists them; like the
//! layering allow-lists it may only shrink: the test fails when a mission outside the list is
//! worse, and when a listed one is no longer worse (then remove it from the list). Each flight
//! is the nominal world of a campaign (`host-sim dispersions --scenario FILE`, the `nominal`
//! records of its summary.json), so the figures are those of the held-out table. About 1 s in
//! a release build (ignored: much slower in a debug build):
//!
//! ```sh
//! cargo test --release -p host-sim --test it nominal_guidance_no_worse_than_stored -- --ignored --nocapture
//! ```

use std::path::PathBuf;

use host_sim::campaign::flight::fly_case;
use host_sim::campaign::{CampaignSetup, Mode};
use host_sim::scenario::read_scenario;

/// The missions of the held-out set without the doubled dispersions (those are a settings
/// file over the nominal mission: the same undispersed flight).
const MISSIONS: [&str; 6] = [
    "nominal",
    "fpa-plus-0.3",
    "fpa-minus-0.3",
    "heading-plus-30",
    "range-minus-10",
    "range-plus-10",
];

/// The missions (file stems) whose guided undispersed flight is worse than the stored
/// profile's today (measured: docs/validation/held-out-results.md). May only shrink.
const KNOWN_WORSE: [&str; 2] = ["horus-2b-fpa-plus-0.3", "horus-2b-fpa-minus-0.3"];

#[test]
#[ignore = "24 flights, slow in a debug build; run in release with --ignored --nocapture (module docs)"]
fn nominal_guidance_no_worse_than_stored_on_the_held_out_set() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/validation");
    let mut worse = Vec::new();
    println!(
        "| mission | stored + reversals miss km | guided miss km | stored q / g / gdot | guided q / g / gdot | never worse |"
    );
    for vehicle in ["horus-2b", "srm-glide"] {
        for mission in MISSIONS {
            let stem = format!("{vehicle}-{mission}");
            let path = dir.join(format!("{stem}.toml"));
            let sc = read_scenario(&path).unwrap();
            let setup = CampaignSetup::new(&sc, &path.display().to_string(), None).unwrap();
            let stored = fly_case(&setup, None, Mode::StoredReversals).unwrap();
            let guided = fly_case(&setup, None, setup.full_mode()).unwrap();
            // The rule of scripts/validation_set.py: no larger miss, and every limit the
            // stored profile holds (ratio <= 1) held.
            let held = stored
                .limit_ratios
                .iter()
                .zip(guided.limit_ratios)
                .all(|(&s, g)| s > 1.0 || g <= 1.0);
            let ok = guided.miss_m <= stored.miss_m && held;
            println!(
                "| {stem} | {:.2} | {:.2} | {:.3?} | {:.3?} | {} |",
                stored.miss_m / 1e3,
                guided.miss_m / 1e3,
                stored.limit_ratios,
                guided.limit_ratios,
                if ok { "yes" } else { "NO" }
            );
            if !ok {
                worse.push(stem);
            }
        }
    }
    let unexpected: Vec<_> = worse
        .iter()
        .filter(|m| !KNOWN_WORSE.contains(&m.as_str()))
        .collect();
    let fixed: Vec<_> = KNOWN_WORSE
        .iter()
        .filter(|m| !worse.iter().any(|w| w == *m))
        .collect();
    assert!(
        unexpected.is_empty(),
        "guided undispersed flight worse than the stored profile on {unexpected:?}"
    );
    assert!(
        fixed.is_empty(),
        "no longer worse than the stored profile (remove from KNOWN_WORSE): {fixed:?}"
    );
}
