//! User-defined vehicles from TOML files.
//!
//! ```toml
//! name = "my-glider"            # optional; defaults to the file stem
//! mass_kg = 1200.0
//! reference_area_m2 = 4.5
//! nose_radius_m = 0.3
//!
//! [limits]
//! heat_flux_kw_m2 = 800.0
//! g_load = 4.0
//! g_load_rate_per_s = 1.0
//! alpha_rate_deg_s = 5.0
//! sigma_rate_deg_s = 10.0
//!
//! [aero]
//! kind = "table"                # Mach x alpha table, bilinear, clamped at the edges
//! mach = [2.0, 10.0]            # strictly increasing
//! alpha_deg = [0.0, 20.0, 40.0] # strictly increasing
//! cl = [[0.0, 0.4, 0.8], [0.0, 0.3, 0.6]]     # one row per Mach number
//! cd = [[0.1, 0.2, 0.5], [0.08, 0.15, 0.4]]
//! ```
//!
//! Other `[aero]` kinds (Mach-independent):
//! * `kind = "polynomial"`: `cl = [c0, c1, ...]`, `cd = [d0, d1, ...]`, C = sum c_i alpha_deg^i;
//!   optional `alpha_min_deg`, `alpha_max_deg` clamp alpha.
//! * `kind = "drag_polar"`: `cd0`, `k` (C_D = cd0 + k C_L^2) and `cl = [c0, c1, ...]` (C_L
//!   polynomial in alpha_deg); optional alpha clamps.
//! * `kind = "trim"`: fixed `cl`, `cd` (bank-angle control only).
//!
//! Every error names the file, the field (dotted path) and the offending value, e.g.
//! `vehicle.toml: field `mass_kg` = -3: must be positive`. Unknown fields are rejected (a
//! misspelt field would otherwise be silently ignored).

use super::models::{
    DragPolar, PolarAerodynamics, PolynomialAerodynamics, TableAerodynamics, TrimAerodynamics,
};
use super::table::CoefficientTable;
use super::{AeroCoefficients, Aerodynamics, Vehicle, VehicleFileError, VehicleLimits};
use toml::{Table, Value};

