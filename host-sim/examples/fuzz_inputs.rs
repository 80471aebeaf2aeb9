//! The input-file fuzzer (issue 24 item 6): a seeded mutator over host-sim's input files (the
//! scenario, the vehicle, the dispersion settings and the optimiser run files), run by
//! `cargo xtask fuzz` beside the flight-code harness (`fuzz/`, which depends on guidance-core
//! only, so the host parsers are fuzzed here, in host-sim).
//!
//! Each case takes a seed file (the built-in scenarios as printed, the examples, vehicles of
//! every aerodynamic kind, the optimiser presets' run files), applies one to three mutations
//! drawn from `(seed, target, case)` (extreme numbers: 0, -0, 1e308, 5e-324, nan, inf, 2^63;
//! a deleted key; a duplicated table; a value of the wrong type; a renamed key; array edits;
//! a truncated or byte-flipped text) and reads it through the library's reading path (for a
//! scenario also its guidance, its vehicle and its warnings). A case fails if that panics,
//! takes more than 10 s, gives an output with a NaN or an infinity, or an error that names no
//! field (errors must name `field `...``, or be a TOML syntax error with line and column, or a
//! file that cannot be read). A finding prints the command that reproduces it.
//!
//! ```sh
//! cargo run --profile fuzz -p host-sim --example fuzz_inputs -- --seed 20261130 --cases 2000
//! cargo run --profile fuzz -p host-sim --example fuzz_inputs -- --seconds 60 --target vehicle
//! ```

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use host_sim::scenario::{
    Scenario, build_guidance, input_warnings, parse_scenario, scenario_to_toml,
};
use toml::{Table, Value};

/// Longest a case may take before it counts as a hang.
const CASE_LIMIT: Duration = Duration::from_secs(10);

/// The file kinds fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    Scenario,
    Vehicle,
    Settings,
    RunConfig,
}

impl Target {
    const ALL: [Self; 4] = [
        Self::Scenario,
        Self::Vehicle,
        Self::Settings,
        Self::RunConfig,
    ];

    fn name(self) -> &'static str {
        match self {
            Self::Scenario => "scenario",
            Self::Vehicle => "vehicle",
            Self::Settings => "settings",
            Self::RunConfig => "run-config",
        }
    }
}

/// SplitMix64: a small, portable, seedable generator (a case reproduces from its seed alone).
struct Rng(u64);

