//! The grid as CSV (`grid.csv`).

use std::fmt::Write as _;

use super::{CompareGrid, Preset};

fn cell(v: Option<f64>) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.6}"),
        _ => String::new(),
    }
}

/// The grid as CSV: one row per point; empty cells where a value does not exist.
#[must_use]
pub fn grid_csv(grid: &CompareGrid) -> String {
    let mut s = format!(
        "{},cl_vertical,cl,bank_deg,lambda,flown_entry_speed_m_s,flown_entry_gamma_deg,analytic_status,\
         simplified_status,full_status",
        grid.x_name()
    );
    for m in &grid.metrics {
        let _ = write!(
            s,
            ",{n}_analytic,{n}_simplified,{n}_full,{n}_err_simplified_{u},{n}_err_full_{u}",
            n = m.name,
            u = m.error_unit
        );
    }
    s.push('\n');
    for p in &grid.points {
        let _ = write!(
            s,
            "{},{},{},{:.6},{:.6},{},{},{},{},{}",
            grid.x_value(p.x),
            p.cl_vertical,
            p.lift.cl,
            p.lift.bank_rad.to_degrees(),
            p.lambda,
            cell(Some(p.entry_speed_m_s)),
            cell(Some(p.entry_gamma_rad.to_degrees())),
            p.analytic.status().replace(',', ";"),
            p.simplified.status(),
            p.full.status()
        );
        for (i, _) in grid.metrics.iter().enumerate() {
            let a = p.analytic.values().and_then(|v| v.get(i).copied());
            let ns = p.simplified.values().and_then(|v| v.get(i).copied());
            let nf = p.full.values().and_then(|v| v.get(i).copied());
            let _ = write!(
                s,
                ",{},{},{},{},{}",
                cell(a),
                cell(ns),
                cell(nf),
                cell(grid.error(p, i, Preset::Simplified)),
                cell(grid.error(p, i, Preset::Full))
            );
        }
        s.push('\n');
    }
    s
}
