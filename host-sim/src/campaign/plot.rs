//! Campaign plots (plotters SVG): the footprint (crossrange against downrange error at the
//! terminal interface, one colour per mode) and histograms of the miss distance.

use plotters::prelude::*;

use super::{CaseResult, Mode};
use crate::report::ReportError;

type PlotError = Box<dyn std::error::Error + Send + Sync>;

fn colour(m: Mode) -> RGBColor {
    match m {
        Mode::Stored => RGBColor(200, 60, 40),
        Mode::StoredReversals => RGBColor(40, 110, 200),
        Mode::ReplanReversals => RGBColor(30, 150, 60),
        Mode::ReplanEstimation => RGBColor(150, 40, 160),
    }
}

fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo.is_finite() && hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else if lo.is_finite() {
        (lo - 1.0, lo + 1.0)
    } else {
        (-1.0, 1.0)
    }
}

fn draw_footprint(svg: &mut String, cases: &[(Mode, Vec<CaseResult>)]) -> Result<(), PlotError> {
    let all = || cases.iter().flat_map(|(_, v)| v.iter());
    let xr = span(all().map(|c| c.downrange_error_m / 1e3));
    let yr = span(all().map(|c| c.crossrange_error_m / 1e3));
    let root = SVGBackend::with_string(svg, (800, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption("Footprint at the terminal interface", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
    chart
        .configure_mesh()
        .x_desc("downrange error [km]")
        .y_desc("crossrange error [km]")
        .draw()?;
    for (m, v) in cases {
        let c = colour(*m);
        chart
            .draw_series(v.iter().map(|r| {
                Circle::new(
                    (r.downrange_error_m / 1e3, r.crossrange_error_m / 1e3),
                    2,
                    c.filled(),
                )
            }))?
            .label(m.name())
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

fn draw_histogram(svg: &mut String, mode: Mode, values_km: &[f64]) -> Result<(), PlotError> {
    let (lo, hi) = span(values_km.iter().copied());
    let lo = lo.max(0.0);
    let bins = 30usize;
    let w = (hi - lo) / bins as f64;
    let mut counts = vec![0u32; bins];
    for v in values_km.iter().filter(|v| v.is_finite()) {
        let k = (((v - lo) / w).floor().max(0.0) as usize).min(bins - 1);
        if let Some(c) = counts.get_mut(k) {
            *c += 1;
        }
    }
    let top = counts.iter().copied().max().unwrap_or(1).max(1);
    let root = SVGBackend::with_string(svg, (800, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("Miss distance, {}", mode.name()),
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(lo..hi, 0u32..top + 1)?;
    chart
        .configure_mesh()
        .x_desc("miss distance [km]")
        .y_desc("flights")
        .draw()?;
    let c = colour(mode);
    chart.draw_series(counts.iter().enumerate().map(|(i, &n)| {
        let x0 = lo + w * i as f64;
        Rectangle::new([(x0, 0), (x0 + w, n)], c.filled())
    }))?;
    root.present()?;
    Ok(())
}

/// The campaign's SVG plots: `(file name, svg)`.
///
/// # Errors
/// [`ReportError::Plot`] if `plotters` fails.
pub fn campaign_plots(
    cases: &[(Mode, Vec<CaseResult>)],
) -> Result<Vec<(String, String)>, ReportError> {
    let plot_err = |name: &str| {
        let name = name.to_string();
        move |source| ReportError::Plot { name, source }
    };
    // The embedded font: without it the first caption fails with FontUnavailable when no
    // other plot of this process registered it (`host-sim dispersions` draws these first).
    crate::report::ensure_font().map_err(plot_err("footprint.svg"))?;
    let mut out = Vec::new();
    let mut svg = String::new();
    draw_footprint(&mut svg, cases).map_err(plot_err("footprint.svg"))?;
    out.push(("footprint.svg".to_string(), svg));
    for (m, v) in cases {
        let name = format!("miss-histogram-{}.svg", m.name());
        let miss: Vec<f64> = v.iter().map(|c| c.miss_m / 1e3).collect();
        let mut svg = String::new();
        draw_histogram(&mut svg, *m, &miss).map_err(plot_err(&name))?;
        out.push((name, svg));
    }
    Ok(out)
}
