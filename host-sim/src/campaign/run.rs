//! The campaign: every case in every requested mode, in parallel on rayon threads, each case
//! a pure function of (setup, settings, index, mode) so the results are bit-identical whatever
//! the thread count; resumable: each case's result is written atomically to
//! `<out>/cases/<mode>/<index>.json` as soon as it is done and reused by a later run with the
//! same inputs: the run directory holds the fingerprint of the campaign's resolved inputs
//! ([`super::fingerprint`]), and a run whose inputs differ is refused before it writes anything
//! (but the number of cases and the modes, which a run may extend).

use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::draw::{CaseDraw, draw_case};
use super::fingerprint::{Fingerprint, check_and_record};
use super::flight::{CaseResult, fly_case, fly_case_traced};
use super::settings::DispersionSettings;
use super::setup::CampaignSetup;
use super::stats::ModeStats;
use super::{CampaignError, Mode};
use crate::report::write_atomic;

/// Options of a run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Modes to fly, in report order.
    pub modes: Vec<Mode>,
    /// Output directory (fingerprint of the inputs, case results, summary, plots); `None`:
    /// nothing written, no resume.
    pub out_dir: Option<PathBuf>,
    /// Rayon threads (`None`: rayon's default).
    pub threads: Option<usize>,
    /// Show a progress bar.
    pub progress: bool,
}

/// A case whose flight failed: recorded, and the campaign goes on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseFailure {
    /// Guidance mode.
    pub mode: Mode,
    /// Case index.
    pub index: u32,
    /// The dispersed values.
    pub draw: CaseDraw,
    /// The error, as displayed (with its sources).
    pub error: String,
}

impl CaseFailure {
    /// The record of case `index` of `mode` (drawn as `draw`) whose flight failed with `e`
    /// (its message and sources, one line).
    #[must_use]
    pub fn new(mode: Mode, index: u32, draw: CaseDraw, e: &dyn std::error::Error) -> Self {
        Self {
            mode,
            index,
            draw,
            error: error_chain(e),
        }
    }
}

/// The error and its sources, one line.
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut src = e.source();
    while let Some(x) = src {
        // Messages that already show their source are not repeated.
        let t = x.to_string();
        if !s.contains(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
        src = x.source();
    }
    s
}

/// What a campaign gives.
#[derive(Clone, Debug, Serialize)]
pub struct CampaignOutput {
    /// The nominal (undispersed) flight of each mode.
    pub nominal: Vec<CaseResult>,
    /// Every case of each mode, by index.
    pub cases: Vec<(Mode, Vec<CaseResult>)>,
    /// Statistics of each mode.
    pub stats: Vec<ModeStats>,
    /// Cases whose flight failed, by mode then index (not in `cases` nor in the statistics).
    pub failed: Vec<CaseFailure>,
    /// Cases reused from an earlier run.
    pub resumed: usize,
}

impl CampaignOutput {
    /// The output of the nominal flights, the flown cases of each mode, the failed ones and
    /// the count of reused ones, with the statistics of each mode.
    #[must_use]
    pub fn new(
        nominal: Vec<CaseResult>,
        cases: Vec<(Mode, Vec<CaseResult>)>,
        failed: Vec<CaseFailure>,
        resumed: usize,
    ) -> Self {
        let stats = cases
            .iter()
            .map(|(m, v)| ModeStats::of(*m, v, failed.iter().filter(|f| f.mode == *m).count()))
            .collect();
        Self {
            nominal,
            cases,
            stats,
            failed,
            resumed,
        }
    }
}

