//! Aerodynamic model implementations: Mach x alpha tables, polynomials in alpha, parabolic
//! drag polars and fixed trim coefficients.

use super::table::CoefficientTable;
use super::{AeroCoefficients, Aerodynamics};

pub use super::types::DragPolar;

/// Drag polars tabulated against Mach, interpolated linearly in Mach (as the thesis does,
/// sec. 8.1.2) and clamped to the first/last Mach number.
#[derive(Clone, Debug, PartialEq)]
pub struct DragPolarTable {
    /// (Mach, polar), Mach strictly increasing, at least one entry.
    points: Vec<(f64, DragPolar)>,
}

impl DragPolarTable {
    /// From (Mach, polar) points; `None` if empty, not strictly increasing in Mach or not
    /// finite.
    #[must_use]
    pub fn new(points: Vec<(f64, DragPolar)>) -> Option<Self> {
        let finite = points
            .iter()
            .all(|(m, p)| m.is_finite() && p.cd0.is_finite() && p.k.is_finite());
        let increasing = points.windows(2).all(|w| matches!(w, [a, b] if b.0 > a.0));
        (finite && increasing && !points.is_empty()).then_some(Self { points })
    }

    /// Polar at Mach `mach` (clamped; NaN Mach gives NaN coefficients).
    #[must_use]
    pub fn at_mach(&self, mach: f64) -> DragPolar {
        let nan = DragPolar {
            cd0: f64::NAN,
            k: f64::NAN,
        };
        let (Some(first), Some(last)) = (self.points.first(), self.points.last()) else {
            return nan;
        };
        if mach.is_nan() {
            return nan;
        }
        if mach <= first.0 {
            return first.1;
        }
        if mach >= last.0 {
            return last.1;
        }
        for w in self.points.windows(2) {
            if let [(m0, p0), (m1, p1)] = w
                && mach <= *m1
            {
                let f = (mach - m0) / (m1 - m0);
                return DragPolar {
                    cd0: p0.cd0 + f * (p1.cd0 - p0.cd0),
                    k: p0.k + f * (p1.k - p0.k),
                };
            }
        }
        last.1
    }

    /// The tabulated points.
    #[must_use]
    pub fn points(&self) -> &[(f64, DragPolar)] {
        &self.points
    }
}

/// Tabulated aerodynamics: C_L and C_D tables over Mach x alpha (bilinear, clamped at the
/// edges), with an optional per-Mach drag polar for the analytical methods.
#[derive(Clone, Debug)]
pub struct TableAerodynamics {
    cl: CoefficientTable,
    cd: CoefficientTable,
    polar: Option<DragPolarTable>,
    /// Whether `cl` and `cd` share their axes (decided once: the right-hand side looks the
    /// coefficients up thousands of times per flight).
    shared_axes: bool,
}

impl TableAerodynamics {
    /// Tabulated aerodynamics from a C_L table `cl`, a C_D table `cd` and, if known, the
    /// per-Mach drag polar `polar`.
    #[must_use]
    pub fn new(cl: CoefficientTable, cd: CoefficientTable, polar: Option<DragPolarTable>) -> Self {
        let shared_axes = cl.same_axes(&cd);
        Self {
            cl,
            cd,
            polar,
            shared_axes,
        }
    }

    /// The C_L table.
    #[must_use]
    pub fn cl(&self) -> &CoefficientTable {
        &self.cl
    }

    /// The C_D table.
    #[must_use]
    pub fn cd(&self) -> &CoefficientTable {
        &self.cd
    }

    /// The per-Mach drag polar, if known.
    #[must_use]
    pub fn polar(&self) -> Option<&DragPolarTable> {
        self.polar.as_ref()
    }
}

impl Aerodynamics for TableAerodynamics {
    fn coefficients(&self, mach: f64, alpha_rad: f64) -> AeroCoefficients {
        // One grid lookup for both coefficients when the tables share their axes (the
        // built-in and file tables do); the values are those of two separate lookups.
        let cell = self.cl.cell(mach, alpha_rad);
        let cd = if self.shared_axes {
            self.cd.value_in(&cell)
        } else {
            self.cd.value(mach, alpha_rad)
        };
        AeroCoefficients {
            cl: self.cl.value_in(&cell),
            cd,
        }
    }

    fn drag_polar(&self, mach: f64) -> Option<DragPolar> {
        self.polar.as_ref().map(|p| p.at_mach(mach))
    }
}

/// Evaluate a polynomial sum c_i x^i (Horner).
fn poly(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, ci| acc * x + ci)
}

/// Clamp alpha [deg] to the optional range (NaN passes through).
fn clamp_alpha(alpha_deg: f64, min_deg: Option<f64>, max_deg: Option<f64>) -> f64 {
    let a = min_deg.map_or(alpha_deg, |m| if alpha_deg < m { m } else { alpha_deg });
    max_deg.map_or(a, |m| if a > m { m } else { a })
}

