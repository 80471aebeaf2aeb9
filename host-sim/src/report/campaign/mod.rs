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
mod types;
pub mod worst;

use super::ReportError;

pub use types::{ErrorTrace, Flight, LABELLED_WORST, ModeReport, TRACED_WORST, TracePoint};

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

#[cfg(test)]
mod tests;
