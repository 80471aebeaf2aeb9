//! Run outputs: trajectory CSV, summary JSON and SVG plots, all written atomically
//! (temporary file in the target directory, then rename).
//!
//! Plots are hand-written minimal SVG (polylines, axes with "nice" ticks, labels, legend,
//! dashed limit lines). This keeps the dependency tree small and the output byte-for-byte
//! deterministic; `plotters` would add a font/rasteriser stack for no gain in four line
//! charts.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::sim::{Peak, Sample, SampleKind, SimResult, TerminationReason};

/// Output failures (always naming the path).
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file or directory could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// JSON serialisation failed.
    #[error("cannot serialise summary: {0}")]
    Json(#[from] serde_json::Error),
}

/// Write `contents` to `path` atomically: a temporary file next to it, flushed and synced,
/// then renamed over `path`.
///
/// # Errors
/// [`ReportError::Io`] naming the path.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), ReportError> {
    let io = |source| ReportError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let res = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if res.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    res.map_err(io)
}

/// Trajectory CSV with labelled units, one row per sample.
#[must_use]
pub fn trajectory_csv(samples: &[Sample]) -> String {
    let mut s = String::from(
        "time_s,altitude_km,longitude_deg,latitude_deg,speed_m_s,gamma_deg,heading_deg,mach,\
         density_kg_m3,dynamic_pressure_pa,alpha_deg,sigma_deg,cl,cd,lift_n,drag_n,\
         heat_flux_kw_m2,heat_load_mj_m2,g_load,normalized_energy,flown_range_deg,event\n",
    );
    for p in samples {
        let c = &p.conditions;
        let st = &p.state;
        let ev = match p.kind {
            SampleKind::Start => "start",
            SampleKind::Output => "",
            SampleKind::Exit => "exit",
            SampleKind::Entry => "entry",
            SampleKind::End => "end",
        };
        let _ = writeln!(
            s,
            "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6e},{:.6},{:.6},{:.6},{:.6},{:.6},{:.3},{:.3},{:.6},{:.6},{:.6},{:.8},{:.6},{}",
            p.time_s,
            c.altitude_m / 1e3,
            st.longitude_rad.to_degrees(),
            st.latitude_rad.to_degrees(),
            st.speed_m_s,
            st.flight_path_angle_rad.to_degrees(),
            st.heading_rad.to_degrees(),
            c.mach,
            c.density_kg_m3,
            c.dynamic_pressure_pa,
            p.attitude.alpha_rad.to_degrees(),
            p.attitude.sigma_rad.to_degrees(),
            c.cl,
            c.cd,
            c.lift_n,
            c.drag_n,
            c.heat_flux_w_m2 / 1e3,
            p.heat_load_j_m2 / 1e6,
            c.g_load,
            p.normalized_energy,
            p.flown_range_rad.to_degrees(),
            ev
        );
    }
    s
}

/// A peak with its time, in report units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PeakOut {
    /// Value (unit in the field name of the owner).
    pub value: f64,
    /// Time of the peak [s].
    pub time_s: f64,
}

impl PeakOut {
    fn scaled(p: Peak, k: f64) -> Self {
        Self {
            value: p.value * k,
            time_s: p.time_s,
        }
    }
}

/// Constraint violations (eq. 4.9-4.11) as written to summary.json: `guidance-core`'s
/// [`Violations`](guidance_core::monitor::Violations), field for field.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ViolationsOut {
    /// Heat flux p_q.
    pub heat_flux: f64,
    /// g-load p_g.
    pub g_load: f64,
    /// g-load rate p_gdot.
    pub g_load_rate: f64,
}

impl From<guidance_core::monitor::Violations<f64>> for ViolationsOut {
    fn from(v: guidance_core::monitor::Violations<f64>) -> Self {
        Self {
            heat_flux: v.heat_flux,
            g_load: v.g_load,
            g_load_rate: v.g_load_rate,
        }
    }
}

