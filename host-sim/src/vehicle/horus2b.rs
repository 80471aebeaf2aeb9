//! HORUS-2B reference vehicle (thesis sec. 2.3.1, tables 2.1 and 2.2; Mooij 1995).
//!
//! * Mass 26 029 kg, reference area 110 m^2, nose radius 0.8 m (thesis table 2.1).
//! * Limits (thesis table 2.1): heat flux 500 kW/m^2, g-load 3.0, g-load rate 0.5 1/s,
//!   alpha rate 5 deg/s, bank rate 15 deg/s.
//! * Aerodynamics: the clean (untrimmed) C_L and C_D of Mooij (1995) over Mach 1.2-20 and
//!   alpha 0-45 deg (`data/horus2b/clean_aero.csv`, embedded at compile time), bilinear in
//!   Mach and alpha and clamped at the table edges (below Mach 1.2 the Mach 1.2 values, above
//!   Mach 20 the Mach 20 values; alpha outside 0-45 deg the edge values). Body-flap trim
//!   increments are not in the data and not modelled.
//! * Unpublished cells (low Mach, high alpha: C_L at Mach 1.2 from 25 deg and at Mach 1.5 from
//!   40 deg, C_D at Mach 1.2 from 35 deg and at Mach 1.5 at 45 deg) are filled by default with
//!   [`GapFill::NeighbourMachIncrement`]: the missing value continues the curve of the
//!   published value below it with the alpha increments of the next higher Mach column
//!   (Mach 1.5 from Mach 2, then Mach 1.2 from the filled Mach 1.5). This keeps lift and drag
//!   rising with alpha as in every published column. [`aerodynamics`] also offers
//!   [`GapFill::HoldLastAlpha`]. The reference trajectory flies these corners only at the end
//!   (low Mach at alpha ~11.5 deg), where the table is published.
//! * Drag polar C_D = C_D0 + K C_L^2 per Mach from thesis table 8.1
//!   (`data/horus2b/drag_polar.csv`), linear in Mach between the tabulated Mach numbers and
//!   clamped outside, available through [`Aerodynamics::drag_polar`](super::Aerodynamics::drag_polar).

use std::sync::OnceLock;

use super::models::{DragPolar, DragPolarTable, TableAerodynamics};
use super::table::{CoefficientTable, GapFill};
use super::{Vehicle, VehicleFileError, VehicleLimits};

/// The clean aerodynamic table (Mooij 1995), `mach,alpha_deg,cl,cd` with empty unpublished
/// cells.
pub const CLEAN_AERO_CSV: &str = include_str!("../../data/horus2b/clean_aero.csv");
/// The per-Mach drag polar (thesis table 8.1), `mach,cd0,k`.
pub const DRAG_POLAR_CSV: &str = include_str!("../../data/horus2b/drag_polar.csv");
const CLEAN_AERO_FILE: &str = "data/horus2b/clean_aero.csv";
const DRAG_POLAR_FILE: &str = "data/horus2b/drag_polar.csv";

/// Mass at entry \[kg\].
pub const MASS_KG: f64 = 26_029.0;
/// Reference area [m^2].
pub const REFERENCE_AREA_M2: f64 = 110.0;
/// Nose radius \[m\].
pub const NOSE_RADIUS_M: f64 = 0.8;

/// Operational limits of HORUS-2B (thesis table 2.1).
#[must_use]
pub fn limits() -> VehicleLimits {
    VehicleLimits {
        heat_flux_w_m2: 500.0e3,
        g_load: 3.0,
        g_load_rate_per_s: 0.5,
        alpha_rate_rad_s: 5.0_f64.to_radians(),
        sigma_rate_rad_s: 15.0_f64.to_radians(),
    }
}

/// Parse one CSV number; empty gives `None`.
fn cell(
    file: &str,
    line_no: usize,
    column: &str,
    s: &str,
) -> Result<Option<f64>, VehicleFileError> {
    let s = s.trim();
    if s.is_empty() {
        return Ok(None);
    }
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map(Some)
        .ok_or_else(|| VehicleFileError::Field {
            file: file.to_string(),
            field: format!("line {line_no} column `{column}`"),
            value: s.to_string(),
            reason: "must be a finite number".to_string(),
        })
}

/// Data lines (1-based line number, fields) after the header.
fn data_lines(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines()
        .enumerate()
        .skip(1)
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|(i, l)| (i + 1, l.split(',').collect()))
}

fn required(
    file: &str,
    line: usize,
    column: &str,
    v: Option<f64>,
) -> Result<f64, VehicleFileError> {
    v.ok_or_else(|| VehicleFileError::Field {
        file: file.to_string(),
        field: format!("line {line} column `{column}`"),
        value: "(empty)".to_string(),
        reason: "required".to_string(),
    })
}

