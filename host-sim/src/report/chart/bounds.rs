//! Axis ranges of a panel: the data of its layers (finite values only), or the panel's own
//! ranges, rounded out to nice tick steps, and widened to equal units per pixel when the panel
//! asks for an equal aspect.

use super::types::{Mark, Panel};
use crate::report::plot::{nice_range, widen};

/// Axis ranges and tick steps of a panel: `((x0, x1, x_step), (y0, y1, y_step))`.
pub(super) type Ranges = ((f64, f64, f64), (f64, f64, f64));

/// Running minimum and maximum of finite values.
#[derive(Clone, Copy)]
struct Span(f64, f64);

impl Span {
    const EMPTY: Span = Span(f64::INFINITY, f64::NEG_INFINITY);

    fn add(&mut self, v: f64) {
        if v.is_finite() {
            self.0 = self.0.min(v);
            self.1 = self.1.max(v);
        }
    }

    fn or_unit(self) -> (f64, f64) {
        if self.0.is_finite() {
            widen(self.0, self.1)
        } else {
            (0.0, 1.0)
        }
    }
}

/// The data spans of the layers (a vertical line counts on the abscissa only; bars from 0).
fn data_spans(p: &Panel) -> (Span, Span) {
    let (mut x, mut y) = (Span::EMPTY, Span::EMPTY);
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for l in &p.layers {
        match &l.mark {
            Mark::Line { points, .. } | Mark::Dots { points, .. } => {
                pts.extend_from_slice(points);
            }
            Mark::Cross { point: q, .. } => pts.push(*q),
            Mark::Labels { items } => pts.extend(items.iter().map(|(q, _)| *q)),
            Mark::Bars { edges, heights } => {
                for (w, h) in edges.windows(2).zip(heights) {
                    if let [a, b] = w {
                        pts.push((*a, 0.0));
                        pts.push((*b, *h));
                    }
                }
            }
            Mark::VerticalLine { x: v, .. } => x.add(*v),
        }
    }
    for (a, b) in pts {
        if a.is_finite() && b.is_finite() {
            x.add(a);
            y.add(b);
        }
    }
    (x, y)
}

/// The ranges of panel `p` drawn on a plotting area of `area` pixels (width, height).
pub(super) fn ranges(p: &Panel, area: (f64, f64)) -> Ranges {
    let (xs, ys) = data_spans(p);
    let (x0, x1) = p.x_range.unwrap_or_else(|| xs.or_unit());
    let (y0, y1) = p.y_range.unwrap_or_else(|| ys.or_unit());
    let (x0, x1) = widen(x0, x1);
    let (y0, y1) = widen(y0, y1);
    let pad = |lo: f64, hi: f64, fixed: bool| {
        if fixed {
            (lo, hi)
        } else {
            // A little room so that extreme points are not on the frame.
            let d = 0.03 * (hi - lo);
            (lo - d, hi + d)
        }
    };
    let (x0, x1) = pad(x0, x1, p.x_range.is_some());
    let (y0, y1) = pad(y0, y1, p.y_range.is_some());
    let mut x = if p.x_log10 && p.x_range.is_none() {
        // Whole decades (the data's, before padding).
        let (d0, d1) = xs.or_unit();
        let (lo, hi) = (d0.floor(), d1.ceil());
        (lo, if hi > lo { hi } else { lo + 1.0 }, 1.0)
    } else {
        nice_or_fixed(x0, x1, 8.0, p.x_range.is_some())
    };
    let mut y = nice_or_fixed(y0, y1, 6.0, p.y_range.is_some());
    if p.equal_aspect && area.0 > 0.0 && area.1 > 0.0 {
        // Units per pixel on each axis; the smaller one grows to the larger (about the centre).
        let ux = (x.1 - x.0) / area.0;
        let uy = (y.1 - y.0) / area.1;
        if ux > uy {
            let c = 0.5 * (y.0 + y.1);
            let h = 0.5 * ux * area.1;
            y = (c - h, c + h, nice_range(c - h, c + h, 6.0).2);
        } else {
            let c = 0.5 * (x.0 + x.1);
            let h = 0.5 * uy * area.0;
            x = (c - h, c + h, nice_range(c - h, c + h, 8.0).2);
        }
    }
    (x, y)
}

fn nice_or_fixed(lo: f64, hi: f64, n: f64, fixed: bool) -> (f64, f64, f64) {
    let nice = nice_range(lo, hi, n);
    if fixed { (lo, hi, nice.2) } else { nice }
}

#[cfg(test)]
mod tests {
    use super::super::types::{Layer, PALETTE};
    use super::*;

    fn panel(points: Vec<(f64, f64)>) -> Panel {
        let mut p = Panel::new("t", "x", "y");
        p.layers.push(Layer::unlabelled(
            PALETTE[0],
            Mark::Dots { points, radius: 2 },
        ));
        p
    }

    /// Equal aspect: the same data units per pixel on both axes, the data still inside.
    #[test]
    fn equal_aspect_keeps_units_per_pixel_equal() {
        let mut p = panel(vec![(-10.0, -1.0), (30.0, 2.0), (f64::NAN, 1e9)]);
        p.equal_aspect = true;
        let area = (800.0, 500.0);
        let ((x0, x1, _), (y0, y1, _)) = ranges(&p, area);
        let ux = (x1 - x0) / area.0;
        let uy = (y1 - y0) / area.1;
        assert!((ux - uy).abs() < 1e-12 * ux, "{ux} {uy}");
        assert!(x0 <= -10.0 && x1 >= 30.0 && y0 <= -1.0 && y1 >= 2.0);
        // Without it the ordinate hugs the data (the NaN point is ignored).
        p.equal_aspect = false;
        let (_, (y0, y1, _)) = ranges(&p, area);
        assert!(y0 >= -2.0 && y1 <= 3.0, "{y0} {y1}");
    }

    /// Bars start at zero; a vertical line widens the abscissa; fixed ranges are kept.
    #[test]
    fn bars_lines_and_fixed_ranges() {
        let mut p = Panel::new("t", "x", "y");
        p.layers.push(Layer::unlabelled(
            PALETTE[0],
            Mark::Bars {
                edges: vec![0.5, 0.6, 0.7],
                heights: vec![3.0, 5.0],
            },
        ));
        p.layers.push(Layer::unlabelled(
            PALETTE[1],
            Mark::VerticalLine {
                x: 1.0,
                dashed: true,
            },
        ));
        let ((x0, x1, _), (y0, y1, _)) = ranges(&p, (800.0, 500.0));
        assert!(x0 <= 0.5 && x1 >= 1.0, "{x0} {x1}");
        assert!(y0 <= 0.0 && y1 >= 5.0, "{y0} {y1}");
        p.y_range = Some((0.0, 1.0));
        let (_, (y0, y1, _)) = ranges(&p, (800.0, 500.0));
        assert_eq!((y0, y1), (0.0, 1.0));
    }
}
