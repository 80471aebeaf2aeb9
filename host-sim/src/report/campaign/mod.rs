//! The campaign report: per guidance mode four figures a GNC engineer reads at a glance, each
//! as SVG and PNG ([`mode_figures`]; docs/guides/run-a-campaign.md):
//!
//! * [`footprint`]: crossrange against downrange error at the terminal interface, the target,
//!   the 1-, 2- and 3-sigma ellipses of the sample covariance ([`ellipse`]) and the worst
//!   cases labelled with their case id ([`worst`]);
//! * [`miss_cdf`]: the empirical CDF of the miss with p50, p90, p99 and p99.9 marked
//!   ([`cdf`]);
//! * [`limits`]: histograms of peak / limit of heat flux, g-load and g-load rate
//!   ([`histogram`]) with the limit at 1;
//! * [`time_to_go`]: downrange and crossrange error against time to go of the worst flights.
//!
//! The figures take plain data ([`ModeReport`]) and are drawn with the general chart helper
//! [`super::chart`]; `campaign::report` fills it from a campaign (replaying the worst flights
//! with their trajectories).

pub mod cdf;
pub mod ellipse;
pub mod footprint;
pub mod histogram;
pub mod limits;
pub mod miss_cdf;
pub mod time_to_go;
pub mod worst;

use super::ReportError;

/// One flight of a mode, at the terminal interface.
#[derive(Clone, Debug, PartialEq)]
pub struct Flight {
    /// Case id (index in the campaign).
    pub id: u32,
    /// Miss distance \[km\].
    pub miss_km: f64,
    /// Downrange error (positive: long) \[km\].
    pub downrange_km: f64,
    /// Crossrange error (positive: right) \[km\].
    pub crossrange_km: f64,
    /// Peak / limit of heat flux, g-load and g-load rate \[-\].
    pub limit_ratios: [f64; 3],
}

/// One point of a flight's error history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracePoint {
    /// Time to go to the flight's end \[s\].
    pub time_to_go_s: f64,
    /// Downrange error \[km\].
    pub downrange_km: f64,
    /// Crossrange error \[km\].
    pub crossrange_km: f64,
}

/// The error history of one (worst) flight.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorTrace {
    /// Case id.
    pub id: u32,
    /// Its miss distance \[km\].
    pub miss_km: f64,
    /// Points, in time order.
    pub points: Vec<TracePoint>,
}

/// What the figures of one mode show.
#[derive(Clone, Debug, PartialEq)]
pub struct ModeReport {
    /// Scenario name (titles).
    pub scenario: String,
    /// Mode name (titles and file names).
    pub mode: String,
    /// The mode's flights (failed ones are not flights).
    pub flights: Vec<Flight>,
    /// Flights that failed (named in the titles).
    pub failed: usize,
    /// The undispersed flight's (downrange, crossrange) error \[km\].
    pub nominal_km: Option<(f64, f64)>,
    /// Error histories of the worst flights, worst first.
    pub traces: Vec<ErrorTrace>,
    /// How the downrange and the crossrange error histories are referenced (notes in the
    /// panels' titles).
    pub trace_reference: [String; 2],
}

/// Worst cases labelled on the footprint.
pub const LABELLED_WORST: usize = 5;

/// Worst flights whose error history is drawn.
pub const TRACED_WORST: usize = 10;

/// File stems of a mode's figures: `footprint-<mode>`, `miss-cdf-<mode>`,
/// `limit-ratios-<mode>`, `errors-time-to-go-<mode>`.
#[must_use]
pub fn figure_stems(mode: &str) -> [String; 4] {
    [
        format!("footprint-{mode}"),
        format!("miss-cdf-{mode}"),
        format!("limit-ratios-{mode}"),
        format!("errors-time-to-go-{mode}"),
    ]
}

/// The four figures of a mode, each as `(file name, bytes)` in SVG and PNG.
///
/// # Errors
/// [`ReportError::Plot`] naming the file if a figure cannot be drawn.
pub fn mode_figures(r: &ModeReport) -> Result<Vec<(String, Vec<u8>)>, ReportError> {
    let [fp, cdf, lim, ttg] = figure_stems(&r.mode);
    let mut out = Vec::with_capacity(8);
    out.extend(footprint::figure(r).files(&fp)?);
    out.extend(miss_cdf::figure(r).files(&cdf)?);
    out.extend(limits::figure(r).files(&lim)?);
    out.extend(time_to_go::figure(r).files(&ttg)?);
    Ok(out)
}

/// "N flights" with the failed ones, for titles.
fn flights_note(r: &ModeReport) -> String {
    if r.failed > 0 {
        format!("{} flights, {} failed", r.flights.len(), r.failed)
    } else {
        format!("{} flights", r.flights.len())
    }
}

#[cfg(test)]
mod tests;
