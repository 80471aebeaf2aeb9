//! Heat maps of a grid's errors, drawn with `plotters`' SVG backend.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{AnalyticOutcome, CompareGrid, Preset};
use crate::analytic::Phase;
use crate::report::ReportError;

type PlotError = Box<dyn std::error::Error + Send + Sync>;

/// Fill colour of a cell at fraction `f` in [0, 1] of the map's largest |error|: white to red.
fn shade(f: f64) -> RGBColor {
    let gb = (255.0 * (1.0 - 0.85 * f)).round() as u8;
    RGBColor(255, gb, gb)
}

/// Out-of-domain cells.
const GREY: RGBColor = RGBColor(0xbd, 0xbd, 0xbd);
/// Cells whose numerical run failed.
const PALE_YELLOW: RGBColor = RGBColor(0xff, 0xf3, 0xb0);
/// Cell borders.
const BORDER: RGBColor = RGBColor(0x55, 0x55, 0x55);

/// Heat map of the error of metric `m` against `fidelity` over the grid, as a standalone SVG:
/// x = grid x values, y = vertical lift coefficient, colour = |error| (white to red, scaled to
/// the largest |error| of the map), value printed in each cell. Out-of-domain points are grey
/// and marked "out of domain"; failed numerical runs are pale yellow and marked "n/a".
///
/// # Errors
/// [`ReportError::Plot`] if `plotters` fails to draw.
pub fn heat_map_svg(grid: &CompareGrid, m: usize, fidelity: Preset) -> Result<String, ReportError> {
    let mut svg = String::new();
    let name = grid
        .metrics
        .get(m)
        .map_or_else(|| format!("metric {m}"), |x| x.name.to_string());
    draw(&mut svg, grid, m, fidelity).map_err(|source| ReportError::Plot { name, source })?;
    Ok(svg)
}

fn draw(svg: &mut String, grid: &CompareGrid, m: usize, fidelity: Preset) -> Result<(), PlotError> {
    let Some(metric) = grid.metrics.get(m) else {
        return Ok(());
    };
    let nx = grid.xs.len().max(1);
    let ny = grid.cl_vertical.len().max(1);
    let (cw, ch) = (96_i32, 44_i32);
    let (ml, mt, mr, mb) = (90_i32, 56_i32, 150_i32, 60_i32);
    let pw = cw * i32::try_from(nx)?;
    let ph = ch * i32::try_from(ny)?;
    // Tall enough for the legend (6 shades, a gap, 2 markers) when the grid has few rows.
    let (w, h) = (
        ml + pw + mr,
        (mt + ph + mb).max(mt + 18 * 6 + 8 + 22 + 16 + 12),
    );
    let scale = grid.max_abs_error(m, fidelity).unwrap_or(0.0).max(1e-12);
    let unit = if metric.relative {
        "%"
    } else {
        metric.error_unit
    };
    let root =
        SVGBackend::with_string(svg, (u32::try_from(w)?, u32::try_from(h)?)).into_drawing_area();
    root.fill(&WHITE)?;
    let font = ("sans-serif", 11).into_font();
    let centred = font
        .clone()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    let right = font
        .clone()
        .color(&BLACK)
        .pos(Pos::new(HPos::Right, VPos::Center));
    let left = font
        .clone()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let title = format!(
        "{} {}: error of {} (analytical - numerical, {} environment) [{unit}]",
        grid.vehicle,
        match grid.phase {
            Phase::Skip => "skip",
            Phase::Glide => "glide",
        },
        metric.name,
        fidelity.name()
    );
    root.draw(&Text::new(
        title,
        (w / 2, 22),
        ("sans-serif", 13)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let cell = |ix: usize, iy: usize| -> Result<(i32, i32), PlotError> {
        // Highest C_L at the top.
        let x = ml + cw * i32::try_from(ix)?;
        let y = mt + ph - ch * (i32::try_from(iy)? + 1);
        Ok((x, y))
    };
    for (iy, clv) in grid.cl_vertical.iter().enumerate() {
        let (_, y) = cell(0, iy)?;
        root.draw(&Text::new(
            clv.to_string(),
            (ml - 6, y + ch / 2),
            right.clone(),
        ))?;
    }
    for (ix, x) in grid.xs.iter().enumerate() {
        let (xp, _) = cell(ix, 0)?;
        root.draw(&Text::new(
            grid.x_value(*x).to_string(),
            (xp + cw / 2, mt + ph + 16),
            centred.clone(),
        ))?;
    }
    for (k, p) in grid.points.iter().enumerate() {
        let (x, y) = cell(k / ny, k % ny)?;
        let (fill, label) = match (&p.analytic, grid.error(p, m, fidelity)) {
            (AnalyticOutcome::OutOfDomain(_), _) | (AnalyticOutcome::Failed(_), _) => {
                (GREY, "out of domain".to_string())
            }
            (_, Some(e)) => {
                let f = (e.abs() / scale).clamp(0.0, 1.0);
                (shade(f), format!("{e:+.2}"))
            }
            (_, None) => (PALE_YELLOW, "n/a".to_string()),
        };
        root.draw(&Rectangle::new([(x, y), (x + cw, y + ch)], fill.filled()))?;
        root.draw(&Rectangle::new(
            [(x, y), (x + cw, y + ch)],
            BORDER.stroke_width(1),
        ))?;
        root.draw(&Text::new(label, (x + cw / 2, y + ch / 2), centred.clone()))?;
    }
    root.draw(&Text::new(
        match grid.phase {
            Phase::Skip => "entry speed [m/s]",
            Phase::Glide => "entry altitude [km]",
        },
        (ml + pw / 2, h - 18),
        centred.clone(),
    ))?;
    root.draw(&Text::new(
        "vertical lift coefficient C_L cos(sigma) [-]",
        (18, mt + ph / 2),
        centred.clone().transform(FontTransform::Rotate270),
    ))?;
    // Legend.
    let lx = ml + pw + 20;
    let swatch = |y: i32, fill: RGBColor, text: String| -> Result<(), PlotError> {
        root.draw(&Rectangle::new([(lx, y), (lx + 16, y + 16)], fill.filled()))?;
        root.draw(&Rectangle::new(
            [(lx, y), (lx + 16, y + 16)],
            BORDER.stroke_width(1),
        ))?;
        root.draw(&Text::new(text, (lx + 22, y + 8), left.clone()))?;
        Ok(())
    };
    let steps = 5;
    for i in 0..=steps {
        let f = f64::from(i) / f64::from(steps);
        swatch(
            mt + 18 * i,
            shade(f),
            format!("|err| {:.3} {unit}", f * scale),
        )?;
    }
    let ly = mt + 18 * (steps + 1) + 8;
    swatch(ly, GREY, "out of domain".into())?;
    swatch(ly + 22, PALE_YELLOW, "numerical n/a".into())?;
    root.present()?;
    Ok(())
}