/// Sorted unique values.
fn axis(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The HORUS-2B aerodynamic model with the given gap treatment.
///
/// # Errors
/// Only if the embedded data were malformed (checked by the tests).
pub fn aerodynamics(fill: GapFill) -> Result<TableAerodynamics, VehicleFileError> {
    let mut rows = Vec::new();
    for (line, f) in data_lines(CLEAN_AERO_CSV) {
        let get = |k: usize, name: &str| {
            cell(CLEAN_AERO_FILE, line, name, f.get(k).copied().unwrap_or(""))
        };
        let mach = required(CLEAN_AERO_FILE, line, "mach", get(0, "mach")?)?;
        let alpha = required(CLEAN_AERO_FILE, line, "alpha_deg", get(1, "alpha_deg")?)?;
        rows.push((mach, alpha, get(2, "cl")?, get(3, "cd")?));
    }
    let machs = axis(rows.iter().map(|r| r.0).collect());
    let alphas = axis(rows.iter().map(|r| r.1).collect());
    let mut cl = vec![vec![None; alphas.len()]; machs.len()];
    let mut cd = cl.clone();
    for (m, a, l, d) in &rows {
        let i = machs.partition_point(|x| x < m);
        let j = alphas.partition_point(|x| x < a);
        if let (Some(rl), Some(rd)) = (cl.get_mut(i), cd.get_mut(i))
            && let (Some(cl_ij), Some(cd_ij)) = (rl.get_mut(j), rd.get_mut(j))
        {
            *cl_ij = *l;
            *cd_ij = *d;
        }
    }
    let alpha_rad: Vec<f64> = alphas.iter().map(|a| a.to_radians()).collect();
    let table_err = |e: super::table::TableError| VehicleFileError::Field {
        file: CLEAN_AERO_FILE.to_string(),
        field: "table".to_string(),
        value: String::new(),
        reason: e.to_string(),
    };
    let cl = CoefficientTable::with_gaps("cl", machs.clone(), alpha_rad.clone(), cl, fill)
        .map_err(table_err)?;
    let cd = CoefficientTable::with_gaps("cd", machs, alpha_rad, cd, fill).map_err(table_err)?;
    Ok(TableAerodynamics::new(cl, cd, Some(drag_polar_table()?)))
}

/// The per-Mach drag polar of thesis table 8.1.
///
/// # Errors
/// Only if the embedded data were malformed (checked by the tests).
pub fn drag_polar_table() -> Result<DragPolarTable, VehicleFileError> {
    let mut points = Vec::new();
    for (line, f) in data_lines(DRAG_POLAR_CSV) {
        let get = |k: usize, name: &str| -> Result<f64, VehicleFileError> {
            let v = cell(DRAG_POLAR_FILE, line, name, f.get(k).copied().unwrap_or(""))?;
            required(DRAG_POLAR_FILE, line, name, v)
        };
        points.push((
            get(0, "mach")?,
            DragPolar {
                cd0: get(1, "cd0")?,
                k: get(2, "k")?,
            },
        ));
    }
    DragPolarTable::new(points).ok_or_else(|| VehicleFileError::Field {
        file: DRAG_POLAR_FILE.to_string(),
        field: "mach".to_string(),
        value: String::new(),
        reason: "must be strictly increasing and finite".to_string(),
    })
}

/// The HORUS-2B vehicle (default gap treatment).
///
/// # Errors
/// Only if the embedded data were malformed (checked by the tests).
pub fn vehicle() -> Result<Vehicle, VehicleFileError> {
    Ok(Vehicle {
        name: "horus-2b".to_string(),
        mass_kg: MASS_KG,
        reference_area_m2: REFERENCE_AREA_M2,
        nose_radius_m: NOSE_RADIUS_M,
        limits: limits(),
        aero: Box::new(default_aerodynamics()?),
    })
}

/// [`aerodynamics`] with the default gap treatment, parsed once per process (every closed-loop
/// flight of an optimisation or campaign builds its vehicle) and cloned.
///
/// # Errors
/// As [`aerodynamics`] (then nothing is kept and the error is that of a fresh parse).
fn default_aerodynamics() -> Result<TableAerodynamics, VehicleFileError> {
    static PARSED: OnceLock<Option<TableAerodynamics>> = OnceLock::new();
    match PARSED.get_or_init(|| aerodynamics(GapFill::default()).ok()) {
        Some(a) => Ok(a.clone()),
        None => aerodynamics(GapFill::default()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::Aerodynamics;

    #[test]
    fn embedded_data_parse() {
        let a = aerodynamics(GapFill::default()).unwrap();
        assert_eq!(a.cl().mach(), &[1.2, 1.5, 2.0, 3.0, 5.0, 10.0, 20.0]);
        assert_eq!(a.cl().alpha_rad().len(), 10);
        assert_eq!(drag_polar_table().unwrap().points().len(), 7);
        assert!(vehicle().is_ok());
    }

    #[test]
    fn hold_last_alpha_variant() {
        let a = aerodynamics(GapFill::HoldLastAlpha).unwrap();
        let c = a.coefficients(1.2, 45.0_f64.to_radians());
        assert_eq!(c.cl, 1.17);
        assert_eq!(c.cd, 1.08);
        let c = a.coefficients(1.5, 45.0_f64.to_radians());
        assert_eq!((c.cl, c.cd), (1.38, 1.32));
    }
}
