//! Run directories that appear whole or not at all ([`RunDir`]).
//!
//! A run is written into a temporary sibling `.<name>.tmp-host-sim-<pid>-<seq>` of the target
//! directory; every file is synced, then the finished directory takes the target's place in
//! one step (Linux: `renameat2(RENAME_EXCHANGE)`, which swaps it with the previous run; then
//! the previous run, now in the temporary name, is removed). Until that step the previous run
//! stays as it was; a kill at any moment leaves the target either the complete previous run,
//! the complete new one, or (for a first run) absent. A failure before the swap removes the
//! temporary directory and leaves the previous run intact.
//!
//! Where the exchange is not available (another OS, or a file system that refuses it) the
//! previous run is first renamed to `.<name>.old-host-sim-<pid>-<seq>`, then the new one into
//! place; a kill between the two leaves the target absent and the old run in the `.old`
//! name, which the next run restores.
//!
//! Leftovers of killed runs (`.<name>.tmp-host-sim-*` and `.<name>.old-host-sim-*` whose
//! process is gone) are removed by [`clean_stale`], which [`RunDir::begin`] calls on the
//! parent directory. Liveness is read from `/proc/<pid>`: without `/proc` nothing is removed.

use std::fs;
use std::io::{self, Write as _};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::ReportError;

/// Temporary-name markers; distinctive, so that only this program's leftovers are touched.
const TMP_MARK: &str = ".tmp-host-sim-";
const OLD_MARK: &str = ".old-host-sim-";

/// The file that marks a directory as a run directory this program may replace whole.
pub const MARKER: &str = ".host-sim-run";
const MARKER_TEXT: &str =
    "A host-sim run directory: the next run to this path replaces it whole.\n";

/// Whether an existing `target` may be replaced: an empty directory or a marked run.
fn replaceable(target: &Path) -> bool {
    target.join(MARKER).is_file() || fs::read_dir(target).is_ok_and(|mut d| d.next().is_none())
}

/// Per-process sequence, so two run directories written by one process never share a name.
static SEQ: AtomicU64 = AtomicU64::new(0);

fn io_err(path: &Path) -> impl FnOnce(io::Error) -> ReportError + '_ {
    move |source| ReportError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// A run directory being written: files go into a temporary sibling, and [`RunDir::commit`]
/// puts the whole directory in place. Dropped without commit, the temporary directory is
/// removed and the target is untouched.
#[derive(Debug)]
pub struct RunDir {
    target: PathBuf,
    parent: PathBuf,
    name: String,
    seq: u64,
    tmp: PathBuf,
    written: Vec<PathBuf>,
    done: bool,
    /// While writing, Ctrl-C asks this writer to stop (it then removes its temporary
    /// directory) instead of exiting the process with the directory left behind.
    _active: crate::sim::ActiveRun,
}

/// A step of [`RunDir::commit`] where a test can inject a fault.
#[cfg_attr(not(test), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CommitStep {
    /// Files synced, before the swap.
    Synced,
    /// The new directory is in place; the previous run is still to be removed.
    Swapped,
}

/// What an injected fault does (test hook).
#[cfg_attr(not(test), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fault {
    /// An I/O error: the writer's own error path runs.
    Fail,
    /// The process dies here: nothing more runs, not even cleanup.
    Kill,
}

impl RunDir {
    /// Start writing the run directory `target`: create its parent if needed, remove stale
    /// leftovers of killed runs there, and create the temporary sibling.
    ///
    /// # Errors
    /// [`ReportError::Io`] naming the path: no final name component (`/`, `..`), the target
    /// exists and is not a directory, or the parent cannot be created or written.
    pub fn begin(target: &Path) -> Result<Self, ReportError> {
        Self::begin_with(target, true)
    }

    /// [`RunDir::begin`] for a sub-directory of a run directory the caller owns (e.g. the
    /// front of an optimisation run): replaced whole whether or not it carries the marker.
    ///
    /// # Errors
    /// As [`RunDir::begin`], except that a non-run directory is replaced.
    pub fn begin_owned(target: &Path) -> Result<Self, ReportError> {
        Self::begin_with(target, false)
    }

    /// The temporary directory the run is written into until [`RunDir::commit`] (for a
    /// writer of its own, such as a nested run directory).
    #[must_use]
    pub fn staging(&self) -> &Path {
        &self.tmp
    }

