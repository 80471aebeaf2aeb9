//! A bounded archive of non-dominated solutions: Zhang & Li's (2007) external population (EP)
//! of MOEA/D, which keeps every non-dominated solution found during a run (pagmo's `moead`
//! has none and returns only its final population), bounded here by a capacity with a
//! hypervolume-keeping truncation.
//!
//! Rules of [`ParetoArchive::offer`]:
//! * only feasible individuals (violation exactly 0, see [`crate::optim::population`]) with
//!   finite objectives of the archive's dimension enter: infeasible, failed and non-finite
//!   ones are refused (so the archive is the feasible non-dominated set, the set the
//!   population's front is taken from too);
//! * a candidate weakly dominated by a member (no worse in every objective, which includes an
//!   exact duplicate of a member's objectives) is refused; members the candidate dominates
//!   leave;
//! * above `capacity` the member with the least exclusive hypervolume contribution leaves
//!   (ties: the first in the archive's order), one per accepted candidate, so the archive never
//!   holds more than `capacity` members.
//!
//! Reference point of the truncation: the archive's own nadir plus 10 % of its extent in every
//! objective (the objectives are first mapped affinely onto the unit box spanned by the
//! members' ideal and nadir points, where the reference point is `1.1` in every coordinate; an
//! affine map scales every contribution by the same factor, so the least contributor is that
//! of the raw objectives with the reference point nadir + 0.1 (nadir - ideal)). No user
//! reference point is needed, the rule is scale-free, and the extreme members, whose boxes
//! reach the margin, are kept unless their contribution is the least. On ZDT1's front the rule
//! gives the reference point (1.1, 1.1).
//!
//! Members are kept sorted lexicographically by objectives, so below capacity the archive's
//! state is a function of the set of points offered, whatever their order. Two objectives have
//! a fast path: the sorted members have strictly increasing `f1` and strictly decreasing `f2`,
//! so dominance is a bisection and each member's contribution is the rectangle between its
//! neighbours (O(log n) to refuse a candidate, O(n) to accept one). More objectives use a
//! linear dominance scan and [`crate::optim::hypervolume::least_contributor`].

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::algorithm::Scratch;
use super::error::ConfigError;
use super::hypervolume::least_contributor;
use super::pareto::dominates;
use super::population::Individual;

/// Reference coordinate of the truncation on the unit box (nadir + 10 % of the extent).
const REFERENCE: f64 = 1.1;

/// A bounded, serialisable archive of feasible non-dominated individuals (see the module
/// documentation for the rules).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(bound(serialize = "D: Serialize", deserialize = "D: DeserializeOwned"))]
pub struct ParetoArchive<D> {
    capacity: usize,
    members: Vec<Individual<D>>,
    /// Two objectives: the members' objectives, flat and contiguous (`[f1, f2]` per member, in
    /// the members' order), so that bisection and the contribution scan never chase the
    /// members' own allocations. Derived from `members`: not serialised, rebuilt when stale.
    #[serde(skip)]
    keys: Scratch<Vec<[f64; 2]>>,
}

impl<D: Clone> ParetoArchive<D> {
    /// An empty archive holding at most `capacity` members.
    ///
    /// # Errors
    /// [`ConfigError::Count`] for a capacity of 0.
    pub fn new(capacity: usize) -> Result<Self, ConfigError> {
        check_capacity("archive", capacity)?;
        Ok(Self {
            capacity,
            members: Vec::with_capacity(capacity + 1),
            keys: Scratch::default(),
        })
    }

    /// The most members the archive holds.
    #[must_use]
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// The members: feasible, mutually non-dominated, distinct objective vectors, sorted
    /// lexicographically by objectives.
    #[must_use]
    pub fn members(&self) -> &[Individual<D>] {
        &self.members
    }

    /// Members held.
    #[must_use]
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// No member yet.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// Offer `candidate`; returns whether it entered (it may still leave at once if it is the
    /// least contributor of a full archive, and then `false` is returned too).
    pub fn offer(&mut self, candidate: &Individual<D>) -> bool {
        let f = candidate.objectives.as_slice();
        if !candidate.is_feasible() || f.is_empty() || !f.iter().all(|v| v.is_finite()) {
            return false;
        }
        if self
            .members
            .first()
            .is_some_and(|m| m.objectives.len() != f.len())
        {
            return false;
        }
        if f.len() == 2 {
            return self.offer_2d(candidate, [f[0], f[1]]);
        }
        let Some(at) = self.place_any(f) else {
            return false;
        };
        self.members.insert(at, candidate.clone());
        if self.members.len() > self.capacity {
            let out = self.least_contributor_any();
            self.members.remove(out);
            return out != at;
        }
        true
    }

    /// Two objectives (members sorted by `f1` ascending, `f2` strictly descending): refuse a
    /// weakly dominated candidate, drop the members it dominates, insert it, truncate.
    fn offer_2d(&mut self, candidate: &Individual<D>, [x, y]: [f64; 2]) -> bool {
        let keys = &mut self.keys.0;
        if keys.len() != self.members.len() {
            keys.clear();
            keys.extend(
                self.members
                    .iter()
                    .map(|m| [m.objectives[0], m.objectives[1]]),
            );
        }
        // The last member with f1 <= x has the smallest f2 of all such members.
        let p = keys.partition_point(|k| k[0] <= x);
        if p > 0 && keys[p - 1][1] <= y {
            return false;
        }
        // Dominated members: f1 >= x and f2 >= y, a contiguous run from the first f1 >= x.
        let q = keys.partition_point(|k| k[0] < x);
        let mut end = q;
        while end < keys.len() && keys[end][1] >= y {
            end += 1;
        }
        if end > q {
            // It replaces the members it dominates (no truncation: the archive shrank or kept
            // its size); the first one's buffers are reused.
            keys.drain(q + 1..end);
            keys[q] = [x, y];
            self.members.drain(q + 1..end);
            self.members[q].clone_from(candidate);
            return true;
        }
        keys.insert(q, [x, y]);
        if keys.len() <= self.capacity {
            self.members.insert(q, candidate.clone());
            return true;
        }
        // Full: the least contributor of members + candidate leaves. Moving only the members
        // between the two positions, the leaving member's buffers take the candidate.
        let out = least_contributor_2d(keys);
        keys.remove(out);
        let slot = match out.cmp(&q) {
            std::cmp::Ordering::Equal => return false,
            std::cmp::Ordering::Greater => {
                self.members[q..out].rotate_right(1);
                q
            }
            std::cmp::Ordering::Less => {
                self.members[out..q].rotate_left(1);
                q - 1
            }
        };
        self.members[slot].clone_from(candidate);
        true
    }

