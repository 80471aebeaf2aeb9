//! User-defined vehicles from TOML files.
//!
//! ```toml
//! name = "my-glider"            # optional (file stem); 1-100 characters, no control characters
//! mass_kg = 1200.0              # [1, 1e7] kg
//! reference_area_m2 = 4.5       # [0.001, 1e4] m^2
//! nose_radius_m = 0.3           # [0.001, 100] m
//!
//! [limits]
//! heat_flux_kw_m2 = 800.0       # [0.001, 1e6] kW/m^2
//! g_load = 4.0                  # [0.001, 1000]
//! g_load_rate_per_s = 1.0       # [1e-6, 1e4] 1/s
//! alpha_rate_deg_s = 5.0        # [0.001, 1000] deg/s
//! sigma_rate_deg_s = 10.0       # [0.001, 1000] deg/s
//!
//! [aero]
//! kind = "table"                # Mach x alpha table, bilinear, clamped at the edges
//! mach = [2.0, 10.0]            # strictly increasing
//! alpha_deg = [0.0, 20.0, 40.0] # strictly increasing
//! cl = [[0.0, 0.4, 0.8], [0.0, 0.3, 0.6]]     # one row per Mach number
//! cd = [[0.1, 0.2, 0.5], [0.08, 0.15, 0.4]]   # every entry > 0
//! ```
//!
//! Drag must be positive wherever it is used (a vehicle with negative drag gains energy):
//! every tabulated `cd`; a polynomial `cd` sampled over its declared alpha range
//! (`alpha_min_deg..alpha_max_deg`, or the guidance range 0..45 deg without clamps); the drag
//! polar's `cd0 > 0`, `k >= 0`; the trim `cd > 0`.
//!
//! Other `[aero]` kinds (Mach-independent):
//! * `kind = "polynomial"`: `cl = [c0, c1, ...]`, `cd = [d0, d1, ...]`, C = sum c_i alpha_deg^i;
//!   optional `alpha_min_deg`, `alpha_max_deg` clamp alpha.
//! * `kind = "drag_polar"`: `cd0`, `k` (C_D = cd0 + k C_L^2) and `cl = [c0, c1, ...]` (C_L
//!   polynomial in alpha_deg); optional alpha clamps.
//! * `kind = "trim"`: fixed `cl`, `cd` (bank-angle control only).
//!
//! The file is read through host-sim's one TOML reading path ([`crate::toml_input`]) into
//! serde structs that reject unknown fields (a misspelt field would otherwise be silently
//! ignored), then range-checked. Every error names the file, the field (dotted path) and the
//! offending value, e.g. `vehicle.toml: field `mass_kg` = -3: must be positive`.

use serde::Deserialize;
use toml::Table;

use super::models::{
    DragPolar, PolarAerodynamics, PolynomialAerodynamics, TableAerodynamics, TrimAerodynamics,
};
use super::table::CoefficientTable;
use super::{AeroCoefficients, Aerodynamics, Vehicle, VehicleFileError, VehicleLimits};
use crate::num_fmt::compact;
use crate::toml_input::{Num, TomlInputError, shown};

/// The whole file (required fields are `Option` so a missing one is reported as such).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct VehicleFile {
    name: Option<String>,
    mass_kg: Option<Num>,
    reference_area_m2: Option<Num>,
    nose_radius_m: Option<Num>,
    limits: Option<LimitsFile>,
    aero: Option<AeroFile>,
}

/// `[limits]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LimitsFile {
    heat_flux_kw_m2: Option<Num>,
    g_load: Option<Num>,
    g_load_rate_per_s: Option<Num>,
    alpha_rate_deg_s: Option<Num>,
    sigma_rate_deg_s: Option<Num>,
}

/// `[aero]` kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
enum AeroKind {
    Table,
    Polynomial,
    DragPolar,
    Trim,
}

/// A coefficient entry: a number (trim), a list (polynomial) or rows (table).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Coef {
    Number(Num),
    List(Vec<Num>),
    Rows(Vec<Vec<Num>>),
}