    fn begin_with(target: &Path, check_marker: bool) -> Result<Self, ReportError> {
        let name = match target.components().next_back() {
            Some(Component::Normal(n)) => n.to_string_lossy().into_owned(),
            _ => {
                return Err(ReportError::Io {
                    path: target.to_path_buf(),
                    source: io::Error::new(
                        io::ErrorKind::InvalidInput,
                        "an output directory needs a name (not `/`, `.` or `..`)",
                    ),
                });
            }
        };
        let parent = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        fs::create_dir_all(&parent).map_err(io_err(&parent))?;
        if let Ok(meta) = fs::symlink_metadata(target)
            && !meta.is_dir()
        {
            return Err(ReportError::Io {
                path: target.to_path_buf(),
                source: io::Error::new(
                    io::ErrorKind::AlreadyExists,
                    "exists and is not a directory; not replaced",
                ),
            });
        }
        if check_marker && fs::symlink_metadata(target).is_ok() && !replaceable(target) {
            return Err(ReportError::Io {
                path: target.to_path_buf(),
                source: io::Error::new(
                    io::ErrorKind::AlreadyExists,
                    format!(
                        "exists, is not empty and is not a host-sim run directory (no {MARKER}); \
                         not replaced: choose another --out or remove it"
                    ),
                ),
            });
        }
        // Count as an active run before the temporary directory exists: Ctrl-C with no run
        // active exits the process at once, which would leave the directory behind.
        let active = crate::sim::ActiveRun::start();
        clean_stale(&parent);
        let seq = SEQ.fetch_add(1, Ordering::Relaxed);
        let tmp = parent.join(format!(".{name}{TMP_MARK}{}-{seq}", std::process::id()));
        if tmp.exists() {
            let _ = fs::remove_dir_all(&tmp);
        }
        fs::create_dir(&tmp).map_err(io_err(&tmp))?;
        if let Err(e) = fs::write(tmp.join(MARKER), MARKER_TEXT) {
            let _ = fs::remove_dir_all(&tmp);
            return Err(io_err(&tmp)(e));
        }
        Ok(Self {
            target: target.to_path_buf(),
            parent,
            name,
            seq,
            tmp,
            written: Vec::new(),
            done: false,
            _active: active,
        })
    }

    /// The directory the run will be in once committed.
    #[must_use]
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Write `contents` to `rel` (a relative path, sub-directories allowed, no `..`) inside
    /// the run, synced. Returns the path the file will have once committed.
    ///
    /// # Errors
    /// [`ReportError::Io`] naming the file.
    pub fn write(
        &mut self,
        rel: impl AsRef<Path>,
        contents: &[u8],
    ) -> Result<PathBuf, ReportError> {
        let rel = rel.as_ref();
        let final_path = self.target.join(rel);
        if crate::sim::stop_requested() {
            return Err(ReportError::Interrupted(self.target.clone()));
        }
        if rel.as_os_str().is_empty()
            || !rel.components().all(|c| matches!(c, Component::Normal(_)))
        {
            return Err(ReportError::Io {
                path: final_path,
                source: io::Error::new(
                    io::ErrorKind::InvalidInput,
                    "a run file needs a relative path without `..`",
                ),
            });
        }
        let path = self.tmp.join(rel);
        let res = (|| {
            if let Some(p) = path.parent() {
                fs::create_dir_all(p)?;
            }
            let mut f = fs::File::create(&path)?;
            f.write_all(contents)?;
            f.sync_all()
        })();
        res.map_err(io_err(&final_path))?;
        self.written.push(final_path.clone());
        Ok(final_path)
    }

    /// Put the finished run in place of the target (replacing the previous run in one step)
    /// and return the paths of the files written.
    ///
    /// # Errors
    /// [`ReportError::Io`]; the previous run is then still in place.
    pub fn commit(self) -> Result<Vec<PathBuf>, ReportError> {
        self.commit_injected(&mut |_| Ok(()))
    }

    /// Simulate a kill: drop the writer without any cleanup (test hook).
    #[cfg(test)]
    pub(crate) fn kill(mut self) {
        self.done = true;
    }

    /// [`RunDir::commit`] with `hook` called at each step (test hook).
    pub(crate) fn commit_injected(
        mut self,
        hook: &mut dyn FnMut(CommitStep) -> Result<(), Fault>,
    ) -> Result<Vec<PathBuf>, ReportError> {
        if crate::sim::stop_requested() {
            return Err(ReportError::Interrupted(self.target.clone()));
        }
        let mut step = |me: &mut Self, s: CommitStep| match hook(s) {
            Ok(()) => Ok(()),
            Err(f) => {
                if f == Fault::Kill {
                    me.done = true;
                }
                Err(ReportError::Io {
                    path: me.target.clone(),
                    source: io::Error::other(format!("injected fault at {s:?}")),
                })
            }
        };
        let sync_dir = |p: &Path| fs::File::open(p).and_then(|f| f.sync_all());
        sync_dir(&self.tmp).map_err(io_err(&self.tmp))?;
        step(&mut self, CommitStep::Synced)?;
        let old = if fs::symlink_metadata(&self.target).is_ok() {
            Some(self.swap_in()?)
        } else {
            fs::rename(&self.tmp, &self.target).map_err(io_err(&self.target))?;
            None
        };
        // From here on the new run is in place: only the previous one is left to remove.
        self.done = true;
        let _ = sync_dir(&self.parent);
        step(&mut self, CommitStep::Swapped)?;
        if let Some(old) = old {
            let _ = fs::remove_dir_all(old);
        }
        Ok(std::mem::take(&mut self.written))
    }