impl Rng {
    fn new(seed: u64, target: Target, case: u64) -> Self {
        let mut r = Self(seed ^ 0x9e37_79b9_7f4a_7c15);
        r.0 ^= (target as u64 + 1).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        r.0 ^= case.wrapping_mul(0x94d0_49bb_1331_11eb);
        r.next();
        r
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The seed files of a target: (label, text). Vehicle and settings paths in them resolve
/// against the examples folder.
fn seeds(target: Target, examples: &Path) -> Vec<(String, String)> {
    let read =
        |f: &str| std::fs::read_to_string(examples.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
    match target {
        Target::Scenario => vec![
            ("default".into(), scenario_to_toml(&Scenario::default())),
            ("srm-glide".into(), scenario_to_toml(&Scenario::srm_glide())),
            ("betts-shuttle".into(), read("betts-shuttle.toml")),
            (
                "srm-glide-replanning".into(),
                read("srm-glide-replanning.toml"),
            ),
        ],
        Target::Vehicle => {
            let v = |aero: &str| {
                format!(
                    "name = \"fuzz\"\nmass_kg = 1200.0\nreference_area_m2 = 4.5\nnose_radius_m = 0.3\n\
                     [limits]\nheat_flux_kw_m2 = 800.0\ng_load = 4.0\ng_load_rate_per_s = 1.0\n\
                     alpha_rate_deg_s = 5.0\nsigma_rate_deg_s = 15.0\n[aero]\n{aero}\n"
                )
            };
            vec![
                (
                    "betts-shuttle-vehicle".into(),
                    read("betts-shuttle-vehicle.toml"),
                ),
                (
                    "table".into(),
                    v(
                        "kind = \"table\"\nmach = [2.0, 10.0]\nalpha_deg = [0.0, 20.0, 40.0]\n\
                       cl = [[0.0, 0.4, 0.8], [0.0, 0.3, 0.6]]\ncd = [[0.1, 0.2, 0.5], [0.08, 0.15, 0.4]]",
                    ),
                ),
                (
                    "drag-polar".into(),
                    v(
                        "kind = \"drag_polar\"\ncd0 = 0.05\nk = 0.5\ncl = [0.0, 0.02]\nalpha_min_deg = 0.0\nalpha_max_deg = 45.0",
                    ),
                ),
                ("trim".into(), v("kind = \"trim\"\ncl = 0.3\ncd = 0.9")),
            ]
        }
        Target::Settings => vec![(
            "dispersions".into(),
            "[dispersions]\ncases = 1000\nseed = 20261130\ninterface_speed_m_s = 2500.0\n\
             density_wavelength_km = 20.0\n\
             [dispersions.speed_m_s]\ndistribution = \"normal\"\nthree_sigma = 20.0\n\
             [dispersions.lift]\ndistribution = \"uniform\"\nthree_sigma = 0.05\n"
                .into(),
        )],
        Target::RunConfig => ["horus-2b", "srm", "srm-analytical"]
            .iter()
            .map(|p| {
                let c = host_sim::design::run::ReentryRunConfig::thesis(p).expect("a preset");
                (
                    (*p).to_string(),
                    toml::to_string(&c).expect("a config serialises"),
                )
            })
            .collect(),
    }
}

/// Values that break parsers: extremes, non-finite numbers, wrong types.
fn hostile_value(r: &mut Rng) -> Value {
    let pick = [
        Value::Float(0.0),
        Value::Float(-0.0),
        Value::Float(1e308),
        Value::Float(-1e308),
        Value::Float(5e-324),
        Value::Float(f64::NAN),
        Value::Float(f64::INFINITY),
        Value::Float(f64::NEG_INFINITY),
        Value::Integer(i64::MAX),
        Value::Integer(i64::MIN),
        Value::Integer(-1),
        Value::Integer(0),
        Value::Float(1e-300),
        Value::Float(0.5),
        Value::String("x".into()),
        Value::String(String::new()),
        Value::Boolean(true),
        Value::Array(vec![]),
        Value::Array(vec![Value::Float(f64::NAN), Value::Float(1e308)]),
        Value::Table(Table::new()),
    ];
    pick[r.below(pick.len())].clone()
}

/// Every leaf path of a table (arrays are leaves; elements of arrays too, by index).
fn leaves(t: &Table, prefix: &[String], out: &mut Vec<Vec<String>>) {
    for (k, v) in t {
        let mut p = prefix.to_vec();
        p.push(k.clone());
        if let Value::Table(s) = v {
            out.push(p.clone());
            leaves(s, &p, out);
        } else {
            out.push(p);
        }
    }
}

/// The value at `path` (its parent table and key).
fn parent_mut<'a>(t: &'a mut Table, path: &[String]) -> Option<(&'a mut Table, String)> {
    let (last, head) = path.split_last()?;
    let mut cur = t;
    for k in head {
        cur = cur.get_mut(k)?.as_table_mut()?;
    }
    Some((cur, last.clone()))
}

/// One structured mutation of `t`.
fn mutate_table(t: &mut Table, r: &mut Rng) {
    let mut paths = Vec::new();
    leaves(t, &[], &mut paths);
    if paths.is_empty() {
        t.insert("x".into(), hostile_value(r));
        return;
    }
    let path = paths[r.below(paths.len())].clone();
    let Some((parent, key)) = parent_mut(t, &path) else {
        return;
    };
    match r.below(7) {
        // Extreme or mistyped value.
        0..=2 => {
            parent.insert(key, hostile_value(r));
        }
        // Missing key.
        3 => {
            parent.remove(&key);
        }
        // Unknown key.
        4 => {
            if let Some(v) = parent.remove(&key) {
                parent.insert(format!("{key}_x"), v);
            }
        }
        // Array edits: drop, repeat or poison an element, or empty it.
        5 => {
            if let Some(Value::Array(a)) = parent.get_mut(&key) {
                if a.is_empty() {
                    a.push(hostile_value(r));
                } else {
                    let i = r.below(a.len());
                    match r.below(4) {
                        0 => {
                            a.remove(i);
                        }
                        1 => {
                            let v = a[i].clone();
                            a.push(v);
                        }
                        2 => a[i] = hostile_value(r),
                        _ => a.clear(),
                    }
                }
            } else {
                parent.insert(key, hostile_value(r));
            }
        }
        // A number scaled by an extreme factor.
        _ => {
            let scale = [1e300, -1.0, 1e-300, 1e6, 1e-6][r.below(5)];
            let v = match parent.get(&key) {
                Some(Value::Float(x)) => Value::Float(x * scale),
                Some(Value::Integer(i)) => Value::Float(*i as f64 * scale),
                _ => hostile_value(r),
            };
            parent.insert(key, v);
        }
    }
}

/// One text-level mutation: a duplicated table, a truncation, a flipped byte.
fn mutate_text(text: &str, r: &mut Rng) -> String {
    let headers: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with('['))
        .collect();
    match r.below(3) {
        0 if !headers.is_empty() => {
            let h = headers[r.below(headers.len())];
            format!("{text}\n{h}\nx = 1\n")
        }
        1 => {
            let cut = r.below(text.len().max(1));
            text.get(..cut).unwrap_or(text).to_string()
        }
        _ => {
            let mut b = text.as_bytes().to_vec();
            if !b.is_empty() {
                let i = r.below(b.len());
                b[i] = [b'=', b'[', b']', b'"', b'\n', b'#', b'9', b'.', b'-'][r.below(9)];
            }
            String::from_utf8_lossy(&b).into_owned()
        }
    }
}

/// The mutated text of case `case`.
fn mutated(target: Target, seed: u64, case: u64, seeds: &[(String, String)]) -> (String, String) {
    let mut r = Rng::new(seed, target, case);
    let (label, text) = &seeds[r.below(seeds.len())];
    let mut out = text.clone();
    for _ in 0..1 + r.below(3) {
        out = match (r.below(5), out.parse::<Table>()) {
            (0, _) | (_, Err(_)) => mutate_text(&out, &mut r),
            (_, Ok(mut t)) => {
                mutate_table(&mut t, &mut r);
                toml::to_string(&t).unwrap_or(out)
            }
        };
    }
    (label.clone(), out)
}

/// A NaN or an infinity in a Debug rendering (as the tokens `NaN` and `inf`).
fn non_finite(debug: &str) -> bool {
    debug
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .any(|t| t == "NaN" || t == "inf")
}

/// An error names a field (`field `f`` or `file: f = value`), or is a syntax error with its position, or a file it cannot read.
fn names_its_field(msg: &str) -> bool {
    let field = msg
        .split("field `")
        .nth(1)
        .is_some_and(|rest| rest.split('`').next().is_some_and(|f| !f.is_empty()));
    // `file: dotted.field = value: reason` (the dispersion settings' form).
    let dotted = msg
        .strip_prefix("fuzz.toml: ")
        .and_then(|rest| rest.split(" = ").next())
        .is_some_and(|f| {
            !f.is_empty()
                && f.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.[]".contains(c))
        });
    field || dotted || (msg.contains("TOML") && msg.contains("line")) || msg.contains("cannot read")
}

/// Read one input; `Ok` carries the outputs' Debug rendering, `Err` the error message.
fn read(target: Target, text: &str, dir: &Path) -> Result<String, String> {
    match target {
        Target::Scenario => {
            let sc = parse_scenario(text, "fuzz.toml", dir).map_err(|e| e.to_string())?;
            let env = sc.environment.build();
            let g = build_guidance(&sc, &env.planet, "fuzz.toml").map_err(|e| e.to_string())?;
            let v = sc.load_vehicle().map_err(|e| e.to_string())?;
            let w = input_warnings(&sc);
            Ok(format!("{sc:?} {:?} {:?} {w:?}", g.command(), v.limits))
        }
        Target::Vehicle => {
            let v =
                host_sim::vehicle::from_toml_str(text, "fuzz.toml").map_err(|e| e.to_string())?;
            let mut coefficients = Vec::new();
            for mach in [0.3, 2.0, 10.0, 30.0] {
                for alpha_deg in [0.0, 10.0, 25.0, 45.0] {
                    coefficients.push(v.aero.coefficients(mach, f64::to_radians(alpha_deg)));
                }
            }
            Ok(format!("{v:?} {coefficients:?}"))
        }
        Target::Settings => host_sim::campaign::parse_settings(text, "fuzz.toml")
            .map(|s| format!("{s:?}"))
            .map_err(|e| e.to_string()),
        Target::RunConfig => host_sim::design::run::check_run_config(text, &dir.join("fuzz.toml"))
            .map(|c| format!("{c:?}"))
            .map_err(|e| e.to_string()),
    }
}

/// Check one case: `Ok(refused)`, or `Err` describing the finding.
fn check(target: Target, text: &str, dir: &Path) -> Result<bool, String> {
    match read(target, text, dir) {
        Ok(debug) if non_finite(&debug) => {
            Err(format!("accepted, with a NaN or infinity in: {debug}"))
        }
        Ok(_) => Ok(false),
        Err(msg) if !names_its_field(&msg) => Err(format!("error names no field: {msg}")),
        Err(_) => Ok(true),
    }
}

struct Options {
    seed: u64,
    cases: Option<u64>,
    seconds: Option<u64>,
    target: Option<Target>,
    case: Option<u64>,
}

const USAGE: &str = "usage: fuzz_inputs [--seed S] [--cases N | --seconds N (per target)] [--target all|scenario|vehicle|settings|run-config] [--case I]";

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        seed: 1,
        cases: None,
        seconds: None,
        target: None,
        case: None,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{flag} needs a value\n{USAGE}"))
        };
        let number = |v: String| {
            v.parse::<u64>()
                .map_err(|_| format!("{flag}: not a whole number: {v:?}"))
        };
        match flag.as_str() {
            "--seed" => o.seed = number(value()?)?,
            "--cases" => o.cases = Some(number(value()?)?),
            "--seconds" => o.seconds = Some(number(value()?)?),
            "--case" => o.case = Some(number(value()?)?),
            "--target" => {
                let v = value()?;
                o.target = match v.as_str() {
                    "all" => None,
                    name => Some(
                        Target::ALL
                            .into_iter()
                            .find(|t| t.name() == name)
                            .ok_or_else(|| format!("--target: unknown target {name:?}\n{USAGE}"))?,
                    ),
                };
            }
            _ => return Err(format!("unknown argument {flag:?}\n{USAGE}")),
        }
    }
    Ok(o)
}

