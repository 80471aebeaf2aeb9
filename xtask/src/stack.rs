//! `cargo xtask stack`: the measured maximum stack of the guidance tick, the navigation
//! conversion and a re-plan on both machines (`onboard-demo`'s `stack-bench`, stack painting),
//! and static RAM of the flight application (the `pil` firmware) plus the largest of them
//! against `<target>_ram_plus_stack_bytes` in `onboard-demo/size-budget.toml`; and each
//! vehicle's full campaign stack (`flight_stack_*`: image decoded, stack built, its recorded
//! flight ticked) plus that static RAM against `<target>_pil_ram_plus_stack_bytes`. (The `pil`
//! image's static RAM plus the deepest stack of a whole PIL run, which the firmware measures
//! itself, is checked against `<target>_pil_ram_plus_stack_bytes` by host-sim's PIL tests,
//! the `cargo xtask pil` step.)

use onboard_spec::machines::MACHINES;

use crate::{budget_value, build_firmware, qemu, root};

/// The `stack NAME: N bytes` lines of one run: (name, bytes).
fn parse(out: &str) -> Result<Vec<(String, u64)>, String> {
    let mut v = Vec::new();
    for line in out.lines() {
        let Some(rest) = line.strip_prefix("stack ") else {
            continue;
        };
        let (name, n) = rest
            .split_once(": ")
            .ok_or_else(|| format!("stack-bench: malformed line {line:?}"))?;
        let bytes = n
            .strip_suffix(" bytes")
            .and_then(|b| b.parse::<u64>().ok())
            .ok_or_else(|| format!("stack-bench: malformed line {line:?}"))?;
        v.push((name.to_string(), bytes));
    }
    if v.is_empty() {
        return Err(format!("stack-bench printed no measurement:\n{out}"));
    }
    Ok(v)
}

/// Run the measurement on each machine and check the budget.
pub fn stack() -> Result<(), String> {
    let budget_file = root().join("onboard-demo").join("size-budget.toml");
    let text = std::fs::read_to_string(&budget_file)
        .map_err(|e| format!("{}: cannot read: {e}", budget_file.display()))?;
    let mut over = Vec::new();
    for m in &MACHINES {
        let fw = build_firmware(m.target)?;
        // The layers' measurements, then the full stack's (a binary of its own).
        let mut rows = Vec::new();
        for bin in ["stack-bench", "stack-bench-flight"] {
            let bench = fw.with_file_name(bin);
            let out = qemu(m, &bench, false)
                .output()
                .map_err(|e| format!("cannot run QEMU on {}: {e}", bench.display()))?;
            let stdout = String::from_utf8_lossy(&out.stdout);
            if !out.status.success() {
                return Err(format!(
                    "{bin} on {} failed ({}): {stdout}{}",
                    m.description,
                    out.status,
                    String::from_utf8_lossy(&out.stderr)
                ));
            }
            rows.extend(parse(&stdout)?);
        }
        let pil = fw.with_file_name("pil");
        let bytes = std::fs::read(&pil).map_err(|e| format!("{}: {e}", pil.display()))?;
        let ram = onboard_spec::footprint::footprint(&bytes)
            .map_err(|e| format!("{}: {e}", pil.display()))?
            .ram;
        for (name, b) in &rows {
            println!("xtask: stack {} {name}: {b} bytes", m.target);
        }
        // The full-stack flights against the full-stack PIL budget, the rest against the
        // layers' budget.
        let (flights, parts): (Vec<_>, Vec<_>) = rows
            .iter()
            .partition(|(name, _)| name.starts_with("flight_stack"));
        for (what, rows, key) in [
            ("deepest stack", parts, "ram_plus_stack_bytes"),
            (
                "deepest full-stack flight",
                flights,
                "pil_ram_plus_stack_bytes",
            ),
        ] {
            let key = format!("{}_{key}", m.target.replace('-', "_"));
            let max = budget_value(&text, &key, &budget_file)?;
            let deepest = rows.iter().map(|(_, b)| *b).max().unwrap_or(0);
            println!(
                "xtask: stack {}: static RAM (pil) {ram} + {what} {deepest} = {} / {max} bytes \
                 ({key})",
                m.target,
                ram + deepest
            );
            if ram + deepest > max {
                over.push(format!(
                    "{} RAM + {what} {} > budget {max} ({key})",
                    m.target,
                    ram + deepest
                ));
            }
        }
    }
    if over.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "over budget ({}): {}",
            budget_file.display(),
            over.join("; ")
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn parses_measurements_and_rejects_garbage() {
        let v = parse("x\nstack guidance_tick: 148 bytes\nstack replan: 3020 bytes\n").unwrap();
        assert_eq!(
            v,
            vec![("guidance_tick".into(), 148), ("replan".into(), 3020)]
        );
        assert!(parse("nothing\n").is_err());
        assert!(parse("stack tick: many bytes\n").is_err());
    }
}
