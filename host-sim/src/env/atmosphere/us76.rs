//! U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562), complete from 0 to 1000 km geometric
//! altitude.
//!
//! # Method
//!
//! * **0-86 km** (geometric): the standard's closed forms. Geometric altitude Z is converted to
//!   geopotential altitude H = r0 Z / (r0 + Z) (r0 = 6356.766 km); the molecular-scale
//!   temperature T_M is piecewise linear in H (thesis table 3.1, eq. 3.91); pressure follows
//!   from the hydrostatic equation layer by layer (base pressures are computed here by
//!   continuity from 101325 Pa, not typed in); density is rho = p M0 / (R* T_M). The kinetic
//!   temperature is T = T_M (M/M0), with the standard's table 8 ratio M/M0 between 80 and 86 km
//!   (1 below 80 km).
//! * **86-1000 km**: the standard's own method, not a fit. The kinetic temperature is defined in
//!   four layers (isothermal 86-91 km, elliptical 91-110 km, linear 110-120 km, exponential
//!   120-1000 km; thesis eq. 3.92-3.95). The number densities of N2, O, O2, Ar and He are
//!   obtained by integrating the standard's diffusion equations (molecular and eddy diffusion,
//!   thermal diffusion, vertical-flux terms of its table 7) upward from their 86 km values;
//!   atomic hydrogen follows the standard's flux solution from its 500 km value (zero below
//!   150 km, as in the standard's tables). The integration runs once per process (lazily, on
//!   first use; well under 0.1 s even in a debug build) with fixed-step fourth-order
//!   Runge-Kutta in ln n_i on a 0.1 km grid, whose nodes contain every break point of the
//!   piecewise definitions (the switch of the N2 molecular weight at 100 km is taken on the
//!   correct side of each step). The hydrogen scale integral tau has a closed form above
//!   120 km and the hydrogen flux integral is done with the trapezoid rule on the same grid.
//!   Between grid nodes ln(rho) and ln(N) are interpolated linearly (error ~1e-5 relative);
//!   temperature is always evaluated from its closed form. Pressure is p = N k T and density
//!   rho = sum(n_i m_i).
//!   Details as in the standard: N2 is in diffusive equilibrium with M = M0 up to 100 km and
//!   M(N2) above; in D_i = a_i (T/273.15)^b_i / n, n is n(N2) for O and O2 and
//!   n(N2) + n(O) + n(O2) for Ar and He (and the sum of all five for H); the mean molecular
//!   weight in the eddy-diffusion term is M0 up to 100 km and that of the same species sums
//!   above (where K vanishes at 115 km).
//!
//! The result is checked against the standard's tabulated levels in
//! `tests/it/env_validation.rs` (`validate_us76_levels_csv_*`, density to 0.1%).
//!
//! # Speed of sound
//!
//! Below 86 km: the standard's definition a = sqrt(gamma R* T_M / M0), gamma = 1.4. The standard
//! does not define a speed of sound above 86 km. Here it is extended as
//! a = sqrt(gamma R* T / M(Z)) with gamma = 1.4 and the local mean molecular weight
//! M(Z) = rho N_A / N. This is continuous at 86 km and is used only to form a Mach number for
//! the aerodynamic tables (which clamp at Mach 20 anyway); in the rarefied thermosphere a
//! continuum sound speed has no strict physical meaning, and the choice of gamma = 1.4 (rather
//! than 5/3 for the atomic gases that dominate above ~200 km) changes a by at most ~9%.
//!
//! # Out of range
//!
//! Below 0 m the 0 m values are returned. Above 1000 km density and pressure are zero; the
//! temperature and speed of sound are held at their 1000 km values. A NaN altitude gives a NaN
//! state (never a panic).

use super::{Atmosphere, AtmosphereState};
use std::sync::OnceLock;

