//! `host-sim optimize` on the re-entry design problems ([`crate::design`]): settings from
//! flags or a TOML file (`--config`, `--print-config` prints a template), `--resume DIR`, a
//! progress bar and the result line. The run itself (checks, checkpoint and resume, records,
//! the run directory) is [`crate::design::run`]'s.

use std::io::Write;
use std::path::Path;

use super::optimize_common::{OptimizeArgs, run_options};
use crate::design::run::{ProgressBar, RunFlags, parse_toml, run as design_run};
pub use crate::design::run::{ReentryError, ReentryRunConfig, check_run_config};
use crate::optim::reference::parse_reference;

/// The run configuration of flags (a preset `--problem`; the flags it does not take are
/// refused before, by `optimize_common::check`) or `--config`.
fn config_of(a: &OptimizeArgs) -> Result<ReentryRunConfig, ReentryError> {
    if let Some(path) = &a.config {
        return parse_toml(path);
    }
    let reference = a
        .reference
        .as_deref()
        .map(parse_reference)
        .transpose()
        .map_err(|e| ReentryError::Setting {
            source_name: "command line".into(),
            field: "reference",
            value: e.value.clone(),
            reason: format!("--ref coordinate {}: {}", e.coordinate, e.reason),
        })?;
    Ok(ReentryRunConfig::of_flags(&RunFlags {
        preset: a.problem.clone(),
        options: run_options(a),
        generations: a.generations,
        seed: a.seed,
        threads: a.threads,
        reference,
        evaluations: a.evaluations,
    })?)
}

/// Run `optimize` on a re-entry problem.
///
/// # Errors
/// [`ReentryError`].
pub(super) fn run(a: &OptimizeArgs, out: &mut dyn Write) -> Result<(), ReentryError> {
    if a.print_config {
        write!(out, "{}", config_of(a)?.to_toml("(template)")?)?;
        return Ok(());
    }
    let (mut c, dir, resume) = match &a.resume {
        Some(dir) => (parse_toml(&dir.join("config.toml"))?, dir.clone(), true),
        None => {
            let c = config_of(a)?;
            let dir = a.out.clone().unwrap_or_else(|| c.default_dir());
            (c, dir, false)
        }
    };
    let src = match (&a.resume, &a.config) {
        (Some(d), _) => d.join("config.toml").display().to_string(),
        (None, Some(p)) => p.display().to_string(),
        (None, None) => "command line".to_string(),
    };
    if resume && a.generations_given() {
        // Resuming may extend the run (an interrupted run resumes to its own target).
        c.generations = a.generations;
    }
    let base_dir = a
        .config
        .as_deref()
        .and_then(Path::parent)
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let done = design_run(
        &c,
        &src,
        &dir,
        resume,
        &base_dir,
        &mut ProgressBar::default(),
        None,
    )?;
    if let Some(line) = done.line(&c, &dir) {
        writeln!(out, "{line}")?;
    }
    Ok(())
}
