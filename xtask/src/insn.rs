//! Instruction counts of the `insn-bench` firmware: parse its output, print them as JSON, check
//! them against `onboard-demo/insn-budget.toml`.
//!
//! The firmware prints one line per benchmark, `bench <name>: <instructions> insn/call ...`.
//! The budget file has one `[<target triple>]` section per firmware target and
//! `<benchmark> = <instructions>` lines (underscores allowed in the number); every benchmark
//! named there must be measured and must not exceed its budget.

use std::collections::BTreeMap;
use std::path::Path;

/// Benchmark name -> instructions per call, for one target.
pub type TargetCounts = BTreeMap<String, u64>;
/// Target triple -> benchmark counts.
pub type Counts = BTreeMap<String, TargetCounts>;

/// The `bench <name>: <n> insn/call` lines of the firmware's output.
pub fn parse(output: &str) -> TargetCounts {
    let mut counts = TargetCounts::new();
    for line in output.lines() {
        let Some(rest) = line.trim().strip_prefix("bench ") else {
            continue;
        };
        let Some((name, value)) = rest.split_once(':') else {
            continue;
        };
        let Some(number) = value.split_whitespace().next() else {
            continue;
        };
        if let Ok(n) = number.parse::<u64>() {
            counts.insert(name.trim().to_string(), n);
        }
    }
    counts
}

/// JSON object `{"<target>": {"<benchmark>": <instructions>, ...}, ...}` (keys sorted; names
/// are `[a-z0-9_-]`, escaped anyway).
pub fn to_json(counts: &Counts) -> String {
    let esc = |s: &str| s.replace('\\', "\\\\").replace('"', "\\\"");
    let targets: Vec<String> = counts
        .iter()
        .map(|(target, benches)| {
            let inner: Vec<String> = benches
                .iter()
                .map(|(name, n)| format!("\"{}\": {n}", esc(name)))
                .collect();
            format!("\"{}\": {{{}}}", esc(target), inner.join(", "))
        })
        .collect();
    format!("{{{}}}", targets.join(", "))
}

/// Parse the budget file: `[target]` sections of `name = integer` lines; `#` comments.
pub fn parse_budget(text: &str, file: &Path) -> Result<Counts, String> {
    let mut budget = Counts::new();
    let mut section: Option<String> = None;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let at = || format!("{}:{}", file.display(), i + 1);
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            let name = name.trim().trim_matches('"').to_string();
            budget.entry(name.clone()).or_default();
            section = Some(name);
            continue;
        }
        let Some((key, value)) = line.split_once('=') else {
            return Err(format!(
                "{}: expected `name = integer`, found {line:?}",
                at()
            ));
        };
        let Some(target) = &section else {
            return Err(format!(
                "{}: `{}` outside a [target] section",
                at(),
                key.trim()
            ));
        };
        let v = value.trim().replace('_', "");
        let n = v.parse::<u64>().map_err(|e| {
            format!(
                "{}: field `{}` = {v:?}: not an integer ({e})",
                at(),
                key.trim()
            )
        })?;
        budget
            .entry(target.clone())
            .or_default()
            .insert(key.trim().to_string(), n);
    }
    Ok(budget)
}

/// Every budgeted benchmark measured and within its budget; the violations otherwise.
pub fn check(counts: &Counts, budget: &Counts, file: &Path) -> Result<(), String> {
    let mut over = Vec::new();
    for (target, benches) in budget {
        let measured = counts.get(target);
        for (name, max) in benches {
            match measured.and_then(|m| m.get(name)) {
                None => over.push(format!("{target} {name}: not measured")),
                Some(&n) if n > *max => over.push(format!("{target} {name}: {n} > budget {max}")),
                Some(_) => {}
            }
        }
    }
    if over.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "instruction counts over budget ({}): {}",
            file.display(),
            over.join("; ")
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_output_budget_and_checks() {
        let out = "bench calibration_10000_nop: 10000 insn/call\n\
                   noise\nbench replan_worst_case_f32: 1108720 insn/call (29 predictor calls)\n";
        let m = parse(out);
        assert_eq!(m.get("replan_worst_case_f32"), Some(&1_108_720));
        assert_eq!(m.len(), 2);
        let mut counts = Counts::new();
        counts.insert("thumbv7em-none-eabihf".into(), m);
        assert_eq!(
            to_json(&counts),
            "{\"thumbv7em-none-eabihf\": {\"calibration_10000_nop\": 10000, \
             \"replan_worst_case_f32\": 1108720}}"
        );
        let f = Path::new("insn-budget.toml");
        let ok = parse_budget(
            "# c\n[thumbv7em-none-eabihf]\nreplan_worst_case_f32 = 1_200_000 # m\n",
            f,
        )
        .unwrap();
        assert!(check(&counts, &ok, f).is_ok());
        let tight =
            parse_budget("[thumbv7em-none-eabihf]\nreplan_worst_case_f32 = 1000\n", f).unwrap();
        assert!(
            check(&counts, &tight, f)
                .unwrap_err()
                .contains("> budget 1000")
        );
        let missing = parse_budget("[thumbv7m-none-eabi]\nreplan_worst_case_f32 = 1\n", f).unwrap();
        assert!(
            check(&counts, &missing, f)
                .unwrap_err()
                .contains("not measured")
        );
        let bad = parse_budget("[t]\nx = 1e5\n", f).unwrap_err();
        assert!(
            bad.contains("insn-budget.toml:2") && bad.contains("`x`"),
            "{bad}"
        );
        assert!(parse_budget("x = 1\n", f).is_err());
    }
}