/// A stored case's values before they are reused: finite, and within what a flight on a
/// planet can give (distances below 1e8 m, peaks and ratios >= 0).
fn check_stored(c: &CaseResult, path: &Path) -> Result<(), CampaignError> {
    let bad = |field: &str, v: f64, reason: &str| CampaignError::CaseValue {
        path: path.to_path_buf(),
        field: field.to_string(),
        value: crate::num_fmt::compact(v),
        reason: reason.to_string(),
    };
    let distance = [
        ("miss_m", c.miss_m, 0.0),
        ("downrange_error_m", c.downrange_error_m, -1e8),
        ("crossrange_error_m", c.crossrange_error_m, -1e8),
    ];
    for (name, v, lo) in distance {
        if !(v.is_finite() && v >= lo && v <= 1e8) {
            return Err(bad(
                name,
                v,
                "must be a finite distance within [-1e8, 1e8] m (miss >= 0)",
            ));
        }
    }
    let positive = [
        ("peak_heat_flux_w_m2", c.peak_heat_flux_w_m2),
        ("peak_g_load", c.peak_g_load),
        ("peak_g_load_rate_per_s", c.peak_g_load_rate_per_s),
        ("limit_ratios[0]", c.limit_ratios[0]),
        ("limit_ratios[1]", c.limit_ratios[1]),
        ("limit_ratios[2]", c.limit_ratios[2]),
        ("flight_time_s", c.flight_time_s),
    ];
    for (name, v) in positive {
        if !(v.is_finite() && (0.0..1e30).contains(&v)) {
            return Err(bad(name, v, "must be finite and >= 0"));
        }
    }
    Ok(())
}

/// The failure recorded for a case not flown after a stop request (never reported: the
/// campaign then ends with [`CampaignError::Interrupted`]).
#[derive(Debug, thiserror::Error)]
#[error("not flown: stop requested")]
struct Stopped;

fn case_path(dir: &Path, mode: Mode, index: u32) -> PathBuf {
    dir.join("cases")
        .join(mode.name())
        .join(format!("{index:06}.json"))
}

/// What replaying one recorded case found ([`replay_case`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Replay {
    /// The directory holds no record of the case.
    NoRecord,
    /// The flight's record is the stored one byte for byte.
    Same,
    /// The stored record differs (other inputs, or a change in the code).
    Differs,
}

/// Fly case `index` of the campaign (`setup`, `settings`) in `mode` alone, from its own draw
/// ([`draw_case`]: the seed and the index only), and compare its record with the one a
/// campaign wrote into `dir` (`dir/cases/<mode>/<index>.json`, the same serialisation).
///
/// # Errors
/// [`CampaignError`] if the flight fails or the record cannot be serialised.
pub fn replay_case(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    mode: Mode,
    index: u32,
    dir: Option<&Path>,
) -> Result<(CaseResult, Replay), CampaignError> {
    let draw = draw_case(settings, index);
    let r = fly_case(setup, Some(&draw), mode)?;
    let json = serde_json::to_vec_pretty(&r).map_err(crate::report::ReportError::from)?;
    let replay = match dir.map(|d| std::fs::read(case_path(d, mode, index))) {
        Some(Ok(stored)) if stored == json => Replay::Same,
        Some(Ok(_)) => Replay::Differs,
        _ => Replay::NoRecord,
    };
    Ok((r, replay))
}

/// Fly case `index` of the campaign in `mode` alone ([`replay_case`]), or the undispersed
/// flight for `None`, with its trajectory: the record (bit for bit the campaign's) and the
/// simulation result with a sample at every guidance tick.
///
/// # Errors
/// [`CampaignError`] if the flight fails.
pub fn replay_case_traced(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    mode: Mode,
    index: Option<u32>,
) -> Result<(CaseResult, crate::sim::SimResult), CampaignError> {
    let draw = index.map(|i| draw_case(settings, i));
    let (r, _, sim) = fly_case_traced(setup, draw.as_ref(), mode)?;
    Ok((r, sim))
}

