//! Downrange and crossrange error against time to go of the worst flights (two panels, one
//! line per flight; time to go runs down to 0 at the right, where each line ends at the
//! flight's footprint point).

use super::types::{ModeReport, TracePoint};
use crate::report::chart::{Figure, Layer, Legend, Mark, PALETTE, Panel};

/// The error-history figure of `r`.
#[must_use]
pub fn figure(r: &ModeReport) -> Figure {
    let longest = r
        .traces
        .iter()
        .flat_map(|t| t.points.iter().map(|q| q.time_to_go_s))
        .filter(|s| s.is_finite())
        .fold(0.0, f64::max);
    let panel = |what: &str, note: &str, legend: Legend, pick: fn(&TracePoint) -> f64| {
        let mut p = Panel::new(
            format!(
                "{} {}: {what} error of the {} worst flights ({})",
                r.scenario,
                r.mode,
                r.traces.len(),
                note
            ),
            "time to go [s]",
            &format!("{what} error [km]"),
        );
        p.x_negated = true;
        // From the longest time to go to the end (0) exactly: no axis beyond the end.
        if longest > 0.0 {
            p.x_range = Some((-longest, 0.0));
        }
        p.legend = legend;
        for (i, t) in r.traces.iter().enumerate() {
            let colour = PALETTE
                .get(i % PALETTE.len())
                .copied()
                .unwrap_or(PALETTE[0]);
            p.layers.push(Layer::new(
                format!("#{} (miss {:.2} km)", t.id, t.miss_km),
                colour,
                Mark::Line {
                    points: t
                        .points
                        .iter()
                        .map(|q| (-q.time_to_go_s, pick(q)))
                        .collect(),
                    width: 2,
                    dashed: false,
                },
            ));
        }
        p
    };
    Figure {
        panels: vec![
            panel("downrange", &r.trace_reference[0], Legend::Hidden, |q| {
                q.downrange_km
            }),
            panel(
                "crossrange",
                &r.trace_reference[1],
                Legend::LowerLeft,
                |q| q.crossrange_km,
            ),
        ],
        columns: 1,
        panel_size: (1100, 520),
    }
}