/// Standard gravity g0 [m/s^2] (the standard's geopotential unit).
pub const G0_M_S2: f64 = 9.806_65;
/// Universal gas constant R* [J/(kmol K)] (the standard's value).
pub const R_STAR_J_KMOL_K: f64 = 8_314.32;
/// Sea-level mean molecular weight M0 [kg/kmol].
pub const M0_KG_KMOL: f64 = 28.964_4;
/// Effective Earth radius r0 \[m\] for the geopotential conversion.
pub const R0_M: f64 = 6_356_766.0;
/// Boltzmann constant k [J/K] (the standard's value).
pub const BOLTZMANN_J_K: f64 = 1.380_622e-23;
/// Avogadro constant N_A [1/kmol] (the standard's value).
pub const AVOGADRO_PER_KMOL: f64 = 6.022_169e26;
/// Ratio of specific heats used for the speed of sound [-].
pub const GAMMA_AIR: f64 = 1.4;
/// Top of the model \[m\].
pub const TOP_ALTITUDE_M: f64 = 1_000_000.0;
/// Altitude where the lower (homosphere) definition hands over to the upper one \[m\].
pub const Z7_M: f64 = 86_000.0;

/// Sea-level pressure [Pa].
const P0_PA: f64 = 101_325.0;
/// Sea-level temperature [K].
const T0_K: f64 = 288.15;
/// Geopotential layer bases H_b [m'] (thesis table 3.1).
const HB_M: [f64; 7] = [
    0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0,
];
/// Molecular-scale temperature gradients L_M,b [K/m'] (thesis table 3.1).
const LB_K_M: [f64; 7] = [-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3];
/// Standard table 8: M/M0 from 80 to 86 km geometric in 0.5 km steps.
const M_RATIO_80_86: [f64; 13] = [
    1.0, 0.999_996, 0.999_989, 0.999_971, 0.999_941, 0.999_909, 0.999_870, 0.999_829, 0.999_786,
    0.999_741, 0.999_694, 0.999_641, 0.999_579,
];

// ---- Upper atmosphere (86-1000 km). Altitudes Z in km in this part. ----

/// r0 in km.
const R0_KM: f64 = R0_M / 1000.0;
/// Kinetic temperature at 86-91 km [K].
const T7_K: f64 = 186.867_3;
/// Elliptical layer (91-110 km): T_c [K], A [K], a [km].
const TC_K: f64 = 263.190_5;
const A8_K: f64 = -76.323_2;
const A8_KM: f64 = -19.942_9;
/// Linear layer (110-120 km): T9 [K], L_K,9 [K/km].
const T9_K: f64 = 240.0;
const LK9_K_KM: f64 = 12.0;
/// Exponential layer (120-1000 km): T10 [K], T_inf [K], Z10 [km].
const T10_K: f64 = 360.0;
const TINF_K: f64 = 1000.0;
const Z10_KM: f64 = 120.0;
/// lambda = L_K,9 / (T_inf - T10) [1/km] (thesis eq. 3.95: 0.01875).
const LAMBDA_PER_KM: f64 = LK9_K_KM / (TINF_K - T10_K);

