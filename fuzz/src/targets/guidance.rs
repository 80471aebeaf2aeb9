//! Guidance updates with hostile times and states, in `f64`, `f32` and fixed point. Checks: no
//! panic; every command and attitude finite and inside the table's bounds; `next_tick_s`
//! finite; and no freeze: after any one hostile sample, the next good sample (time within the
//! plausibility window of the last good one, later than it) is accepted.

use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{Command, Guidance, GuidanceConfig, RateLimits};
use guidance_core::interp::Interpolation;
use guidance_core::nav::NavState;
use guidance_core::nodes::{AngleBounds, Independent, NodeTable};
use guidance_core::scalar::{Fixed, Scalar};
use rand::{Rng, RngExt};

use crate::hostile::value;

/// One navigation sample of the scripted sequence, in `f64`.
#[derive(Clone, Copy, Debug)]
struct Sample {
    nav: [f64; 7],
    /// True for a good sample that must be accepted.
    good: bool,
}

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    let period = if rng.random_bool(0.9) {
        2.0
    } else {
        value(rng, 0.25, 8.0, 0.0)
    };
    let rates = [value(rng, 0.5, 20.0, 0.0), value(rng, 1.0, 30.0, 0.0)];
    let energy_indexed = rng.random_bool(0.5);
    let kind = rng.random_range(0..3u8);
    let samples = script(rng, period);
    let case = Case {
        period,
        rates,
        energy_indexed,
        kind,
        samples: &samples,
    };
    case.fly::<f64>()?;
    case.fly::<f32>()?;
    case.fly::<Fixed>()
}

/// A sequence of 80 samples: good ones advancing by up to three periods, with isolated hostile
/// ones (a wild time, or a wild state) in between; the first one good.
fn script<R: Rng>(rng: &mut R, period: f64) -> Vec<Sample> {
    let mut t = value(rng, 0.0, 1000.0, 0.0);
    let mut out = Vec::new();
    // The first sample sets the time base (nothing to judge its time against): a good one.
    let mut prev_hostile = true;
    for _ in 0..80 {
        let r = EARTH_RADIUS_M + value(rng, 20e3, 120e3, 0.0);
        let v = value(rng, 300.0, 7800.0, 0.0);
        let base = [t, r, v, -0.02, 1.2, -0.3, -1.8];
        if !prev_hostile && rng.random_bool(0.15) {
            let mut nav = base;
            if rng.random_bool(0.6) {
                // A time glitch far outside the plausibility window (forwards or backwards),
                // or a special value.
                nav[0] = match rng.random_range(0..4u8) {
                    0 => t + value(rng, 1e4, 1e13, 0.0),
                    1 => t - value(rng, 1e4, 1e13, 0.0),
                    2 => t - value(rng, 0.0, 30.0 * period, 0.0),
                    _ => value(rng, 0.0, 0.0, 1.0),
                };
            } else {
                let i = rng.random_range(1..7);
                nav[i] = value(rng, -1e7, 1e7, 0.5);
            }
            out.push(Sample { nav, good: false });
            prev_hostile = true;
        } else {
            t += value(rng, 0.01, 3.0 * period, 0.0);
            out.push(Sample {
                nav: [t, r, v, -0.02, 1.2, -0.3, -1.8],
                good: true,
            });
            prev_hostile = false;
        }
    }
    out
}

struct Case<'a> {
    period: f64,
    rates: [f64; 2],
    energy_indexed: bool,
    kind: u8,
    samples: &'a [Sample],
}

impl Case<'_> {
    fn fly<S: Scalar>(&self) -> Result<(), String> {
        let ty = core::any::type_name::<S>();
        let table: NodeTable<S> = if self.energy_indexed {
            NodeTable::from_deg(
                Independent::NormalizedEnergy,
                &[
                    (1.2, 40.0, 0.0),
                    (0.8, 35.0, 60.0),
                    (0.5, 25.0, 80.0),
                    (0.2, 15.0, 30.0),
                    (-0.1, 10.0, 10.0),
                ],
                AngleBounds::thesis_default(),
            )
            .map_err(|e| format!("{ty}: fixture table rejected: {e:?}"))?
        } else {
            guidance_core::missions::horus2b_reference::<S>()
                .map_err(|e| format!("{ty}: reference mission rejected: {e:?}"))?
                .table
        };
        let kind = match self.kind {
            0 => Interpolation::Linear,
            1 => Interpolation::NaturalCubic,
            _ => Interpolation::CardinalHermite {
                tension: S::from_f64(0.3),
            },
        };
        let config = GuidanceConfig {
            period_s: S::from_f64(self.period),
            rates: RateLimits {
                alpha_rad_s: S::from_f64(self.rates[0].to_radians()),
                sigma_rad_s: S::from_f64(self.rates[1].to_radians()),
            },
        };
        let energy = EnergyNormalizer::new(
            EARTH_MU_M3_S2,
            EARTH_RADIUS_M,
            EARTH_RADIUS_M + 122e3,
            7435.5,
        )
        .map_err(|e| format!("{ty}: fixture energy rejected: {e:?}"))?;
        let initial = Command::from_deg(40.0, 0.0).ok_or("initial attitude")?;
        let mut g = Guidance::new(config, table, kind, energy, initial)
            .map_err(|e| format!("{ty}: fixture guidance rejected: {e:?}"))?;
        let b = g.table().bounds();
        let in_bounds =
            |c: Command<S>| c.is_finite() && b.alpha_ok(c.alpha_rad) && b.sigma_ok(c.sigma_rad);
        for (i, s) in self.samples.iter().enumerate() {
            let [t, r, v, gam, chi, lat, lon] = s.nav.map(S::from_f64);
            let nav = NavState {
                time_s: t,
                radius_m: r,
                speed_m_s: v,
                flight_path_angle_rad: gam,
                heading_rad: chi,
                latitude_rad: lat,
                longitude_rad: lon,
            };
            let result = g.update(&nav);
            match result {
                Ok(out) if !in_bounds(out.command) => {
                    return Err(format!(
                        "{ty} sample {i}: command {:?} out of {b:?}",
                        out.command
                    ));
                }
                Err(e) if s.good => {
                    return Err(format!(
                        "{ty} sample {i} (t = {:e} s): good sample rejected with {e:?} (frozen?)",
                        s.nav[0]
                    ));
                }
                _ => {}
            }
            if !g.next_tick_s().is_finite() {
                return Err(format!("{ty} sample {i}: next_tick_s not finite"));
            }
            for dt in [-1.0, 0.0, 0.3, 1.0, 1e6] {
                let a = g.attitude_at(S::from_f64(s.nav[0] + dt));
                if !in_bounds(a) {
                    return Err(format!(
                        "{ty} sample {i}: attitude_at(+{dt}) = {a:?} out of {b:?}"
                    ));
                }
            }
        }
        Ok(())
    }
}
