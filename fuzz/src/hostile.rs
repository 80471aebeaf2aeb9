//! Hostile values: mostly plausible numbers, sometimes the ones that break code (NaN, infinities,
//! signed zeros, subnormals, the extremes of `f64` and of the narrower types).

use rand::{Rng, RngExt};

/// Values chosen to break arithmetic.
const SPECIAL: [f64; 16] = [
    0.0,
    -0.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    5e-324,
    -5e-324,
    1e300,
    -1e300,
    3.4e38,
    -3.4e38,
    2_147_483_648.0,
    -2_147_483_649.0,
];

/// A value in `[lo, hi]` most of the time, a special value with probability `p_special`.
pub fn value<R: Rng>(rng: &mut R, lo: f64, hi: f64, p_special: f64) -> f64 {
    if rng.random_bool(p_special) {
        SPECIAL[rng.random_range(0..SPECIAL.len())]
    } else {
        lo + (hi - lo) * rng.random::<f64>()
    }
}