/// A worker thread running cases, so a hang is seen (the main thread waits at most
/// [`CASE_LIMIT`] per case) and a panic is caught and reported.
struct Worker {
    send: mpsc::Sender<(Target, String)>,
    recv: mpsc::Receiver<Result<bool, String>>,
}

impl Worker {
    fn start(dir: PathBuf) -> Self {
        let (send, cases) = mpsc::channel::<(Target, String)>();
        let (results, recv) = mpsc::channel();
        std::thread::spawn(move || {
            for (target, text) in cases {
                let r = std::panic::catch_unwind(AssertUnwindSafe(|| check(target, &text, &dir)))
                    .unwrap_or_else(|p| {
                        let m = p
                            .downcast_ref::<String>()
                            .cloned()
                            .or_else(|| p.downcast_ref::<&str>().map(|s| (*s).to_string()))
                            .unwrap_or_default();
                        Err(format!("panicked: {m}"))
                    });
                if results.send(r).is_err() {
                    return;
                }
            }
        });
        Self { send, recv }
    }

    fn run(&self, target: Target, text: String) -> Result<bool, String> {
        self.send
            .send((target, text))
            .map_err(|_| "the worker stopped".to_string())?;
        match self.recv.recv_timeout(CASE_LIMIT) {
            Ok(r) => r,
            Err(_) => Err(format!(
                "no answer within {} s (a hang)",
                CASE_LIMIT.as_secs()
            )),
        }
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let o = match parse_args(&args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    // Panics are findings, reported with their case; keep the default hook's noise out.
    std::panic::set_hook(Box::new(|_| {}));
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let targets: Vec<Target> = o.target.map_or_else(|| Target::ALL.to_vec(), |t| vec![t]);
    let mut worker = Worker::start(examples.clone());
    let mut failed = false;
    for target in targets {
        let seeds = seeds(target, &examples);
        let started = Instant::now();
        let (first, budget) = match (o.case, o.cases, o.seconds) {
            (Some(c), _, _) => (c, 1),
            (None, Some(n), _) => (0, n),
            (None, None, Some(_)) => (0, u64::MAX),
            (None, None, None) => (0, 2000),
        };
        let deadline = o.seconds.map(|s| started + Duration::from_secs(s));
        let (mut cases, mut refused) = (0u64, 0u64);
        for case in first..first.saturating_add(budget) {
            if deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
            let (label, text) = mutated(target, o.seed, case, &seeds);
            cases += 1;
            match worker.run(target, text.clone()) {
                Ok(true) => refused += 1,
                Ok(false) => {}
                Err(finding) => {
                    failed = true;
                    println!(
                        "FINDING {} case {case} (from {label}): {finding}\n  input:\n{text}\n  reproduce: cargo run --profile fuzz -p host-sim --example fuzz_inputs -- --seed {} --target {} --case {case}",
                        target.name(),
                        o.seed,
                        target.name()
                    );
                    if finding.contains("a hang") {
                        // The worker is stuck; start another for the rest.
                        worker = Worker::start(examples.clone());
                    }
                }
            }
        }
        println!(
            "{}: {cases} cases ({refused} refused, {} accepted) in {:.1} s",
            target.name(),
            cases - refused,
            started.elapsed().as_secs_f64()
        );
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
