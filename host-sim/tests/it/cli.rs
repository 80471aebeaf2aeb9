//! The `host-sim` command line: run directories, error messages on bad input, help and the
//! small subcommands. The binary is run through `std::process::Command`.

use std::path::PathBuf;
use std::process::Command;

use host_sim::cli::run;
use host_sim::scenario::{Scenario, parse_scenario, scenario_to_toml};

use crate::support::complete_scenario;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_host-sim"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("host-sim-it-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const TINY: &str = r#"
name = "tiny"
vehicle = "horus-2b"

[environment]
preset = "simplified"

[entry]
altitude_km = 122.0
longitude_deg = 0.0
latitude_deg = 0.0
speed_m_s = 7400.0
flight_path_angle_deg = -1.5
heading_deg = 90.0

[guidance]
independent = "energy"
interpolation = "hermite"
tension = 0.5
period_s = 2.0
alpha_rate_deg_s = 5.0
sigma_rate_deg_s = 15.0
initial_alpha_deg = 40.0
initial_sigma_deg = 0.0
nodes = [[1.0, 40, 0], [0.9, 35, 45], [0.5, 20, 60]]

[termination]
max_time_s = 30.0

[output]
interval_s = 1.0
"#;

#[test]
fn simulate_tiny_scenario_writes_csv_json_svg() {
    let dir = temp_dir("tiny");
    let sc = dir.join("tiny.toml");
    std::fs::write(&sc, TINY).unwrap();
    let out = dir.join("run");
    let o = bin()
        .args(["simulate", "--scenario"])
        .arg(&sc)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"));
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for col in [
        "time_s",
        "altitude_km",
        "speed_m_s",
        "gamma_deg",
        "alpha_deg",
        "sigma_deg",
        "heat_flux_kw_m2",
        "g_load",
    ] {
        assert!(
            header.split(',').any(|c| c == col),
            "missing column {col}: {header}"
        );
    }
    // Start, 1 s samples up to 30 s (the 30 s one is the end), end: 1 + 29 + 1 rows.
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 31, "{csv}");
    let last: Vec<&str> = rows[rows.len() - 1].split(',').collect();
    assert_eq!(last[0].parse::<f64>().unwrap(), 30.0);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["scenario"], "tiny");
    assert_eq!(json["termination"], "max_time");
    assert!(json["heat_load_mj_m2"].as_f64().unwrap() > 0.0);
    assert!(json["rhs_evals"].as_u64().unwrap() > 0);
    // The PIL counters are written only for PIL runs.
    assert!(json.get("pil").is_none(), "{json}");
    for svg in [
        "altitude_velocity.svg",
        "heat_flux.svg",
        "g_load.svg",
        "attitude.svg",
        "g_load_rate.svg",
        "ground_track.svg",
        "attitude_rate.svg",
    ] {
        let text = std::fs::read_to_string(out.join(svg)).unwrap();
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{svg}"
        );
        assert!(text.contains("<polyline"), "{svg}");
        // The same chart as a PNG image of the plot size (8-bit RGB).
        let png_path = out.join(svg.replace(".svg", ".png"));
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(&png_path).unwrap(),
        ));
        let reader = decoder.read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.width, info.height), (720, 460), "{svg}");
        assert_eq!(info.color_type, png::ColorType::Rgb, "{svg}");
    }
    // No temporary files left behind by the atomic writes.
    for e in std::fs::read_dir(&out).unwrap() {
        let n = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!n.contains(".tmp-"), "left over {n}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each bad scenario must fail with a non-zero exit, no panic, and a message naming the
/// file, the field and the value.
#[test]
fn bad_scenarios_name_file_field_and_value() {
    let dir = temp_dir("bad");
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "alt_string.toml",
            "[entry]\naltitude_km = \"high\"\n",
            &["entry.altitude_km", "\"high\"", "number"],
        ),
        (
            "alt_negative.toml",
            "[entry]\naltitude_km = -5.0\n",
            &["entry.altitude_km", "-5", "must be"],
        ),
        (
            "vehicle.toml",
            "vehicle = \"x-37\"\n",
            &["vehicle", "\"x-37\"", "unknown vehicle"],
        ),
        (
            "typo.toml",
            "[entry]\naltitde_km = 100.0\n",
            &["entry.altitde_km", "100", "unknown field"],
        ),
        (
            "nodes.toml",
            "[guidance]\nnodes = [[0, 40, 0], [10, 60, 0]]\n",
            &["guidance.nodes[1]", "60", "alpha"],
        ),
        (
            "order.toml",
            "[guidance]\nnodes = [[0, 40, 0], [0, 30, 0]]\n",
            &["guidance.nodes[1]", "increase"],
        ),
        (
            "syntax.toml",
            "[entry]\naltitude_km = = 3\n",
            &["malformed TOML", "line 2", "altitude_km = = 3"],
        ),
        (
            "vfile.toml",
            "vehicle_file = \"does-not-exist.toml\"\n",
            &["does-not-exist.toml", "cannot read"],
        ),
        (
            "rtol.toml",
            "[integrator]\nrtol = 0.5\n",
            &["integrator.rtol", "0.5", "must be"],
        ),
    ];
    for (name, text, needles) in cases {
        let p = dir.join(name);
        // Each case changes one thing of a complete scenario.
        let text = match *name {
            "syntax.toml" => (*text).to_string(),
            "vfile.toml" => complete_scenario(text).replace("vehicle = \"horus-2b\"\n", ""),
            _ => complete_scenario(text),
        };
        std::fs::write(&p, text).unwrap();
        let o = bin()
            .args(["simulate", "--quiet", "--scenario"])
            .arg(&p)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{name} should fail");
        assert!(!err.contains("panicked"), "{name}: {err}");
        // The scenario file is named, except for a missing vehicle file, which names itself.
        if *name != "vfile.toml" {
            assert!(err.contains(name), "{name}: file not named: {err}");
        }
        for n in *needles {
            assert!(err.contains(n), "{name}: `{n}` not in: {err}");
        }
    }
    // A missing scenario file is named too.
    let missing = dir.join("nope.toml");
    let o = bin()
        .args(["simulate", "--scenario"])
        .arg(&missing)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("nope.toml") && err.contains("cannot read"),
        "{err}"
    );
    assert!(!dir.join("out").exists(), "nothing written on bad input");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn help_on_every_subcommand() {
    for sub in [
        &["--help"][..],
        &["simulate", "--help"],
        &["atmosphere", "--help"],
        &["vehicles", "--help"],
        &["compare", "--help"],
    ] {
        let o = bin().args(sub).output().unwrap();
        assert!(o.status.success(), "{sub:?}");
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("Usage"), "{sub:?}: {text}");
    }
    let o = bin().args(["simulate", "--help"]).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("--scenario") && text.contains("--out"));
    let o = bin().args(["compare", "--help"]).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("--altitudes-km") && text.contains("--gamma-deg"),
        "{text}"
    );
    // A one-point skip comparison in the simplified environment writes its grid.
    let dir = std::env::temp_dir().join(format!("host-sim-compare-{}", std::process::id()));
    let o = bin()
        .args([
            "compare",
            "--phase",
            "skip",
            "--speeds-m-s",
            "9000",
            "--cl-vertical",
            "1",
        ])
        .args(["--environments", "simplified", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("grid.csv").is_file());
    let _ = std::fs::remove_dir_all(&dir);
    // Bad compare input: error naming the option and value, non-zero exit.
    let o = bin()
        .args(["compare", "--vehicle", "nope"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("nope"));
    // Unknown subcommand: usage error, non-zero.
    let o = bin().arg("fly").output().unwrap();
    assert!(!o.status.success());
}

#[test]
fn atmosphere_and_vehicles_subcommands() {
    let mut out = Vec::new();
    run(
        ["host-sim", "atmosphere", "--model", "us76", "0", "11"],
        &mut out,
    )
    .unwrap();
    let text = String::from_utf8(out).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2);
    // US76 sea level (NOAA 1976 table): 288.15 K, 101325 Pa, 1.225 kg/m^3, 340.29 m/s.
    assert!((rows[0][1] - 288.15).abs() < 1e-3);
    assert!((rows[0][2] - 101_325.0).abs() < 1.0);
    assert!((rows[0][3] - 1.225).abs() < 1e-3);
    assert!((rows[0][4] - 340.29).abs() < 0.05);
    assert!(rows[1][3] < rows[0][3]);

    let mut out = Vec::new();
    let e = run(["host-sim", "atmosphere", "5000"], &mut out).unwrap_err();
    assert!(e.to_string().contains("5000"), "{e}");

    let mut out = Vec::new();
    run(["host-sim", "vehicles"], &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains("horus-2b,26029"), "{text}");
    assert!(text.to_lowercase().contains("srm"), "{text}");
}

