//! Lift down (issue 24 item 3): an Apollo-style capsule flying a bank of more than 90 deg,
//! written in a scenario file and flown closed loop, against an independent integration of
//! the planar entry equations (classic RK4 written here, not the simulator's code). In a
//! non-rotating central field the radius, speed and flight-path angle do not depend on the
//! heading, so the planar equations with the vertical lift L cos(sigma) give them exactly.

use std::path::PathBuf;

use host_sim::scenario::{fly, parse_scenario};

const MU: f64 = 3.986_004_418e14;
const RE: f64 = 6_378_137.0;
const RHO0: f64 = 1.225;
const H_S: f64 = 7200.0;
const MASS: f64 = 5000.0;
const AREA: f64 = 12.0;
const CL: f64 = 0.4;
const CD: f64 = 1.3;

const VEHICLE: &str = "name = \"apollo-like\"\nmass_kg = 5000.0\nreference_area_m2 = 12.0\n\
    nose_radius_m = 2.0\n[limits]\nheat_flux_kw_m2 = 5000.0\ng_load = 20.0\n\
    g_load_rate_per_s = 10.0\nalpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\n\
    [aero]\nkind = \"trim\"\ncl = 0.4\ncd = 1.3\n";

fn scenario(bank_deg: f64) -> String {
    format!(
        "name = \"lift-down\"\nvehicle_file = \"capsule.toml\"\n\
         [environment]\natmosphere = \"exponential\"\ngravity = \"central\"\nrotating = false\n\
         [environment.planet]\nradius_m = {RE:?}\nmu_m3_s2 = {MU:?}\nj2 = 0.0\n\
         [environment.exponential]\nrho0_kg_m3 = {RHO0:?}\nscale_height_m = {H_S:?}\n\
         [entry]\naltitude_km = 120.0\nlongitude_deg = 0.0\nlatitude_deg = 0.0\n\
         speed_m_s = 7800.0\nflight_path_angle_deg = -1.5\nheading_deg = 90.0\n\
         [guidance]\nindependent = \"time\"\ninterpolation = \"linear\"\nperiod_s = 2.0\n\
         alpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\ninitial_alpha_deg = 0.0\n\
         initial_sigma_deg = {bank_deg:?}\nnodes = [[0, 0, {bank_deg:?}], [5000, 0, {bank_deg:?}]]\n\
         [termination]\naltitude_km = 20.0\nmax_time_s = 3000.0\n\
         [integrator]\nrtol = 1e-11\n[output]\ninterval_s = 10.0\n"
    )
}

/// Planar entry equations: state (r, V, gamma), constant bank `sigma` \[rad\].
fn rhs(y: [f64; 3], sigma: f64) -> [f64; 3] {
    let [r, v, g] = y;
    let rho = RHO0 * (-(r - RE) / H_S).exp();
    let q = 0.5 * rho * v * v * AREA / MASS;
    let grav = MU / (r * r);
    [
        v * g.sin(),
        -q * CD - grav * g.sin(),
        (q * CL * sigma.cos() - (grav - v * v / r) * g.cos()) / v,
    ]
}

/// RK4 from the entry to `t_end` \[s\] with step `h` \[s\].
fn rk4(sigma: f64, t_end: f64, h: f64) -> [f64; 3] {
    let mut y = [RE + 120e3, 7800.0, (-1.5f64).to_radians()];
    let n = (t_end / h).round() as usize;
    let h = t_end / n as f64;
    let add =
        |y: [f64; 3], k: [f64; 3], s: f64| [y[0] + s * k[0], y[1] + s * k[1], y[2] + s * k[2]];
    for _ in 0..n {
        let k1 = rhs(y, sigma);
        let k2 = rhs(add(y, k1, h / 2.0), sigma);
        let k3 = rhs(add(y, k2, h / 2.0), sigma);
        let k4 = rhs(add(y, k3, h), sigma);
        for i in 0..3 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    y
}

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-lift-down-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("capsule.toml"), VEHICLE).unwrap();
    d
}

#[test]
fn validate_rk4_planar_lift_down_capsule() {
    let d = dir("rk4");
    let mut worst = [0.0f64; 3];
    let mut ends = Vec::new();
    for bank in [150.0, -150.0, 120.0] {
        let sc = parse_scenario(&scenario(bank), "lift-down.toml", &d).unwrap();
        let f = fly(&sc, "lift-down.toml", &mut |_| {}).unwrap();
        let sigma = f64::to_radians(bank);
        // Flown as written: the bank of every sample is the file's.
        for s in &f.result.samples {
            assert!(
                (s.attitude.sigma_rad - sigma).abs() < 1e-12,
                "{bank}: {:?}",
                s.attitude
            );
        }
        let mut compared = 0;
        for s in f.result.samples.iter().filter(|s| s.time_s > 0.0) {
            // Each sample against RK4 at its time (0.01 s steps: RK4's error is ~1e-9 there).
            let y = rk4(sigma, s.time_s, 0.01);
            let e = [
                (s.state.radius_m - y[0]).abs(),
                (s.state.speed_m_s - y[1]).abs(),
                (s.state.flight_path_angle_rad - y[2]).abs(),
            ];
            for i in 0..3 {
                worst[i] = worst[i].max(e[i]);
            }
            compared += 1;
        }
        assert!(compared > 10, "{bank}: {compared} samples");
        ends.push((
            f.result.summary.flight_time_s,
            f.result.summary.peak_g_load.value,
        ));
    }
    println!(
        "lift-down against RK4: worst |dr| {:.3e} m, |dV| {:.3e} m/s, |dgamma| {:.3e} rad; ends {ends:?}",
        worst[0], worst[1], worst[2]
    );
    assert!(
        worst[0] < 1e-3 && worst[1] < 1e-4 && worst[2] < 1e-8,
        "{worst:?}"
    );
    // The sign of a lift-down bank turns the vehicle, it does not change r, V, gamma.
    assert!((ends[0].0 - ends[1].0).abs() < 1e-6, "{ends:?}");
    // More lift down (150 deg: cos = -0.87 against -0.5) dives faster and pulls harder.
    assert!(ends[0].0 < ends[2].0 && ends[0].1 > ends[2].1, "{ends:?}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Banks outside (-180, 180] deg are refused naming the field and the range.
#[test]
fn banks_outside_plus_minus_180_are_refused() {
    let d = dir("range");
    for (from, to, field) in [
        (
            "initial_sigma_deg = 150.0",
            "initial_sigma_deg = -180.0",
            "guidance.initial_sigma_deg",
        ),
        (
            "initial_sigma_deg = 150.0",
            "initial_sigma_deg = 181.0",
            "guidance.initial_sigma_deg",
        ),
        ("[0, 0, 150.0]", "[0, 0, 190.0]", "guidance.nodes[0]"),
        ("[0, 0, 150.0]", "[0, 0, -180.0]", "guidance.nodes[0]"),
    ] {
        let text = scenario(150.0).replacen(from, to, 1);
        assert_ne!(text, scenario(150.0));
        let e = parse_scenario(&text, "b.toml", &d).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains("(-180, 180] deg"), "{e}");
    }
    // 180 deg itself (full lift down) is a bank.
    let text = scenario(180.0);
    parse_scenario(&text, "b.toml", &d).unwrap();
    let _ = std::fs::remove_dir_all(&d);
}