/// Field-access context: file name for error messages.
struct Ctx<'a> {
    file: &'a str,
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

    fn path(prefix: &str, key: &str) -> String {
        if prefix.is_empty() {
            key.to_string()
        } else {
            format!("{prefix}.{key}")
        }
    }

    fn get<'t>(
        &self,
        t: &'t Table,
        prefix: &str,
        key: &str,
    ) -> Result<&'t Value, VehicleFileError> {
        t.get(key)
            .ok_or_else(|| self.err(&Self::path(prefix, key), "(missing)", "required"))
    }

    fn number(&self, field: &str, v: &Value) -> Result<f64, VehicleFileError> {
        let x = match v {
            Value::Float(f) => *f,
            Value::Integer(i) => *i as f64,
            other => return Err(self.err(field, other.to_string(), "must be a number")),
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err(field, v.to_string(), "must be finite"))
        }
    }

    fn f64(&self, t: &Table, prefix: &str, key: &str) -> Result<f64, VehicleFileError> {
        self.number(&Self::path(prefix, key), self.get(t, prefix, key)?)
    }

    fn opt_f64(&self, t: &Table, prefix: &str, key: &str) -> Result<Option<f64>, VehicleFileError> {
        t.get(key)
            .map(|v| self.number(&Self::path(prefix, key), v))
            .transpose()
    }

    fn positive(&self, t: &Table, prefix: &str, key: &str) -> Result<f64, VehicleFileError> {
        let x = self.f64(t, prefix, key)?;
        if x > 0.0 {
            Ok(x)
        } else {
            let v = self.get(t, prefix, key)?;
            Err(self.err(&Self::path(prefix, key), v.to_string(), "must be positive"))
        }
    }

    fn non_negative(&self, t: &Table, prefix: &str, key: &str) -> Result<f64, VehicleFileError> {
        let x = self.f64(t, prefix, key)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            let v = self.get(t, prefix, key)?;
            Err(self.err(
                &Self::path(prefix, key),
                v.to_string(),
                "must not be negative",
            ))
        }
    }

    fn table<'t>(
        &self,
        t: &'t Table,
        prefix: &str,
        key: &str,
    ) -> Result<&'t Table, VehicleFileError> {
        let field = Self::path(prefix, key);
        match self.get(t, prefix, key)? {
            Value::Table(inner) => Ok(inner),
            other => Err(self.err(&field, other.to_string(), "must be a table")),
        }
    }

    fn array<'t>(&self, field: &str, v: &'t Value) -> Result<&'t Vec<Value>, VehicleFileError> {
        match v {
            Value::Array(a) => Ok(a),
            other => Err(self.err(field, other.to_string(), "must be an array")),
        }
    }

    fn numbers(&self, field: &str, v: &Value) -> Result<Vec<f64>, VehicleFileError> {
        let a = self.array(field, v)?;
        a.iter()
            .enumerate()
            .map(|(i, x)| self.number(&format!("{field}[{i}]"), x))
            .collect()
    }

    fn num_array(&self, t: &Table, prefix: &str, key: &str) -> Result<Vec<f64>, VehicleFileError> {
        let field = Self::path(prefix, key);
        let v = self.get(t, prefix, key)?;
        let xs = self.numbers(&field, v)?;
        if xs.is_empty() {
            return Err(self.err(&field, v.to_string(), "must not be empty"));
        }
        Ok(xs)
    }

    fn increasing(&self, t: &Table, prefix: &str, key: &str) -> Result<Vec<f64>, VehicleFileError> {
        let xs = self.num_array(t, prefix, key)?;
        if xs.windows(2).all(|w| matches!(w, [a, b] if b > a)) {
            Ok(xs)
        } else {
            let v = self.get(t, prefix, key)?;
            Err(self.err(
                &Self::path(prefix, key),
                v.to_string(),
                "must be strictly increasing",
            ))
        }
    }

    fn reject_unknown(
        &self,
        t: &Table,
        prefix: &str,
        known: &[&str],
    ) -> Result<(), VehicleFileError> {
        match t.iter().find(|(k, _)| !known.contains(&k.as_str())) {
            Some((k, v)) => Err(self.err(
                &Self::path(prefix, k),
                v.to_string(),
                format!("unknown field (expected one of: {})", known.join(", ")),
            )),
            None => Ok(()),
        }
    }

    /// Mach x alpha rows: `rows` arrays of `cols` numbers each.
    fn rows(
        &self,
        t: &Table,
        prefix: &str,
        key: &str,
        rows: usize,
        cols: usize,
    ) -> Result<Vec<Vec<f64>>, VehicleFileError> {
        let field = Self::path(prefix, key);
        let v = self.get(t, prefix, key)?;
        let a = self.array(&field, v)?;
        if a.len() != rows {
            return Err(self.err(
                &field,
                v.to_string(),
                format!(
                    "must have {rows} rows (one per Mach number), found {}",
                    a.len()
                ),
            ));
        }
        a.iter()
            .enumerate()
            .map(|(i, r)| {
                let f = format!("{field}[{i}]");
                let xs = self.numbers(&f, r)?;
                if xs.len() == cols {
                    Ok(xs)
                } else {
                    Err(self.err(
                        &f,
                        r.to_string(),
                        format!(
                            "must have {cols} values (one per alpha), found {}",
                            xs.len()
                        ),
                    ))
                }
            })
            .collect()
    }

    fn alpha_clamps(&self, t: &Table) -> Result<(Option<f64>, Option<f64>), VehicleFileError> {
        let lo = self.opt_f64(t, "aero", "alpha_min_deg")?;
        let hi = self.opt_f64(t, "aero", "alpha_max_deg")?;
        if let (Some(l), Some(h)) = (lo, hi)
            && h < l
        {
            let v = t
                .get("alpha_max_deg")
                .map(Value::to_string)
                .unwrap_or_default();
            return Err(self.err(
                "aero.alpha_max_deg",
                v,
                "must not be below `aero.alpha_min_deg`",
            ));
        }
        Ok((lo, hi))
    }
}

