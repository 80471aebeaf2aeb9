//! Standard test problems with known fronts: ZDT1-4 and 6, DTLZ1-7, and Deb's constrained
//! CONSTR. [`TestProblem`] gathers them behind one type (for the CLI and the tests).

pub mod constr;
pub mod dtlz;
pub mod vlmop;
pub mod zdt;

pub use constr::Constr;
pub use dtlz::Dtlz;
pub use vlmop::{VL_NAMES, Vlmop};
pub use zdt::Zdt;

use super::error::{BoundsError, EvalError};
use super::hypervolume::hypervolume;
use super::problem::{Bounds, Evaluation, Problem, RealProblem};

/// Names accepted by [`TestProblem::by_name`].
pub const NAMES: [&str; 13] = [
    "zdt1", "zdt2", "zdt3", "zdt4", "zdt6", "dtlz1", "dtlz2", "dtlz3", "dtlz4", "dtlz5", "dtlz6",
    "dtlz7", "constr",
];

/// Any of the test problems.
#[derive(Clone, Debug, PartialEq)]
pub enum TestProblem {
    /// ZDT1-4, 6.
    Zdt(Zdt),
    /// DTLZ1-7.
    Dtlz(Dtlz),
    /// CONSTR.
    Constr(Constr),
}

impl TestProblem {
    /// The problem called `name` (see [`NAMES`]) with its standard size; DTLZ problems take
    /// `objectives` (ignored by the others). `None` for an unknown name.
    ///
    /// # Errors
    /// [`BoundsError`] for a DTLZ with fewer than 2 objectives.
    pub fn by_name(name: &str, objectives: usize) -> Result<Option<Self>, BoundsError> {
        let lower = name.to_ascii_lowercase();
        if lower == "constr" {
            return Ok(Some(Self::Constr(Constr::default())));
        }
        let parse = |prefix: &str| {
            lower
                .strip_prefix(prefix)
                .and_then(|s| s.parse::<u8>().ok())
        };
        if let Some(id) = parse("zdt").filter(|i| matches!(i, 1 | 2 | 3 | 4 | 6)) {
            return Ok(Some(Self::Zdt(Zdt::standard(id)?)));
        }
        if let Some(id) = parse("dtlz").filter(|i| (1..=7).contains(i)) {
            return Ok(Some(Self::Dtlz(Dtlz::standard(id, objectives)?)));
        }
        Ok(None)
    }

    /// The reference point used for its hypervolume: (1.1, 1.1) for ZDT, see
    /// [`Dtlz::reference_point`] for DTLZ, (1.1, 10) for CONSTR.
    #[must_use]
    pub fn reference_point(&self) -> Vec<f64> {
        match self {
            Self::Zdt(_) => vec![1.1, 1.1],
            Self::Dtlz(d) => d.reference_point(),
            Self::Constr(_) => vec![1.1, 10.0],
        }
    }

    /// About `n` points of the true front.
    #[must_use]
    pub fn pareto_front(&self, n: usize) -> Vec<Vec<f64>> {
        match self {
            Self::Zdt(p) => p.pareto_front(n),
            Self::Dtlz(p) => p.pareto_front(n),
            Self::Constr(p) => p.pareto_front(n),
        }
    }

    /// Hypervolume of the true front: exact where known, else that of a dense sample of the
    /// front (`samples` points; a slight underestimate).
    #[must_use]
    pub fn front_hypervolume(&self, reference: &[f64], samples: usize) -> Option<f64> {
        let exact = match self {
            Self::Zdt(p) => p.front_hypervolume(reference),
            Self::Dtlz(p) => p.front_hypervolume(reference),
            Self::Constr(p) => p.front_hypervolume(reference),
        };
        exact.or_else(|| hypervolume(&self.pareto_front(samples), reference).ok())
    }
}

impl Problem for TestProblem {
    type Decision = Vec<f64>;

    fn objectives(&self) -> usize {
        match self {
            Self::Zdt(p) => p.objectives(),
            Self::Dtlz(p) => p.objectives(),
            Self::Constr(p) => p.objectives(),
        }
    }

    fn constraints(&self) -> usize {
        match self {
            Self::Zdt(p) => p.constraints(),
            Self::Dtlz(p) => p.constraints(),
            Self::Constr(p) => p.constraints(),
        }
    }

