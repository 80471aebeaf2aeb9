//! Line charts through `plotters`: the four standard plots of a run (altitude against
//! velocity, heat flux, g-load, attitude) with titles, axis labels with units, a legend and
//! dashed limit lines, each as SVG and as PNG (the same drawing code on `plotters`' SVG and
//! bitmap backends). Axis ranges are rounded out to "nice" tick steps.
//!
//! Text is laid out and rasterised with `plotters`' `ab_glyph` feature and the DejaVu Sans
//! font embedded by the `dejavu` crate, so neither backend needs a system font library
//! (fontconfig, FreeType); PNGs are encoded with the `png` crate.

use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use super::ReportError;
use crate::sim::{Sample, SimResult};
use crate::vehicle::VehicleLimits;

pub(super) type PlotError = Box<dyn std::error::Error + Send + Sync>;

/// Plot size \[px\] (SVG user units and PNG pixels).
const SIZE: (u32, u32) = (720, 460);

/// Register the embedded font as `plotters`' "sans-serif" once per process (every plot
/// drawing text calls it first: without it plotters has no font at all).
pub(crate) fn ensure_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular()).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err("the embedded DejaVu Sans font could not be loaded".into())
    }
}

/// One polyline series of a plot.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Dashed (for limit lines).
    pub dashed: bool,
}

/// Most ticks on an axis.
const MAX_TICKS: usize = 20;

/// Series of at most this many points are drawn with a marker at every point.
const MAX_MARKED: usize = 200;

/// Series colours (matplotlib's first four).
const COLOURS: [RGBColor; 4] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
];

/// "Nice" tick step for a span of `span` with about `n` ticks.
pub(super) fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(f64::MIN_POSITIVE);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nf = if f < 1.5 {
        1.0
    } else if f < 3.0 {
        2.0
    } else if f < 7.0 {
        5.0
    } else {
        10.0
    };
    nf * mag
}