    /// Any number of objectives: the same by a linear scan; lexicographic position.
    fn place_any(&mut self, f: &[f64]) -> Option<usize> {
        if self
            .members
            .iter()
            .any(|m| m.objectives.iter().zip(f).all(|(a, b)| a <= b))
        {
            return None;
        }
        self.members.retain(|m| !dominates(f, &m.objectives));
        Some(
            self.members
                .partition_point(|m| lex_cmp(&m.objectives, f) == std::cmp::Ordering::Less),
        )
    }

    /// More than two objectives: index of the member with the least exclusive contribution
    /// (first of equals), on the unit box of the members' ideal and nadir points with
    /// reference point 1.1.
    fn least_contributor_any(&self) -> usize {
        let n = self.members.len();
        let m = self.members[0].objectives.len();
        let (ideal, nadir) = self.bounds(m);
        let unit = |i: usize, k: usize| to_unit(self.members[i].objectives[k], ideal[k], nadir[k]);
        let points: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..m).map(|k| unit(i, k)).collect())
            .collect();
        // The unit-box points are finite and strictly dominate the reference point, so the
        // hypervolume code cannot fail; should it, the last member leaves.
        least_contributor(&points, &vec![REFERENCE; m]).unwrap_or(n - 1)
    }

    /// Ideal and nadir points of the members.
    fn bounds(&self, m: usize) -> (Vec<f64>, Vec<f64>) {
        let mut ideal = vec![f64::INFINITY; m];
        let mut nadir = vec![f64::NEG_INFINITY; m];
        for ind in &self.members {
            for (k, &v) in ind.objectives.iter().enumerate() {
                ideal[k] = ideal[k].min(v);
                nadir[k] = nadir[k].max(v);
            }
        }
        (ideal, nadir)
    }
}

/// Two objectives, at least two sorted members (`f1` ascending, `f2` strictly descending):
/// index of the least exclusive contributor (first of equals). Member `i` alone dominates the
/// rectangle `[x_i, x_{i+1}) x [y_i, y_{i-1})`, the reference point `r = nadir + 0.1 (nadir -
/// ideal)` closing the ends (nadir `(x_last, y_first)`, ideal `(x_first, y_last)`). Raw
/// coordinates: the unit-box areas of the module documentation times one common factor.
fn least_contributor_2d(keys: &[[f64; 2]]) -> usize {
    let n = keys.len();
    let (first, last) = (keys[0], keys[n - 1]);
    let rx = last[0] + (REFERENCE - 1.0) * (last[0] - first[0]);
    let ry = first[1] + (REFERENCE - 1.0) * (first[1] - last[1]);
    if !(rx > last[0] && ry > first[1] && rx.is_finite() && ry.is_finite()) {
        // The margin is lost to rounding or overflows: the same on the unit box.
        let unit: Vec<[f64; 2]> = keys
            .iter()
            .map(|k| {
                [
                    to_unit(k[0], first[0], last[0]),
                    to_unit(k[1], last[1], first[1]),
                ]
            })
            .collect();
        let (ux, uy) = (unit[n - 1][0], unit[0][1]);
        if ux + (REFERENCE - 1.0) * ux > ux && uy + (REFERENCE - 1.0) * uy > uy {
            return least_contributor_2d(&unit);
        }
        return n - 1;
    }
    let mut best = (0, (keys[1][0] - first[0]) * (ry - first[1]));
    for i in 1..n {
        let right = if i + 1 < n { keys[i + 1][0] } else { rx };
        let c = (right - keys[i][0]) * (keys[i - 1][1] - keys[i][1]);
        if c < best.1 {
            best = (i, c);
        }
    }
    best.0
}

/// Check an archive capacity (at least 1) for the setting `name` of `algorithm`.
///
/// # Errors
/// [`ConfigError::Count`] for 0.
pub fn check_capacity(algorithm: &'static str, capacity: usize) -> Result<(), ConfigError> {
    if capacity == 0 {
        return Err(ConfigError::Count {
            algorithm,
            name: "archive",
            value: 0,
            range: "[1, inf) (the archive's capacity)",
        });
    }
    crate::optim::algorithms::check_size(algorithm, "archive", capacity)
}

/// `v` on the unit interval of `[lo, hi]` (0 when the extent is 0); halved differences so
/// that no finite input overflows.
#[inline]
fn to_unit(v: f64, lo: f64, hi: f64) -> f64 {
    let extent = 0.5 * hi - 0.5 * lo;
    if extent > 0.0 {
        (0.5 * v - 0.5 * lo) / extent
    } else {
        0.0
    }
}

fn lex_cmp(a: &[f64], b: &[f64]) -> std::cmp::Ordering {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

#[cfg(test)]
mod tests;