/// Species order: N2, O, O2, Ar, He, H.
const N_SPECIES: usize = 6;
/// Molecular weights [kg/kmol].
const M_I: [f64; N_SPECIES] = [28.0134, 15.9994, 31.9988, 39.948, 4.0026, 1.00797];
/// Number densities at 86 km [1/m^3] (standard, for N2..He).
const N7: [f64; 5] = [1.129_794e20, 8.6e16, 3.030_898e19, 1.351_400e18, 7.5817e14];
/// Thermal diffusion coefficients alpha_i [-] (O, O2, Ar, He; H separately).
const ALPHA_I: [f64; 4] = [0.0, 0.0, 0.0, -0.40];
/// Molecular diffusion coefficient constants a_i [1/(m s)] and b_i [-] (O, O2, Ar, He).
const A_I: [f64; 4] = [6.986e20, 4.863e20, 4.487e20, 1.700e21];
const B_I: [f64; 4] = [0.750, 0.750, 0.870, 0.691];
/// Vertical-flux constants (standard table 7) for O, O2, Ar, He: Q_i [km^-3], U_i [km],
/// W_i [km^-3].
const Q_I: [f64; 4] = [-5.809_644e-4, 1.366_212e-4, 9.434_079e-5, -2.457_369e-4];
const U_I: [f64; 4] = [56.903_11, 86.0, 86.0, 86.0];
const W_I: [f64; 4] = [2.706_240e-5, 8.333_333e-5, 8.333_333e-5, 6.666_667e-4];
/// Second flux term, atomic oxygen only, applied below u = 97 km: q [km^-3], u [km], w [km^-3].
const Q_O2ND: f64 = -3.416_248e-3;
const U_O2ND_KM: f64 = 97.0;
const W_O2ND: f64 = 5.008_765e-4;
/// Eddy diffusion: K7 [m^2/s] up to 95 km, decaying to zero at 115 km (K8 = 400 km^2).
const K7_M2_S: f64 = 120.0;
const K8_KM2: f64 = 400.0;
/// Hydrogen: alpha_H, a_H [1/(m s)], b_H, flux phi [1/(m^2 s)], n_H(500 km) [1/m^3].
const ALPHA_H: f64 = -0.25;
const A_H: f64 = 3.305e21;
const B_H: f64 = 0.500;
const PHI_H: f64 = 7.2e11;
const N_H_500: f64 = 8.0e10;
/// Hydrogen reference altitude Z11 [km] and lowest altitude with hydrogen [km].
const Z11_KM: f64 = 500.0;
const Z_H_LOW_KM: f64 = 150.0;

/// Grid: 86 km + k * 0.1 km, k = 0..=9140.
const GRID_STEPS_PER_KM: usize = 10;
const GRID_Z0_KM: f64 = 86.0;
const GRID_N: usize = (1000 - 86) * GRID_STEPS_PER_KM + 1;

/// Altitude [km] of node `k` of a grid with `per_km` nodes per km from 86 km (exact at
/// integer kilometres).
fn grid_z_km_with(k: usize, per_km: usize) -> f64 {
    (GRID_Z0_KM * per_km as f64 + k as f64) / per_km as f64
}

/// Kinetic temperature T [K] and dT/dZ [K/km] above 86 km (Z in km).
fn upper_temperature(z_km: f64) -> (f64, f64) {
    if z_km < 91.0 {
        (T7_K, 0.0)
    } else if z_km < 110.0 {
        let x = (z_km - 91.0) / A8_KM;
        let s = (1.0 - x * x).max(0.0).sqrt();
        let t = TC_K + A8_K * s;
        // dT/dZ = -A/a * x / sqrt(1 - x^2)  (thesis eq. 3.93)
        let dt = if s > 0.0 { -A8_K / A8_KM * x / s } else { 0.0 };
        (t, dt)
    } else if z_km < Z10_KM {
        (T9_K + LK9_K_KM * (z_km - 110.0), LK9_K_KM)
    } else {
        let ratio = (R0_KM + Z10_KM) / (R0_KM + z_km);
        let xi = (z_km - Z10_KM) * ratio;
        let e = (TINF_K - T10_K) * (-LAMBDA_PER_KM * xi).exp();
        (TINF_K - e, LAMBDA_PER_KM * ratio * ratio * e)
    }
}

/// Gravity [m/s^2] at geometric altitude Z [km] (inverse-square from g0 at r0).
fn gravity_km(z_km: f64) -> f64 {
    let ratio = R0_KM / (R0_KM + z_km);
    G0_M_S2 * ratio * ratio
}

/// Eddy diffusion coefficient K [m^2/s] at Z [km].
fn eddy_k(z_km: f64) -> f64 {
    if z_km < 95.0 {
        K7_M2_S
    } else if z_km < 115.0 {
        let d = z_km - 95.0;
        K7_M2_S * (1.0 - K8_KM2 / (K8_KM2 - d * d)).exp()
    } else {
        0.0
    }
}