/// Final state in report units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FinalState {
    /// Altitude [km].
    pub altitude_km: f64,
    /// Longitude [deg].
    pub longitude_deg: f64,
    /// Latitude [deg].
    pub latitude_deg: f64,
    /// Planet-relative speed [m/s].
    pub speed_m_s: f64,
    /// Flight-path angle [deg].
    pub gamma_deg: f64,
    /// Heading [deg].
    pub heading_deg: f64,
    /// Mach number [-].
    pub mach: f64,
    /// Normalised energy [-].
    pub normalized_energy: f64,
}

/// The summary JSON document.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummaryReport {
    /// Scenario name.
    pub scenario: String,
    /// Vehicle name.
    pub vehicle: String,
    /// Environment description (atmosphere, gravity, rotating or not).
    pub environment: String,
    /// Why the run stopped.
    pub termination: TerminationReason,
    /// Flight time [s].
    pub flight_time_s: f64,
    /// Great-circle range angle entry -> end [deg].
    pub range_angle_deg: f64,
    /// Great-circle range over the sphere [km].
    pub range_km: f64,
    /// Integral of V cos(gamma)/r (eq. 3.15) [deg].
    pub flown_range_angle_deg: f64,
    /// Heat load [MJ/m^2].
    pub heat_load_mj_m2: f64,
    /// Peak heat flux [kW/m^2].
    pub peak_heat_flux_kw_m2: PeakOut,
    /// Peak g-load [-].
    pub peak_g_load: PeakOut,
    /// Peak g-load rate [1/s].
    pub peak_g_load_rate_per_s: PeakOut,
    /// Atmosphere exits above the interface.
    pub exits: u32,
    /// Skips (exit followed by re-entry).
    pub skips: u32,
    /// Interface crossing times [s] and kinds.
    pub interface_crossings: Vec<(f64, SampleKind)>,
    /// Constraint violations, eq. 4.9-4.11.
    pub violations: ViolationsOut,
    /// Final state.
    pub final_state: FinalState,
    /// RHS evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted_steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Guidance ticks.
    pub guidance_ticks: u64,
}

