//! The scenario as TOML text (the inverse of [`parse_scenario`](super::parse_scenario)).

use guidance_core::nodes::Independent;

use super::{AtmosphereSpec, InterpolationKind, Scenario, VehicleSpec};

/// Rounding to 10 decimals for printing degree values (keeps 40.0 from printing as
/// 39.99999999999999 after a radian round trip).
trait Round10 {
    fn r10(self) -> f64;
}

impl Round10 for f64 {
    fn r10(self) -> f64 {
        (self * 1e10).round() / 1e10
    }
}

/// The scenario as annotated TOML text: every key with a comment giving its meaning, unit,
/// range and default, under a header naming the vehicle keys (the template that `host-sim
/// simulate --print-scenario` prints). It parses back to the same scenario (angles to
/// 1e-10 deg) wherever it is saved: file paths (`vehicle_file`, the atmosphere table) are
/// printed absolute.
#[must_use]
pub fn scenario_to_toml(sc: &Scenario) -> String {
    super::annotate::annotate(&plain_toml(sc), &plain_toml(&Scenario::default()))
}

/// `path` absolute (against the current directory, where the scenario's relative paths were
/// resolved), as printed; the path itself if the current directory is unknown.
fn absolute(path: &std::path::Path) -> String {
    std::path::absolute(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

/// The scenario as plain TOML text, without comments.
fn plain_toml(sc: &Scenario) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let r = sc.environment.planet.radius_m;
    let _ = writeln!(s, "name = {:?}", sc.name);
    match &sc.vehicle {
        VehicleSpec::Name(n) => {
            let _ = writeln!(s, "vehicle = {n:?}");
        }
        VehicleSpec::File(p) => {
            let _ = writeln!(s, "vehicle_file = {:?}", absolute(p));
        }
    }
    let e = &sc.environment;
    let _ = writeln!(
        s,
        "\n[environment]\natmosphere = {:?}\ngravity = {:?}\nrotating = {}",
        e.atmosphere.kind().as_str(),
        e.gravity.as_str(),
        e.rotating
    );
    let p = &e.planet;
    let _ = writeln!(
        s,
        "\n[environment.planet]\nradius_m = {:?}\nmu_m3_s2 = {:?}\nj2 = {:?}\nrotation_rate_rad_s = {:?}",
        p.radius_m, p.mu_m3_s2, p.j2, p.rotation_rate_rad_s
    );
    match &e.atmosphere {
        AtmosphereSpec::Us76 => {}
        AtmosphereSpec::Exponential(x) => {
            let _ = writeln!(
                s,
                "\n[environment.exponential]\nrho0_kg_m3 = {:?}\nscale_height_m = {:?}",
                x.rho0_kg_m3(),
                x.scale_height_m()
            );
        }
        AtmosphereSpec::Table(t) => {
            let _ = writeln!(
                s,
                "\n[environment.table]\nfile = {:?}\ngas_constant_j_kg_k = {:?}\nheat_capacity_ratio = {:?}",
                absolute(&t.file),
                t.model.gas_constant_j_kg_k(),
                t.model.heat_capacity_ratio()
            );
        }
    }
    let h = &e.heat_flux;
    let _ = writeln!(
        s,
        "\n[heat_flux]\ncoefficient = {:?}\nreference_density_kg_m3 = {:?}\nreference_speed_m_s = {:?}\nspeed_exponent = {:?}",
        h.coefficient, h.reference_density_kg_m3, h.reference_speed_m_s, h.speed_exponent
    );
    if let Some(rn) = sc.nose_radius_m {
        let _ = writeln!(s, "nose_radius_m = {rn:?}");
    }
    let en = &sc.entry;
    let _ = writeln!(
        s,
        "\n[entry]\naltitude_km = {:?}\nlongitude_deg = {:?}\nlatitude_deg = {:?}\nspeed_m_s = {:?}\nflight_path_angle_deg = {:?}\nheading_deg = {:?}",
        ((en.radius_m - r) / 1e3).r10(),
        en.longitude_rad.to_degrees().r10(),
        en.latitude_rad.to_degrees().r10(),
        en.speed_m_s,
        en.flight_path_angle_rad.to_degrees().r10(),
        en.heading_rad.to_degrees().r10()
    );
    let g = &sc.guidance;
    let (interp, tension) = match g.interpolation {
        InterpolationKind::Linear => ("linear", None),
        InterpolationKind::NaturalCubic => ("natural-cubic", None),
        InterpolationKind::Hermite { tension } => ("hermite", Some(tension)),
    };
    let _ = writeln!(
        s,
        "\n[guidance]\nindependent = {:?}\ninterpolation = {interp:?}",
        match g.independent {
            Independent::TimeS => "time",
            Independent::NormalizedEnergy => "energy",
        }
    );
    if let Some(t) = tension {
        let _ = writeln!(s, "tension = {t:?}");
    }
    let _ = writeln!(
        s,
        "period_s = {:?}\nalpha_rate_deg_s = {:?}\nsigma_rate_deg_s = {:?}\ninitial_alpha_deg = {:?}\ninitial_sigma_deg = {:?}\nnodes = [",
        g.period_s,
        g.alpha_rate_rad_s.to_degrees().r10(),
        g.sigma_rate_rad_s.to_degrees().r10(),
        g.initial.alpha_rad.to_degrees().r10(),
        g.initial.sigma_rad.to_degrees().r10()
    );
    for n in &g.nodes {
        let _ = writeln!(
            s,
            "  [{:?}, {:?}, {:?}],",
            n[0],
            n[1].to_degrees().r10(),
            n[2].to_degrees().r10()
        );
    }
    s.push_str("]\n\n[termination]\n");
    let t = &sc.termination;
    if let Some(h) = t.altitude_m {
        let _ = writeln!(s, "altitude_km = {:?}", h / 1e3);
    }
    if let Some(m) = t.mach {
        let _ = writeln!(s, "mach = {m:?}");
    }
    if let Some(e) = t.normalized_energy {
        let _ = writeln!(s, "normalized_energy = {e:?}");
    }
    let _ = writeln!(s, "max_time_s = {:?}", t.max_time_s);
    let tl = &sc.tolerances;
    let _ = writeln!(
        s,
        "\n[integrator]\nrtol = {:?}\nh_init_s = {:?}\nh_min_s = {:?}\nh_max_s = {:?}\nmax_steps = {}\nevent_time_tol_s = {:?}",
        tl.rtol, tl.h_init, tl.h_min, tl.h_max, tl.max_steps, tl.event_time_tol_s
    );
    let _ = writeln!(
        s,
        "\n[monitors]\ninterface_altitude_km = {:?}\ng_rate_window_s = {:?}",
        sc.interface_altitude_m / 1e3,
        sc.g_rate_window_s
    );
    let _ = writeln!(s, "\n[output]\ninterval_s = {:?}", sc.output_interval_s);
    if let Some(l) = &sc.layers {
        layers(&mut s, l);
        target(&mut s, l.target, r);
        if let Some(i) = l.interface {
            let _ = writeln!(s, "{} = {:?}", i.key(), i.value());
        }
    }
    s
}

/// The `[guidance.target]` section (planet radius `r` \[m\]).
fn target(s: &mut String, t: super::TargetSpec, r: f64) {
    use std::fmt::Write as _;
    let _ = writeln!(s, "\n[guidance.target]");
    let _ = match t {
        super::TargetSpec::Nominal => writeln!(s, "nominal = true"),
        super::TargetSpec::Point {
            latitude_rad,
            longitude_rad,
        } => writeln!(
            s,
            "latitude_deg = {:?}\nlongitude_deg = {:?}",
            latitude_rad.to_degrees(),
            longitude_rad.to_degrees()
        ),
        super::TargetSpec::Range {
            downrange_rad,
            crossrange_rad,
        } => writeln!(
            s,
            "downrange_km = {:?}\ncrossrange_km = {:?}",
            downrange_rad * r / 1e3,
            crossrange_rad * r / 1e3
        ),
    };
}

/// The layer sections `[guidance.<layer>]` of the layers on, every key of each
/// ([`super::guidance_layers::LAYER_KEYS`]; an unset optional setting is left out).
fn layers(s: &mut String, l: &super::GuidanceLayers) {
    use std::fmt::Write as _;
    let Ok(toml::Value::Table(mut t)) = toml::Value::try_from(&l.settings) else {
        return;
    };
    // The settings a case record leaves out at their defaults: printed here (the template
    // shows every key; only an unset optional one is left out).
    let g = &l.settings;
    for (field, v) in [
        (
            "predictor_aero_mach",
            toml::Value::Boolean(g.predictor_aero_mach),
        ),
        (
            "predictor_rotation",
            toml::Value::Boolean(g.predictor_rotation),
        ),
        ("bank_shape", toml::Value::Boolean(g.bank_shape)),
        (
            "predictor_lift_profile",
            toml::Value::Boolean(g.predictor_lift_profile),
        ),
        (
            "path_bound_predicted",
            toml::Value::Boolean(g.path_bound_predicted),
        ),
        (
            "path_bound_descent_time_s",
            toml::Value::Float(g.path_bound_descent_time_s),
        ),
        (
            "terminal_tolerance_km",
            toml::Value::Float(g.terminal_tolerance_km),
        ),
        (
            "terminal_reversal_lead_s",
            toml::Value::Float(g.terminal_reversal_lead_s),
        ),
        (
            "replan_limit_scale",
            toml::Value::Array(g.replan_limit_scale.map(toml::Value::Float).to_vec()),
        ),
        (
            "replan_solver_steps_per_tick",
            toml::Value::Integer(i64::from(g.replan_solver_steps_per_tick)),
        ),
    ] {
        t.entry(field).or_insert(v);
    }
    let on = l.layers;
    for (section, enabled) in [
        ("lateral", on.lateral),
        ("replanning", on.replan),
        ("estimator", on.estimator),
        ("barrier", on.barrier),
    ] {
        if !enabled {
            continue;
        }
        let _ = writeln!(s, "\n[guidance.{section}]");
        let keys = super::guidance_layers::LAYER_KEYS
            .iter()
            .filter(|(_, sec, _)| *sec == section);
        for (field, _, key) in keys {
            let Some(v) = t.get(*field) else { continue };
            let v = match (*field, *key, v) {
                ("path_bound_barrier", "frequency_rad_s", toml::Value::Array(a)) => a.first(),
                ("path_bound_barrier", _, toml::Value::Array(a)) => a.get(1),
                _ => Some(v),
            };
            if let Some(v) = v {
                let _ = writeln!(s, "{key} = {v}");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::parse_scenario;

    /// Every key the printout can hold has a note (a new key needs one in `annotate.rs`).
    #[test]
    fn every_printed_key_is_annotated() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/srm-glide-replanning.toml"
        ))
        .unwrap();
        let replanning = parse_scenario(&text, "x.toml", std::path::Path::new(".")).unwrap();
        let exponential = parse_scenario(
            "vehicle = \"horus-2b\"\n[environment]\natmosphere = \"exponential\"\n[entry]\naltitude_km = 122.0\nlongitude_deg = -106.7\nlatitude_deg = -22.3\nspeed_m_s = 7435.5\nflight_path_angle_deg = -1.43\nheading_deg = 70.75\n[guidance]\nindependent = \"energy\"\ninterpolation = \"hermite\"\ntension = 0.5\nperiod_s = 2.0\nalpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\ninitial_alpha_deg = 40.0\ninitial_sigma_deg = 0.0\nnodes = [[1.0, 40.0, 0.0], [0.5, 30.0, 50.0], [0.0, 10.0, 0.0]]\n[termination]\nmax_time_s = 2500.0\nmach = 3.0\nnormalized_energy = 0.01\n",
            "x.toml",
            std::path::Path::new("."),
        )
        .unwrap();
        let scenarios = [
            Scenario::default(),
            Scenario::srm_glide(),
            replanning,
            exponential,
        ];
        for sc in &scenarios {
            let missing = super::super::annotate::keys_without_notes(&plain_toml(sc));
            assert!(
                missing.is_empty(),
                "{}: keys without a note: {missing:?}",
                sc.name
            );
            let annotated = scenario_to_toml(sc);
            assert!(
                annotated.contains("vehicle_file"),
                "the header names vehicle_file"
            );
            let back = parse_scenario(&annotated, "x.toml", std::path::Path::new(".")).unwrap();
            assert_eq!(plain_toml(&back), plain_toml(sc));
        }
    }
}
