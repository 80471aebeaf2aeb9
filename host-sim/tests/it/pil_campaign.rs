//! Campaign cases in PIL (issue 19 items 4 and 5): each vehicle's campaign stack, every layer
//! the mode flies, uploaded to the firmware as one set-up image and flown in the case's
//! dispersed world; compared with its SIL flight.

use host_sim::campaign::draw::draw_case;
use host_sim::campaign::flight::fly_case;
use host_sim::campaign::{CampaignSetup, DispersionSettings, Mode};
use host_sim::pil::{PilConfig, PilError, fly_case_pil};
use host_sim::scenario::Scenario;

use crate::pil_support::{check_pil_memory_budget, pil_elf};

fn setup(name: &str) -> CampaignSetup {
    let sc = Scenario::try_builtin(name).unwrap();
    CampaignSetup::new(&sc, &format!("builtin:{name}"), None).unwrap()
}

fn fly(name: &str, target: &str, cases: &[Option<u32>]) {
    let setup = setup(name);
    let settings = DispersionSettings::default();
    let mode = Mode::ReplanEstimation;
    let elf = pil_elf(target);
    for &index in cases {
        let draw = index.map(|i| draw_case(&settings, i));
        let label = format!("{name} case {index:?} on {target}");
        let started = std::time::Instant::now();
        let pil = match fly_case_pil(&setup, draw.as_ref(), mode, PilConfig::new(elf.clone())) {
            Ok(r) => r,
            Err(e @ (PilError::QemuMissing { .. } | PilError::ElfMissing(_)))
                if std::env::var_os("PIL_REQUIRED").is_none() =>
            {
                println!("SKIPPED {label}: {e}");
                return;
            }
            Err(e) => panic!("{label}: {e}"),
        };
        let sil = fly_case(&setup, draw.as_ref(), mode).unwrap();
        println!(
            "{label}: {:.1} s; image {} B; twin {:?}; PIL miss {:.3} km rev {} replans {}; SIL miss {:.3} km rev {} replans {}; stack {:?}",
            started.elapsed().as_secs_f64(),
            pil.image_bytes,
            pil.twin,
            pil.result.miss_m / 1e3,
            pil.result.reversals,
            pil.result.replans,
            sil.miss_m / 1e3,
            sil.reversals,
            sil.replans,
            pil.stats.firmware_stack_bytes
        );
        let _ = check_pil_memory_budget;
    }
}

#[test]
fn pil_campaign_experiment() {
    fly("srm-glide", "thumbv7em-none-eabihf", &[None, Some(0)]);
    fly("horus-2b-reference", "thumbv7em-none-eabihf", &[None, Some(0)]);
}
