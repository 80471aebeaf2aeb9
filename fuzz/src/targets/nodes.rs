//! Node tables from hostile rows, then every interpolation kind at hostile abscissae: a table is
//! built or rejected with a typed error; a built interpolator's output is finite and in bounds.

use guidance_core::interp::{Interpolation, Interpolator};
use guidance_core::nodes::{AngleBounds, Independent, MAX_NODES, Node, NodeTable};
use guidance_core::scalar::{Fixed, Scalar};
use rand::{Rng, RngExt};

use crate::hostile::value;

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    let independent = if rng.random_bool(0.5) {
        Independent::TimeS
    } else {
        Independent::NormalizedEnergy
    };
    let n = rng.random_range(0..=MAX_NODES + 3);
    let sorted = rng.random_bool(0.8);
    let p = 0.03;
    let mut rows: Vec<(f64, f64, f64)> = (0..n)
        .map(|_| {
            (
                value(rng, -10.0, 2000.0, p),
                value(rng, -0.2, 1.0, p),
                value(rng, -0.2, 1.8, p),
            )
        })
        .collect();
    if sorted {
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        if independent == Independent::NormalizedEnergy {
            rows.reverse();
        }
    }
    let bounds_raw = if rng.random_bool(0.9) {
        [0.0, 0.785, 0.0, 1.571]
    } else {
        [
            value(rng, -1.0, 1.0, 0.2),
            value(rng, -1.0, 1.0, 0.2),
            value(rng, -2.0, 2.0, 0.2),
            value(rng, -2.0, 2.0, 0.2),
        ]
    };
    let tension = value(rng, -0.5, 1.5, 0.1);
    let probes: Vec<f64> = (0..16).map(|_| value(rng, -100.0, 2500.0, 0.2)).collect();
    check::<f64>(independent, &rows, bounds_raw, tension, &probes)?;
    check::<f32>(independent, &rows, bounds_raw, tension, &probes)?;
    check::<Fixed>(independent, &rows, bounds_raw, tension, &probes)
}

fn check<S: Scalar + core::fmt::Debug>(
    independent: Independent,
    rows: &[(f64, f64, f64)],
    raw: [f64; 4],
    tension: f64,
    probes: &[f64],
) -> Result<(), String> {
    let bounds = AngleBounds {
        alpha_min_rad: S::from_f64(raw[0]),
        alpha_max_rad: S::from_f64(raw[1]),
        sigma_min_rad: S::from_f64(raw[2]),
        sigma_max_rad: S::from_f64(raw[3]),
    };
    let nodes: Vec<Node<S>> = rows
        .iter()
        .map(|&(x, a, s)| Node {
            x: S::from_f64(x),
            alpha_rad: S::from_f64(a),
            sigma_rad: S::from_f64(s),
        })
        .collect();
    let Ok(table) = NodeTable::<S>::new(independent, &nodes, bounds) else {
        return Ok(());
    };
    let b = table.bounds();
    let kinds = [
        Interpolation::Linear,
        Interpolation::NaturalCubic,
        Interpolation::CardinalHermite {
            tension: S::from_f64(tension),
        },
    ];
    for kind in kinds {
        let Ok(interp) = Interpolator::new(&table, kind) else {
            continue;
        };
        for &x in probes {
            let c = interp.evaluate(S::from_f64(x));
            if !(c.is_finite() && b.alpha_ok(c.alpha_rad) && b.sigma_ok(c.sigma_rad)) {
                return Err(format!(
                    "{kind:?} at x = {x:e}: {c:?} outside {b:?} ({} nodes)",
                    table.len()
                ));
            }
        }
    }
    Ok(())
}
