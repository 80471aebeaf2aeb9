//! `host-sim compare`: command-line arguments, the grid they define, and the run that writes
//! the files and prints the summary.

use std::path::PathBuf;

use crate::analytic::{self, AnalyticVehicle, GlideEnd, Placement};
use crate::compare::{
    AnalyticOutcome, CompareConfig, CompareError, GridKind, NumericalSettings, run_grid_with,
    write_case_into, write_grid_into,
};
use crate::env::Preset;
use crate::report::RunDir;

fn setting(field: &'static str, value: impl ToString, reason: &'static str) -> CompareError {
    CompareError::setting(field, value, reason)
}

/// A numerical environment of `compare` (the library's [`Preset`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EnvArg {
    /// Non-rotating sphere, central gravity, the closed forms' exponential atmosphere.
    Simplified,
    /// Rotating sphere, US76, central + J2 gravity.
    Full,
}

impl From<EnvArg> for Preset {
    fn from(a: EnvArg) -> Self {
        match a {
            EnvArg::Simplified => Preset::Simplified,
            EnvArg::Full => Preset::Full,
        }
    }
}

/// Which closed form the `compare` subcommand maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CliPhase {
    /// Skip from a fixed entry altitude and flight-path angle over entry speeds.
    Skip,
    /// Glide over entry altitudes (entry speed and angle imposed by the method).
    Glide,
}

/// Arguments of `host-sim compare` (SI units or the unit in the name).
#[derive(Debug, Clone, clap::Args)]
pub struct CompareCliArgs {
    /// Vehicle: a built-in name (srm, horus-2b) or a vehicle TOML file.
    #[arg(long, default_value = "srm")]
    pub vehicle: String,
    /// Closed form to compare.
    #[arg(long, value_enum, default_value = "glide")]
    pub phase: CliPhase,
    /// Glide: entry altitudes (km) (grid x axis), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "70,80,90,100,110")]
    pub altitudes_km: Vec<f64>,
    /// Skip: entry speeds [m/s] (grid x axis), comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "7000,7500,8000,9000,10000"
    )]
    pub speeds_m_s: Vec<f64>,
    /// Skip: entry altitude (km) (also the exit altitude).
    #[arg(long, default_value_t = 100.0)]
    pub altitude_km: f64,
    /// Skip: entry flight-path angle (deg) (negative: descending).
    #[arg(long, default_value_t = -3.0, allow_negative_numbers = true)]
    pub gamma_deg: f64,
    /// Vertical lift coefficients C_L cos(sigma) [-] (grid y axis), comma-separated. Bank-only
    /// vehicles fly their trim C_L banked; others fly C_L = this value, lift up. Default: five
    /// values from 0.3 to 1 times the maximum (trim C_L, or C_L at maximum L/D).
    #[arg(long, value_delimiter = ',')]
    pub cl_vertical: Vec<f64>,
    /// Glide: end at this altitude (km) instead of a speed.
    #[arg(long, conflicts_with = "end_speed_fraction")]
    pub end_altitude_km: Option<f64>,
    /// Glide: end at this fraction of the imposed entry speed [-].
    #[arg(long, default_value_t = 0.5)]
    pub end_speed_fraction: f64,
    /// Mach number at which a tabulated drag polar is taken [-].
    #[arg(long, default_value_t = crate::analytic::DEFAULT_POLAR_MACH)]
    pub polar_mach: f64,
    /// Two altitudes (km) through which the exponential atmosphere is fitted to US76.
    #[arg(long, value_delimiter = ',', num_args = 1, default_value = "50,100")]
    pub fit_altitudes_km: Vec<f64>,
    /// Numerical environments to fly, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "simplified,full"
    )]
    pub environments: Vec<EnvArg>,
    /// Start latitude (deg).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub latitude_deg: f64,
    /// Start longitude (deg).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub longitude_deg: f64,
    /// Start heading (deg), clockwise from north.
    #[arg(long, default_value_t = 90.0, allow_negative_numbers = true)]
    pub heading_deg: f64,
    /// Integrator relative tolerance [-].
    #[arg(long, default_value_t = 1e-8)]
    pub rtol: f64,
    /// Numerical sample interval (s).
    #[arg(long, default_value_t = 1.0)]
    pub output_interval_s: f64,
    /// Samples per analytical trajectory.
    #[arg(long, default_value_t = crate::analytic::DEFAULT_POINTS)]
    pub points: usize,
    /// Also write every point's trajectories (analytic/, simplified/, full/ run directories
    /// under `point_<i>/`).
    #[arg(long)]
    pub trajectories: bool,
    /// Output directory (default: `runs/compare-<vehicle>-<phase>/`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

fn finite_arg(field: &'static str, v: f64) -> Result<f64, CompareError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(setting(field, crate::num_fmt::Compact(v), "must be finite"))
    }
}

