//! Drawing a [`Figure`] with `plotters` on its SVG and bitmap backends (one code path).

use plotters::chart::SeriesAnno;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::bounds::ranges;
use super::types::{Figure, Layer, Legend, Mark, Panel, Rgb};
use crate::report::plot::{PlotError, encode_png, ensure_font, fmt_tick};

/// Margin around a panel \[px\].
const MARGIN: u32 = 14;
/// Height of the area under the plot for the abscissa's ticks and label \[px\].
const X_AREA: u32 = 48;
/// Width of the area left of the plot for the ordinate's ticks and label \[px\].
const Y_AREA: u32 = 72;
/// Caption font size \[px\] and the height it takes with its gap \[px\].
const CAPTION: (u32, u32) = (18, 32);
/// Most ticks on an axis.
const MAX_TICKS: usize = 20;

/// The tick label of `10^v` (whole decades print as 0.01, 1, 100, 1e+06).
fn decade(v: f64) -> String {
    let x = 10f64.powf(v);
    if !(1e-4..1e6).contains(&x) {
        format!("{x:.0e}")
    } else if x >= 1.0 {
        format!("{x:.0}")
    } else {
        let digits = (-v.floor()).max(0.0) as usize;
        format!("{x:.digits$}")
    }
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// The SVG document of `fig`.
pub(super) fn svg(fig: &Figure) -> Result<String, PlotError> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, fig.size()).into_drawing_area();
        draw_figure(&root, fig)?;
    }
    Ok(out)
}

/// The PNG image of `fig`.
pub(super) fn png(fig: &Figure) -> Result<Vec<u8>, PlotError> {
    let (w, h) = fig.size();
    let mut buf = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw_figure(&root, fig)?;
    }
    encode_png(&buf, w, h)
}

fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    fig: &Figure,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    ensure_font()?;
    root.fill(&WHITE)?;
    let cols = fig.columns.max(1);
    let rows = fig.panels.len().div_ceil(cols).max(1);
    let areas = root.split_evenly((rows, cols));
    for (panel, area) in fig.panels.iter().zip(&areas) {
        draw_panel(area, panel, fig.panel_size)?;
    }
    root.present()?;
    Ok(())
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
    size: (u32, u32),
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let plot_px = (
        f64::from(size.0.saturating_sub(Y_AREA + 2 * MARGIN)),
        f64::from(size.1.saturating_sub(X_AREA + 2 * MARGIN + CAPTION.1)),
    );
    let ((x0, x1, xs), (y0, y1, ys)) = ranges(p, plot_px);
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ("sans-serif", CAPTION.0))
        .margin(MARGIN)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let x_ticks = (((x1 - x0) / xs).round() as usize + 1).min(MAX_TICKS);
    let y_ticks = (((y1 - y0) / ys).round() as usize + 1).min(MAX_TICKS);
    let negate = p.x_negated;
    let log = p.x_log10;
    let x_fmt = move |v: &f64| {
        if log {
            decade(*v)
        } else {
            fmt_tick(if negate { -*v } else { *v }, xs)
        }
    };
    let y_fmt = |v: &f64| fmt_tick(*v, ys);
    chart
        .configure_mesh()
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .x_labels(x_ticks)
        .y_labels(y_ticks)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .max_light_lines(0)
        .bold_line_style(RGBColor(0xe0, 0xe0, 0xe0))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .draw()?;
    for layer in &p.layers {
        draw_layer(&mut chart, layer, (y0, y1))?;
    }
    let position = match p.legend {
        Legend::UpperLeft => Some(SeriesLabelPosition::UpperLeft),
        Legend::UpperRight => Some(SeriesLabelPosition::UpperRight),
        Legend::LowerLeft => Some(SeriesLabelPosition::LowerLeft),
        Legend::LowerRight => Some(SeriesLabelPosition::LowerRight),
        Legend::Hidden => None,
    };
    if let Some(position) = position
        && p.layers.iter().any(|l| l.label.is_some())
    {
        chart
            .configure_series_labels()
            .position(position)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .draw()?;
    }
    Ok(())
}