fn aero(ctx: &Ctx<'_>, t: &Table) -> Result<Box<dyn Aerodynamics>, VehicleFileError> {
    let kind_v = ctx.get(t, "aero", "kind")?;
    let kind = match kind_v {
        Value::String(s) => s.as_str(),
        other => return Err(ctx.err("aero.kind", other.to_string(), "must be a string")),
    };
    const KINDS: &str = "expected \"table\", \"polynomial\", \"drag_polar\" or \"trim\"";
    match kind {
        "table" => {
            ctx.reject_unknown(t, "aero", &["kind", "mach", "alpha_deg", "cl", "cd"])?;
            let mach = ctx.increasing(t, "aero", "mach")?;
            let alpha_deg = ctx.increasing(t, "aero", "alpha_deg")?;
            let cl = ctx.rows(t, "aero", "cl", mach.len(), alpha_deg.len())?;
            let cd = ctx.rows(t, "aero", "cd", mach.len(), alpha_deg.len())?;
            let alpha_rad: Vec<f64> = alpha_deg.iter().map(|a| a.to_radians()).collect();
            let table_err = |e: super::table::TableError| ctx.err("aero", "(table)", e.to_string());
            Ok(Box::new(TableAerodynamics {
                cl: CoefficientTable::new("cl", mach.clone(), alpha_rad.clone(), cl)
                    .map_err(table_err)?,
                cd: CoefficientTable::new("cd", mach, alpha_rad, cd).map_err(table_err)?,
                polar: None,
            }))
        }
        "polynomial" => {
            ctx.reject_unknown(
                t,
                "aero",
                &["kind", "cl", "cd", "alpha_min_deg", "alpha_max_deg"],
            )?;
            let (alpha_min_deg, alpha_max_deg) = ctx.alpha_clamps(t)?;
            Ok(Box::new(PolynomialAerodynamics {
                cl: ctx.num_array(t, "aero", "cl")?,
                cd: ctx.num_array(t, "aero", "cd")?,
                alpha_min_deg,
                alpha_max_deg,
            }))
        }
        "drag_polar" => {
            ctx.reject_unknown(
                t,
                "aero",
                &["kind", "cd0", "k", "cl", "alpha_min_deg", "alpha_max_deg"],
            )?;
            let (alpha_min_deg, alpha_max_deg) = ctx.alpha_clamps(t)?;
            Ok(Box::new(PolarAerodynamics {
                polar: DragPolar {
                    cd0: ctx.positive(t, "aero", "cd0")?,
                    k: ctx.non_negative(t, "aero", "k")?,
                },
                cl: ctx.num_array(t, "aero", "cl")?,
                alpha_min_deg,
                alpha_max_deg,
            }))
        }
        "trim" => {
            ctx.reject_unknown(t, "aero", &["kind", "cl", "cd"])?;
            Ok(Box::new(TrimAerodynamics {
                trim: AeroCoefficients {
                    cl: ctx.f64(t, "aero", "cl")?,
                    cd: ctx.positive(t, "aero", "cd")?,
                },
            }))
        }
        _ => Err(ctx.err("aero.kind", kind_v.to_string(), KINDS)),
    }
}

/// Parse a vehicle from TOML text; `file` names the source in error messages.
///
/// # Errors
/// [`VehicleFileError::Toml`] for malformed TOML, [`VehicleFileError::Field`] for a missing,
/// mistyped, out-of-range or unknown field (naming file, field and value).
pub fn from_toml_str(text: &str, file: &str) -> Result<Vehicle, VehicleFileError> {
    let doc: Table = text
        .parse()
        .map_err(|e: toml::de::Error| VehicleFileError::Toml {
            file: file.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
    let ctx = Ctx { file };
    ctx.reject_unknown(
        &doc,
        "",
        &[
            "name",
            "mass_kg",
            "reference_area_m2",
            "nose_radius_m",
            "limits",
            "aero",
        ],
    )?;
    let name = match doc.get("name") {
        None => std::path::Path::new(file)
            .file_stem()
            .map_or_else(|| file.to_string(), |s| s.to_string_lossy().into_owned()),
        Some(Value::String(s)) if !s.trim().is_empty() => s.clone(),
        Some(other) => {
            return Err(ctx.err("name", other.to_string(), "must be a non-empty string"));
        }
    };
    let mass_kg = ctx.positive(&doc, "", "mass_kg")?;
    let reference_area_m2 = ctx.positive(&doc, "", "reference_area_m2")?;
    let nose_radius_m = ctx.positive(&doc, "", "nose_radius_m")?;
    let lim = ctx.table(&doc, "", "limits")?;
    ctx.reject_unknown(
        lim,
        "limits",
        &[
            "heat_flux_kw_m2",
            "g_load",
            "g_load_rate_per_s",
            "alpha_rate_deg_s",
            "sigma_rate_deg_s",
        ],
    )?;
    let limits = VehicleLimits {
        heat_flux_w_m2: ctx.positive(lim, "limits", "heat_flux_kw_m2")? * 1.0e3,
        g_load: ctx.positive(lim, "limits", "g_load")?,
        g_load_rate_per_s: ctx.positive(lim, "limits", "g_load_rate_per_s")?,
        alpha_rate_rad_s: ctx
            .positive(lim, "limits", "alpha_rate_deg_s")?
            .to_radians(),
        sigma_rate_rad_s: ctx
            .positive(lim, "limits", "sigma_rate_deg_s")?
            .to_radians(),
    };
    let aero = aero(&ctx, ctx.table(&doc, "", "aero")?)?;
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
    let text = std::fs::read_to_string(path).map_err(|e| VehicleFileError::Io {
        file: file.clone(),
        message: e.to_string(),
    })?;
    from_toml_str(&text, &file)
}