/// Vertical flux term v_i / (D_i + K) [1/km] for species O, O2, Ar, He (index 0..4).
fn flux_term(i: usize, z_km: f64) -> f64 {
    let (q, u, w) = (Q_I[i], U_I[i], W_I[i]);
    let d = z_km - u;
    let mut v = q * d * d * (-w * d * d * d).exp();
    if i == 0 && z_km < U_O2ND_KM {
        let d2 = U_O2ND_KM - z_km;
        v += Q_O2ND * d2 * d2 * (-W_O2ND * d2 * d2 * d2).exp();
    }
    v
}

/// d(ln n_i)/dZ [1/km] for N2, O, O2, Ar, He at altitude `z_km` with state `ln_n`.
/// `above_100` selects the side of the 100 km switch of the molecular weight used for N2 and
/// in the eddy-diffusion term (the standard uses M0 up to 100 km).
fn species_derivative(z_km: f64, ln_n: &[f64; 5], above_100: bool) -> [f64; 5] {
    let (t, dt) = upper_temperature(z_km);
    let g = gravity_km(z_km);
    let k_eddy = eddy_k(z_km);
    let n = ln_n.map(f64::exp);
    let dlnt = dt / t;
    // gravity term per unit molecular weight [1/km per kg/kmol]
    let gm = g / (R_STAR_J_KMOL_K * t) * 1000.0;
    let mut out = [0.0; 5];
    let m_n2 = if above_100 { M_I[0] } else { M0_KG_KMOL };
    out[0] = -dlnt - gm * m_n2;
    // Sums used by the standard in the diffusion coefficients and mixture weights.
    let n_n2 = n[0];
    let n_3 = n[0] + n[1] + n[2];
    let m_3 = (n[0] * M_I[0] + n[1] * M_I[1] + n[2] * M_I[2]) / n_3;
    for i in 0..4 {
        let (n_sum, m_mix) = if i < 2 {
            (n_n2, if above_100 { M_I[0] } else { M0_KG_KMOL })
        } else {
            (n_3, if above_100 { m_3 } else { M0_KG_KMOL })
        };
        let d_i = A_I[i] * (t / 273.15).powf(B_I[i]) / n_sum;
        let m_i = M_I[i + 1];
        let f = (gm * (d_i * m_i + k_eddy * m_mix) + ALPHA_I[i] * d_i * dlnt) / (d_i + k_eddy);
        out[i + 1] = -dlnt - f - flux_term(i, z_km);
    }
    out
}

/// Closed-form antiderivative for the hydrogen tau integral above 120 km:
/// tau(Z) = C [F(xi(Z)) - F(xi(Z11))], F(xi) = ln(T_inf e^(lambda xi) - (T_inf - T10)).
fn tau_hydrogen(z_km: f64) -> f64 {
    let xi = |z: f64| (z - Z10_KM) * (R0_KM + Z10_KM) / (R0_KM + z);
    let f = |x: f64| (TINF_K * (LAMBDA_PER_KM * x).exp() - (TINF_K - T10_K)).ln();
    let ratio = R0_KM / (R0_KM + Z10_KM);
    let c = 1000.0 * G0_M_S2 * M_I[5] * ratio * ratio / (R_STAR_J_KMOL_K * LAMBDA_PER_KM * TINF_K);
    c * (f(xi(z_km)) - f(xi(Z11_KM)))
}

/// Tabulated upper atmosphere on the 0.1 km grid.
#[derive(Debug)]
struct UpperTable {
    /// ln of number densities [ln(1/m^3)] per node; H is -inf below 150 km.
    ln_n: Vec<[f64; N_SPECIES]>,
    /// ln(rho [kg/m^3]) per node.
    ln_rho: Vec<f64>,
    /// ln(N [1/m^3]) per node (total number density).
    ln_ntot: Vec<f64>,
}

impl UpperTable {
    fn build() -> Self {
        Self::build_with(GRID_STEPS_PER_KM)
    }

