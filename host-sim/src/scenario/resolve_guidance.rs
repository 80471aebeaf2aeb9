//! The `[guidance]` section of a scenario file and its node table.

use guidance_core::nodes::{HOST_NODE_CAPACITY, Independent};

use super::fields::Fields;
use super::file::{GuidanceFile, IndependentFile, InterpolationFile, Num};
use super::{InterpolationKind, Scenario, ScenarioError, node_to_rad};
use crate::num_fmt::compact;

/// Shortest guidance period \[s\]: 10 ms (100 Hz, faster than any re-entry guidance cycle;
/// shorter ones only multiply the integrator's breakpoints).
pub const MIN_PERIOD_S: f64 = 0.01;
/// Longest guidance period \[s\].
pub const MAX_PERIOD_S: f64 = 100.0;
/// Attitude-rate limits \[deg/s\]: 0.001 (a ramp over 40 deg takes 11 h) to 1000.
pub const MIN_RATE_DEG_S: f64 = 1e-3;
/// See [`MIN_RATE_DEG_S`].
pub const MAX_RATE_DEG_S: f64 = 1e3;

/// The `[guidance]` section: node variable, interpolation, rates, initial attitude, nodes.
pub(super) fn guidance(
    f: &Fields<'_>,
    t: GuidanceFile,
    sc: &mut Scenario,
) -> Result<(), ScenarioError> {
    let mut t = t;
    sc.layers = super::resolve_layers::layers(
        f,
        super::resolve_layers::LayerFiles {
            lateral: t.lateral.take(),
            replanning: t.replanning.take(),
            estimator: t.estimator.take(),
            barrier: t.barrier.take(),
            target: t.target.take(),
        },
        sc.environment.planet.radius_m,
        sc.entry.speed_m_s,
        sc.entry.radius_m - sc.environment.planet.radius_m,
    )?;
    let g = &mut sc.guidance;
    if let Some(s) = t.independent {
        g.independent = match s {
            IndependentFile::Time => Independent::TimeS,
            IndependentFile::Energy => Independent::NormalizedEnergy,
        };
    }
    let tension = f.checked(
        "guidance.tension",
        t.tension,
        |v| (0.0..=1.0).contains(&v),
        "must be within [0, 1]",
    )?;
    if let Some(s) = t.interpolation {
        g.interpolation = match s {
            InterpolationFile::Linear => InterpolationKind::Linear,
            InterpolationFile::NaturalCubic => InterpolationKind::NaturalCubic,
            InterpolationFile::Hermite => InterpolationKind::Hermite {
                tension: tension.unwrap_or(0.0),
            },
        };
    }
    if let Some(v) = f.checked(
        "guidance.period_s",
        t.period_s,
        |v| (MIN_PERIOD_S..=MAX_PERIOD_S).contains(&v),
        "must be in [0.01, 100] s (a guidance cycle of at least 10 ms)",
    )? {
        g.period_s = v;
    }
    let rate = |v: f64| (MIN_RATE_DEG_S..=MAX_RATE_DEG_S).contains(&v);
    let rate_reason = "must be in [0.001, 1000] deg/s";
    if let Some(v) = f.checked(
        "guidance.alpha_rate_deg_s",
        t.alpha_rate_deg_s,
        rate,
        rate_reason,
    )? {
        g.alpha_rate_rad_s = v.to_radians();
    }
    if let Some(v) = f.checked(
        "guidance.sigma_rate_deg_s",
        t.sigma_rate_deg_s,
        rate,
        rate_reason,
    )? {
        g.sigma_rate_rad_s = v.to_radians();
    }
    if let Some(v) = f.checked(
        "guidance.initial_alpha_deg",
        t.initial_alpha_deg,
        |v| (0.0..=45.0).contains(&v),
        "must be within [0, 45] deg",
    )? {
        g.initial.alpha_rad = v.to_radians();
    }
    if let Some(v) = f.checked(
        "guidance.initial_sigma_deg",
        t.initial_sigma_deg,
        |v| v > -180.0 && v <= 180.0,
        "must be within (-180, 180] deg",
    )? {
        g.initial.sigma_rad = v.to_radians();
    }
    if let Some(rows) = t.nodes {
        g.nodes = nodes(f, &rows, g.independent)?;
    } else if g.independent == Independent::NormalizedEnergy {
        return Err(f.err(
            "guidance.nodes",
            "(missing)",
            "energy-indexed guidance needs its own node table",
        ));
    }
    Ok(())
}

/// A node row as written, for messages: `[264, 40, 79.6]`.
fn fmt_row(row: &[Num]) -> String {
    let cells: Vec<String> = row.iter().map(|c| compact(c.0)).collect();
    format!("[{}]", cells.join(", "))
}

fn nodes(
    f: &Fields<'_>,
    rows: &[Vec<Num>],
    ind: Independent,
) -> Result<Vec<[f64; 3]>, ScenarioError> {
    let field = "guidance.nodes";
    if rows.len() < 2 || rows.len() > HOST_NODE_CAPACITY {
        return Err(f.err(
            field,
            &format!("({} nodes)", rows.len()),
            &format!("needs 2 to {HOST_NODE_CAPACITY} nodes"),
        ));
    }
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        let fi = format!("{field}[{i}]");
        let shown = fmt_row(row);
        let [x, a, s] = row[..] else {
            return Err(f.err(
                &fi,
                &shown,
                "must have exactly 3 numbers [x, alpha_deg, sigma_deg]",
            ));
        };
        let n = [x.0, a.0, s.0];
        if n.iter().any(|v| !v.is_finite()) {
            return Err(f.err(&fi, &shown, "entries must be finite numbers"));
        }
        if !(0.0..=45.0).contains(&n[1]) {
            return Err(f.err(
                &fi,
                &shown,
                "alpha must be within [0, 45] deg (thesis 4.2.1)",
            ));
        }
        if !(n[2] > -180.0 && n[2] <= 180.0) {
            return Err(f.err(&fi, &shown, "sigma must be within (-180, 180] deg"));
        }
        if let Some(prev) = out.last() {
            let ok = match ind {
                Independent::TimeS => n[0] > prev[0],
                Independent::NormalizedEnergy => n[0] < prev[0],
            };
            if !ok {
                return Err(f.err(
                    &fi,
                    &shown,
                    match ind {
                        Independent::TimeS => "node times must increase strictly",
                        Independent::NormalizedEnergy => {
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
