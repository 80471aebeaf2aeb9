//! The miss CDF: the empirical distribution of the miss distance with p50, p90, p99 and
//! p99.9 marked (nearest rank, the percentiles of `summary.json`), on a logarithmic miss axis
//! when the worst miss is more than [`LOG_RATIO`] times the median (a tail that a linear
//! axis would squeeze the body of the distribution against the origin for).

use super::cdf::{ecdf_steps, nearest_rank, sorted};
use super::types::{ModeReport, flights_note};
use crate::report::chart::{Figure, Layer, Legend, Mark, PALETTE, Panel};

/// The marked percentiles: (fraction, label, colour index in the palette).
pub const MARKED: [(f64, &str, usize); 4] = [
    (0.5, "p50", 2),
    (0.9, "p90", 1),
    (0.99, "p99", 3),
    (0.999, "p99.9", 4),
];

/// Worst / median miss above which the miss axis is logarithmic.
pub const LOG_RATIO: f64 = 20.0;

/// The marked percentiles of `r`'s misses \[km\] (`None` without flights).
#[must_use]
pub fn marked_percentiles(r: &ModeReport) -> Option<[f64; 4]> {
    let v = sorted(&r.flights.iter().map(|f| f.miss_km).collect::<Vec<_>>());
    let mut out = [0.0; 4];
    for (o, (p, _, _)) in out.iter_mut().zip(MARKED) {
        *o = nearest_rank(&v, p)?;
    }
    Some(out)
}

/// The miss CDF figure of `r`.
#[must_use]
pub fn figure(r: &ModeReport) -> Figure {
    let v = sorted(&r.flights.iter().map(|f| f.miss_km).collect::<Vec<_>>());
    let mut p = Panel::new(
        format!(
            "{} {}: miss distance, cumulative distribution ({})",
            r.scenario,
            r.mode,
            flights_note(r)
        ),
        "miss distance [km]",
        "fraction of flights with a smaller miss [-]",
    );
    p.y_range = Some((0.0, 1.0));
    let median = nearest_rank(&v, 0.5).unwrap_or(0.0);
    let worst = v
        .iter()
        .copied()
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    // Misses below a metre are drawn at a metre on the logarithmic axis.
    let log = median > 0.0 && worst > LOG_RATIO * median;
    let x_of = move |x: f64| if log { x.max(1e-3).log10() } else { x };
    if log {
        p.x_log10 = true;
        p.x_label = "miss distance [km] (logarithmic)".into();
    }
    p.legend = Legend::LowerRight;
    p.layers.push(Layer::new(
        "empirical CDF",
        PALETTE[0],
        Mark::Line {
            points: ecdf_steps(&v)
                .into_iter()
                .map(|(x, f)| (x_of(x), f))
                .collect(),
            width: 2,
            dashed: false,
        },
    ));
    if let Some(values) = marked_percentiles(r) {
        for ((frac, name, colour), x) in MARKED.into_iter().zip(values) {
            let colour = PALETTE.get(colour).copied().unwrap_or(PALETTE[0]);
            p.layers.push(Layer::new(
                format!("{name} = {x:.2} km"),
                colour,
                Mark::VerticalLine {
                    x: x_of(x),
                    dashed: true,
                },
            ));
            p.layers.push(Layer::unlabelled(
                colour,
                Mark::Dots {
                    points: vec![(x_of(x), frac)],
                    radius: 5,
                },
            ));
        }
    }
    Figure::single(p)
}
