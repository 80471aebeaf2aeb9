//! Run outputs: trajectory CSV ([`trajectory_csv`]), summary JSON ([`summary_report`]) and
//! the four standard plots ([`standard_plots`], drawn with `plotters`' SVG backend), all
//! written atomically (temporary file in the target directory, then rename).

mod csv;
mod plot;
mod summary;

use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::sim::SimResult;

pub use csv::trajectory_csv;
pub use plot::{Series, line_plot_svg, standard_plots};
pub use summary::{FinalState, PeakOut, SummaryReport, ViolationsOut, summary_report};

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
    /// A plot could not be drawn.
    #[error("cannot draw plot {name}: {source}")]
    Plot {
        /// The plot's file name.
        name: String,
        /// The plotting library's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
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
    for (name, svg) in standard_plots(res, heat_limit_w_m2, g_limit)? {
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