/// `[aero]`: the union of every kind's keys; each kind checks it has only its own.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AeroFile {
    kind: Option<AeroKind>,
    mach: Option<Vec<Num>>,
    alpha_deg: Option<Vec<Num>>,
    cl: Option<Coef>,
    cd: Option<Coef>,
    cd0: Option<Num>,
    k: Option<Num>,
    alpha_min_deg: Option<Num>,
    alpha_max_deg: Option<Num>,
}

impl AeroFile {
    /// The keys present.
    fn present(&self) -> Vec<&'static str> {
        let mut p = vec!["kind"];
        for (k, there) in [
            ("mach", self.mach.is_some()),
            ("alpha_deg", self.alpha_deg.is_some()),
            ("cl", self.cl.is_some()),
            ("cd", self.cd.is_some()),
            ("cd0", self.cd0.is_some()),
            ("k", self.k.is_some()),
            ("alpha_min_deg", self.alpha_min_deg.is_some()),
            ("alpha_max_deg", self.alpha_max_deg.is_some()),
        ] {
            if there {
                p.push(k);
            }
        }
        p
    }
}

/// Range checks against the parsed document (to show values as written).
struct Ctx<'a> {
    file: &'a str,
    doc: &'a Table,
}

impl Ctx<'_> {
    fn err(
        &self,
        field: &str,
        value: impl Into<String>,
        reason: impl Into<String>,
    ) -> VehicleFileError {
        VehicleFileError::Field {
            file: self.file.to_string(),
            field: field.to_string(),
            value: value.into(),
            reason: reason.into(),
        }
    }

    /// The error naming `field` with its value as written.
    fn bad(&self, field: &str, reason: impl Into<String>) -> VehicleFileError {
        self.err(field, shown(self.doc, field), reason)
    }

    fn required<T>(&self, field: &str, v: Option<T>) -> Result<T, VehicleFileError> {
        v.ok_or_else(|| self.err(field, "(missing)", "required"))
    }

    fn finite(&self, field: &str, v: Num) -> Result<f64, VehicleFileError> {
        if v.0.is_finite() {
            Ok(v.0)
        } else {
            Err(self.bad(field, "must be finite"))
        }
    }

    fn number(&self, field: &str, v: Option<Num>) -> Result<f64, VehicleFileError> {
        let v = self.required(field, v)?;
        self.finite(field, v)
    }

    fn opt_number(&self, field: &str, v: Option<Num>) -> Result<Option<f64>, VehicleFileError> {
        v.map(|x| self.finite(field, x)).transpose()
    }

    fn positive(&self, field: &str, v: Option<Num>) -> Result<f64, VehicleFileError> {
        let x = self.number(field, v)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.err(field, compact(x), "must be positive"))
        }
    }

    /// A number of `field` in `[lo, hi]` (`unit` for the message).
    fn ranged(
        &self,
        field: &str,
        v: Option<Num>,
        (lo, hi): (f64, f64),
        unit: &str,
    ) -> Result<f64, VehicleFileError> {
        let x = self.number(field, v)?;
        if (lo..=hi).contains(&x) {
            Ok(x)
        } else {
            Err(self.err(
                field,
                compact(x),
                format!("must be in [{}, {}]{unit}", compact(lo), compact(hi)),
            ))
        }
    }

    /// Drag must be positive everywhere it is used: every entry of a table, or a polynomial
    /// sampled over its declared alpha range (the clamps, or the guidance range 0..45 deg
    /// without them).
    fn positive_drag_poly(
        &self,
        cd: &[f64],
        (lo, hi): (Option<f64>, Option<f64>),
    ) -> Result<(), VehicleFileError> {
        let (lo, hi) = (lo.unwrap_or(0.0), hi.unwrap_or(45.0));
        let n = 1000;
        for i in 0..=n {
            let a = lo + (hi - lo) * f64::from(i) / f64::from(n);
            let v = cd.iter().rev().fold(0.0, |acc, c| acc * a + c);
            if !(v.is_finite() && v > 0.0) {
                return Err(self.bad(
                    "aero.cd",
                    format!(
                        "drag coefficient must be positive over alpha in [{}, {}] deg: \
                         C_D({} deg) = {}",
                        compact(lo),
                        compact(hi),
                        compact(a),
                        compact(v)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A lift polynomial must be finite over its declared alpha range (the clamps, or the
    /// guidance range 0..45 deg without them), and so must the drag polar built on it
    /// (`k`: its induced-drag factor, 0 for a polynomial drag).
    fn finite_lift_poly(
        &self,
        cl: &[f64],
        k: f64,
        (lo, hi): (Option<f64>, Option<f64>),
    ) -> Result<(), VehicleFileError> {
        let (lo, hi) = (lo.unwrap_or(0.0), hi.unwrap_or(45.0));
        let n = 1000;
        for i in 0..=n {
            let a = lo + (hi - lo) * f64::from(i) / f64::from(n);
            let v = cl.iter().rev().fold(0.0, |acc, c| acc * a + c);
            if !(v.is_finite() && (k * v * v).is_finite()) {
                return Err(self.bad(
                    "aero.cl",
                    format!(
                        "lift coefficient must be finite over alpha in [{}, {}] deg: \
                         C_L({} deg) = {}",
                        compact(lo),
                        compact(hi),
                        compact(a),
                        compact(v)
                    ),
                ));
            }
        }
        Ok(())
    }

    fn non_negative(&self, field: &str, v: Option<Num>) -> Result<f64, VehicleFileError> {
        let x = self.number(field, v)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(self.err(field, compact(x), "must not be negative"))
        }
    }

    fn numbers(&self, field: &str, xs: &[Num]) -> Result<Vec<f64>, VehicleFileError> {
        xs.iter()
            .enumerate()
            .map(|(i, x)| self.finite(&format!("{field}[{i}]"), *x))
            .collect()
    }

    fn list(&self, field: &str, v: Option<&[Num]>) -> Result<Vec<f64>, VehicleFileError> {
        let xs = self.numbers(field, self.required(field, v)?)?;
        if xs.is_empty() {
            return Err(self.bad(field, "must not be empty"));
        }
        Ok(xs)
    }

    fn increasing(&self, field: &str, v: Option<&[Num]>) -> Result<Vec<f64>, VehicleFileError> {
        let xs = self.list(field, v)?;
        if xs.windows(2).all(|w| matches!(w, [a, b] if b > a)) {
            Ok(xs)
        } else {
            Err(self.bad(field, "must be strictly increasing"))
        }
    }

    /// A coefficient list (polynomial kinds).
    fn coef_list(&self, field: &str, c: Option<&Coef>) -> Result<Vec<f64>, VehicleFileError> {
        match self.required(field, c)? {
            Coef::List(xs) => self.list(field, Some(xs)),
            _ => Err(self.bad(field, "must be an array of numbers")),
        }
    }

    /// A coefficient number (trim kind).
    fn coef_number(&self, field: &str, c: Option<&Coef>) -> Result<Num, VehicleFileError> {
        match self.required(field, c)? {
            Coef::Number(x) => Ok(*x),
            _ => Err(self.bad(field, "must be a number")),
        }
    }

    /// Mach x alpha rows: `rows` arrays of `cols` numbers each.
    fn rows(
        &self,
        field: &str,
        c: Option<&Coef>,
        rows: usize,
        cols: usize,
    ) -> Result<Vec<Vec<f64>>, VehicleFileError> {
        let rs: Vec<Vec<Num>> = match self.required(field, c)? {
            Coef::Rows(r) => r.clone(),
            // An empty array parses as a list.
            Coef::List(l) if l.is_empty() => Vec::new(),
            _ => return Err(self.bad(field, "must be an array of rows")),
        };
        if rs.len() != rows {
            return Err(self.bad(
                field,
                format!(
                    "must have {rows} rows (one per Mach number), found {}",
                    rs.len()
                ),
            ));
        }
        rs.iter()
            .enumerate()
            .map(|(i, r)| {
                let f = format!("{field}[{i}]");
                let xs = self.numbers(&f, r)?;
                if xs.len() == cols {
                    Ok(xs)
                } else {
                    Err(self.bad(
                        &f,
                        format!(
                            "must have {cols} values (one per alpha), found {}",
                            xs.len()
                        ),
                    ))
                }
            })
            .collect()
    }

    fn alpha_clamps(&self, a: &AeroFile) -> Result<(Option<f64>, Option<f64>), VehicleFileError> {
        let lo = self.opt_number("aero.alpha_min_deg", a.alpha_min_deg)?;
        let hi = self.opt_number("aero.alpha_max_deg", a.alpha_max_deg)?;
        if let (Some(l), Some(h)) = (lo, hi)
            && h < l
        {
            return Err(self.bad(
                "aero.alpha_max_deg",
                "must not be below `aero.alpha_min_deg`",
            ));
        }
        Ok((lo, hi))
    }

    /// Reject keys of `[aero]` that the kind does not use.
    fn only(&self, a: &AeroFile, kind: &str, allowed: &[&str]) -> Result<(), VehicleFileError> {
        match a.present().into_iter().find(|k| !allowed.contains(k)) {
            Some(k) => Err(self.bad(
                &format!("aero.{k}"),
                format!(
                    "unknown field for kind \"{kind}\" (expected one of: {})",
                    allowed.join(", ")
                ),
            )),
            None => Ok(()),
        }
    }
}

fn aero(ctx: &Ctx<'_>, a: &AeroFile) -> Result<Box<dyn Aerodynamics>, VehicleFileError> {
    match ctx.required("aero.kind", a.kind)? {
        AeroKind::Table => {
            ctx.only(a, "table", &["kind", "mach", "alpha_deg", "cl", "cd"])?;
            let mach = ctx.increasing("aero.mach", a.mach.as_deref())?;
            let alpha_deg = ctx.increasing("aero.alpha_deg", a.alpha_deg.as_deref())?;
            let cl = ctx.rows("aero.cl", a.cl.as_ref(), mach.len(), alpha_deg.len())?;
            let cd = ctx.rows("aero.cd", a.cd.as_ref(), mach.len(), alpha_deg.len())?;
            for (i, row) in cd.iter().enumerate() {
                if let Some(j) = row.iter().position(|v| *v <= 0.0) {
                    return Err(ctx.err(
                        &format!("aero.cd[{i}][{j}]"),
                        compact(row[j]),
                        "drag coefficients must be positive",
                    ));
                }
            }
            let alpha_rad: Vec<f64> = alpha_deg.iter().map(|a| a.to_radians()).collect();
            let table_err = |e: super::table::TableError| ctx.err("aero", "(table)", e.to_string());
            Ok(Box::new(TableAerodynamics::new(
                CoefficientTable::new("cl", mach.clone(), alpha_rad.clone(), cl)
                    .map_err(table_err)?,
                CoefficientTable::new("cd", mach, alpha_rad, cd).map_err(table_err)?,
                None,
            )))
        }
        AeroKind::Polynomial => {
            ctx.only(
                a,
                "polynomial",
                &["kind", "cl", "cd", "alpha_min_deg", "alpha_max_deg"],
            )?;
            let (alpha_min_deg, alpha_max_deg) = ctx.alpha_clamps(a)?;
            let cd = ctx.coef_list("aero.cd", a.cd.as_ref())?;
            ctx.positive_drag_poly(&cd, (alpha_min_deg, alpha_max_deg))?;
            let cl = ctx.coef_list("aero.cl", a.cl.as_ref())?;
            ctx.finite_lift_poly(&cl, 0.0, (alpha_min_deg, alpha_max_deg))?;
            Ok(Box::new(PolynomialAerodynamics {
                cl,
                cd,
                alpha_min_deg,
                alpha_max_deg,
            }))
        }
        AeroKind::DragPolar => {
            ctx.only(
                a,
                "drag_polar",
                &["kind", "cd0", "k", "cl", "alpha_min_deg", "alpha_max_deg"],
            )?;
            let (alpha_min_deg, alpha_max_deg) = ctx.alpha_clamps(a)?;
            let polar = DragPolar {
                cd0: ctx.positive("aero.cd0", a.cd0)?,
                k: ctx.non_negative("aero.k", a.k)?,
            };
            let cl = ctx.coef_list("aero.cl", a.cl.as_ref())?;
            ctx.finite_lift_poly(&cl, polar.k, (alpha_min_deg, alpha_max_deg))?;
            Ok(Box::new(PolarAerodynamics {
                polar,
                cl,
                alpha_min_deg,
                alpha_max_deg,
            }))
        }
        AeroKind::Trim => {
            ctx.only(a, "trim", &["kind", "cl", "cd"])?;
            let cl = ctx.coef_number("aero.cl", a.cl.as_ref())?;
            let cd = ctx.coef_number("aero.cd", a.cd.as_ref())?;
            Ok(Box::new(TrimAerodynamics {
                trim: AeroCoefficients {
                    cl: ctx.number("aero.cl", Some(cl))?,
                    cd: ctx.positive("aero.cd", Some(cd))?,
                },
            }))
        }
    }
}

/// Parse a vehicle from TOML text; `file` names the source in error messages.
///
/// # Errors
/// [`VehicleFileError::Toml`] for malformed TOML, [`VehicleFileError::Field`] for a missing,
/// mistyped, out-of-range or unknown field (naming file, field and value).
pub fn from_toml_str(text: &str, file: &str) -> Result<Vehicle, VehicleFileError> {
    let (vf, doc): (VehicleFile, Table) = crate::toml_input::parse(text).map_err(|e| match e {
        TomlInputError::Syntax(source) => VehicleFileError::Toml {
            file: file.to_string(),
            source,
        },
        TomlInputError::Field {
            field,
            value,
            reason,
        } => VehicleFileError::Field {
            file: file.to_string(),
            field,
            value,
            reason,
        },
    })?;
    let ctx = Ctx { file, doc: &doc };
    let name = match vf.name {
        None => std::path::Path::new(file)
            .file_stem()
            .map_or_else(|| file.to_string(), |s| s.to_string_lossy().into_owned()),
        Some(s) => match crate::toml_input::check_name(&s) {
            Ok(()) => s,
            Err(reason) => return Err(ctx.err("name", format!("{s:?}"), reason)),
        },
    };
    let mass_kg = ctx.ranged("mass_kg", vf.mass_kg, (1.0, 1e7), " kg")?;
    let reference_area_m2 = ctx.ranged(
        "reference_area_m2",
        vf.reference_area_m2,
        (1e-3, 1e4),
        " m^2",
    )?;
    let nose_radius_m = ctx.ranged("nose_radius_m", vf.nose_radius_m, (1e-3, 100.0), " m")?;
    let lim = ctx.required("limits", vf.limits)?;
    let limits = VehicleLimits {
        heat_flux_w_m2: ctx.ranged(
            "limits.heat_flux_kw_m2",
            lim.heat_flux_kw_m2,
            (1e-3, 1e6),
            " kW/m^2",
        )? * 1.0e3,
        g_load: ctx.ranged("limits.g_load", lim.g_load, (1e-3, 1e3), "")?,
        g_load_rate_per_s: ctx.ranged(
            "limits.g_load_rate_per_s",
            lim.g_load_rate_per_s,
            (1e-6, 1e4),
            " 1/s",
        )?,
        alpha_rate_rad_s: ctx
            .ranged(
                "limits.alpha_rate_deg_s",
                lim.alpha_rate_deg_s,
                (1e-3, 1e3),
                " deg/s",
            )?
            .to_radians(),
        sigma_rate_rad_s: ctx
            .ranged(
                "limits.sigma_rate_deg_s",
                lim.sigma_rate_deg_s,
                (1e-3, 1e3),
                " deg/s",
            )?
            .to_radians(),
    };
    let aero = aero(&ctx, &ctx.required("aero", vf.aero)?)?;
    Ok(Vehicle {
        name,
        mass_kg,
        reference_area_m2,
        nose_radius_m,
        limits,
        aero,
    })
}

/// Read and parse a vehicle TOML file.
///
/// # Errors
/// [`VehicleFileError::Io`] if the file cannot be read, otherwise as [`from_toml_str`].
pub fn from_toml_file(path: &std::path::Path) -> Result<Vehicle, VehicleFileError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| VehicleFileError::Io {
        file: file.clone(),
        source,
    })?;
    from_toml_str(&text, &file)
}