    /// Integrate on a grid of `per_km` nodes per km (the model uses [`GRID_STEPS_PER_KM`];
    /// other values only for the convergence test).
    fn build_with(per_km: usize) -> Self {
        let grid_n = (1000 - 86) * per_km + 1;
        let grid_z_km = |k: usize| grid_z_km_with(k, per_km);
        let h = 1.0 / per_km as f64;
        let mut ln5 = Vec::with_capacity(grid_n);
        let mut y = N7.map(f64::ln);
        ln5.push(y);
        for k in 0..grid_n - 1 {
            let z = grid_z_km(k);
            let above_100 = 0.5 * (z + grid_z_km(k + 1)) > 100.0;
            let add = |a: &[f64; 5], b: &[f64; 5], s: f64| -> [f64; 5] {
                let mut r = *a;
                for (ri, bi) in r.iter_mut().zip(b) {
                    *ri += s * bi;
                }
                r
            };
            let k1 = species_derivative(z, &y, above_100);
            let k2 = species_derivative(z + 0.5 * h, &add(&y, &k1, 0.5 * h), above_100);
            let k3 = species_derivative(z + 0.5 * h, &add(&y, &k2, 0.5 * h), above_100);
            let k4 = species_derivative(z + h, &add(&y, &k3, h), above_100);
            for j in 0..5 {
                y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
            }
            ln5.push(y);
        }

        // Hydrogen (150-1000 km): n_H(Z) = [n_H11 - I(Z)] (T11/T)^(1+alpha) e^(-tau),
        // I(Z) = int_{Z11}^{Z} phi/D_H (T/T11)^(1+alpha) e^(tau) dZ (dZ in m).
        let t11 = upper_temperature(Z11_KM).0;
        let integrand = |k: usize| -> f64 {
            let z = grid_z_km(k);
            let t = upper_temperature(z).0;
            let n_sum: f64 = ln5[k].iter().map(|l| l.exp()).sum();
            let d_h = A_H * (t / 273.15).powf(B_H) / n_sum;
            PHI_H / d_h * (t / t11).powf(1.0 + ALPHA_H) * tau_hydrogen(z).exp()
        };
        let k_low = (Z_H_LOW_KM - GRID_Z0_KM) as usize * per_km;
        let k11 = (Z11_KM - GRID_Z0_KM) as usize * per_km;
        let mut flux_int = vec![0.0; grid_n];
        let h_m = h * 1000.0;
        let mut acc = 0.0;
        let mut prev = integrand(k11);
        for (k, slot) in flux_int.iter_mut().enumerate().skip(k11 + 1) {
            let cur = integrand(k);
            acc += 0.5 * h_m * (prev + cur);
            *slot = acc;
            prev = cur;
        }
        acc = 0.0;
        prev = integrand(k11);
        for (k, slot) in flux_int.iter_mut().enumerate().take(k11).skip(k_low).rev() {
            let cur = integrand(k);
            acc -= 0.5 * h_m * (prev + cur);
            *slot = acc;
            prev = cur;
        }

        let mut ln_n = Vec::with_capacity(grid_n);
        let mut ln_rho = Vec::with_capacity(grid_n);
        let mut ln_ntot = Vec::with_capacity(grid_n);
        for (k, l5) in ln5.iter().enumerate() {
            let z = grid_z_km(k);
            let n_h = if k >= k_low {
                let t = upper_temperature(z).0;
                (N_H_500 - flux_int[k]) * (t11 / t).powf(1.0 + ALPHA_H) * (-tau_hydrogen(z)).exp()
            } else {
                0.0
            };
            let mut row = [0.0; N_SPECIES];
            row[..5].copy_from_slice(l5);
            row[5] = if n_h > 0.0 {
                n_h.ln()
            } else {
                f64::NEG_INFINITY
            };
            let mut mass = 0.0;
            let mut ntot = 0.0;
            for (l, m) in row.iter().zip(M_I) {
                let n = l.exp();
                mass += n * m;
                ntot += n;
            }
            ln_n.push(row);
            ln_rho.push((mass / AVOGADRO_PER_KMOL).ln());
            ln_ntot.push(ntot.ln());
        }
        Self {
            ln_n,
            ln_rho,
            ln_ntot,
        }
    }