#[test]
fn printed_scenario_parses_back() {
    let d = Scenario::default();
    let text = scenario_to_toml(&d);
    let back = parse_scenario(&text, "printed.toml", std::path::Path::new(".")).unwrap();
    assert_eq!(back.name, d.name);
    assert_eq!(back.vehicle, d.vehicle);
    assert_eq!(back.environment, d.environment);
    assert_eq!(back.guidance.independent, d.guidance.independent);
    assert_eq!(back.guidance.interpolation, d.guidance.interpolation);
    assert_eq!(back.termination, d.termination);
    assert_eq!(back.tolerances, d.tolerances);
    assert_eq!(back.interface_altitude_m, d.interface_altitude_m);
    assert_eq!(back.g_rate_window_s, d.g_rate_window_s);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(1.0);
    for (a, b) in back.entry.to_array().iter().zip(d.entry.to_array()) {
        assert!(close(*a, b), "{a} vs {b}");
    }
    assert_eq!(back.guidance.nodes.len(), 7);
    for (a, b) in back.guidance.nodes.iter().zip(&d.guidance.nodes) {
        for k in 0..3 {
            assert!(close(a[k], b[k]));
        }
    }
}

/// Same scenario, same output, byte for byte.
#[test]
fn runs_are_deterministic() {
    let dir = temp_dir("det");
    let sc = parse_scenario(TINY, "tiny.toml", &dir).unwrap();
    let mut outs = vec![];
    for k in 0..2 {
        let out = dir.join(format!("run{k}"));
        host_sim::scenario::simulate_scenario(&sc, "tiny.toml", &out, &mut |_| {}).unwrap();
        outs.push((
            std::fs::read(out.join("trajectory.csv")).unwrap(),
            std::fs::read(out.join("summary.json")).unwrap(),
        ));
    }
    assert!(outs[0] == outs[1]);
    let _ = std::fs::remove_dir_all(&dir);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// Arbitrary values in the scenario fields never panic: either a named error or a
    /// short run that completes or fails with an error.
    #[test]
    fn scenario_values_never_panic(
        alt in proptest::prelude::prop_oneof![-20.0..200.0f64, proptest::prelude::Just(f64::NAN), proptest::prelude::Just(1e308)],
        speed in -100.0..20_000.0f64,
        gamma in -100.0..100.0f64,
        lat in -100.0..100.0f64,
        x2 in -10.0..3000.0f64,
        a2 in -10.0..60.0f64,
        rtol_exp in -16.0..0.0f64,
        junk in "[a-z =\\[\\]\"0-9.]{0,12}",
    ) {
        let rtol = 10f64.powf(rtol_exp);
        let text = format!(
            "[entry]\naltitude_km = {alt:?}\nspeed_m_s = {speed:?}\nflight_path_angle_deg = {gamma:?}\nlatitude_deg = {lat:?}\n\
             [guidance]\nnodes = [[0, 40, 0], [{x2:?}, {a2:?}, 30]]\n[integrator]\nrtol = {rtol:?}\n[termination]\nmax_time_s = 4.0\n# {junk}\n"
        );
        let text = complete_scenario(&text.replace("NaN", "nan"));
        match parse_scenario(&text, "p.toml", std::path::Path::new(".")) {
            Err(e) => {
                let m = e.to_string();
                proptest::prop_assert!(m.starts_with("p.toml: "), "{}", m);
            }
            Ok(sc) => {
                // Flies (or fails cleanly) without panicking.
                let _ = host_sim::scenario::fly(&sc, "p.toml", &mut |_| {});
            }
        }
        // Garbage after a valid key is a syntax error naming the file.
        let bad = format!("name = {junk}\n");
        if let Err(e) = parse_scenario(&bad, "q.toml", std::path::Path::new(".")) {
            proptest::prop_assert!(e.to_string().starts_with("q.toml: "));
        }
    }
}