pub(super) fn fmt_tick(v: f64, step: f64) -> String {
    if step >= 1e9 || (step < 1e-9 && step > 0.0) {
        return format!("{v:e}");
    }
    let decimals = if step >= 1.0 {
        0
    } else {
        (-step.log10().floor()) as usize
    };
    let text = format!("{v:.decimals$}");
    // A tick that rounds to zero prints without a sign.
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// Axis range covering `lo..hi`, rounded out to multiples of a nice step for about `n`
/// ticks; returns `(lo, hi, step)`.
pub(super) fn nice_range(lo: f64, hi: f64, n: f64) -> (f64, f64, f64) {
    let step = nice_step(hi - lo, n);
    ((lo / step).floor() * step, (hi / step).ceil() * step, step)
}

/// Data bounds of the finite points of `series` (unit box if none; widened if flat).
fn bounds(series: &[Series]) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
    {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let (x0, x1) = widen(x0, x1);
    let (y0, y1) = widen(y0, y1);
    (x0, x1, y0, y1)
}

/// A data range made drawable: within +-1e306 (so that spans and steps stay finite) and,
/// if flat, widened by 1 or by a tenth of its magnitude when that is larger (`1e300 + 1` is
/// still `1e300`: a flat range at a huge value would have a zero span and endless ticks).
pub(super) fn widen(lo: f64, hi: f64) -> (f64, f64) {
    const LIMIT: f64 = 1e306;
    let (lo, hi) = (lo.clamp(-LIMIT, LIMIT), hi.clamp(-LIMIT, LIMIT));
    if hi - lo > 0.0 {
        return (lo, hi);
    }
    (lo, lo + (0.1 * lo.abs()).max(1.0))
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    ensure_font()?;
    let (x0, x1, y0, y1) = bounds(series);
    let (x0, x1, xs) = nice_range(x0, x1, 8.0);
    let (y0, y1, ys) = nice_range(y0, y1, 6.0);
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let x_ticks = (((x1 - x0) / xs).round() as usize + 1).min(MAX_TICKS);
    let y_ticks = (((y1 - y0) / ys).round() as usize + 1).min(MAX_TICKS);
    let x_fmt = |v: &f64| fmt_tick(*v, xs);
    let y_fmt = |v: &f64| fmt_tick(*v, ys);
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(x_ticks)
        .y_labels(y_ticks)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .max_light_lines(0)
        .bold_line_style(RGBColor(0xe0, 0xe0, 0xe0))
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()?;
    // A series labelled "-NAME" is the mirror of series NAME (a lower limit): its colour, no
    // legend entry of its own; "NAME limit" takes the colour of series NAME; the other series
    // take the colours in turn.
    let mut legend_index = 0;
    let mut colour_of: Vec<(String, RGBColor)> = Vec::new();
    for ser in series {
        let mirror_of = ser.label.strip_prefix('-');
        let parent = mirror_of.or_else(|| ser.label.strip_suffix(" limit"));
        let colour = match parent.and_then(|m| colour_of.iter().find(|(l, _)| l == m)) {
            Some((_, c)) => *c,
            None => {
                let c = COLOURS[legend_index % COLOURS.len()];
                legend_index += 1;
                c
            }
        };
        colour_of.push((ser.label.clone(), colour));
        let in_legend = mirror_of.is_none();
        let style = ShapeStyle {
            color: colour.to_rgba(),
            filled: false,
            stroke_width: 2,
        };
        let points: Vec<(f64, f64)> = ser
            .points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        let label = ser.label.as_str();
        if let [point] = points.as_slice() {
            // A one-point series is a marker (entry, end, target of a ground track).
            let marker = style.filled();
            let drawn = chart.draw_series(std::iter::once(Circle::new(*point, 5, marker)))?;
            if in_legend {
                drawn
                    .label(label)
                    .legend(move |(x, y)| Circle::new((x + 12, y), 5, marker));
            }
        } else if ser.dashed {
            let drawn = chart.draw_series(DashedLineSeries::new(points, 6, 4, style))?;
            if in_legend {
                drawn.label(label).legend(move |(x, y)| {
                    DashedPathElement::new(vec![(x, y), (x + 24, y)], 6, 4, style)
                });
            }
        } else {
            // A marker at every point of a short series, so a few points (a small front) are
            // visible, not an empty line.
            let dots = if points.len() <= MAX_MARKED {
                points.clone()
            } else {
                Vec::new()
            };
            let drawn = chart.draw_series(LineSeries::new(points, style))?;
            if in_legend {
                drawn
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
            }
            chart.draw_series(dots.into_iter().map(|p| Circle::new(p, 3, style.filled())))?;
        }
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// A line chart as a standalone SVG document (`plotters`' SVG backend).
///
/// # Errors
/// [`ReportError::Plot`] if `plotters` fails to draw.
pub fn line_plot_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<String, ReportError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw(&root, title, x_label, y_label, series).map_err(|source| ReportError::Plot {
            name: title.to_string(),
            source,
        })?;
    }
    Ok(svg)
}

/// The same line chart as a PNG image (8-bit RGB, 720 x 460 pixels).
///
/// # Errors
/// [`ReportError::Plot`] if `plotters` fails to draw or the PNG cannot be encoded.
pub fn line_plot_png(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<Vec<u8>, ReportError> {
    let plot_err = |source: PlotError| ReportError::Plot {
        name: title.to_string(),
        source,
    };
    let (w, h) = SIZE;
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, title, x_label, y_label, series).map_err(plot_err)?;
    }
    encode_png(&rgb, w, h).map_err(plot_err)
}

/// An 8-bit RGB buffer of `w` x `h` pixels as a PNG file.
pub(super) fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, PlotError> {
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_bytes, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header()?;
        writer.write_image_data(rgb)?;
    }
    Ok(png_bytes)
}

/// One chart as its SVG and PNG files: `[(stem.svg, bytes), (stem.png, bytes)]`.
fn svg_and_png(
    stem: &str,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<[(String, Vec<u8>); 2], ReportError> {
    Ok([
        (
            format!("{stem}.svg"),
            line_plot_svg(title, x_label, y_label, series)?.into_bytes(),
        ),
        (
            format!("{stem}.png"),
            line_plot_png(title, x_label, y_label, series)?,
        ),
    ])
}

/// What the standard plots draw besides the trajectory: the limits (dashed) and the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlotLimits {
    /// Heat-flux limit \[W/m^2\].
    pub heat_flux_w_m2: f64,
    /// g-load limit \[-\].
    pub g_load: f64,
    /// g-load-rate limit \[1/s\] (drawn at plus and minus).
    pub g_load_rate_per_s: f64,
    /// Angle-of-attack rate limit \[rad/s\] (the guidance's rate limiter).
    pub alpha_rate_rad_s: f64,
    /// Bank rate limit \[rad/s\].
    pub sigma_rate_rad_s: f64,
    /// Target point (geocentric latitude, longitude) \[rad\], if the run aims at one.
    pub target: Option<(f64, f64)>,
}

