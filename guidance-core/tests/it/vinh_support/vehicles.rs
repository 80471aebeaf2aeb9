//! Reference vehicles, environment and entry conditions of the thesis.

/// Earth gravitational parameter [m^3/s^2] (thesis).
pub const MU: f64 = 3.986_004_418e14;
/// Earth radius [m] (thesis, spherical).
pub const R_EARTH: f64 = 6_378_137.0;
/// Exponential atmosphere: sea-level density [kg/m^3] and scale height [m]. The thesis does not
/// state H_s; 7200 m is the value used throughout the validation (see docs/validation/vinh-numerical.md).
pub const RHO0: f64 = 1.225;
pub const H_S: f64 = 7200.0;

/// A vehicle with a parabolic drag polar.
#[derive(Clone, Copy, Debug)]
pub struct Vehicle {
    pub name: &'static str,
    pub mass_kg: f64,
    pub area_m2: f64,
    pub cd0: f64,
    pub k: f64,
    pub nose_radius_m: f64,
}

impl Vehicle {
    pub fn cl_star(&self) -> f64 {
        (self.cd0 / self.k).sqrt()
    }
}

/// HORUS-2B drag polars, read from the repository's copy of `shared/data/horus2b/drag_polar.csv`
/// (`host-sim/data/horus2b/drag_polar.csv`, thesis table 8.1):
/// `(mach, cd0, k)`.
pub fn horus_polars() -> Vec<(f64, f64, f64)> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../host-sim/data/horus2b/drag_polar.csv"
    );
    let text = std::fs::read_to_string(path).expect("host-sim/data/horus2b/drag_polar.csv");
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>().expect("number"))
            .collect();
        assert_eq!(f.len(), 3, "row {line}");
        out.push((f[0], f[1], f[2]));
    }
    out
}

/// HORUS-2B (thesis table 2.1: 26029 kg, 110 m^2, R_N 0.8 m) with the polar at `mach`.
pub fn horus(mach: f64) -> Vehicle {
    let (_, cd0, k) = horus_polars()
        .into_iter()
        .find(|(m, _, _)| (*m - mach).abs() < 1e-9)
        .expect("tabulated Mach");
    Vehicle {
        name: if mach >= 20.0 {
            "HORUS-2B M20"
        } else {
            "HORUS-2B M10"
        },
        mass_kg: 26_029.0,
        area_m2: 110.0,
        cd0,
        k,
        nose_radius_m: 0.8,
    }
}

/// SRM capsule of thesis table 2.3 (38.77 kg, 0.441 m^2, R_N 0.9 m). The thesis does not give
/// its drag polar. It is back-derived from the thesis' sec. 9.2 statement that eq. 3.78/3.79 at
/// 100 km give 7658.34 m/s and -0.056 deg (taken at lambda = 1, sigma = 0, with the exponential
/// atmosphere above): k1 = 1/u_E - 1 fixes C_L* = sqrt(C_D0/K), gamma_E fixes E* (see
/// `srm_polar_from_thesis_glide_entry`).
pub fn srm() -> Vehicle {
    let (cd0, k) = srm_polar_from_thesis_glide_entry();
    Vehicle {
        name: "SRM",
        mass_kg: 38.77,
        area_m2: 0.441,
        cd0,
        k,
        nose_radius_m: 0.9,
    }
}

/// The SRM capsule with its polar factor K set for a maximum lift-to-drag ratio `ld`
/// (E* = 1/(2 sqrt(K C_D0))): mass, area, C_D0 and nose radius unchanged.
pub fn srm_with_max_ld(ld: f64) -> Vehicle {
    let mut v = srm();
    v.k = 1.0 / (4.0 * ld * ld * v.cd0);
    v
}

/// `(C_D0, K)` of the SRM capsule from the thesis' sec. 9.2 glide entry at 100 km.
pub fn srm_polar_from_thesis_glide_entry() -> (f64, f64) {
    let (m, s_ref) = (38.77, 0.441);
    let r = R_EARTH + 100_000.0;
    let rho = RHO0 * (-100_000.0 / H_S).exp();
    let u = 7658.34_f64.powi(2) / (MU / r);
    let k1 = 1.0 / u - 1.0;
    let cl_star = k1 * 2.0 * m / (rho * s_ref * r);
    let s = r / H_S;
    let sin_g = (0.056_f64).to_radians().sin();
    let e = 2.0 * k1 * (1.0 + k1) / (sin_g * (2.0 * (1.0 + k1).powi(2) + s * k1));
    // E* = E at lambda = 1; C_L* = sqrt(C_D0/K), E* = 1/(2 sqrt(K C_D0)) => C_D0 = C_L*/(2E*).
    let cd0 = cl_star / (2.0 * e);
    let k = cd0 / (cl_star * cl_star);
    (cd0, k)
}