    fn get() -> &'static Self {
        static TABLE: OnceLock<UpperTable> = OnceLock::new();
        TABLE.get_or_init(Self::build)
    }

    /// Grid cell and fraction for `z_km` in [86, 1000].
    fn locate(z_km: f64) -> (usize, f64) {
        let s = ((z_km - GRID_Z0_KM) * GRID_STEPS_PER_KM as f64).clamp(0.0, (GRID_N - 1) as f64);
        let k = (s.floor() as usize).min(GRID_N - 2);
        (k, s - k as f64)
    }

    fn lerp(v: &[f64], k: usize, f: f64) -> f64 {
        match (v.get(k), v.get(k + 1)) {
            (Some(a), Some(b)) => a + f * (b - a),
            _ => f64::NAN,
        }
    }
}

/// The U.S. Standard Atmosphere 1976 (see the module documentation for the method).
#[derive(Clone, Copy, Debug, Default)]
pub struct Us76 {
    _private: (),
}

impl Us76 {
    /// The model. The upper-atmosphere table is built once per process on first use.
    #[must_use]
    pub fn new() -> Self {
        Self { _private: () }
    }

    /// Molecular-scale temperature T_M [K] and pressure [Pa] at the base of each layer,
    /// computed once by continuity from sea level.
    fn layer_bases() -> &'static [(f64, f64); 7] {
        static BASES: OnceLock<[(f64, f64); 7]> = OnceLock::new();
        BASES.get_or_init(|| {
            let gmr = G0_M_S2 * M0_KG_KMOL / R_STAR_J_KMOL_K;
            let mut out = [(T0_K, P0_PA); 7];
            for b in 1..out.len() {
                let (tb, pb) = out[b - 1];
                out[b] = Self::layer_step(tb, pb, LB_K_M[b - 1], HB_M[b] - HB_M[b - 1], gmr);
            }
            out
        })
    }

    /// Molecular-scale temperature T_M [K] and pressure [Pa] at geopotential altitude H [m']
    /// (0 <= H <= 84 852 m').
    fn lower_tm_p(h_m: f64) -> (f64, f64) {
        let gmr = G0_M_S2 * M0_KG_KMOL / R_STAR_J_KMOL_K;
        // Last layer whose base is at or below h (layer 0 for h < 0 or NaN).
        let layer = HB_M.partition_point(|&hb| hb <= h_m).saturating_sub(1);
        let (tb, pb) = Self::layer_bases()[layer];
        Self::layer_step(tb, pb, LB_K_M[layer], h_m - HB_M[layer], gmr)
    }

    /// Temperature and pressure at `dh` above the base of a layer with gradient `l`.
    fn layer_step(tb: f64, pb: f64, l: f64, dh: f64, gmr: f64) -> (f64, f64) {
        if l == 0.0 {
            (tb, pb * (-gmr * dh / tb).exp())
        } else {
            let t = tb + l * dh;
            (t, pb * (tb / t).powf(gmr / l))
        }
    }

    /// M/M0 at geometric altitude `z_m` (standard table 8, linear between its 0.5 km points).
    fn molecular_weight_ratio(z_m: f64) -> f64 {
        if z_m <= 80_000.0 {
            return 1.0;
        }
        let s = ((z_m - 80_000.0) / 500.0).clamp(0.0, 12.0);
        let k = (s.floor() as usize).min(11);
        let f = s - k as f64;
        match (M_RATIO_80_86.get(k), M_RATIO_80_86.get(k + 1)) {
            (Some(a), Some(b)) => a + f * (b - a),
            _ => 1.0,
        }
    }

    /// Geopotential altitude H [m'] from geometric altitude Z \[m\].
    #[must_use]
    pub fn geopotential_altitude_m(z_m: f64) -> f64 {
        R0_M * z_m / (R0_M + z_m)
    }

    /// Number densities [1/m^3] of N2, O, O2, Ar, He, H at geometric altitude `altitude_m`
    /// between 86 and 1000 km (the standard defines species only there); `None` outside.
    #[must_use]
    pub fn number_densities(&self, altitude_m: f64) -> Option<[f64; 6]> {
        if !(Z7_M..=TOP_ALTITUDE_M).contains(&altitude_m) {
            return None;
        }
        let table = UpperTable::get();
        let (k, f) = UpperTable::locate(altitude_m / 1000.0);
        let (a, b) = (table.ln_n.get(k)?, table.ln_n.get(k + 1)?);
        let mut out = [0.0; 6];
        for ((o, la), lb) in out.iter_mut().zip(a).zip(b) {
            *o = if la.is_finite() && lb.is_finite() {
                (la + f * (lb - la)).exp()
            } else {
                0.0
            };
        }
        Some(out)
    }

    /// Mean molecular weight M [kg/kmol] at geometric altitude `altitude_m` (M0 below 80 km,
    /// the standard's table 8 to 86 km, rho N_A / N above; held outside 0-1000 km).
    #[must_use]
    pub fn mean_molecular_weight(&self, altitude_m: f64) -> f64 {
        let z = altitude_m.clamp(0.0, TOP_ALTITUDE_M);
        if z < Z7_M {
            M0_KG_KMOL * Self::molecular_weight_ratio(z)
        } else {
            let table = UpperTable::get();
            let (k, f) = UpperTable::locate(z / 1000.0);
            let ln_rho = UpperTable::lerp(&table.ln_rho, k, f);
            let ln_n = UpperTable::lerp(&table.ln_ntot, k, f);
            (ln_rho - ln_n).exp() * AVOGADRO_PER_KMOL
        }
    }

    fn state_inner(z_m: f64) -> AtmosphereState {
        if z_m < Z7_M {
            let h = Self::geopotential_altitude_m(z_m);
            let (tm, p) = Self::lower_tm_p(h);
            let rho = p * M0_KG_KMOL / (R_STAR_J_KMOL_K * tm);
            AtmosphereState {
                temperature_k: tm * Self::molecular_weight_ratio(z_m),
                pressure_pa: p,
                density_kg_m3: rho,
                speed_of_sound_m_s: (GAMMA_AIR * R_STAR_J_KMOL_K * tm / M0_KG_KMOL).sqrt(),
            }
        } else {
            let z_km = z_m / 1000.0;
            let table = UpperTable::get();
            let (k, f) = UpperTable::locate(z_km);
            let rho = UpperTable::lerp(&table.ln_rho, k, f).exp();
            let ntot = UpperTable::lerp(&table.ln_ntot, k, f).exp();
            let t = upper_temperature(z_km).0;
            let m = rho * AVOGADRO_PER_KMOL / ntot;
            AtmosphereState {
                temperature_k: t,
                pressure_pa: ntot * BOLTZMANN_J_K * t,
                density_kg_m3: rho,
                speed_of_sound_m_s: (GAMMA_AIR * R_STAR_J_KMOL_K * t / m).sqrt(),
            }
        }
    }
}