impl PlotLimits {
    /// The vehicle's limits, no target.
    #[must_use]
    pub fn of_vehicle(l: &VehicleLimits) -> Self {
        Self {
            heat_flux_w_m2: l.heat_flux_w_m2,
            g_load: l.g_load,
            g_load_rate_per_s: l.g_load_rate_per_s,
            alpha_rate_rad_s: l.alpha_rate_rad_s,
            sigma_rate_rad_s: l.sigma_rate_rad_s,
            target: None,
        }
    }
}

/// Time derivative of `f` between consecutive samples: `(t_mid, df/dt)` \[s, unit/s\].
fn difference_rate(smp: &[Sample], f: &dyn Fn(&Sample) -> f64) -> Vec<(f64, f64)> {
    smp.windows(2)
        .filter_map(|w| match w {
            [a, b] if b.time_s - a.time_s > 1e-9 => Some((
                0.5 * (a.time_s + b.time_s),
                (f(b) - f(a)) / (b.time_s - a.time_s),
            )),
            _ => None,
        })
        .collect()
}

/// Longitude \[deg\] unwrapped along the track (no jump at +-180 deg).
fn unwrapped_longitudes_deg(smp: &[Sample]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(smp.len());
    for s in smp {
        let lon = s.state.longitude_rad.to_degrees();
        let v = match out.last() {
            Some(&prev) => prev + (lon - prev + 180.0).rem_euclid(360.0) - 180.0,
            None => lon,
        };
        out.push(v);
    }
    out
}

