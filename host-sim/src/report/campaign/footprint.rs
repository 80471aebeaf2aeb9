//! The footprint: crossrange against downrange error at the terminal interface, the target,
//! the 1-, 2- and 3-sigma ellipses of the sample covariance (with the fraction of flights
//! inside each against a normal's) and the worst flights labelled with their case id; two
//! panels, every flight and the core (the 3-sigma ellipse's box), since a few far flights
//! would otherwise hide the distribution.

use super::ellipse::{Gaussian2, normal_fraction_inside};
use super::types::{LABELLED_WORST, ModeReport, flights_note};
use super::worst::worst_flights;
use crate::report::chart::{BLACK, Figure, Layer, Legend, Mark, PALETTE, Panel, Rgb};

/// Colours of the 1-, 2- and 3-sigma ellipses.
const SIGMA_COLOURS: [Rgb; 3] = [PALETTE[2], PALETTE[1], PALETTE[3]];

/// A box (x0, x1, y0, y1) in km.
type Box = (f64, f64, f64, f64);

fn inside(b: Option<Box>, p: (f64, f64)) -> bool {
    b.is_none_or(|(x0, x1, y0, y1)| (x0..=x1).contains(&p.0) && (y0..=y1).contains(&p.1))
}

/// The panel of `r` showing what is inside `zoom` (`None`: everything).
fn panel(r: &ModeReport, g: Option<&Gaussian2>, zoom: Option<Box>) -> Panel {
    let pts: Vec<(f64, f64)> = r
        .flights
        .iter()
        .map(|f| (f.downrange_km, f.crossrange_km))
        .collect();
    let shown: Vec<(f64, f64)> = pts.iter().copied().filter(|p| inside(zoom, *p)).collect();
    let title = match zoom {
        None => format!(
            "{} {}: footprint at the terminal interface ({})",
            r.scenario,
            r.mode,
            flights_note(r)
        ),
        Some(_) => format!(
            "core: the 3-sigma ellipse ({} of {} flights outside this box)",
            pts.len() - shown.len(),
            pts.len()
        ),
    };
    let mut p = Panel::new(
        title,
        "downrange error [km] (+: long)",
        "crossrange error [km] (+: right)",
    );
    p.equal_aspect = true;
    if let Some((x0, x1, y0, y1)) = zoom {
        p.x_range = Some((x0, x1));
        p.y_range = Some((y0, y1));
    }
    p.legend = if zoom.is_some() {
        Legend::Hidden
    } else {
        Legend::UpperRight
    };
    p.layers.push(Layer::new(
        "flights",
        PALETTE[0],
        Mark::Dots {
            points: shown,
            radius: 2,
        },
    ));
    if let Some(g) = g {
        for (k, colour) in (1..=3).zip(SIGMA_COLOURS) {
            let k = f64::from(k);
            let within = g
                .fraction_inside(&pts, k)
                .map_or_else(String::new, |f| format!(", {:.1} % inside", 100.0 * f));
            p.layers.push(Layer::new(
                format!(
                    "{k:.0}-sigma (normal: {:.1} %{within})",
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
    if let Some(n) = r.nominal_km.filter(|n| inside(zoom, *n)) {
        p.layers.push(Layer::new(
            "undispersed flight",
            PALETTE[4],
            Mark::Dots {
                points: vec![n],
                radius: 5,
            },
        ));
    }
    if inside(zoom, (0.0, 0.0)) {
        p.layers.push(Layer::new(
            "target",
            BLACK,
            Mark::Cross {
                point: (0.0, 0.0),
                size: 9,
            },
        ));
    }
    let items = worst_flights(&r.flights, LABELLED_WORST)
        .into_iter()
        .filter_map(|i| r.flights.get(i))
        .map(|f| ((f.downrange_km, f.crossrange_km), format!("#{}", f.id)))
        .filter(|(q, _)| inside(zoom, *q))
        .collect();
    p.layers.push(Layer::new(
        format!("worst {LABELLED_WORST} (case id)"),
        PALETTE[3],
        Mark::Labels { items },
    ));
    p
}

/// The box of the 3-sigma ellipse of `g`, with a tenth of room.
fn core_box(g: &Gaussian2) -> Option<Box> {
    let e = g.ellipse(3.0, 360);
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in e {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (dx, dy) = (0.1 * (x1 - x0), 0.1 * (y1 - y0));
    (x1 > x0 && y1 > y0 && dx.is_finite() && dy.is_finite()).then_some((
        x0 - dx,
        x1 + dx,
        y0 - dy,
        y1 + dy,
    ))
}

/// The footprint figure of `r`: every flight, and the core when the flights have a
/// covariance.
#[must_use]
pub fn figure(r: &ModeReport) -> Figure {
    let pts: Vec<(f64, f64)> = r
        .flights
        .iter()
        .map(|f| (f.downrange_km, f.crossrange_km))
        .collect();
    let g = Gaussian2::of(&pts);
    let mut panels = vec![panel(r, g.as_ref(), None)];
    if let Some(b) = g.as_ref().and_then(core_box) {
        panels.push(panel(r, g.as_ref(), Some(b)));
    }
    let columns = panels.len();
    Figure {
        panels,
        columns,
        panel_size: (860, 720),
    }
}
