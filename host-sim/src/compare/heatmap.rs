//! SVG heat maps of a grid's errors.

use std::fmt::Write as _;

use super::{AnalyticOutcome, CompareGrid, Preset};
use crate::analytic::Phase;
use crate::report::xml_escape;

/// Fill colour of a cell at fraction `f` in [0, 1] of the map's largest |error|: white to red.
fn shade(f: f64) -> String {
    let gb = (255.0 * (1.0 - 0.85 * f)).round() as u8;
    format!("rgb(255,{gb},{gb})")
}

/// Heat map of the error of metric `m` against `fidelity` over the grid, as a standalone SVG:
/// x = grid x values, y = vertical lift coefficient, colour = |error| (white to red, scaled to
/// the largest |error| of the map), value printed in each cell. Out-of-domain points are grey
/// and marked "out of domain"; failed numerical runs are hatched yellow and marked "n/a".
#[must_use]
pub fn heat_map_svg(grid: &CompareGrid, m: usize, fidelity: Preset) -> String {
    let Some(metric) = grid.metrics.get(m) else {
        return String::new();
    };
    let nx = grid.xs.len().max(1);
    let ny = grid.cl_vertical.len().max(1);
    let (cw, ch) = (96.0, 44.0);
    let (ml, mt, mr, mb) = (90.0, 56.0, 150.0, 60.0);
    let pw = cw * nx as f64;
    let ph = ch * ny as f64;
    let (w, h) = (ml + pw + mr, mt + ph + mb);
    let scale = grid.max_abs_error(m, fidelity).unwrap_or(0.0).max(1e-12);
    let unit = if metric.relative {
        "%"
    } else {
        metric.error_unit
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        s,
        r##"<defs><pattern id="hatch" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="#fff3b0"/><line x1="0" y1="0" x2="0" y2="6" stroke="#c8a800" stroke-width="2"/></pattern></defs>"##
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
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
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="22" text-anchor="middle" font-size="13">{}</text>"#,
        w / 2.0,
        xml_escape(&title)
    );
    for (iy, clv) in grid.cl_vertical.iter().enumerate() {
        // Highest C_L at the top.
        let y = mt + ph - ch * (iy as f64 + 1.0);
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{clv}</text>"#,
            ml - 6.0,
            y + ch / 2.0 + 4.0
        );
    }
    for (ix, x) in grid.xs.iter().enumerate() {
        let xp = ml + cw * ix as f64;
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            xp + cw / 2.0,
            mt + ph + 16.0,
            grid.x_value(*x)
        );
    }
    for (k, p) in grid.points.iter().enumerate() {
        let (ix, iy) = (k / ny, k % ny);
        let x = ml + cw * ix as f64;
        let y = mt + ph - ch * (iy as f64 + 1.0);
        let (fill, label) = match (&p.analytic, grid.error(p, m, fidelity)) {
            (AnalyticOutcome::OutOfDomain(_), _) | (AnalyticOutcome::Failed(_), _) => {
                ("#bdbdbd".to_string(), "out of domain".to_string())
            }
            (_, Some(e)) => {
                let f = (e.abs() / scale).clamp(0.0, 1.0);
                (shade(f), format!("{e:+.2}"))
            }
            (_, None) => ("url(#hatch)".to_string(), "n/a".to_string()),
        };
        let _ = writeln!(
            s,
            r##"<rect x="{x:.1}" y="{y:.1}" width="{cw}" height="{ch}" fill="{fill}" stroke="#555"/><text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            x + cw / 2.0,
            y + ch / 2.0 + 4.0,
            xml_escape(&label)
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        ml + pw / 2.0,
        h - 18.0,
        match grid.phase {
            Phase::Skip => "entry speed [m/s]",
            Phase::Glide => "entry altitude [km]",
        }
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{:.1}" text-anchor="middle" transform="rotate(-90 18 {:.1})">vertical lift coefficient C_L cos(sigma) [-]</text>"#,
        mt + ph / 2.0,
        mt + ph / 2.0
    );
    // Legend.
    let lx = ml + pw + 20.0;
    let steps = 5;
    for i in 0..=steps {
        let f = f64::from(i) / f64::from(steps);
        let fill = shade(f);
        let ly = mt + 18.0 * f64::from(i);
        let _ = writeln!(
            s,
            r##"<rect x="{lx:.1}" y="{ly:.1}" width="16" height="16" fill="{fill}" stroke="#555"/><text x="{:.1}" y="{:.1}">|err| {:.3} {unit}</text>"##,
            lx + 22.0,
            ly + 12.0,
            f * scale
        );
    }
    let ly = mt + 18.0 * f64::from(steps + 1) + 8.0;
    let _ = writeln!(
        s,
        r##"<rect x="{lx:.1}" y="{ly:.1}" width="16" height="16" fill="#bdbdbd" stroke="#555"/><text x="{:.1}" y="{:.1}">out of domain</text>"##,
        lx + 22.0,
        ly + 12.0
    );
    let _ = writeln!(
        s,
        r##"<rect x="{lx:.1}" y="{:.1}" width="16" height="16" fill="url(#hatch)" stroke="#555"/><text x="{:.1}" y="{:.1}">numerical n/a</text>"##,
        ly + 22.0,
        lx + 22.0,
        ly + 34.0
    );
    s.push_str("</svg>\n");
    s
}