/// The standard plots of a run, each as SVG and PNG: `(file name, bytes)`: altitude against
/// speed; heat flux, g-load and g-load rate against time with their limits; the ground track
/// (latitude against longitude, with the entry, the end and the target); the angle of attack
/// and the bank angle; their rates against the guidance's rate limits.
///
/// # Errors
/// [`ReportError::Plot`] if a plot cannot be drawn.
pub fn standard_plots(
    res: &SimResult,
    limits: &PlotLimits,
) -> Result<Vec<(String, Vec<u8>)>, ReportError> {
    let smp = &res.samples;
    let t_end = smp.last().map_or(1.0, |s| s.time_s);
    let series = |label: &str, f: &dyn Fn(&Sample) -> (f64, f64)| Series {
        label: label.into(),
        points: smp.iter().map(f).collect(),
        dashed: false,
    };
    let limit = |label: &str, v: f64| Series {
        label: label.into(),
        points: vec![(0.0, v), (t_end, v)],
        dashed: true,
    };
    let lons = unwrapped_longitudes_deg(smp);
    let track: Vec<(f64, f64)> = lons
        .iter()
        .zip(smp.iter())
        .map(|(&lon, s)| (lon, s.state.latitude_rad.to_degrees()))
        .collect();
    let point = |label: &str, p: Option<&(f64, f64)>| Series {
        label: label.into(),
        points: p.copied().into_iter().collect(),
        dashed: false,
    };
    let mut ground = vec![
        Series {
            label: "track".into(),
            points: track.clone(),
            dashed: false,
        },
        point("entry", track.first()),
        point("end", track.last()),
    ];
    if let Some((lat, lon)) = limits.target {
        // The target's longitude unwrapped next to the track's end (no jump of 360 deg).
        let near = lons.last().copied().unwrap_or(0.0);
        let lon = near + (lon.to_degrees() - near + 180.0).rem_euclid(360.0) - 180.0;
        ground.push(point("target", Some(&(lon, lat.to_degrees()))));
    }
    let deg = f64::to_degrees;
    let g_rate = limits.g_load_rate_per_s;
    let charts = [
        svg_and_png(
            "altitude_velocity",
            "Altitude against velocity",
            "planet-relative speed [km/s]",
            "altitude [km]",
            &[series("trajectory", &|s| {
                (s.state.speed_m_s / 1e3, s.conditions.altitude_m / 1e3)
            })],
        )?,
        svg_and_png(
            "heat_flux",
            "Stagnation heat flux (Chapman)",
            "time [s]",
            "heat flux [kW/m^2]",
            &[
                series("heat flux", &|s| {
                    (s.time_s, s.conditions.heat_flux_w_m2 / 1e3)
                }),
                limit("limit", limits.heat_flux_w_m2 / 1e3),
            ],
        )?,
        svg_and_png(
            "g_load",
            "Aerodynamic load factor",
            "time [s]",
            "g-load [-]",
            &[
                series("g-load", &|s| (s.time_s, s.conditions.g_load)),
                limit("limit", limits.g_load),
            ],
        )?,
        svg_and_png(
            "g_load_rate",
            "g-load rate (between output samples)",
            "time [s]",
            "g-load rate [1/s]",
            &[
                Series {
                    label: "g-load rate".into(),
                    points: difference_rate(smp, &|s| s.conditions.g_load),
                    dashed: false,
                },
                limit("limit", g_rate),
                limit("-limit", -g_rate),
            ],
        )?,
        svg_and_png(
            "ground_track",
            "Ground track",
            "longitude [deg]",
            "geocentric latitude [deg]",
            &ground,
        )?,
        svg_and_png(
            "attitude",
            "Angle of attack and bank angle",
            "time [s]",
            "angle [deg]",
            &[
                series("alpha", &|s| (s.time_s, deg(s.attitude.alpha_rad))),
                series("sigma", &|s| (s.time_s, deg(s.attitude.sigma_rad))),
            ],
        )?,
        svg_and_png(
            "attitude_rate",
            "Attitude rates (between output samples) and the rate limits",
            "time [s]",
            "rate [deg/s]",
            &[
                Series {
                    label: "alpha rate".into(),
                    points: difference_rate(smp, &|s| deg(s.attitude.alpha_rad)),
                    dashed: false,
                },
                Series {
                    label: "sigma rate".into(),
                    points: difference_rate(smp, &|s| deg(s.attitude.sigma_rad)),
                    dashed: false,
                },
                limit("alpha rate limit", deg(limits.alpha_rate_rad_s)),
                limit("-alpha rate limit", -deg(limits.alpha_rate_rad_s)),
                limit("sigma rate limit", deg(limits.sigma_rate_rad_s)),
                limit("-sigma rate limit", -deg(limits.sigma_rate_rad_s)),
            ],
        )?,
    ];
    Ok(charts.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(1400.0, 8.0), 200.0);
        assert_eq!(nice_step(1.0, 5.0), 0.2);
        assert_eq!(nice_step(75.0, 6.0), 10.0);
        assert_eq!(fmt_tick(0.2, 0.2), "0.2");
        assert_eq!(fmt_tick(1200.0, 200.0), "1200");
    }

    #[test]
    fn svg_escapes_and_handles_empty_series() {
        let s = line_plot_svg("a < b & c", "x", "y", &[]).unwrap();
        assert!(s.contains("a &lt; b &amp; c"));
        assert!(s.contains("<svg") && s.trim_end().ends_with("</svg>"));
        let s = line_plot_svg(
            "t",
            "x",
            "y",
            &[Series {
                label: "flat".into(),
                points: vec![(0.0, 1.0), (1.0, 1.0), (f64::NAN, 2.0)],
                dashed: true,
            }],
        )
        .unwrap();
        assert!(!s.contains("NaN") && s.contains("flat"), "{s}");
    }

    /// Huge or flat-at-huge values draw in bounded time (a flat range at 1e300 once had a
    /// zero span, a tick step of 1e-308 and no end of ticks).
    #[test]
    fn huge_values_plot() {
        for pts in [
            vec![(0.0, 1e300)],
            vec![(0.0, -1.7e308), (1.0, 1.7e308)],
            vec![(f64::MAX, 1.0), (-f64::MAX, 2.0)],
            vec![(0.0, 0.4), (1.0, 1e300)],
        ] {
            let s = line_plot_svg(
                "t",
                "x",
                "y",
                &[Series {
                    label: "a".into(),
                    points: pts,
                    dashed: false,
                }],
            )
            .unwrap();
            assert!(s.len() < 100_000, "{}", s.len());
        }
    }

    /// A series of one point (a 1-member front) is drawn as a marker, not an empty line;
    /// long series (trajectories) have none.
    #[test]
    fn short_series_have_markers() {
        let one = |n: usize| {
            line_plot_svg(
                "front",
                "x",
                "y",
                &[Series {
                    label: "generation 0".into(),
                    points: (0..n).map(|i| (i as f64, 1.0 / (1.0 + i as f64))).collect(),
                    dashed: false,
                }],
            )
            .unwrap()
        };
        // One point: its marker and the marker of its legend entry.
        assert_eq!(one(1).matches("<circle").count(), 2);
        assert_eq!(one(5).matches("<circle").count(), 5);
        assert_eq!(one(MAX_MARKED + 1).matches("<circle").count(), 0);
    }

    #[test]
    fn plot_keeps_title_labels_units_legend_and_limit_line() {
        let s = line_plot_svg(
            "Stagnation heat flux (Chapman)",
            "time [s]",
            "heat flux [kW/m^2]",
            &[
                Series {
                    label: "heat flux".into(),
                    points: vec![(0.0, 10.0), (100.0, 480.0), (200.0, 20.0)],
                    dashed: false,
                },
                Series {
                    label: "limit".into(),
                    points: vec![(0.0, 500.0), (200.0, 500.0)],
                    dashed: true,
                },
            ],
        )
        .unwrap();
        for needle in [
            "Stagnation heat flux (Chapman)",
            "time [s]",
            "heat flux [kW/m^2]",
            ">\nlimit\n<",
            "<polyline",
            "#1F77B4",
            "#D62728",
        ] {
            assert!(s.contains(needle), "`{needle}` missing");
        }
        // Nice axis range: 0..200 s in steps of 20 s, 0..500 kW/m^2 in steps of 100.
        assert!(s.contains(">\n200\n<") && s.contains(">\n500\n<"));
    }

    /// The run's plots: the limits drawn (both signs of the rates), the ground track with its
    /// entry, end and target markers.
    #[test]
    fn standard_plots_draw_limits_and_the_ground_track() {
        let sc = crate::scenario::Scenario::srm_glide();
        let flight = crate::scenario::fly(&sc, "srm", &mut |_| {}).unwrap();
        let mut limits = PlotLimits::of_vehicle(&flight.vehicle.limits);
        limits.target = Some((0.01, 1.0));
        let files = standard_plots(&flight.result, &limits).unwrap();
        let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
        for stem in [
            "altitude_velocity",
            "heat_flux",
            "g_load",
            "g_load_rate",
            "ground_track",
            "attitude",
            "attitude_rate",
        ] {
            assert!(names.contains(&format!("{stem}.svg").as_str()), "{names:?}");
            assert!(names.contains(&format!("{stem}.png").as_str()), "{names:?}");
        }
        let svg = |stem: &str| {
            let (_, bytes) = files
                .iter()
                .find(|(n, _)| n == &format!("{stem}.svg"))
                .unwrap();
            String::from_utf8(bytes.clone()).unwrap()
        };
        for stem in ["heat_flux", "g_load", "g_load_rate"] {
            assert!(svg(stem).contains(">\nlimit\n<"), "{stem} has its limit");
        }
        let track = svg("ground_track");
        for label in ["track", "entry", "end", "target"] {
            assert!(
                track.contains(&format!(">\n{label}\n<")),
                "ground track: {label}"
            );
        }
        let rates = svg("attitude_rate");
        assert!(
            rates.contains(">\nalpha rate limit\n<") && rates.contains(">\nsigma rate limit\n<")
        );
        assert!(
            !rates.contains("-sigma rate limit"),
            "mirrored limits have no legend entry"
        );
        // The rates between samples respect the guidance's rate limiter.
        let rate = difference_rate(&flight.result.samples, &|s| s.attitude.sigma_rad);
        assert!(
            rate.iter()
                .all(|(_, r)| r.abs() <= sc.guidance.sigma_rate_rad_s * (1.0 + 1e-9))
        );
    }
}
