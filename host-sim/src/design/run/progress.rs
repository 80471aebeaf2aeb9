//! What a front end shows of a design run: a terminal progress bar ([`ProgressBar`]) and the
//! one-line result of a finished run ([`Finished::line`]).

use std::path::Path;

use super::{Finished, Progress, ReentryRunConfig};
use crate::optim::run::Record;

/// A progress bar on stderr over the run's generations, with the last record's feasible
/// fraction, best objectives and hypervolume (hidden when stderr is not a terminal).
#[derive(Debug, Default)]
pub struct ProgressBar(Option<indicatif::ProgressBar>);

impl Progress for ProgressBar {
    fn start(&mut self, total: u64, done: u64) {
        let bar = indicatif::ProgressBar::new(total);
        bar.set_position(done);
        self.0 = Some(bar);
    }
    fn record(&mut self, rec: &Record) {
        if let Some(bar) = &self.0 {
            bar.set_position(rec.generation + 1);
            bar.set_message(format!(
                "gen {} feasible {:.0} % best f {:?} hv {:.4}",
                rec.generation,
                100.0 * rec.feasible_fraction,
                rec.best,
                rec.hypervolume
            ));
        }
    }
    fn finish(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

impl Finished {
    /// The result of the run of `c` in `dir` in one line (no newline): the last generation's
    /// evaluations, feasible fraction, hypervolume and front size; `None` when no generation
    /// was recorded.
    #[must_use]
    pub fn line(&self, c: &ReentryRunConfig, dir: &Path) -> Option<String> {
        let r = self.last.as_ref()?;
        Some(format!(
            "{} on {}: generation {}, {} evaluations in {:.2} s in this run, feasible {:.0} %, hypervolume {:.6} w.r.t. {:?}, {} front members{}; wrote {}",
            c.algorithm,
            c.problem.base,
            r.generation,
            r.evaluations,
            self.wall_time_s,
            100.0 * r.feasible_fraction,
            r.hypervolume,
            c.reference,
            r.front.len(),
            c.archive
                .map_or_else(String::new, |n| format!(" (external archive of {n})")),
            dir.display()
        ))
    }
}
