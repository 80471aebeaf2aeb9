//! The `[guidance]` section of a scenario file and its node table.

use toml::{Table, Value};

use super::fields::{Fields, fmt_value};
use super::scenario::node_to_rad;
use super::{CliError, Independent, InterpolationKind, Scenario};

/// The `[guidance]` section: node variable, interpolation, rates, initial attitude, nodes.
pub(super) fn guidance(f: &Fields<'_>, t: &Table, sc: &mut Scenario) -> Result<(), CliError> {
    let p = "guidance";
    f.reject_unknown(
        t,
        p,
        &[
            "independent",
            "interpolation",
            "tension",
            "period_s",
            "alpha_rate_deg_s",
            "sigma_rate_deg_s",
            "initial_alpha_deg",
            "initial_sigma_deg",
            "nodes",
        ],
    )?;
    let g = &mut sc.guidance;
    if let Some(s) = f.string(t, p, "independent")? {
        g.independent = match s.as_str() {
            "time" => Independent::Time,
            "energy" | "normalized-energy" | "normalized_energy" => Independent::Energy,
            _ => {
                return Err(f.err(
                    "guidance.independent",
                    &format!("{s:?}"),
                    "must be \"time\" or \"energy\"",
                ));
            }
        };
    }
    let tension = f.checked(
        t,
        p,
        "tension",
        |v| (0.0..=1.0).contains(&v),
        "must be within [0, 1]",
    )?;
    if let Some(s) = f.string(t, p, "interpolation")? {
        g.interpolation = match s.as_str() {
            "linear" => InterpolationKind::Linear,
            "natural-cubic" | "cubic" => InterpolationKind::NaturalCubic,
            "hermite" => InterpolationKind::Hermite {
                tension: tension.unwrap_or(0.0),
            },
            _ => {
                return Err(f.err(
                    "guidance.interpolation",
                    &format!("{s:?}"),
                    "must be \"linear\", \"natural-cubic\" or \"hermite\"",
                ));
            }
        };
    }
    if let Some(v) = f.checked(
        t,
        p,
        "period_s",
        |v| v > 0.0 && v <= 100.0,
        "must be in (0, 100] s",
    )? {
        g.period_s = v;
    }
    if let Some(v) = f.checked(t, p, "alpha_rate_deg_s", |v| v > 0.0, "must be > 0")? {
        g.alpha_rate_rad_s = v.to_radians();
    }
    if let Some(v) = f.checked(t, p, "sigma_rate_deg_s", |v| v > 0.0, "must be > 0")? {
        g.sigma_rate_rad_s = v.to_radians();
    }
    if let Some(v) = f.checked(
        t,
        p,
        "initial_alpha_deg",
        |v| (0.0..=45.0).contains(&v),
        "must be within [0, 45] deg",
    )? {
        g.initial.alpha_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        t,
        p,
        "initial_sigma_deg",
        |v| (-90.0..=90.0).contains(&v),
        "must be within [-90, 90] deg",
    )? {
        g.initial.sigma_rad = v.to_radians();
    }
    if let Some(v) = t.get("nodes") {
        g.nodes = parse_nodes(f, v, g.independent)?;
    } else if g.independent == Independent::Energy {
        return Err(f.err(
            "guidance.nodes",
            "(missing)",
            "energy-indexed guidance needs its own node table",
        ));
    }
    Ok(())
}

fn parse_nodes(f: &Fields<'_>, v: &Value, ind: Independent) -> Result<Vec<[f64; 3]>, CliError> {
    let field = "guidance.nodes";
    let Value::Array(rows) = v else {
        return Err(f.err(
            field,
            &fmt_value(v),
            "must be an array of [x, alpha_deg, sigma_deg]",
        ));
    };
    if rows.len() < 2 || rows.len() > 16 {
        return Err(f.err(
            field,
            &format!("({} nodes)", rows.len()),
            "needs 2 to 16 nodes",
        ));
    }
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        let fi = format!("{field}[{i}]");
        let Value::Array(cols) = row else {
            return Err(f.err(&fi, &fmt_value(row), "must be [x, alpha_deg, sigma_deg]"));
        };
        if cols.len() != 3 {
            return Err(f.err(
                &fi,
                &fmt_value(row),
                "must have exactly 3 numbers [x, alpha_deg, sigma_deg]",
            ));
        }
        let mut n = [0.0; 3];
        for (j, c) in cols.iter().enumerate() {
            n[j] = match c {
                Value::Float(x) if x.is_finite() => *x,
                Value::Integer(x) => *x as f64,
                _ => return Err(f.err(&fi, &fmt_value(row), "entries must be finite numbers")),
            };
        }
        if !(0.0..=45.0).contains(&n[1]) {
            return Err(f.err(
                &fi,
                &fmt_value(row),
                "alpha must be within [0, 45] deg (thesis 4.2.1)",
            ));
        }
        if !(-90.0..=90.0).contains(&n[2]) {
            return Err(f.err(&fi, &fmt_value(row), "sigma must be within [-90, 90] deg"));
        }
        if let Some(prev) = out.last() {
            let ok = match ind {
                Independent::Time => n[0] > prev[0],
                Independent::Energy => n[0] < prev[0],
            };
            if !ok {
                return Err(f.err(
                    &fi,
                    &fmt_value(row),
                    match ind {
                        Independent::Time => "node times must increase strictly",
                        Independent::Energy => {
                            "node energies must decrease strictly (flight order)"
                        }
                    },
                ));
            }
        }
        out.push(node_to_rad(&n));
    }
    Ok(out)
}
