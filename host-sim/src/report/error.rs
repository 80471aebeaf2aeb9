//! [`ReportError`]: why an output could not be written (below the writers and the run
//! directory that return it).

use std::path::PathBuf;

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
    /// A run's CSV file could not be written (a row of another length than its header).
    #[error("cannot write CSV: {0}")]
    Csv(#[from] crate::optim::rows::RowsError),
    /// A stop was requested (Ctrl-C) while a run directory was being written: nothing was
    /// put in place and the temporary directory is removed.
    #[error("interrupted while writing {0}")]
    Interrupted(PathBuf),
    /// A plot could not be drawn.
    #[error("cannot draw plot {name}: {source}")]
    Plot {
        /// The plot's file name.
        name: String,
        /// The plotting library's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}