impl Atmosphere for Us76 {
    fn state(&self, altitude_m: f64) -> AtmosphereState {
        if altitude_m.is_nan() {
            return AtmosphereState {
                temperature_k: f64::NAN,
                pressure_pa: f64::NAN,
                density_kg_m3: f64::NAN,
                speed_of_sound_m_s: f64::NAN,
            };
        }
        if altitude_m > TOP_ALTITUDE_M {
            let top = Self::state_inner(TOP_ALTITUDE_M);
            return AtmosphereState {
                pressure_pa: 0.0,
                density_kg_m3: 0.0,
                ..top
            };
        }
        Self::state_inner(altitude_m.max(0.0))
    }

    fn name(&self) -> &'static str {
        "us76"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_base_pressures_match_the_standard_table_4() {
        // Standard's tabulated base pressures P_b [Pa] at H_b.
        let expected = [
            101_325.0, 22_632.06, 5_474.889, 868.018_7, 110.906_3, 66.938_87, 3.956_420,
        ];
        for (h, p_ref) in HB_M.iter().zip(expected) {
            let (_, p) = Us76::lower_tm_p(*h);
            assert!((p / p_ref - 1.0).abs() < 2e-6, "H = {h}: {p} vs {p_ref}");
        }
    }

    #[test]
    fn temperature_profile_is_continuous_at_layer_joins() {
        for z_km in [91.0, 110.0, 120.0] {
            let (a, da) = upper_temperature(z_km - 1e-9);
            let (b, db) = upper_temperature(z_km + 1e-9);
            // The standard's constants are printed to 6-7 digits: the ellipse gives
            // 239.9997 K at 110 km against 240 K for the linear layer.
            assert!((a - b).abs() < 1e-3, "T jump at {z_km}: {a} vs {b}");
            assert!((da - db).abs() < 1e-3, "dT/dZ jump at {z_km}: {da} vs {db}");
        }
        // 86 km: lower definition T_M (M/M0) meets the isothermal layer.
        let lower = Us76::state_inner(Z7_M - 1e-6).temperature_k;
        assert!((lower - T7_K).abs() < 1e-3, "{lower}");
    }