/// Mach-independent polynomials in the angle of attack in degrees:
/// C_L = sum cl\[i\] alpha_deg^i, C_D = sum cd\[i\] alpha_deg^i, alpha optionally clamped.
#[derive(Clone, Debug, PartialEq)]
pub struct PolynomialAerodynamics {
    /// C_L coefficients, constant term first (per deg^i).
    pub cl: Vec<f64>,
    /// C_D coefficients, constant term first (per deg^i).
    pub cd: Vec<f64>,
    /// Lower alpha clamp \[deg\], if any.
    pub alpha_min_deg: Option<f64>,
    /// Upper alpha clamp \[deg\], if any.
    pub alpha_max_deg: Option<f64>,
}

impl Aerodynamics for PolynomialAerodynamics {
    fn coefficients(&self, _mach: f64, alpha_rad: f64) -> AeroCoefficients {
        let a = clamp_alpha(
            alpha_rad.to_degrees(),
            self.alpha_min_deg,
            self.alpha_max_deg,
        );
        AeroCoefficients {
            cl: poly(&self.cl, a),
            cd: poly(&self.cd, a),
        }
    }
}

/// Mach-independent drag polar with C_L a polynomial in alpha \[deg\]:
/// C_L = sum cl\[i\] alpha_deg^i, C_D = C_D0 + K C_L^2.
#[derive(Clone, Debug, PartialEq)]
pub struct PolarAerodynamics {
    /// The drag polar.
    pub polar: DragPolar,
    /// C_L coefficients, constant term first (per deg^i).
    pub cl: Vec<f64>,
    /// Lower alpha clamp \[deg\], if any.
    pub alpha_min_deg: Option<f64>,
    /// Upper alpha clamp \[deg\], if any.
    pub alpha_max_deg: Option<f64>,
}

impl Aerodynamics for PolarAerodynamics {
    fn coefficients(&self, _mach: f64, alpha_rad: f64) -> AeroCoefficients {
        let a = clamp_alpha(
            alpha_rad.to_degrees(),
            self.alpha_min_deg,
            self.alpha_max_deg,
        );
        let cl = poly(&self.cl, a);
        AeroCoefficients {
            cl,
            cd: self.polar.cd(cl),
        }
    }

    fn drag_polar(&self, _mach: f64) -> Option<DragPolar> {
        Some(self.polar)
    }
}

/// Fixed trim coefficients, independent of Mach and angle of attack: a vehicle flown by
/// bank-angle modulation only ([`Aerodynamics::controls_alpha`] is false).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrimAerodynamics {
    /// Trim coefficients.
    pub trim: AeroCoefficients,
}

impl Aerodynamics for TrimAerodynamics {
    fn coefficients(&self, _mach: f64, _alpha_rad: f64) -> AeroCoefficients {
        self.trim
    }

    fn controls_alpha(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polar_quantities() {
        let p = DragPolar { cd0: 0.05, k: 1.25 };
        assert!((p.cd(0.2) - 0.1).abs() < 1e-15);
        // E* = 1/(2 sqrt(0.0625)) = 2; at C_L* the ratio C_L/C_D equals E*.
        assert!((p.max_lift_to_drag() - 2.0).abs() < 1e-15);
        let cls = p.cl_at_max_lift_to_drag();
        assert!((cls / p.cd(cls) - 2.0).abs() < 1e-14);
    }

    #[test]
    fn polar_table_interpolates_and_clamps() {
        let a = DragPolar { cd0: 0.1, k: 1.0 };
        let b = DragPolar { cd0: 0.2, k: 3.0 };
        let t = DragPolarTable::new(vec![(2.0, a), (4.0, b)]).unwrap();
        assert_eq!(t.at_mach(1.0), a);
        assert_eq!(t.at_mach(9.0), b);
        let m = t.at_mach(3.0);
        assert!((m.cd0 - 0.15).abs() < 1e-15 && (m.k - 2.0).abs() < 1e-15);
        assert!(t.at_mach(f64::NAN).cd0.is_nan());
        assert!(DragPolarTable::new(vec![(4.0, a), (2.0, b)]).is_none());
        assert!(DragPolarTable::new(vec![]).is_none());
    }

    #[test]
    fn polynomial_clamps_alpha() {
        let p = PolynomialAerodynamics {
            cl: vec![0.0, 0.1],
            cd: vec![1.0],
            alpha_min_deg: Some(0.0),
            alpha_max_deg: Some(10.0),
        };
        assert!((p.coefficients(3.0, 20.0_f64.to_radians()).cl - 1.0).abs() < 1e-12);
        assert_eq!(p.coefficients(3.0, -0.2).cl, 0.0);
    }
}