/// Build the summary document.
#[must_use]
pub fn summary_report(
    res: &SimResult,
    scenario: &str,
    vehicle: &str,
    environment: &str,
    planet_radius_m: f64,
) -> SummaryReport {
    let s = &res.summary;
    let last = res.samples.last();
    let final_state = last.map_or(
        FinalState {
            altitude_km: f64::NAN,
            longitude_deg: f64::NAN,
            latitude_deg: f64::NAN,
            speed_m_s: f64::NAN,
            gamma_deg: f64::NAN,
            heading_deg: f64::NAN,
            mach: f64::NAN,
            normalized_energy: f64::NAN,
        },
        |p| FinalState {
            altitude_km: p.conditions.altitude_m / 1e3,
            longitude_deg: p.state.longitude_rad.to_degrees(),
            latitude_deg: p.state.latitude_rad.to_degrees(),
            speed_m_s: p.state.speed_m_s,
            gamma_deg: p.state.flight_path_angle_rad.to_degrees(),
            heading_deg: p.state.heading_rad.to_degrees(),
            mach: p.conditions.mach,
            normalized_energy: p.normalized_energy,
        },
    );
    SummaryReport {
        scenario: scenario.into(),
        vehicle: vehicle.into(),
        environment: environment.into(),
        termination: s.termination,
        flight_time_s: s.flight_time_s,
        range_angle_deg: s.range_angle_rad.to_degrees(),
        range_km: s.range_angle_rad * planet_radius_m / 1e3,
        flown_range_angle_deg: s.flown_range_angle_rad.to_degrees(),
        heat_load_mj_m2: s.heat_load_j_m2 / 1e6,
        peak_heat_flux_kw_m2: PeakOut::scaled(s.peak_heat_flux_w_m2, 1e-3),
        peak_g_load: PeakOut::scaled(s.peak_g_load, 1.0),
        peak_g_load_rate_per_s: PeakOut::scaled(s.peak_g_load_rate_per_s, 1.0),
        exits: s.exits,
        skips: s.skips,
        interface_crossings: s.interface_crossings_s.clone(),
        violations: s.violations.into(),
        final_state,
        rhs_evals: s.rhs_evals,
        accepted_steps: s.accepted_steps,
        rejected_steps: s.rejected_steps,
        guidance_ticks: s.ticks,
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

const COLOURS: [&str; 4] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];

/// "Nice" tick step for a span of `span` with about `n` ticks.
fn nice_step(span: f64, n: f64) -> f64 {
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

fn fmt_tick(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 {
        0
    } else {
        (-step.log10().floor()) as usize
    };
    format!("{v:.decimals$}")
}

/// Escape text for SVG/XML content.
pub(crate) fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A line chart as a standalone SVG document.
#[must_use]
pub fn line_plot_svg(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    let (w, h) = (720.0, 460.0);
    let (ml, mr, mt, mb) = (80.0, 30.0, 40.0, 60.0);
    let pts = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 <= 0.0 {
        x1 = x0 + 1.0;
    }
    if y1 - y0 <= 0.0 {
        y1 = y0 + 1.0;
    }
    let (xs, ys) = (nice_step(x1 - x0, 8.0), nice_step(y1 - y0, 6.0));
    let (x0, x1) = ((x0 / xs).floor() * xs, (x1 / xs).ceil() * xs);
    let (y0, y1) = ((y0 / ys).floor() * ys, (y1 / ys).ceil() * ys);
    let pw = w - ml - mr;
    let ph = h - mt - mb;
    let px = |x: f64| ml + (x - x0) / (x1 - x0) * pw;
    let py = |y: f64| mt + ph - (y - y0) / (y1 - y0) * ph;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
        w / 2.0,
        xml_escape(title)
    );
    // Grid and ticks.
    let mut k = 0;
    let mut xv = x0;
    while xv <= x1 + 1e-9 * xs && k < 100 {
        let xp = px(xv);
        let _ = writeln!(
            s,
            r##"<line x1="{xp:.2}" y1="{mt}" x2="{xp:.2}" y2="{:.2}" stroke="#e0e0e0"/><text x="{xp:.2}" y="{:.2}" text-anchor="middle">{}</text>"##,
            mt + ph,
            mt + ph + 16.0,
            fmt_tick(xv, xs)
        );
        k += 1;
        xv = x0 + xs * f64::from(k);
    }
    let mut k = 0;
    let mut yv = y0;
    while yv <= y1 + 1e-9 * ys && k < 100 {
        let yp = py(yv);
        let _ = writeln!(
            s,
            r##"<line x1="{ml}" y1="{yp:.2}" x2="{:.2}" y2="{yp:.2}" stroke="#e0e0e0"/><text x="{:.2}" y="{:.2}" text-anchor="end">{}</text>"##,
            ml + pw,
            ml - 6.0,
            yp + 4.0,
            fmt_tick(yv, ys)
        );
        k += 1;
        yv = y0 + ys * f64::from(k);
    }
    let _ = writeln!(
        s,
        r#"<rect x="{ml}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="black"/>"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.2}" y="{:.2}" text-anchor="middle">{}</text>"#,
        ml + pw / 2.0,
        h - 16.0,
        xml_escape(x_label)
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{:.2}" text-anchor="middle" transform="rotate(-90 18 {:.2})">{}</text>"#,
        mt + ph / 2.0,
        mt + ph / 2.0,
        xml_escape(y_label)
    );
    for (i, ser) in series.iter().enumerate() {
        let col = COLOURS[i % COLOURS.len()];
        let mut d = String::new();
        for &(x, y) in ser
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
        {
            let _ = write!(d, "{:.2},{:.2} ", px(x), py(y));
        }
        let dash = if ser.dashed {
            r#" stroke-dasharray="6 4""#
        } else {
            ""
        };
        let _ = writeln!(
            s,
            r#"<polyline fill="none" stroke="{col}" stroke-width="1.5"{dash} points="{}"/>"#,
            d.trim_end()
        );
        let ly = mt + 14.0 + 16.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<line x1="{:.2}" y1="{ly:.2}" x2="{:.2}" y2="{ly:.2}" stroke="{col}" stroke-width="2"{dash}/><text x="{:.2}" y="{:.2}">{}</text>"#,
            ml + pw - 150.0,
            ml + pw - 126.0,
            ml + pw - 120.0,
            ly + 4.0,
            xml_escape(&ser.label)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// The four standard plots of a run: `(file name, svg)`.
#[must_use]
pub fn standard_plots(
    res: &SimResult,
    heat_limit_w_m2: f64,
    g_limit: f64,
) -> Vec<(&'static str, String)> {
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
    vec![
        (
            "altitude_velocity.svg",
            line_plot_svg(
                "Altitude against velocity",
                "planet-relative speed [km/s]",
                "altitude [km]",
                &[series("trajectory", &|s| {
                    (s.state.speed_m_s / 1e3, s.conditions.altitude_m / 1e3)
                })],
            ),
        ),
        (
            "heat_flux.svg",
            line_plot_svg(
                "Stagnation heat flux (Chapman)",
                "time [s]",
                "heat flux [kW/m^2]",
                &[
                    series("heat flux", &|s| {
                        (s.time_s, s.conditions.heat_flux_w_m2 / 1e3)
                    }),
                    limit("limit", heat_limit_w_m2 / 1e3),
                ],
            ),
        ),
        (
            "g_load.svg",
            line_plot_svg(
                "Aerodynamic load factor",
                "time [s]",
                "g-load [-]",
                &[
                    series("g-load", &|s| (s.time_s, s.conditions.g_load)),
                    limit("limit", g_limit),
                ],
            ),
        ),
        (
            "attitude.svg",
            line_plot_svg(
                "Angle of attack and bank angle",
                "time [s]",
                "angle [deg]",
                &[
                    series("alpha", &|s| (s.time_s, s.attitude.alpha_rad.to_degrees())),
                    series("sigma", &|s| (s.time_s, s.attitude.sigma_rad.to_degrees())),
                ],
            ),
        ),
    ]
}

/// Write `trajectory.csv`, `summary.json` and the SVG plots into `dir` (created if needed).
/// Returns the paths written.
///
/// # Errors
/// [`ReportError`] naming the path that failed.
pub fn write_run(
    dir: &Path,
    res: &SimResult,
    summary: &SummaryReport,
    heat_limit_w_m2: f64,
    g_limit: f64,
) -> Result<Vec<PathBuf>, ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = vec![];
    let csv = dir.join("trajectory.csv");
    write_atomic(&csv, trajectory_csv(&res.samples).as_bytes())?;
    written.push(csv);
    let json = dir.join("summary.json");
    let mut text = serde_json::to_string_pretty(summary)?;
    text.push('\n');
    write_atomic(&json, text.as_bytes())?;
    written.push(json);
    for (name, svg) in standard_plots(res, heat_limit_w_m2, g_limit) {
        let p = dir.join(name);
        write_atomic(&p, svg.as_bytes())?;
        written.push(p);
    }
    Ok(written)
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
    fn atomic_write_replaces_and_leaves_no_temp() {
        let dir = std::env::temp_dir().join(format!("host-sim-report-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"two");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        // A path in a missing directory is an error naming the path.
        let bad = dir.join("missing").join("b.txt");
        let e = write_atomic(&bad, b"x").unwrap_err().to_string();
        assert!(e.contains("b.txt"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn svg_escapes_and_handles_empty_series() {
        let s = line_plot_svg("a < b & c", "x", "y", &[]);
        assert!(s.contains("a &lt; b &amp; c"));
        assert!(s.starts_with("<svg") && s.ends_with("</svg>\n"));
        let s = line_plot_svg(
            "t",
            "x",
            "y",
            &[Series {
                label: "flat".into(),
                points: vec![(0.0, 1.0), (1.0, 1.0), (f64::NAN, 2.0)],
                dashed: true,
            }],
        );
        assert!(s.contains("stroke-dasharray") && !s.contains("NaN"));
    }
}