/// Run the campaign.
///
/// # Errors
/// [`CampaignError`] for bad settings, an output directory holding the cases of other inputs
/// ([`CampaignError::ResumeMismatch`], [`CampaignError::ResumeUnverified`]), a bad stored case
/// file, a write failure or a failed nominal flight. A failed dispersed flight is not an error: it is recorded in
/// [`CampaignOutput::failed`] with its error and the other cases go on.
pub fn run_campaign(
    setup: &CampaignSetup,
    settings: &DispersionSettings,
    opts: &RunOptions,
) -> Result<CampaignOutput, CampaignError> {
    settings.validate(&setup.file)?;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = opts.threads
        && !(1..=crate::optim::evaluate::MAX_THREADS).contains(&t)
    {
        return Err(CampaignError::Setting {
            file: "(run options)".into(),
            field: "threads".into(),
            value: t.to_string(),
            reason: "use 1 to 1024 threads".into(),
        });
    }
    if let Some(t) = opts.threads {
        pool = pool.num_threads(t);
    }
    let pool = pool.build()?;
    let nominal = pool.install(|| {
        opts.modes
            .par_iter()
            .map(|&m| fly_case(setup, None, m))
            .collect::<Result<Vec<_>, _>>()
    })?;
    if let Some(dir) = &opts.out_dir {
        check_and_record(dir, &Fingerprint::of(setup, settings, &nominal)?)?;
        for m in &opts.modes {
            let d = dir.join("cases").join(m.name());
            std::fs::create_dir_all(&d).map_err(|source| crate::report::ReportError::Io {
                path: d.clone(),
                source,
            })?;
        }
    }
    let n = settings.cases;
    let jobs: Vec<(Mode, u32)> = opts
        .modes
        .iter()
        .flat_map(|&m| (0..n).map(move |i| (m, i)))
        .collect();
    let bar = if opts.progress {
        let b = ProgressBar::new(jobs.len() as u64);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} flights, {per_sec}, eta {eta}")
        {
            b.set_style(style);
        }
        b
    } else {
        ProgressBar::hidden()
    };
    type Outcome = Result<(CaseResult, bool), CaseFailure>;
    let results: Vec<Result<Outcome, CampaignError>> = pool.install(|| {
        jobs.par_iter()
            .map(|&(mode, index)| {
                let draw = draw_case(settings, index);
                let path = opts.out_dir.as_ref().map(|d| case_path(d, mode, index));
                if let Some(p) = &path
                    && let Ok(text) = std::fs::read_to_string(p)
                {
                    let stored: CaseResult =
                        serde_json::from_str(&text).map_err(|source| CampaignError::CaseFile {
                            path: p.clone(),
                            source,
                        })?;
                    check_stored(&stored, p)?;
                    if stored.draw == Some(draw)
                        && stored.mode == mode
                        && stored.guidance == setup.guidance_key()
                    {
                        bar.inc(1);
                        return Ok(Ok((stored, true)));
                    }
                }
                // After a stop request no flight starts (the campaign ends without a
                // summary): this case is not done.
                if crate::sim::stop_requested() {
                    return Ok(Err(CaseFailure::new(mode, index, draw, &Stopped)));
                }
                // A failed flight is recorded with its error; the campaign goes on.
                let r = match fly_case(setup, Some(&draw), mode) {
                    Ok(r) => r,
                    Err(e) => {
                        bar.inc(1);
                        return Ok(Err(CaseFailure::new(mode, index, draw, &e)));
                    }
                };
                if let Some(p) = &path {
                    let json =
                        serde_json::to_vec_pretty(&r).map_err(crate::report::ReportError::from)?;
                    write_atomic(p, &json)?;
                }
                bar.inc(1);
                Ok(Ok((r, false)))
            })
            .collect()
    });
    bar.finish_and_clear();
    if crate::sim::stop_requested() {
        // A flight the stop interrupted is no result (it ended `Interrupted`, and would count
        // as a failure): no statistics of a partial campaign.
        let done = results.iter().filter(|r| matches!(r, Ok(Ok(_)))).count();
        return Err(CampaignError::Interrupted {
            done,
            total: jobs.len(),
        });
    }
    let mut by_mode: Vec<(Mode, Vec<CaseResult>)> =
        opts.modes.iter().map(|&m| (m, Vec::new())).collect();
    let mut resumed = 0;
    let mut failed = Vec::new();
    for r in results {
        let (c, reused) = match r? {
            Ok(x) => x,
            Err(f) => {
                failed.push(f);
                continue;
            }
        };
        resumed += usize::from(reused);
        if let Some((_, v)) = by_mode.iter_mut().find(|(m, _)| *m == c.mode) {
            v.push(c);
        }
    }
    Ok(CampaignOutput::new(nominal, by_mode, failed, resumed))
}
