//! `guidance-fuzz`: a seeded fuzz harness on stable Rust over guidance-core's flight-code entry
//! points (issue 8.11). Run it through `cargo xtask fuzz --seconds N` (a time budget, for
//! exploring) or with a fixed `--cases N` (what CI does, with a fixed seed: deterministic).
//! `cargo xtask fuzz` builds it with the workspace's `fuzz` profile (optimised, integer overflow
//! checks and debug assertions on), so an overflow in the code under test is a finding.
//!
//! Every case draws its inputs from a ChaCha generator seeded by `(seed, target, case)`, so a
//! finding is reproduced by `--seed S --target T --case I`. A case fails if the code under test
//! panics, returns a non-finite or out-of-bounds output, accepts a corrupted frame, or (for
//! guidance) freezes on good samples after a hostile one.
//!
//! Targets: `nodes` (node tables and interpolation), `guidance` (updates with hostile times and
//! states, in f64, f32 and fixed point), `link` (the frame decoder on random bytes and on valid
//! frames with 1 to 3 flipped bits, all below the CRC's guaranteed distance of 4), `navconv` (the
//! navigation interface on hostile Cartesian states, f64 and f32), `closed-forms` (the Vinh
//! predictor chain and the re-planning solver, f64 and f32), `lateral` (bank reversals),
//! `estimate` (onboard aerodynamic estimation, f64 and f32).

mod hostile;
mod targets;

use std::process::ExitCode;
use std::time::{Duration, Instant};

use targets::Target;

const USAGE: &str = "usage: guidance-fuzz [--seed S] [--cases N | --seconds N (per target)] [--target all|nodes|guidance|link|navconv|closed-forms|lateral|estimate] [--case I]";

struct Options {
    seed: u64,
    budget: Budget,
    target: Option<Target>,
    case: Option<u64>,
}

enum Budget {
    Cases(u64),
    Seconds(u64),
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        seed: 1,
        budget: Budget::Cases(10_000),
        target: None,
        case: None,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value\n{USAGE}"))
                .cloned()
        };
        let number = |name: &str, v: String| {
            v.parse::<u64>()
                .map_err(|_| format!("{name}: not a whole number: {v:?}"))
        };
        match flag.as_str() {
            "--seed" => o.seed = number("--seed", value("--seed")?)?,
            "--cases" => o.budget = Budget::Cases(number("--cases", value("--cases")?)?),
            "--seconds" => o.budget = Budget::Seconds(number("--seconds", value("--seconds")?)?),
            "--case" => o.case = Some(number("--case", value("--case")?)?),
            "--target" => {
                let v = value("--target")?;
                o.target = match v.as_str() {
                    "all" => None,
                    name => Some(Target::from_name(name).ok_or_else(|| {
                        format!("--target: unknown target {name:?} (all, nodes, guidance, link, navconv, closed-forms, lateral, estimate)")
                    })?),
                };
            }
            "--help" | "-h" => return Err(USAGE.to_string()),
            other => return Err(format!("unknown argument {other:?}\n{USAGE}")),
        }
    }
    Ok(o)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let o = match parse(&args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let targets: Vec<Target> = match o.target {
        Some(t) => vec![t],
        None => Target::ALL.to_vec(),
    };
    // A panic is a finding: report it as such (the hook would print it before we can).
    std::panic::set_hook(Box::new(|_| {}));
    let mut failures = 0u64;
    let mut total = 0u64;
    for target in targets {
        let cases: Box<dyn Iterator<Item = u64>> = match (o.case, &o.budget) {
            (Some(c), _) => Box::new(std::iter::once(c)),
            (None, Budget::Cases(n)) => Box::new(0..*n),
            (None, Budget::Seconds(s)) => {
                let end = Instant::now() + Duration::from_secs(*s);
                Box::new((0..).take_while(move |_| Instant::now() < end))
            }
        };
        let mut ran = 0u64;
        for case in cases {
            ran += 1;
            let outcome = std::panic::catch_unwind(|| target.run(o.seed, case));
            let finding = match outcome {
                Ok(Ok(())) => continue,
                Ok(Err(msg)) => msg,
                Err(p) => format!(
                    "panic: {}",
                    p.downcast_ref::<&str>()
                        .map(|s| (*s).to_string())
                        .or_else(|| p.downcast_ref::<String>().cloned())
                        .unwrap_or_default()
                ),
            };
            failures += 1;
            println!(
                "FINDING {} case {case}: {finding}\n  reproduce: cargo run -p guidance-fuzz --profile fuzz -- --seed {} --target {} --case {case}",
                target.name(),
                o.seed,
                target.name()
            );
            if failures >= 20 {
                break;
            }
        }
        total += ran;
        println!("fuzz {}: {ran} cases (seed {})", target.name(), o.seed);
    }
    println!("fuzz: {} passed, {failures} failed", total - failures);
    if failures == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