/// The grid of a `compare` command line.
///
/// # Errors
/// [`CompareError`] naming the argument and value (or the vehicle file, field and value).
pub(super) fn config_from_args(a: &CompareCliArgs) -> Result<CompareConfig, CompareError> {
    let veh = crate::vehicle::load(&a.vehicle)?;
    let vehicle = AnalyticVehicle::from_vehicle(&veh, a.polar_mach)?;
    let [h1, h2] = a.fit_altitudes_km[..] else {
        return Err(setting(
            "--fit-altitudes-km",
            format!("{:?}", a.fit_altitudes_km),
            "needs exactly two altitudes",
        ));
    };
    // Two different altitudes inside US76 (0..1000 km): the fit's scale height is their
    // difference over the log of the density ratio.
    let shown = || {
        format!(
            "[{}, {}]",
            crate::num_fmt::Compact(h1),
            crate::num_fmt::Compact(h2)
        )
    };
    if ![h1, h2].iter().all(|h| (0.0..=1000.0).contains(h)) {
        return Err(setting(
            "--fit-altitudes-km",
            shown(),
            "altitudes must be in [0, 1000] km (US76)",
        ));
    }
    if (h1 - h2).abs() < 0.1 {
        return Err(setting(
            "--fit-altitudes-km",
            shown(),
            "needs two different altitudes (at least 0.1 km apart)",
        ));
    }
    let atmosphere = analytic::fit_us76(h1 * 1e3, h2 * 1e3)?;
    let cl_max = vehicle
        .trim_cl
        .unwrap_or_else(|| vehicle.polar.cl_at_max_lift_to_drag());
    let cl_vertical = if a.cl_vertical.is_empty() {
        [0.3, 0.475, 0.65, 0.825, 1.0]
            .iter()
            .map(|f| (f * cl_max * 1e4).round() / 1e4)
            .collect()
    } else {
        a.cl_vertical.clone()
    };
    let km = |v: &[f64]| v.iter().map(|x| x * 1e3).collect::<Vec<_>>();
    let kind = match a.phase {
        CliPhase::Skip => GridKind::Skip {
            entry_altitude_m: finite_arg("--altitude-km", a.altitude_km)? * 1e3,
            flight_path_angle_rad: finite_arg("--gamma-deg", a.gamma_deg)?.to_radians(),
            entry_speeds_m_s: a.speeds_m_s.clone(),
        },
        CliPhase::Glide => GridKind::Glide {
            entry_altitudes_m: km(&a.altitudes_km),
            end: match a.end_altitude_km {
                Some(h) => GlideEnd::Altitude {
                    altitude_m: finite_arg("--end-altitude-km", h)? * 1e3,
                },
                None => GlideEnd::SpeedFraction {
                    fraction: a.end_speed_fraction,
                },
            },
        },
    };
    // A grid flies many runs, each recording its samples: 10 ms is finer than any metric
    // needs and keeps a run at a few hundred thousand samples.
    if !(0.01..=1e4).contains(&a.output_interval_s) {
        return Err(setting(
            "--output-interval-s",
            crate::num_fmt::Compact(a.output_interval_s),
            "must be in [0.01, 1e4] s",
        ));
    }
    if a.environments.is_empty() {
        return Err(setting("--environments", "[]", "needs at least one"));
    }
    Ok(CompareConfig {
        vehicle,
        kind,
        cl_vertical,
        atmosphere,
        placement: Placement {
            latitude_rad: finite_arg("--latitude-deg", a.latitude_deg)?.to_radians(),
            longitude_rad: finite_arg("--longitude-deg", a.longitude_deg)?.to_radians(),
            heading_rad: finite_arg("--heading-deg", a.heading_deg)?.to_radians(),
        },
        fidelities: a.environments.iter().map(|&e| e.into()).collect(),
        numerical: NumericalSettings {
            rtol: a.rtol,
            output_interval_s: a.output_interval_s,
            ..NumericalSettings::default()
        },
        points: a.points,
    })
}

/// `host-sim compare`: run the grid, write `grid.csv`, the heat maps and (with
/// `--trajectories`) every point's run directories, and print a summary to `out`. Returns the
/// files written.
///
/// # Errors
/// [`CompareError`] naming the argument and value, or the path that could not be written.
pub(super) fn run(
    a: &CompareCliArgs,
    out: &mut dyn std::io::Write,
) -> Result<Vec<PathBuf>, CompareError> {
    let cfg = config_from_args(a)?;
    let phase = match a.phase {
        CliPhase::Skip => "skip",
        CliPhase::Glide => "glide",
    };
    let dir = a.out.clone().unwrap_or_else(|| {
        PathBuf::from("runs").join(format!(
            "compare-{}-{phase}",
            cfg.vehicle.name.replace([' ', '/', '\\'], "_")
        ))
    });
    // The whole output (grid, heat maps, trajectories) is one run directory, put in place
    // only when complete.
    let mut rd = RunDir::begin(&dir)?;
    let scenario = format!("compare {} {phase}", cfg.vehicle.name);
    let grid = run_grid_with(&cfg, &mut |done, total, _, runs| {
        if a.trajectories {
            let sub = PathBuf::from(format!("point_{}", done - 1));
            write_case_into(&mut rd, &sub, runs, &cfg.vehicle, &scenario)?;
        }
        eprint!("\rcompare: {done}/{total} points");
        Ok(())
    })?;
    eprintln!();
    write_grid_into(&mut rd, &grid, &cfg.fidelities)?;
    let files = rd.commit()?;
    writeln!(
        out,
        "{} {phase}: {} points, {} out of the closed form's domain; exponential atmosphere \
         H_s = {:.1} m",
        grid.vehicle,
        grid.points.len(),
        grid.points
            .iter()
            .filter(|p| matches!(p.analytic, AnalyticOutcome::OutOfDomain(_)))
            .count(),
        grid.atmosphere.scale_height_m()
    )?;
    for (i, m) in grid.metrics.iter().enumerate() {
        for &f in &cfg.fidelities {
            let compared = grid
                .points
                .iter()
                .filter(|p| grid.error(p, i, f).is_some())
                .count();
            match grid.max_abs_error(i, f) {
                Some(e) => writeln!(
                    out,
                    "  {:<24} {:<10} max |error| {e:.3} {} over {compared} points",
                    m.name,
                    f.name(),
                    if m.relative { "%" } else { m.error_unit }
                )?,
                None => writeln!(out, "  {:<24} {:<10} no point compared", m.name, f.name())?,
            }
        }
    }
    writeln!(out, "wrote {}", dir.display())?;
    Ok(files)
}
