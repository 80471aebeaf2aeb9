//! The footprint: crossrange against downrange error at the terminal interface, the target,
//! the 1-, 2- and 3-sigma ellipses of the sample covariance (with the fraction of flights
//! inside each against a normal's) and the worst flights labelled with their case id.

use super::ellipse::{Gaussian2, normal_fraction_inside};
use super::worst::worst_flights;
use super::{LABELLED_WORST, ModeReport, flights_note};
use crate::report::chart::{BLACK, Figure, Layer, Legend, Mark, PALETTE, Panel, Rgb};

/// Colours of the 1-, 2- and 3-sigma ellipses.
const SIGMA_COLOURS: [Rgb; 3] = [PALETTE[2], PALETTE[1], PALETTE[3]];

/// The footprint figure of `r`.
#[must_use]
pub fn figure(r: &ModeReport) -> Figure {
    let pts: Vec<(f64, f64)> = r
        .flights
        .iter()
        .map(|f| (f.downrange_km, f.crossrange_km))
        .collect();
    let mut p = Panel::new(
        format!(
            "{} {}: footprint at the terminal interface ({})",
            r.scenario,
            r.mode,
            flights_note(r)
        ),
        "downrange error [km] (+: long)",
        "crossrange error [km] (+: right)",
    );
    p.equal_aspect = true;
    p.legend = Legend::UpperRight;
    p.layers.push(Layer::new(
        "flights",
        PALETTE[0],
        Mark::Dots {
            points: pts.clone(),
            radius: 2,
        },
    ));
    if let Some(g) = Gaussian2::of(&pts) {
        for (k, colour) in (1..=3).zip(SIGMA_COLOURS) {
            let k = f64::from(k);
            let inside = g
                .fraction_inside(&pts, k)
                .map_or_else(String::new, |f| format!(", {:.1} % inside", 100.0 * f));
            p.layers.push(Layer::new(
                format!(
                    "{k:.0}-sigma (normal: {:.1} %{inside})",
                    100.0 * normal_fraction_inside(k)
                ),
                colour,
                Mark::Line {
                    points: g.ellipse(k, 180),
                    width: 2,
                    dashed: false,
                },
            ));
        }
    }
    if let Some(n) = r.nominal_km {
        p.layers.push(Layer::new(
            "undispersed flight",
            PALETTE[4],
            Mark::Dots {
                points: vec![n],
                radius: 5,
            },
        ));
    }
    p.layers.push(Layer::new(
        "target",
        BLACK,
        Mark::Cross {
            point: (0.0, 0.0),
            size: 9,
        },
    ));
    let items = worst_flights(&r.flights, LABELLED_WORST)
        .into_iter()
        .filter_map(|i| r.flights.get(i))
        .map(|f| ((f.downrange_km, f.crossrange_km), format!("#{}", f.id)))
        .collect();
    p.layers.push(Layer::new(
        format!("worst {LABELLED_WORST} (case id)"),
        PALETTE[3],
        Mark::Labels { items },
    ));
    let mut fig = Figure::single(p);
    fig.panel_size = (1000, 760);
    fig
}