    fn evaluate(&self, x: &Vec<f64>) -> Result<Evaluation, EvalError> {
        match self {
            Self::Zdt(p) => p.evaluate(x),
            Self::Dtlz(p) => p.evaluate(x),
            Self::Constr(p) => p.evaluate(x),
        }
    }
}

impl RealProblem for TestProblem {
    fn bounds(&self) -> &Bounds {
        match self {
            Self::Zdt(p) => p.bounds(),
            Self::Dtlz(p) => p.bounds(),
            Self::Constr(p) => p.bounds(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::pareto::dominates;

    /// Analytic front hypervolumes agree with the hypervolume of dense front samples
    /// (which underestimate slightly).
    #[test]
    fn analytic_front_hypervolumes_match_dense_samples() {
        for name in NAMES {
            let p = TestProblem::by_name(name, 3).unwrap().unwrap();
            let r = p.reference_point();
            let samples = if p.objectives() == 2 { 20_000 } else { 1_000 };
            let sampled = hypervolume(&p.pareto_front(samples), &r).unwrap();
            let exact = match &p {
                TestProblem::Zdt(z) => z.front_hypervolume(&r),
                TestProblem::Dtlz(d) => d.front_hypervolume(&r),
                TestProblem::Constr(c) => c.front_hypervolume(&r),
            };
            if let Some(exact) = exact {
                let tol = if p.objectives() == 2 { 2e-4 } else { 3e-2 };
                assert!(
                    sampled <= exact + 1e-12 && sampled > exact * (1.0 - tol),
                    "{name}: sampled {sampled} exact {exact}"
                );
            }
            assert!(sampled > 0.0, "{name}");
        }
        // ZDT1 with (1.1, 1.1): the 0.8767.
        let z = Zdt::standard(1).unwrap();
        assert!((z.front_hypervolume(&[1.1, 1.1]).unwrap() - 0.876_666_666).abs() < 1e-8);
        assert!((zdt::zdt6_front_start() - 0.280_775_319_1).abs() < 1e-9);
    }

    /// Decisions on the Pareto set evaluate onto the sampled front, and no random decision
    /// dominates a front point.
    #[test]
    fn fronts_are_not_dominated_by_random_decisions() {
        let mut rng = crate::optim::rng::OptimRng::new(4);
        for name in NAMES {
            let p = TestProblem::by_name(name, 3).unwrap().unwrap();
            let front = p.pareto_front(200);
            for _ in 0..300 {
                let x = crate::optim::operators::random_point(p.bounds(), &mut rng);
                let e = p.evaluate(&x).unwrap();
                if e.constraints.iter().any(|&g| g > 0.0) {
                    continue;
                }
                for f in &front {
                    assert!(
                        !dominates(&e.objectives, f),
                        "{name}: {x:?} dominates {f:?}"
                    );
                }
            }
        }
        // ZDT: x1 = 0.25 and zeros elsewhere lands on f2 = 1 - sqrt(f1).
        let mut x = vec![0.0; 30];
        x[0] = 0.25;
        let e = Zdt::standard(1).unwrap().evaluate(&x).unwrap();
        assert_eq!(e.objectives, vec![0.25, 0.5]);
        // DTLZ2 at the centre of the distance variables lies on the unit sphere.
        let d = Dtlz::standard(2, 3).unwrap();
        let mut x = vec![0.5; 12];
        x[0] = 0.3;
        x[1] = 0.8;
        let f = d.evaluate(&x).unwrap().objectives;
        assert!((f.iter().map(|v| v * v).sum::<f64>() - 1.0).abs() < 1e-12);
        // DTLZ1 at the centre: the simplex sum f = 0.5.
        let d = Dtlz::standard(1, 3).unwrap();
        let mut x = vec![0.5; 7];
        x[0] = 0.3;
        let f = d.evaluate(&x).unwrap().objectives;
        assert!((f.iter().sum::<f64>() - 0.5).abs() < 1e-12);
        assert!(matches!(
            d.evaluate(&vec![0.5; 3]),
            Err(EvalError::Dimension {
                expected: 7,
                got: 3
            })
        ));
    }
}
