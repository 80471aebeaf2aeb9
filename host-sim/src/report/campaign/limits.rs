//! Limit-ratio histograms: peak / limit of heat flux, g-load and g-load rate over the flights,
//! with the limit (ratio 1) as a line and the count of flights over it in the title.

use super::histogram::histogram;
use super::types::{ModeReport, flights_note};
use crate::report::chart::{Figure, LIMIT_RED, Layer, Legend, Mark, PALETTE, Panel};

/// The quantities, in the order of the flights' `limit_ratios`.
pub const QUANTITIES: [&str; 3] = ["heat flux", "g-load", "g-load rate"];

/// Bins of each histogram.
const BINS: usize = 40;

/// The limit-ratio figure of `r` (three panels side by side).
#[must_use]
pub fn figure(r: &ModeReport) -> Figure {
    let panels = QUANTITIES
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let v: Vec<f64> = r
                .flights
                .iter()
                .filter_map(|f| f.limit_ratios.get(i).copied())
                .collect();
            let finite = v.iter().copied().filter(|x| x.is_finite());
            let lo = finite.clone().fold(f64::INFINITY, f64::min).min(1.0);
            let hi = finite.fold(f64::NEG_INFINITY, f64::max).max(1.0);
            let (lo, hi) = if lo.is_finite() && hi > lo {
                let pad = 0.02 * (hi - lo);
                ((lo - pad).max(0.0), hi + pad)
            } else {
                (0.0, 1.1)
            };
            let over = v.iter().filter(|x| x.is_nan() || **x > 1.0).count();
            let worst = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let mut p = Panel::new(
                format!(
                    "{} {}: {name}, worst {:.3}, {over} over",
                    r.scenario,
                    r.mode,
                    if worst.is_finite() { worst } else { f64::NAN }
                ),
                format!("peak {name} / limit [-]"),
                "flights",
            );
            p.legend = Legend::UpperLeft;
            let (edges, heights) = histogram(&v, lo, hi, BINS);
            let top = heights.iter().copied().fold(1.0, f64::max);
            p.y_range = Some((0.0, (1.1 * top).ceil()));
            p.layers.push(Layer::new(
                flights_note(r),
                PALETTE[0],
                Mark::Bars { edges, heights },
            ));
            p.layers.push(Layer::new(
                "limit",
                LIMIT_RED,
                Mark::VerticalLine {
                    x: 1.0,
                    dashed: true,
                },
            ));
            p
        })
        .collect();
    Figure {
        panels,
        columns: 3,
        panel_size: (620, 460),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_panels_with_the_limit() {
        let r = ModeReport {
            scenario: "s".into(),
            mode: "m".into(),
            flights: Vec::new(),
            failed: 0,
            nominal_km: None,
            traces: Vec::new(),
            trace_reference: [String::new(), String::new()],
        };
        let f = figure(&r);
        assert_eq!(f.panels.len(), 3);
        assert!(f.panels.iter().all(|p| p.layers.iter().any(|l| matches!(
            l.mark,
            Mark::VerticalLine { x, .. } if x == 1.0
        ))));
    }
}