    /// Replace the existing target with the temporary directory; returns where the previous
    /// run now is (to be removed).
    fn swap_in(&mut self) -> Result<PathBuf, ReportError> {
        #[cfg(target_os = "linux")]
        {
            use rustix::fs::{CWD, RenameFlags, renameat_with};
            if renameat_with(CWD, &self.tmp, CWD, &self.target, RenameFlags::EXCHANGE).is_ok() {
                return Ok(self.tmp.clone());
            }
        }
        let old = self.parent.join(format!(
            ".{}{OLD_MARK}{}-{}",
            self.name,
            std::process::id(),
            self.seq
        ));
        fs::rename(&self.target, &old).map_err(io_err(&self.target))?;
        if let Err(e) = fs::rename(&self.tmp, &self.target) {
            let _ = fs::rename(&old, &self.target);
            return Err(io_err(&self.target)(e));
        }
        Ok(old)
    }
}

impl Drop for RunDir {
    fn drop(&mut self) {
        if !self.done {
            let _ = fs::remove_dir_all(&self.tmp);
        }
    }
}

/// Start a run directory that is written in place as the run goes (a checkpointed
/// optimisation, resumable from it): a directory that is not a host-sim run (no [`MARKER`],
/// not empty) is refused; a previous run there is removed whole (none of its files is left
/// beside the new run's); the directory is created with the marker.
///
/// # Errors
/// [`ReportError::Io`] naming the path: a non-run directory or a file there, or the
/// directory cannot be removed or created.
pub fn begin_in_place(target: &Path) -> Result<(), ReportError> {
    if let Ok(meta) = fs::symlink_metadata(target) {
        let refuse = |why: String| ReportError::Io {
            path: target.to_path_buf(),
            source: io::Error::new(io::ErrorKind::AlreadyExists, why),
        };
        if !meta.is_dir() {
            return Err(refuse("exists and is not a directory; not replaced".into()));
        }
        if !replaceable(target) {
            return Err(refuse(format!(
                "exists, is not empty and is not a host-sim run directory (no {MARKER}); \
                 not replaced: choose another --out or remove it"
            )));
        }
        fs::remove_dir_all(target).map_err(io_err(target))?;
    }
    fs::create_dir_all(target).map_err(io_err(target))?;
    fs::write(target.join(MARKER), MARKER_TEXT).map_err(io_err(target))
}

/// Whether process `pid` is alive (`None`: cannot tell, no `/proc`).
fn alive(pid: u32) -> Option<bool> {
    if !Path::new("/proc/self").exists() {
        return None;
    }
    Some(pid == std::process::id() || Path::new(&format!("/proc/{pid}")).exists())
}

/// Split a leftover's file name `.<name><mark><pid>-<seq>` into its name and pid.
fn leftover(file: &str, mark: &str) -> Option<(String, u32)> {
    let rest = file.strip_prefix('.')?;
    let at = rest.rfind(mark)?;
    let (pid, seq) = rest[at + mark.len()..].split_once('-')?;
    seq.parse::<u64>().ok()?;
    Some((rest[..at].to_string(), pid.parse().ok()?))
}

/// Remove the leftovers of killed runs in `dir`: temporary run directories (and temporary
/// files of [`super::write_atomic`]) whose process is gone; a previous run moved aside
/// (`.old`) is put back if its run directory is absent, else removed. Best effort: errors are
/// ignored. Returns how many entries were removed or restored.
pub fn clean_stale(dir: &Path) -> usize {
    let Ok(entries) = fs::read_dir(dir) else {
        return 0;
    };
    let mut n = 0;
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let path = e.path();
        if let Some((_, pid)) = leftover(&file, TMP_MARK) {
            if alive(pid) == Some(false) {
                let ok = if path.is_dir() {
                    fs::remove_dir_all(&path)
                } else {
                    fs::remove_file(&path)
                };
                n += usize::from(ok.is_ok());
            }
        } else if let Some((name, pid)) = leftover(&file, OLD_MARK)
            && alive(pid) == Some(false)
        {
            let run = dir.join(&name);
            let ok = if fs::symlink_metadata(&run).is_err() {
                fs::rename(&path, &run)
            } else {
                fs::remove_dir_all(&path)
            };
            n += usize::from(ok.is_ok());
        }
    }
    n
}

/// The temporary name [`super::write_atomic`] uses for `path`'s file `name` in `dir`.
pub(super) fn temp_file_name(dir: &Path, name: &str) -> PathBuf {
    let seq = SEQ.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{name}{TMP_MARK}{}-{seq}", std::process::id()))
}

#[cfg(test)]
mod tests;
