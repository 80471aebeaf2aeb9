//! The campaign report: [`crate::report::campaign`]'s figures of each mode filled from a
//! campaign, the worst flights replayed with their trajectories ([`replay_case_traced`]) for
//! their error against time to go.
//!
//! The error history of a flight, from its position along and across the great circle from the
//! nominal entry to the target (as at the terminal interface): the downrange error is its
//! along-track position less the undispersed flight's (same mode) at the same time to go, plus
//! the undispersed flight's own terminal downrange error (the error to the undispersed path
//! moved to end on the target; where the flight has more time to go than the undispersed
//! flight lasted it is not drawn); the crossrange error is its distance off that great circle.
//! At time to go 0 both are the flight's footprint point.

use guidance_core::geo::along_cross_track;
use rayon::prelude::*;

use super::run::{CampaignOutput, replay_case_traced};
use super::settings::DispersionSettings;
use super::setup::CampaignSetup;
use super::{CampaignError, CaseResult, Mode};
use crate::report::campaign::worst::worst_flights;
use crate::report::campaign::{
    ErrorTrace, Flight, ModeReport, TRACED_WORST, TracePoint, mode_figures,
};
use crate::sim::SimResult;

/// How the downrange and crossrange error histories are referenced (in the figure's titles).
pub const TRACE_REFERENCE: [&str; 2] = [
    "to the undispersed path at equal time to go",
    "off the great circle from the entry to the target",
];

/// A flight's (time to go, downrange, crossrange) positions \[s, m, m\] along and across the
/// great circle from the nominal entry to the target.
fn track(setup: &CampaignSetup, sim: &SimResult) -> Vec<(f64, f64, f64)> {
    let e = &setup.scenario.entry;
    let t = setup.target();
    let r = setup.planet_radius_m;
    let end = sim.samples.last().map_or(0.0, |s| s.time_s);
    sim.samples
        .iter()
        .filter_map(|s| {
            let (at, xt) = along_cross_track(
                (e.latitude_rad, e.longitude_rad),
                (t.latitude_rad, t.longitude_rad),
                (s.state.latitude_rad, s.state.longitude_rad),
            )?;
            Some((end - s.time_s, at * r, xt * r))
        })
        .collect()
}

/// Linear interpolation of the along-track position of `track` (time to go decreasing) at
/// time to go `tg`; `None` outside it.
fn at_time_to_go(track: &[(f64, f64, f64)], tg: f64) -> Option<f64> {
    // First point with time to go <= tg (the track runs from the longest time to go to 0).
    let k = track.partition_point(|p| p.0 > tg);
    let b = track.get(k)?;
    if k == 0 {
        return (b.0 == tg).then_some(b.1);
    }
    let a = track.get(k - 1)?;
    let w = a.0 - b.0;
    if w <= 0.0 {
        return Some(b.1);
    }
    let f = (a.0 - tg) / w;
    Some(a.1 + f * (b.1 - a.1))
}

/// The error history of `case` (flown as `sim`) against the undispersed flight `nominal`
/// (flown as `nominal_sim`) \[km\].
#[must_use]
pub fn error_trace(
    setup: &CampaignSetup,
    case: &CaseResult,
    sim: &SimResult,
    nominal: &CaseResult,
    nominal_sim: &SimResult,
) -> ErrorTrace {
    let reference = track(setup, nominal_sim);
    let offset = nominal.downrange_error_m;
    let points = track(setup, sim)
        .into_iter()
        .filter_map(|(tg, at, xt)| {
            let ra = at_time_to_go(&reference, tg)?;
            Some(TracePoint {
                time_to_go_s: tg,
                downrange_km: (at - ra + offset) / 1e3,
                crossrange_km: xt / 1e3,
            })
        })
        .collect();
    ErrorTrace {
        id: case.index,
        miss_km: case.miss_m / 1e3,
        points,
    }
}

fn flight(c: &CaseResult) -> Flight {
    Flight {
        id: c.index,
        miss_km: c.miss_m / 1e3,
        downrange_km: c.downrange_error_m / 1e3,
        crossrange_km: c.crossrange_error_m / 1e3,
        limit_ratios: c.limit_ratios,
    }
}

/// The report data of `mode` in `out`: its flights, its undispersed flight and the error
/// histories of its [`TRACED_WORST`] worst flights (replayed on rayon's threads).
///
/// # Errors
/// [`CampaignError`] if a replayed flight fails.
pub fn mode_report(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    out: &CampaignOutput,
    mode: Mode,
) -> Result<ModeReport, CampaignError> {
    let cases: &[CaseResult] = out
        .cases
        .iter()
        .find(|(m, _)| *m == mode)
        .map_or(&[], |(_, v)| v.as_slice());
    let flights: Vec<Flight> = cases.iter().map(flight).collect();
    let worst: Vec<u32> = worst_flights(&flights, TRACED_WORST)
        .into_iter()
        .filter_map(|i| flights.get(i).map(|f| f.id))
        .collect();
    let nominal = out.nominal.iter().find(|n| n.mode == mode);
    let traces = if worst.is_empty() {
        Vec::new()
    } else {
        let (nom, nom_sim) = replay_case_traced(setup, settings, mode, None)?;
        let flown: Vec<(CaseResult, SimResult)> = worst
            .par_iter()
            .map(|&i| replay_case_traced(setup, settings, mode, Some(i)))
            .collect::<Result<_, _>>()?;
        flown
            .iter()
            .map(|(c, sim)| error_trace(setup, c, sim, &nom, &nom_sim))
            .collect()
    };
    Ok(ModeReport {
        scenario: setup.scenario.name.clone(),
        mode: mode.name().to_string(),
        flights,
        failed: out.failed.iter().filter(|f| f.mode == mode).count(),
        nominal_km: nominal.map(|n| (n.downrange_error_m / 1e3, n.crossrange_error_m / 1e3)),
        traces,
        trace_reference: TRACE_REFERENCE.map(String::from),
    })
}

/// The report's figures of every mode of `out`: `(file name, bytes)`, SVG and PNG
/// ([`crate::report::campaign::figure_stems`]).
///
/// # Errors
/// [`CampaignError`] if a replayed flight fails or a figure cannot be drawn.
pub fn report_files(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    out: &CampaignOutput,
) -> Result<Vec<(String, Vec<u8>)>, CampaignError> {
    let mut files = Vec::new();
    for (mode, _) in &out.cases {
        let r = mode_report(setup, settings, out, *mode)?;
        files.extend(mode_figures(&r)?);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_at_time_to_go() {
        let t = [
            (10.0, 0.0, 0.0),
            (6.0, 4.0, -4.0),
            (6.0, 5.0, 1.0),
            (0.0, 11.0, 7.0),
        ];
        assert_eq!(at_time_to_go(&t, 10.0), Some(0.0));
        assert_eq!(at_time_to_go(&t, 8.0), Some(2.0));
        assert_eq!(at_time_to_go(&t, 3.0), Some(8.0));
        assert_eq!(at_time_to_go(&t, 0.0), Some(11.0));
        assert_eq!(at_time_to_go(&t, 11.0), None);
        assert_eq!(at_time_to_go(&t, -1.0), None);
    }
}