/// A legend entry of a line: a short solid or dashed stroke.
fn line_legend<DB: DrawingBackend>(anno: &mut SeriesAnno<'_, DB>, dashed: bool, style: ShapeStyle) {
    if dashed {
        anno.legend(move |(x, y)| DashedPathElement::new(vec![(x, y), (x + 24, y)], 7, 5, style));
    } else {
        anno.legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
    }
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn draw_layer<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    layer: &Layer,
    (y0, y1): (f64, f64),
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let colour = rgb(layer.colour);
    let finite = |pts: &[(f64, f64)]| -> Vec<(f64, f64)> {
        pts.iter()
            .copied()
            .filter(|q| q.0.is_finite() && q.1.is_finite())
            .collect()
    };
    let line = |width: u32| ShapeStyle {
        color: colour.to_rgba(),
        filled: false,
        stroke_width: width,
    };
    let label = layer.label.as_deref();
    match &layer.mark {
        Mark::Line {
            points,
            width,
            dashed,
        } => {
            let style = line(*width);
            let pts = finite(points);
            let drawn = if *dashed {
                chart.draw_series(DashedLineSeries::new(pts, 7, 5, style))?
            } else {
                chart.draw_series(LineSeries::new(pts, style))?
            };
            if let Some(l) = label {
                line_legend(drawn.label(l), *dashed, style);
            }
        }
        Mark::Dots { points, radius } => {
            let r = *radius;
            let style = colour.mix(0.75).filled();
            let drawn = chart.draw_series(
                finite(points)
                    .into_iter()
                    .map(move |q| Circle::new(q, r, style)),
            )?;
            if let Some(l) = label {
                drawn
                    .label(l)
                    .legend(move |(x, y)| Circle::new((x + 12, y), r.max(3), style));
            }
        }
        Mark::Cross { point, size } => {
            let s = *size;
            let style = line(3);
            let drawn = chart.draw_series(
                finite(&[*point])
                    .into_iter()
                    .map(move |q| Cross::new(q, s, style)),
            )?;
            if let Some(l) = label {
                drawn
                    .label(l)
                    .legend(move |(x, y)| Cross::new((x + 12, y), 6, style));
            }
        }
        Mark::Bars { edges, heights } => {
            let fill = colour.mix(0.7).filled();
            let bars: Vec<Rectangle<(f64, f64)>> = edges
                .windows(2)
                .zip(heights)
                .filter_map(|(w, h)| match w {
                    [a, b] if a.is_finite() && b.is_finite() && h.is_finite() && *h > 0.0 => {
                        Some(Rectangle::new([(*a, 0.0), (*b, *h)], fill))
                    }
                    _ => None,
                })
                .collect();
            let drawn = chart.draw_series(bars)?;
            if let Some(l) = label {
                drawn
                    .label(l)
                    .legend(move |(x, y)| Rectangle::new([(x + 4, y - 5), (x + 20, y + 5)], fill));
            }
        }
        Mark::VerticalLine { x, dashed } => {
            if x.is_finite() {
                let style = line(2);
                let pts = vec![(*x, y0), (*x, y1)];
                let drawn = if *dashed {
                    chart.draw_series(DashedLineSeries::new(pts, 7, 5, style))?
                } else {
                    chart.draw_series(LineSeries::new(pts, style))?
                };
                if let Some(l) = label {
                    line_legend(drawn.label(l), *dashed, style);
                }
            }
        }
        Mark::Labels { items } => {
            let font = ("sans-serif", 13).into_font().color(&colour);
            chart.draw_series(
                items
                    .iter()
                    .filter(|(q, _)| q.0.is_finite() && q.1.is_finite())
                    .map(|(q, text)| {
                        EmptyElement::at(*q)
                            + Circle::new((0, 0), 4, colour.stroke_width(2))
                            + Text::new(text.clone(), (6, -16), font.clone())
                    }),
            )?;
        }
    }
    Ok(())
}
