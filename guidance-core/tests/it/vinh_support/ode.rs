//! Adaptive Dormand-Prince 5(4) (Dormand & Prince 1980 coefficients, FSAL not exploited) with
//! a mixed error norm `|err_i| <= atol + rtol |y_i|`, and event location by bisection on the
//! step size of a single step from the last accepted state.

/// Integrator settings.
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    pub rtol: f64,
    pub atol: f64,
    pub h_init: f64,
    pub h_max: f64,
    pub max_steps: usize,
}

impl Settings {
    pub fn tight(h_max: f64) -> Self {
        Self {
            rtol: 1e-11,
            atol: 1e-13,
            h_init: 1e-4,
            h_max,
            max_steps: 2_000_000,
        }
    }
}

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

fn comb<const N: usize>(y: &[f64; N], h: f64, terms: &[(f64, &[f64; N])]) -> [f64; N] {
    let mut out = *y;
    for (c, k) in terms {
        for i in 0..N {
            out[i] += h * c * k[i];
        }
    }
    out
}

/// One DP5(4) step: (5th-order solution, error estimate vector).
pub fn dp_step<const N: usize, F: Fn(f64, &[f64; N]) -> [f64; N]>(
    f: &F,
    t: f64,
    y: &[f64; N],
    h: f64,
) -> ([f64; N], [f64; N]) {
    let k1 = f(t, y);
    let k2 = f(t + C2 * h, &comb(y, h, &[(A21, &k1)]));
    let k3 = f(t + C3 * h, &comb(y, h, &[(A31, &k1), (A32, &k2)]));
    let k4 = f(
        t + C4 * h,
        &comb(y, h, &[(A41, &k1), (A42, &k2), (A43, &k3)]),
    );
    let k5 = f(
        t + C5 * h,
        &comb(y, h, &[(A51, &k1), (A52, &k2), (A53, &k3), (A54, &k4)]),
    );
    let k6 = f(
        t + h,
        &comb(
            y,
            h,
            &[(A61, &k1), (A62, &k2), (A63, &k3), (A64, &k4), (A65, &k5)],
        ),
    );
    let y5 = comb(
        y,
        h,
        &[(B1, &k1), (B3, &k3), (B4, &k4), (B5, &k5), (B6, &k6)],
    );
    let k7 = f(t + h, &y5);
    let mut err = [0.0; N];
    for i in 0..N {
        err[i] = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
    }
    (y5, err)
}

/// Result of [`integrate`].
pub struct Solution<const N: usize> {
    /// Accepted samples `(t, y)`, including the start and the event (if any).
    pub samples: Vec<(f64, [f64; N])>,
    /// The located event `(t, y)`, if the event function crossed zero in the wanted direction.
    pub event: Option<(f64, [f64; N])>,
}

/// Integrate `dy/dt = f(t, y)` from `t0` until `t_end` or until `event(t, y)` crosses zero from
/// positive to non-positive (after the first accepted step), whichever first.
pub fn integrate<const N: usize, F, G>(
    f: F,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    set: Settings,
    event: G,
) -> Solution<N>
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
    G: Fn(f64, &[f64; N]) -> f64,
{
    let mut t = t0;
    let mut y = y0;
    let mut h = set.h_init.min(set.h_max);
    let mut samples = vec![(t, y)];
    let mut g_prev = event(t, &y);
    for _ in 0..set.max_steps {
        if t >= t_end {
            break;
        }
        if t + h > t_end {
            h = t_end - t;
        }
        let (yn, err) = dp_step(&f, t, &y, h);
        let mut en: f64 = 0.0;
        for i in 0..N {
            let sc = set.atol + set.rtol * y[i].abs().max(yn[i].abs());
            en = en.max((err[i] / sc).abs());
        }
        if !en.is_finite() {
            h *= 0.25;
            continue;
        }
        if en <= 1.0 {
            let tn = t + h;
            let g_new = event(tn, &yn);
            if g_prev > 0.0 && g_new <= 0.0 {
                // Locate by bisection on the sub-step size.
                let (mut lo, mut hi) = (0.0, h);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    let (ym, _) = dp_step(&f, t, &y, mid);
                    if event(t + mid, &ym) > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (ye, _) = dp_step(&f, t, &y, hi);
                samples.push((t + hi, ye));
                return Solution {
                    samples,
                    event: Some((t + hi, ye)),
                };
            }
            g_prev = g_new;
            t = tn;
            y = yn;
            samples.push((t, y));
        }
        let fac = if en == 0.0 {
            5.0
        } else {
            (0.9 * en.powf(-0.2)).clamp(0.2, 5.0)
        };
        h = (h * fac).min(set.h_max);
    }
    Solution {
        samples,
        event: None,
    }
}

/// Maximum of `q(t, y)` over the samples, refined by a parabola through the best sample and its
/// neighbours. Returns `(t, q)`.
pub fn sampled_max<const N: usize>(
    samples: &[(f64, [f64; N])],
    q: impl Fn(f64, &[f64; N]) -> f64,
) -> (f64, f64) {
    let vals: Vec<f64> = samples.iter().map(|(t, y)| q(*t, y)).collect();
    let (i, _) = vals
        .iter()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |(bi, bv), (i, v)| {
            if *v > bv { (i, *v) } else { (bi, bv) }
        });
    if i == 0 || i + 1 >= vals.len() {
        return (samples[i].0, vals[i]);
    }
    let (t0, t1, t2) = (samples[i - 1].0, samples[i].0, samples[i + 1].0);
    let (f0, f1, f2) = (vals[i - 1], vals[i], vals[i + 1]);
    // Vertex of the parabola through three (possibly unequally spaced) points.
    let d01 = (f1 - f0) / (t1 - t0);
    let d12 = (f2 - f1) / (t2 - t1);
    let a = (d12 - d01) / (t2 - t0);
    if a >= 0.0 {
        return (t1, f1);
    }
    let b = d01 - a * (t0 + t1);
    let tv = -b / (2.0 * a);
    let fv = f1 + (tv - t1) * (d01 + a * (tv - t0));
    if tv > t0 && tv < t2 && fv >= f1 {
        (tv, fv)
    } else {
        (t1, f1)
    }
}