    #[test]
    fn density_is_continuous_at_86_km() {
        let below = Us76::state_inner(Z7_M - 1e-6).density_kg_m3;
        let above = Us76::state_inner(Z7_M).density_kg_m3;
        assert!((below / above - 1.0).abs() < 1e-4, "{below} vs {above}");
    }

    #[test]
    fn density_decreases_monotonically() {
        let atm = Us76::new();
        let mut prev = f64::INFINITY;
        let mut z = 0.0;
        while z <= TOP_ALTITUDE_M {
            let rho = atm.density_kg_m3(z);
            assert!(rho < prev && rho > 0.0, "z = {z}");
            prev = rho;
            z += 250.0;
        }
    }

    #[test]
    fn out_of_range_and_nan() {
        let atm = Us76::new();
        assert_eq!(atm.state(-100.0), atm.state(0.0));
        let above = atm.state(1.5e6);
        assert_eq!(above.density_kg_m3, 0.0);
        assert_eq!(above.pressure_pa, 0.0);
        assert!(above.speed_of_sound_m_s.is_finite());
        assert!(atm.state(f64::NAN).density_kg_m3.is_nan());
        assert!(atm.number_densities(50_000.0).is_none());
    }

    #[test]
    fn speed_of_sound_sea_level_and_continuity_at_86_km() {
        let atm = Us76::new();
        // Standard table: 340.294 m/s at sea level.
        assert!((atm.state(0.0).speed_of_sound_m_s - 340.294).abs() < 1e-3);
        let a = atm.state(Z7_M - 1.0).speed_of_sound_m_s;
        let b = atm.state(Z7_M + 1.0).speed_of_sound_m_s;
        assert!((a - b).abs() < 0.05, "{a} vs {b}");
    }

    #[test]
    fn upper_table_is_converged_in_the_grid_step() {
        // Halving the step (0.2 km -> 0.1 km) changes ln(rho) and ln(N) by far less than the
        // 1e-3 validation tolerance anywhere between 86 and 1000 km.
        let fine = UpperTable::get();
        let coarse = UpperTable::build_with(GRID_STEPS_PER_KM / 2);
        let mut worst = 0.0_f64;
        for (k, (lr, ln)) in coarse.ln_rho.iter().zip(&coarse.ln_ntot).enumerate() {
            worst = worst
                .max((lr - fine.ln_rho[2 * k]).abs())
                .max((ln - fine.ln_ntot[2 * k]).abs());
        }
        eprintln!("US76 upper table: max |d ln| between 0.2 and 0.1 km grids = {worst:.2e}");
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn species_at_86_km_are_the_standards_initial_values() {
        let n = Us76::new().number_densities(Z7_M).unwrap();
        for (a, b) in n.iter().zip(N7) {
            assert!((a / b - 1.0).abs() < 1e-12);
        }
        assert_eq!(n[5], 0.0);
    }
}
