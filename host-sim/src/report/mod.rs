//! Run outputs: trajectory CSV ([`trajectory_csv`]), summary JSON ([`summary_report`]) and
//! the four standard plots ([`standard_plots`], drawn with `plotters`' SVG backend). A run
//! directory is written whole or not at all ([`RunDir`]: built in a temporary sibling, then
//! put in place in one step); single files with [`write_atomic`]. An optimisation run on a
//! test problem: [`write_optimize_run`].

pub mod campaign;
pub mod chart;
mod csv;
mod error;
pub mod optimize_run;
mod plot;
pub mod run_dir;
mod summary;

use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::sim::SimResult;

pub use csv::trajectory_csv;
pub use error::ReportError;
pub use optimize_run::{write_chromosome_run_report, write_optimize_run, write_run_report};
pub use plot::{PlotLimits, Series, line_plot_png, line_plot_svg, standard_plots};
pub use run_dir::{RunDir, begin_in_place, clean_stale};
pub use summary::{
    FinalState, LinkFaultsOut, PeakOut, PilOut, SummaryReport, TargetOut, ViolationsOut,
    summary_report,
};

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
    run_dir::clean_stale(dir);
    let tmp = run_dir::temp_file_name(dir, &name);
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

/// Write the run directory `dir` (`trajectory.csv`, `summary.json` and the SVG plots) whole
/// or not at all, replacing a previous run there. Returns the paths written.
///
/// # Errors
/// [`ReportError`] naming the path that failed; the previous run is then left as it was.
pub fn write_run(
    dir: &Path,
    res: &SimResult,
    summary: &SummaryReport,
    limits: &PlotLimits,
) -> Result<Vec<PathBuf>, ReportError> {
    let mut rd = RunDir::begin(dir)?;
    write_run_files(&mut rd, Path::new(""), res, summary, limits)?;
    rd.commit()
}

/// Write a run's files (`trajectory.csv`, `summary.json`, the SVG plots) into `sub` (relative,
/// empty for the top) of the run directory being written.
///
/// # Errors
/// [`ReportError`] naming the path that failed.
pub fn write_run_files(
    rd: &mut RunDir,
    sub: &Path,
    res: &SimResult,
    summary: &SummaryReport,
    limits: &PlotLimits,
) -> Result<(), ReportError> {
    rd.write(
        sub.join("trajectory.csv"),
        trajectory_csv(&res.samples).as_bytes(),
    )?;
    let mut text = serde_json::to_string_pretty(summary)?;
    text.push('\n');
    rd.write(sub.join("summary.json"), text.as_bytes())?;
    for (name, bytes) in standard_plots(res, limits)? {
        rd.write(sub.join(name), &bytes)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