/// `host-sim simulate --pil ELF` names a missing ELF, and a missing scenario file.
#[test]
fn pil_cli_errors_are_named() {
    let mut out = Vec::new();
    let e = run(
        [
            "host-sim",
            "simulate",
            "--pil",
            "/nonexistent/pil.elf",
            "--quiet",
        ],
        &mut out,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("/nonexistent/pil.elf") || e.contains("QEMU is missing"),
        "{e}"
    );
    let e = run(
        [
            "host-sim",
            "simulate",
            "--pil",
            "x.elf",
            "--scenario",
            "s.toml",
        ],
        &mut out,
    )
    .unwrap_err()
    .to_string();
    // Any scenario flies in PIL now: the missing scenario file is what is named.
    assert!(e.contains("s.toml"), "{e}");
}

/// The `compare` command-line front end (the lead wires it into `host-sim compare`): a 2 x 1
/// skip grid with trajectories, files written, summary printed; bad arguments name themselves.
#[test]
fn compare_command_line_runs_a_small_grid() {
    use clap::CommandFactory as _;
    host_sim::cli::Cli::command().debug_assert();
    let compare =
        |args: &[&str], out: &mut Vec<u8>| run(["host-sim", "compare"].iter().chain(args), out);
    let dir = std::env::temp_dir().join(format!("host-sim-compare-cli-{}", std::process::id()));
    let out_dir = dir.display().to_string();
    let mut out = Vec::new();
    compare(
        &[
            "--vehicle",
            "srm",
            "--phase",
            "skip",
            "--speeds-m-s",
            "7000,9000",
            "--gamma-deg",
            "-3",
            "--cl-vertical",
            "0.4",
            "--environments",
            "simplified",
            "--points",
            "41",
            "--trajectories",
            "--out",
            &out_dir,
        ],
        &mut out,
    )
    .unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(
        text.contains("2 points, 1 out of the closed form's domain"),
        "{text}"
    );
    assert!(text.contains("exit_speed_m_s"), "{text}");
    assert!(dir.join("grid.csv").exists());
    assert!(dir.join("exit_speed_m_s_err_simplified.svg").exists());
    // Point 0 (7000 m/s) is out of domain: no trajectories; point 1 has both runs.
    assert!(!dir.join("point_0/analytic").exists());
    assert!(dir.join("point_1/analytic/trajectory.csv").exists());
    assert!(dir.join("point_1/simplified/summary.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();

    let bad = |args: &[&str]| compare(args, &mut Vec::new()).unwrap_err().to_string();
    let e = bad(&["--fit-altitudes-km", "50", "--out", &out_dir]);
    assert!(e.contains("--fit-altitudes-km") && e.contains("50"), "{e}");
    // Issue 8 item 9: equal altitudes named an internal parameter (`scale_height_m = NaN`).
    let e = bad(&["--fit-altitudes-km", "50,50", "--out", &out_dir]);
    assert!(
        e.contains("--fit-altitudes-km") && e.contains("[50, 50]") && e.contains("different"),
        "{e}"
    );
    assert!(!e.contains("scale_height") && !e.contains("NaN"), "{e}");
    // Issue 8 item 8: a tiny output interval ran for minutes with memory growing; it is
    // refused before the grid runs, naming the option, the value and the range.
    for (v, shown) in [("1e-9", "1e-9"), ("0", "0"), ("1e308", "1e308")] {
        let e = bad(&["--output-interval-s", v, "--out", &out_dir]);
        assert!(
            e.contains("--output-interval-s") && e.contains(shown) && e.contains("[0.01, 1e4] s"),
            "{e}"
        );
    }
    let e = bad(&["--vehicle", "nope", "--out", &out_dir]);
    assert!(e.contains("nope"), "{e}");
    let e = bad(&["--points", "1", "--out", &out_dir]);
    assert!(e.contains("points") && e.contains('1'), "{e}");
    assert!(!dir.exists(), "nothing written on bad input");
}

/// `host-sim dispersions` of 2 SRM cases in mode `stored` with the interface at `speed` m/s
/// into `out`.
fn srm_dispersions(speed: &str, out: &std::path::Path) -> std::process::Output {
    bin()
        .args([
            "dispersions",
            "--builtin",
            "srm-glide",
            "-n",
            "2",
            "--interface-speed",
            speed,
            "--modes",
            "stored",
            "--quiet",
            "--out",
        ])
        .arg(out)
        .output()
        .unwrap()
}

/// `host-sim dispersions --out` in a fresh process writes its report, SVG and PNG, per mode:
/// the figures register the embedded font themselves (without it the first caption failed
/// with "Font loading error: FontUnavailable" and the command exited 1).
#[test]
fn dispersions_writes_its_plots_in_a_fresh_process() {
    let d = temp_dir("dispersions-plots");
    let o = srm_dispersions("2500", &d);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["summary.json", "cases-stored.csv"] {
        assert!(d.join(f).exists(), "{f} missing");
    }
    for stem in host_sim::report::campaign::figure_stems("stored") {
        for ext in ["svg", "png"] {
            let f = d.join(format!("{stem}.{ext}"));
            let len = std::fs::metadata(&f).map_or(0, |m| m.len());
            assert!(len > 1000, "{} missing or empty ({len} bytes)", f.display());
        }
    }
    let svg = std::fs::read_to_string(d.join("footprint-stored.svg")).unwrap();
    assert!(
        svg.contains("<text") && svg.contains("downrange error") && svg.contains("3-sigma"),
        "{svg}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// `host-sim dispersions --out DIR` again with another `--interface-speed` is refused, naming
/// the directory, the field and both values, and leaves the directory as it was; with the same
/// arguments it reuses both cases and rewrites byte-identical files.
#[test]
fn dispersions_resume_refuses_other_inputs() {
    let d = temp_dir("dispersions-resume");
    let run = |speed: &str| srm_dispersions(speed, &d);
    let first = run("2500");
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let read = |f: &str| std::fs::read(d.join(f)).unwrap();
    let (summary, fingerprint) = (read("summary.json"), read("fingerprint.json"));
    let other = run("2400");
    assert!(!other.status.success());
    let err = String::from_utf8_lossy(&other.stderr);
    assert!(
        err.contains(&d.display().to_string())
            && err.contains("dispersions.interface_speed_m_s was 2500.0, now 2400.0")
            && err.contains("--out"),
        "{err}"
    );
    assert_eq!(read("fingerprint.json"), fingerprint);
    let again = run("2500");
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert!(
        String::from_utf8_lossy(&again.stdout).contains("(2 resumed)"),
        "{}",
        String::from_utf8_lossy(&again.stdout)
    );
    assert_eq!(read("summary.json"), summary);
    assert_eq!(read("fingerprint.json"), fingerprint);
    let _ = std::fs::remove_dir_all(&d);
}

/// An out-of-range `--pil-fault-rate` is rejected before any PIL run, naming the option and
/// printing its value compactly (`1e300`, not a 301-digit integer).
#[test]
fn pil_fault_rate_out_of_range_is_named_compactly() {
    let dir = temp_dir("pilrate");
    let out = bin()
        .args(["simulate", "--quiet", "--pil"])
        .arg(dir.join("no-such.elf"))
        .args(["--pil-fault-rate", "1e300", "--out"])
        .arg(dir.join("run"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--pil-fault-rate") && err.contains("1e300") && !err.contains("10000000"),
        "{err}"
    );
    assert!(!dir.join("run").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
