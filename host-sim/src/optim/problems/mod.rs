//! Standard test problems with known fronts: ZDT1-4 and 6, DTLZ1-7, and Deb's constrained
//! CONSTR. [`TestProblem`] gathers them behind one type (for the CLI and the tests). The
//! variable-length ones over chromosomes: [`Vlmop`] and [`OptionalNodes`].

pub mod constr;
pub mod dtlz;
pub mod optional;
pub mod vlmop;
pub mod zdt;

pub use constr::Constr;
pub use dtlz::Dtlz;
pub use optional::OptionalNodes;
pub use vlmop::{VL_NAMES, Vlmop};
pub use zdt::Zdt;

use super::error::EvalError;
use super::hypervolume::hypervolume;
use super::problem::{Bounds, Evaluation, Problem, RealProblem};

/// A test problem that does not exist or is too small.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TestProblemError {
    /// No such ZDT.
    #[error("zdt{id} does not exist here; use zdt1, zdt2, zdt3, zdt4 or zdt6")]
    UnknownZdt {
        /// The number given.
        id: u8,
    },
    /// No such DTLZ.
    #[error("dtlz{id} does not exist; use dtlz1 to dtlz7")]
    UnknownDtlz {
        /// The number given.
        id: u8,
    },
    /// Too few decision variables.
    #[error("{problem}: {given} variables is too few; use at least {minimum}")]
    TooFewVariables {
        /// Problem name.
        problem: String,
        /// Variables asked for.
        given: usize,
        /// Smallest legal number.
        minimum: usize,
    },
    /// Too few objectives.
    #[error("{problem}: {given} objectives is too few; use at least 2")]
    TooFewObjectives {
        /// Problem name.
        problem: String,
        /// Objectives asked for.
        given: usize,
    },
}

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
    /// [`TestProblemError`] for a DTLZ with fewer than 2 objectives.
    pub fn by_name(name: &str, objectives: usize) -> Result<Option<Self>, TestProblemError> {
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
        assert_eq!(Zdt::new(5, 30), Err(TestProblemError::UnknownZdt { id: 5 }));
        assert!(
            Zdt::new(1, 1)
                .unwrap_err()
                .to_string()
                .contains("use at least 2")
        );
        assert_eq!(
            Dtlz::new(8, 3, 5),
            Err(TestProblemError::UnknownDtlz { id: 8 })
        );
        let e = TestProblem::by_name("dtlz2", 1).unwrap_err();
        assert_eq!(
            e.to_string(),
            "dtlz2: 1 objectives is too few; use at least 2"
        );
        assert_eq!(TestProblem::by_name("zdt5", 3), Ok(None));
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

    /// Objective values computed by pygmo 2.20 (`pg.zdt(id, dim)`, `pg.dtlz(id, dim, 3)`) at
    /// pseudo-random decisions (printed by `scripts/pygmo_problem_values.py`).
    const PYGMO: &[(&str, &[f64], &[f64])] = &[
        (
            "zdt1",
            &[
                0.227, 0.317, 0.797, 0.676, 0.391, 0.333, 0.598, 0.187, 0.673, 0.942, 0.248, 0.949,
                0.667, 0.096, 0.442, 0.886, 0.697, 0.326, 0.734, 0.22, 0.082, 0.16, 0.34, 0.465,
                0.266, 0.816, 0.193, 0.129, 0.092, 0.599,
            ],
            &[0.227, 4.054547297462658],
        ),
        (
            "zdt1",
            &[
                0.855, 0.602, 0.932, 0.725, 0.861, 0.929, 0.546, 0.938, 0.495, 0.274, 0.452, 0.665,
                0.331, 0.903, 0.257, 0.34, 0.259, 0.355, 0.005, 0.629, 0.282, 0.068, 0.617, 0.176,
                0.304, 0.441, 0.15, 0.218, 0.474, 0.476,
            ],
            &[0.855, 3.1337001923607555],
        ),
        (
            "zdt2",
            &[
                0.255, 0.298, 0.279, 0.261, 0.483, 0.212, 0.496, 0.246, 0.838, 0.18, 0.862, 0.178,
                0.751, 0.611, 0.209, 0.76, 0.249, 0.086, 0.618, 0.537, 0.635, 0.174, 0.248, 0.685,
                0.081, 0.875, 0.429, 0.618, 0.313, 0.179,
            ],
            &[0.255, 4.832063043137375],
        ),
        (
            "zdt2",
            &[
                0.01, 0.21, 0.87, 0.973, 0.442, 0.379, 0.276, 0.966, 0.058, 0.409, 0.169, 0.24,
                0.78, 0.204, 0.552, 0.367, 0.507, 0.333, 0.283, 0.282, 0.085, 0.482, 0.883, 0.947,
                0.027, 0.918, 0.122, 0.748, 0.897, 0.168,
            ],
            &[0.01, 5.213532543355751],
        ),
        (
            "zdt3",
            &[
                0.331, 0.378, 0.347, 0.516, 0.009, 0.423, 0.878, 0.087, 0.484, 0.481, 0.783, 0.965,
                0.707, 0.274, 0.67, 0.348, 0.768, 0.676, 0.978, 0.867, 0.046, 0.29, 0.862, 0.601,
                0.344, 0.056, 0.763, 0.002, 0.093, 0.994,
            ],
            &[0.331, 4.476256708354828],
        ),
        (
            "zdt3",
            &[
                0.776, 0.868, 0.477, 0.169, 0.534, 0.426, 0.163, 0.166, 0.258, 0.943, 0.987, 0.704,
                0.723, 0.732, 0.517, 0.177, 0.878, 0.88, 0.71, 0.933, 0.98, 0.503, 0.758, 0.617,
                0.115, 0.316, 0.068, 0.887, 0.022, 0.537,
            ],
            &[0.776, 4.357370481006144],
        ),
        (
            "zdt4",
            &[
                0.178,
                -3.5300000000000002,
                -3.34,
                3.7699999999999996,
                -0.0600000000000005,
                -1.5899999999999999,
                4.99,
                0.46000000000000085,
                -1.9700000000000002,
                -1.29,
            ],
            &[0.178, 130.9789646493195],
        ),
        (
            "zdt4",
            &[
                0.696,
                -3.8,
                2.58,
                3.84,
                -0.25,
                -0.6299999999999999,
                -3.5700000000000003,
                -0.7700000000000005,
                2.6400000000000006,
                -0.8600000000000003,
            ],
            &[0.696, 162.05136045666353],
        ),
        (
            "zdt6",
            &[
                0.62, 0.044, 0.22, 0.204, 0.981, 0.045, 0.215, 0.031, 0.64, 0.653,
            ],
            &[0.9824761176503107, 7.734400512830982],
        ),
        (
            "zdt6",
            &[
                0.346, 0.036, 0.435, 0.171, 0.427, 0.373, 0.221, 0.842, 0.693, 0.471,
            ],
            &[0.9999561557892516, 8.069421600989134],
        ),
        (
            "dtlz1",
            &[0.4, 0.109, 0.603, 0.504, 0.905, 0.969, 0.81],
            &[4.704203753742833, 38.45362884940243, 64.73674890471789],
        ),
        (
            "dtlz1",
            &[0.867, 0.496, 0.374, 0.479, 0.531, 0.818, 0.151],
            &[129.11013335211024, 131.19255485778942, 39.93109288571702],
        ),
        (
            "dtlz2",
            &[
                0.601, 0.906, 0.222, 0.288, 0.842, 0.652, 0.965, 0.642, 0.949, 0.827, 0.675, 0.19,
            ],
            &[0.16687438603455398, 1.1219400180011345, 1.5663739843642717],
        ),
        (
            "dtlz2",
            &[
                0.214, 0.863, 0.334, 0.686, 0.435, 0.459, 0.011, 0.822, 0.311, 0.337, 0.072, 0.625,
            ],
            &[0.33705133347865984, 1.541977551653095, 0.5515057191382374],
        ),
        (
            "dtlz3",
            &[
                0.779, 0.511, 0.478, 0.772, 0.097, 0.541, 0.749, 0.366, 0.876, 0.457, 0.116, 0.977,
            ],
            &[293.66188138919625, 303.9895852203542, 1168.240337522747],
        ),
        (
            "dtlz3",
            &[
                0.456, 0.753, 0.078, 0.809, 0.152, 0.125, 0.276, 0.425, 0.485, 0.428, 0.035, 0.597,
            ],
            &[283.4933883250311, 693.640936487738, 652.3079029431974],
        ),
        (
            "dtlz4",
            &[
                0.742, 0.979, 0.554, 0.932, 0.952, 0.212, 0.066, 0.17, 0.744, 0.261, 0.112, 0.943,
            ],
            &[
                2.1980274543536713,
                0.41839539904678535,
                3.8572011212161784e-13,
            ],
        ),
        (
            "dtlz4",
            &[
                0.684, 0.958, 0.33, 0.192, 0.137, 0.943, 0.164, 0.802, 0.212, 0.863, 0.057, 0.381,
            ],
            &[
                2.080523531420523,
                0.044762095912473376,
                1.0471361978505634e-16,
            ],
        ),
        (
            "dtlz5",
            &[
                0.402, 0.976, 0.898, 0.384, 0.425, 0.715, 0.64, 0.894, 0.687, 0.515, 0.901, 0.331,
            ],
            &[0.6262150390337714, 1.1507614608702894, 0.9581559828481002],
        ),
        (
            "dtlz5",
            &[
                0.367, 0.351, 0.49, 0.035, 0.453, 0.317, 0.243, 0.247, 0.798, 0.386, 0.981, 0.413,
            ],
            &[1.1165397040167682, 0.9162810123535479, 0.9390665245207632],
        ),
        (
            "dtlz6",
            &[
                0.698, 0.305, 0.826, 0.213, 0.275, 0.293, 0.129, 0.751, 0.432, 0.126, 0.536, 0.488,
            ],
            &[3.9833264789502745, 2.226815385340757, 8.887253629384707],
        ),
        (
            "dtlz6",
            &[
                0.505, 0.712, 0.067, 0.492, 0.052, 0.976, 0.66, 0.169, 0.92, 0.175, 0.355, 0.047,
            ],
            &[3.1836418123732377, 6.01628693146157, 6.914476877972854],
        ),
        (
            "dtlz7",
            &[
                0.371, 0.731, 0.122, 0.777, 0.427, 0.802, 0.174, 0.902, 0.727, 0.048, 0.479, 0.066,
                0.722, 0.363, 0.774, 0.883, 0.176, 0.81, 0.386, 0.382, 0.654, 0.974,
            ],
            &[0.371, 0.731, 18.98519321655228],
        ),
        (
            "dtlz7",
            &[
                0.682, 0.221, 0.0, 0.111, 0.295, 0.069, 0.066, 0.946, 0.152, 0.334, 0.966, 0.534,
                0.693, 0.288, 0.666, 0.163, 0.346, 0.907, 0.73, 0.462, 0.458, 0.742,
            ],
            &[0.682, 0.221, 16.858932889454355],
        ),
    ];

    #[test]
    fn validate_pygmo_zdt_and_dtlz_objectives() {
        for (name, x, expected) in PYGMO {
            let p = TestProblem::by_name(name, 3).unwrap().unwrap();
            let f = p.evaluate(&x.to_vec()).unwrap().objectives;
            assert_eq!(f.len(), expected.len(), "{name}");
            for (a, b) in f.iter().zip(expected.iter()) {
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                    "{name} {x:?}: {f:?} vs pygmo {expected:?}"
                );
            }
        }
    }
}
