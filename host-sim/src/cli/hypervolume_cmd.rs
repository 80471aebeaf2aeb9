//! `host-sim hypervolume FRONT.csv --ref R1,R2[,...]`: the exact hypervolume of a front read
//! from CSV (one point per row, one minimised objective per column), optionally each point's
//! exclusive contribution, and with `--repeat K` the median time of K computations (for
//! benchmarks against other tools, see scripts/compare_hypervolume.py).
//!
//! CSV: comma-separated numbers; blank lines and lines starting with `#` are skipped; a first
//! line in which no field is a number is a header (without data lines after it, it must name
//! one column per objective). Every other malformed line is an error
//! naming the file and the line.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use super::error::{CliError, HypervolumeCmdError};
use crate::optim::hypervolume::{contributions, hypervolume};
use crate::optim::reference::parse_reference;

/// Arguments of `hypervolume`.
#[derive(Debug, clap::Args)]
pub struct HypervolumeArgs {
    /// Front CSV: one point per row, objectives (minimised) as columns.
    #[arg(value_name = "FRONT.csv")]
    pub front: PathBuf,
    /// Reference point, comma-separated, one value per objective (e.g. 1.1,1.1).
    #[arg(long = "ref", value_name = "R1,R2,...", allow_hyphen_values = true)]
    pub reference: String,
    /// Also print each point's exclusive contribution (CSV `index,contribution`).
    #[arg(long)]
    pub contributions: bool,
    /// Compute K times and print the median wall time of one computation.
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub repeat: u32,
}

/// Run `hypervolume` with arguments `a`, writing the results to `out`.
pub(super) fn run(a: &HypervolumeArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let reference = parse_reference(&a.reference).map_err(HypervolumeCmdError::from)?;
    let text = std::fs::read_to_string(&a.front).map_err(|source| HypervolumeCmdError::Read {
        path: a.front.clone(),
        source,
    })?;
    let points = parse_front(&a.front, &text, reference.len())?;
    let hv_err = |source| HypervolumeCmdError::Hypervolume {
        path: a.front.clone(),
        source,
    };
    let mut times = Vec::with_capacity(a.repeat as usize);
    let mut hv = 0.0;
    for _ in 0..a.repeat {
        let t = Instant::now();
        hv = hypervolume(std::hint::black_box(&points), &reference).map_err(hv_err)?;
        times.push(t.elapsed().as_secs_f64());
    }
    writeln!(out, "file: {}", a.front.display())?;
    writeln!(out, "points: {}", points.len())?;
    writeln!(out, "objectives: {}", reference.len())?;
    writeln!(out, "hypervolume: {hv}")?;
    if a.repeat > 1 {
        writeln!(out, "repeats: {}", a.repeat)?;
        writeln!(out, "median_time_s: {:e}", median(&mut times))?;
    }
    if a.contributions {
        let mut times = Vec::with_capacity(a.repeat as usize);
        let mut c = Vec::new();
        for _ in 0..a.repeat {
            let t = Instant::now();
            c = contributions(std::hint::black_box(&points), &reference).map_err(hv_err)?;
            times.push(t.elapsed().as_secs_f64());
        }
        if a.repeat > 1 {
            writeln!(out, "contributions_median_time_s: {:e}", median(&mut times))?;
        }
        writeln!(out, "index,contribution")?;
        for (i, v) in c.iter().enumerate() {
            writeln!(out, "{i},{v}")?;
        }
    }
    Ok(())
}

/// Median of a non-empty sample (mean of the middle two for an even count).
fn median(v: &mut [f64]) -> f64 {
    v.sort_unstable_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// Parse the front: `d` finite numbers per data line.
fn parse_front(path: &Path, text: &str, d: usize) -> Result<Vec<Vec<f64>>, HypervolumeCmdError> {
    let mut points = Vec::new();
    let mut first = true;
    let mut head = None;
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let header = first && fields.iter().all(|f| f.parse::<f64>().is_err());
        first = false;
        if header {
            head = Some((k + 1, fields.len()));
            continue;
        }
        if fields.len() != d {
            return Err(HypervolumeCmdError::Columns {
                path: path.to_path_buf(),
                line: k + 1,
                found: fields.len(),
                expected: d,
            });
        }
        let mut p = Vec::with_capacity(d);
        for (j, f) in fields.iter().enumerate() {
            let bad = |reason| HypervolumeCmdError::Field {
                path: path.to_path_buf(),
                line: k + 1,
                field: j + 1,
                value: (*f).to_string(),
                reason,
            };
            match f.parse::<f64>() {
                Ok(v) if v.is_finite() => p.push(v),
                Ok(_) => return Err(bad("must be finite")),
                Err(_) => return Err(bad("not a number")),
            }
        }
        points.push(p);
    }
    // Only a first line without numbers: a header of an empty front if it names one column
    // per objective, else a malformed file (a one-word text file is no front).
    if let Some((line, found)) = head
        && points.is_empty()
        && found != d
    {
        return Err(HypervolumeCmdError::Columns {
            path: path.to_path_buf(),
            line,
            found,
            expected: d,
        });
    }
    Ok(points)
}
