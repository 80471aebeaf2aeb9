//! Interpolation between guidance nodes (thesis sec. 5.2): linear (eq. 5.2), natural cubic
//! spline (sec. 5.2.2) and cardinal Hermite spline (sec. 5.2.3, with the ERRATA fix
//! `h10(t) = t^3 - 2 t^2 + t`).
//!
//! # Form
//! All three are evaluated per segment `i` (nodes `i`, `i + 1`) on the normalised parameter
//! `t = (x - x_i) / (x_{i+1} - x_i)` in `\[0, 1\]` (eq. 5.9):
//!
//! * linear: `p = p_i + (p_{i+1} - p_i) t`;
//! * splines, in cubic Hermite form (eq. 5.7/5.10): `p = p_i + h01(t) (p_{i+1} - p_i)
//!   + h10(t) T0_i + h11(t) T1_i` (using `h00 = 1 - h01`), where `T0_i`, `T1_i` are the end
//!   tangents *in segment units* (radians per unit `t`, i.e. `(x_{i+1} - x_i) m`).
//!
//! The tangents are computed once, at construction, into fixed arrays (no allocation):
//!
//! * natural cubic: the first derivatives `s_j` (per unit of the span-normalised variable
//!   `u = (x - x_0) / (x_{n-1} - x_0)`) solve the tridiagonal system
//!   `mu_j s_{j-1} + 2 s_j + lam_j s_{j+1} = 3 (mu_j d_{j-1} + lam_j d_j)` with
//!   `mu_j = h_j / (h_{j-1} + h_j)`, `lam_j = 1 - mu_j`, `d_j = (p_{j+1} - p_j) / h_j`, and the
//!   natural end conditions (zero second derivative) `2 s_0 + s_1 = 3 d_0`,
//!   `s_{n-2} + 2 s_{n-1} = 3 d_{n-2}`; solved by the Thomas algorithm (the matrix is strictly
//!   diagonally dominant, pivots >= 1.5, so no pivoting is needed). This is the same spline as
//!   eq. 5.3-5.6 (which solves for second derivatives); the slope form is used so that
//!   fixed point only ever sees ratios of spacings and angle differences, never products of raw
//!   spacings (time tables have spacings of hundreds of seconds). Note eq. 5.5 as printed has
//!   a `+` on its right-hand side; the correct right-hand side is the *difference* of the
//!   slopes, as eq. 5.6 shows.
//! * cardinal Hermite (eq. 5.11): `m_j = (1 - c) (p_{j+1} - p_{j-1}) / (x_{j+1} - x_{j-1})` at
//!   interior nodes, so `T0_i = (1 - c) (p_{i+1} - p_{i-1}) h_i / (h_{i-1} + h_i)`; at the end
//!   nodes (where eq. 5.11 has no neighbour) the one-sided `m_0 = (1 - c)(p_1 - p_0)/h_0` and
//!   `m_{n-1} = (1 - c)(p_{n-1} - p_{n-2})/h_{n-2}`. Tension `c` in `\[0, 1\]`: 0 gives the
//!   Catmull-Rom spline, 1 gives zero tangents.
//!
//! Energy-indexed tables (x decreasing in flight order) are handled by interpolating over the
//! increasing key `-x`; all three interpolants are invariant under this affine change of
//! variable. The segment is found by bisection on node indices, with the midpoint
//! `lo + (hi - lo) / 2` (the ERRATA midpoint fix of sec. 5.1.1).
//!
//! # Clamping
//! * Outside the node range the end node's value is returned (no extrapolation).
//! * Splines can overshoot the node values between nodes (e.g. a bank step of 0 -> 79.6 deg
//!   over 26 s followed by a slow decrease). **The evaluated command is always clamped into the
//!   table's [`AngleBounds`]**, so it can flatten against a bound; the linear interpolant never
//!   leaves the node values of its segment, so clamping never changes it.
//! * A NaN `x` (floating point only) returns the first node's command.
//!
//! # Precision
//! Every node is reproduced exactly at its `x` (t = 0 gives `p_i` with no arithmetic); the
//! last node is returned by the clamp. Between nodes, one evaluation does about a dozen
//! rounded operations on quantities of order of the angles (and, for splines, the tangents),
//! see [`crate::guidance`] for the derived f32/fixed-point bounds.
//!
//! For fixed point, all quantities formed are angles, angle differences, ratios of spacings in
//! (0, 1] and slopes per unit span; with node spacings below about 1e-9 of the span the slopes
//! saturate (no panic: the output is still clamped into bounds, but the spline shape is then
//! not meaningful).

use crate::command::Command;
use crate::error::GuidanceError;
use crate::nodes::{AngleBounds, DEFAULT_NODE_CAPACITY, NodeTable};
use crate::scalar::Scalar;

/// Which interpolant to use between nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Interpolation<S> {
    /// Piecewise linear (thesis eq. 5.2).
    Linear,
    /// Natural cubic spline (thesis sec. 5.2.2): C2, zero second derivative at both ends.
    NaturalCubic,
    /// Cardinal Hermite spline (thesis sec. 5.2.3, eq. 5.11); tension `c` in `\[0, 1\]`.
    CardinalHermite {
        /// Tension `c` \[-\], 0 (Catmull-Rom) to 1 (zero tangents).
        tension: S,
    },
}

/// Interpolator over one node table of capacity `N`. Copies the nodes and precomputes the
/// spline tangents (seven arrays of `N` values, inline).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Interpolator<S, const N: usize = DEFAULT_NODE_CAPACITY> {
    kind: Interpolation<S>,
    /// False for energy tables: keys are `-x`.
    increasing: bool,
    len: usize,
    /// Increasing keys (`x` or `-x`), flight order.
    keys: [S; N],
    alpha: [S; N],
    sigma: [S; N],
    /// Per segment: tangents at the segment start/end in segment units \[rad\].
    alpha_t0: [S; N],
    alpha_t1: [S; N],
    sigma_t0: [S; N],
    sigma_t1: [S; N],
    bounds: AngleBounds<S>,
}

/// Read `a\[i\]`, zero if out of range (never happens for in-range indices; keeps the code free
/// of panicking indexing).
#[inline]
fn at<S: Scalar>(a: &[S], i: usize) -> S {
    a.get(i).copied().unwrap_or(S::ZERO)
}

/// Write `a\[i\] = v` if in range.
#[inline]
fn put<S: Scalar>(a: &mut [S], i: usize, v: S) {
    if let Some(slot) = a.get_mut(i) {
        *slot = v;
    }
}

impl<S: Scalar, const N: usize> Interpolator<S, N> {
    /// Build the interpolator for `table` (copied) and precompute the spline tangents.
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for a non-finite tension or one outside `\[0, 1\]`.
    pub fn new(table: &NodeTable<S, N>, kind: Interpolation<S>) -> Result<Self, GuidanceError> {
        if let Interpolation::CardinalHermite { tension } = kind
            && !(tension.is_finite() && tension >= S::ZERO && tension <= S::ONE)
        {
            return Err(GuidanceError::InvalidConfig);
        }
        let increasing = table.independent().increasing();
        let mut out = Self {
            kind,
            increasing,
            len: table.len(),
            keys: [S::ZERO; N],
            alpha: [S::ZERO; N],
            sigma: [S::ZERO; N],
            alpha_t0: [S::ZERO; N],
            alpha_t1: [S::ZERO; N],
            sigma_t0: [S::ZERO; N],
            sigma_t1: [S::ZERO; N],
            bounds: table.bounds(),
        };
        for (i, n) in table.nodes().iter().enumerate() {
            put(&mut out.keys, i, if increasing { n.x } else { -n.x });
            put(&mut out.alpha, i, n.alpha_rad);
            put(&mut out.sigma, i, n.sigma_rad);
        }
        match kind {
            Interpolation::Linear => {}
            Interpolation::NaturalCubic => {
                natural_tangents::<S, N>(
                    &out.keys,
                    &out.alpha,
                    out.len,
                    &mut out.alpha_t0,
                    &mut out.alpha_t1,
                );
                natural_tangents::<S, N>(
                    &out.keys,
                    &out.sigma,
                    out.len,
                    &mut out.sigma_t0,
                    &mut out.sigma_t1,
                );
            }
            Interpolation::CardinalHermite { tension } => {
                let scale = S::ONE - tension;
                cardinal_tangents(
                    &out.keys,
                    &out.alpha,
                    out.len,
                    scale,
                    &mut out.alpha_t0,
                    &mut out.alpha_t1,
                );
                cardinal_tangents(
                    &out.keys,
                    &out.sigma,
                    out.len,
                    scale,
                    &mut out.sigma_t0,
                    &mut out.sigma_t1,
                );
            }
        }
        Ok(out)
    }

    /// The interpolant kind.
    #[must_use]
    pub fn kind(&self) -> Interpolation<S> {
        self.kind
    }

    /// The angle bounds results are clamped into.
    #[must_use]
    pub fn bounds(&self) -> AngleBounds<S> {
        self.bounds
    }

    /// Command at independent value `x` (E-hat \[-\] or time \[s\], as the table). Outside the
    /// node range, the end node's command; the result is clamped into the angle bounds, so it
    /// is always finite and within bounds.
    #[must_use]
    pub fn evaluate(&self, x: S) -> Command<S> {
        let key = if self.increasing { x } else { -x };
        let last = self.len.saturating_sub(1);
        // At or before the first node, or NaN (incomparable).
        let first = !matches!(
            key.partial_cmp(&at(&self.keys, 0)),
            Some(core::cmp::Ordering::Greater)
        );
        let (alpha, sigma) = if first {
            // At or before the first node, or NaN.
            (at(&self.alpha, 0), at(&self.sigma, 0))
        } else if key >= at(&self.keys, last) {
            (at(&self.alpha, last), at(&self.sigma, last))
        } else {
            let i = self.segment(key);
            let k0 = at(&self.keys, i);
            let k1 = at(&self.keys, i + 1);
            let t = ((key - k0) / (k1 - k0)).clamp(S::ZERO, S::ONE);
            match self.kind {
                Interpolation::Linear => (
                    lerp(at(&self.alpha, i), at(&self.alpha, i + 1), t),
                    lerp(at(&self.sigma, i), at(&self.sigma, i + 1), t),
                ),
                _ => {
                    let basis = HermiteBasis::at(t);
                    (
                        basis.eval(
                            at(&self.alpha, i),
                            at(&self.alpha, i + 1),
                            at(&self.alpha_t0, i),
                            at(&self.alpha_t1, i),
                        ),
                        basis.eval(
                            at(&self.sigma, i),
                            at(&self.sigma, i + 1),
                            at(&self.sigma_t0, i),
                            at(&self.sigma_t1, i),
                        ),
                    )
                }
            }
        };
        Command {
            alpha_rad: self.bounds.clamp_alpha(alpha),
            sigma_rad: self.bounds.clamp_sigma(sigma),
        }
    }

    /// Segment `i` with `keys\[i\] <= key < keys\[i + 1\]`, given `keys\[0\] < key < keys\[len-1\]`.
    /// Bisection on indices with midpoint `lo + (hi - lo) / 2`.
    fn segment(&self, key: S) -> usize {
        let mut lo = 0usize;
        let mut hi = self.len.saturating_sub(1);
        while hi > lo + 1 {
            let mid = lo + (hi - lo) / 2;
            if at(&self.keys, mid) <= key {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }
}

/// `p0 + (p1 - p0) t`; for `t` in \[0, 1\] the result lies between `p0` and `p1` up to rounding.
#[inline]
fn lerp<S: Scalar>(p0: S, p1: S, t: S) -> S {
    p0 + (p1 - p0) * t
}

/// Cubic Hermite basis at `t` (thesis eq. 5.8 with the ERRATA fix of `h10`).
#[derive(Clone, Copy, Debug)]
struct HermiteBasis<S> {
    /// `h01(t) = -2 t^3 + 3 t^2` (and `h00 = 1 - h01`).
    h01: S,
    /// `h10(t) = t^3 - 2 t^2 + t` (ERRATA; printed as `... + 1`).
    h10: S,
    /// `h11(t) = t^3 - t^2`.
    h11: S,
}

impl<S: Scalar> HermiteBasis<S> {
    fn at(t: S) -> Self {
        let t2 = t * t;
        let t3 = t2 * t;
        let two = S::ONE + S::ONE;
        let three = two + S::ONE;
        Self {
            h01: three * t2 - two * t3,
            h10: t3 - two * t2 + t,
            h11: t3 - t2,
        }
    }

    /// `h00 p0 + h10 T0 + h01 p1 + h11 T1`, written as `p0 + h01 (p1 - p0) + ...`.
    fn eval(&self, p0: S, p1: S, t0: S, t1: S) -> S {
        p0 + self.h01 * (p1 - p0) + self.h10 * t0 + self.h11 * t1
    }
}

/// Cardinal-spline segment tangents (see module docs). `scale = 1 - c`.
fn cardinal_tangents<S: Scalar>(
    keys: &[S],
    p: &[S],
    n: usize,
    scale: S,
    t0: &mut [S],
    t1: &mut [S],
) {
    // Tangent at node j in units of segment i (which has node j as an end): for interior j,
    // scale * (p_{j+1} - p_{j-1}) * h_i / (h_{j-1} + h_j); for end nodes, scale * (p_1 - p_0)
    // resp. scale * (p_{n-1} - p_{n-2}) (h_i cancels).
    let tangent = |j: usize, i: usize| -> S {
        let hi = at(keys, i + 1) - at(keys, i);
        if j == 0 {
            scale * (at(p, 1) - at(p, 0))
        } else if j + 1 >= n {
            scale * (at(p, j) - at(p, j - 1))
        } else {
            let span = at(keys, j + 1) - at(keys, j - 1);
            scale * (at(p, j + 1) - at(p, j - 1)) * (hi / span)
        }
    };
    for i in 0..n.saturating_sub(1) {
        put(t0, i, tangent(i, i));
        put(t1, i, tangent(i + 1, i));
    }
}

/// Natural cubic spline segment tangents via the Thomas algorithm (see module docs).
fn natural_tangents<S: Scalar, const N: usize>(
    keys: &[S],
    p: &[S],
    n: usize,
    t0: &mut [S],
    t1: &mut [S],
) {
    if n < 2 {
        return;
    }
    let two = S::ONE + S::ONE;
    let three = two + S::ONE;
    let span = at(keys, n - 1) - at(keys, 0);
    // Normalised spacings hn_j in (0, 1] and divided differences d_j per unit u.
    let mut hn = [S::ZERO; N];
    let mut d = [S::ZERO; N];
    for j in 0..n - 1 {
        let h = (at(keys, j + 1) - at(keys, j)) / span;
        put(&mut hn, j, h);
        put(&mut d, j, (at(p, j + 1) - at(p, j)) / h);
    }
    // Forward sweep: c' (modified super-diagonal) and r' (modified right-hand side).
    let mut cp = [S::ZERO; N];
    let mut rp = [S::ZERO; N];
    // Row 0: 2 s_0 + 1 s_1 = 3 d_0.
    put(&mut cp, 0, S::ONE / two);
    put(&mut rp, 0, three * at(&d, 0) / two);
    for j in 1..n {
        let (a, c, r) = if j + 1 < n {
            let (h_prev, h_next) = (at(&hn, j - 1), at(&hn, j));
            let mu = h_next / (h_prev + h_next);
            let lam = S::ONE - mu;
            (mu, lam, three * (mu * at(&d, j - 1) + lam * at(&d, j)))
        } else {
            // Last row: s_{n-2} + 2 s_{n-1} = 3 d_{n-2}.
            (S::ONE, S::ZERO, three * at(&d, j - 1))
        };
        let denom = two - a * at(&cp, j - 1);
        put(&mut cp, j, c / denom);
        let prev = at(&rp, j - 1);
        put(&mut rp, j, (r - a * prev) / denom);
    }
    // Back substitution into slopes s (reuse rp).
    for j in (0..n - 1).rev() {
        let next = at(&rp, j + 1);
        let s = at(&rp, j) - at(&cp, j) * next;
        put(&mut rp, j, s);
    }
    for i in 0..n - 1 {
        let h = at(&hn, i);
        put(t0, i, h * at(&rp, i));
        put(t1, i, h * at(&rp, i + 1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::{Independent, Node};
    use crate::scalar::Fixed;

    fn table(ind: Independent, pts: &[(f64, f64, f64)]) -> NodeTable<f64> {
        let nodes: heapless::Vec<Node<f64>, DEFAULT_NODE_CAPACITY> = pts
            .iter()
            .map(|&(x, a, s)| Node {
                x,
                alpha_rad: a,
                sigma_rad: s,
            })
            .collect();
        NodeTable::new(ind, &nodes, AngleBounds::thesis_default()).unwrap()
    }

    #[test]
    fn linear_known_values_and_clamping_outside() {
        let t = table(
            Independent::TimeS,
            &[(0.0, 0.1, 0.2), (10.0, 0.3, 1.2), (30.0, 0.5, 0.2)],
        );
        let i = Interpolator::new(&t, Interpolation::Linear).unwrap();
        let c = i.evaluate(5.0);
        assert!((c.alpha_rad - 0.2).abs() < 1e-15 && (c.sigma_rad - 0.7).abs() < 1e-15);
        let c = i.evaluate(20.0);
        assert!((c.alpha_rad - 0.4).abs() < 1e-15 && (c.sigma_rad - 0.7).abs() < 1e-15);
        assert_eq!(
            i.evaluate(-5.0),
            Command {
                alpha_rad: 0.1,
                sigma_rad: 0.2
            }
        );
        assert_eq!(
            i.evaluate(99.0),
            Command {
                alpha_rad: 0.5,
                sigma_rad: 0.2
            }
        );
        assert_eq!(
            i.evaluate(f64::NAN),
            Command {
                alpha_rad: 0.1,
                sigma_rad: 0.2
            }
        );
        // Energy table: x decreasing.
        let e = table(
            Independent::NormalizedEnergy,
            &[(1.0, 0.1, 0.2), (0.5, 0.3, 1.2)],
        );
        let i = Interpolator::new(&e, Interpolation::Linear).unwrap();
        assert!((i.evaluate(0.75).sigma_rad - 0.7).abs() < 1e-15);
        assert_eq!(i.evaluate(2.0).sigma_rad, 0.2);
        assert_eq!(i.evaluate(0.0).sigma_rad, 1.2);
    }

    /// Natural spline through (0, 0), (1, 0.5), (2, 0): by hand (eq. 5.6 with h = 1):
    /// 4 M1 = 6 ((0 - 0.5) - (0.5 - 0)) = -6, M1 = -1.5; at x = 0.5, A = B = 0.5:
    /// y = 0.5 * 0.5 + (B^3 - B) M1 / 6 = 0.25 + (-0.375)(-1.5)/6 = 0.34375.
    /// The same spline with x reversed (energy order) and scaled (time, x 0..200 s) must agree.
    #[test]
    fn natural_cubic_known_value() {
        let t = table(
            Independent::TimeS,
            &[(0.0, 0.0, 0.0), (1.0, 0.5, 0.5), (2.0, 0.0, 0.0)],
        );
        let i = Interpolator::new(&t, Interpolation::NaturalCubic).unwrap();
        assert!((i.evaluate(0.5).alpha_rad - 0.34375).abs() < 1e-14);
        assert!((i.evaluate(1.5).sigma_rad - 0.34375).abs() < 1e-14);
        let e = table(
            Independent::NormalizedEnergy,
            &[(0.9, 0.0, 0.0), (0.8, 0.5, 0.5), (0.7, 0.0, 0.0)],
        );
        let i = Interpolator::new(&e, Interpolation::NaturalCubic).unwrap();
        assert!((i.evaluate(0.85).alpha_rad - 0.34375).abs() < 1e-12);
        let nodes = [(0.0, 0.0, 0.0), (100.0, 0.5, 0.5), (200.0, 0.0, 0.0)];
        let tf: NodeTable<Fixed> = NodeTable::new(
            Independent::TimeS,
            &nodes.map(|(x, a, s)| Node {
                x: Fixed::from_f64(x),
                alpha_rad: Fixed::from_f64(a),
                sigma_rad: Fixed::from_f64(s),
            }),
            AngleBounds::thesis_default(),
        )
        .unwrap();
        let i = Interpolator::new(&tf, Interpolation::NaturalCubic).unwrap();
        assert!((i.evaluate(Fixed::from_f64(50.0)).alpha_rad.to_f64() - 0.34375).abs() < 1e-8);
    }

    /// Natural spline: second derivative zero at the ends and continuous inside, first
    /// derivative continuous (finite differences on a non-uniform table).
    #[test]
    fn natural_cubic_is_c2_with_natural_ends() {
        let t = table(
            Independent::TimeS,
            &[
                (0.0, 0.1, 0.0),
                (264.0, 0.3, 0.2),
                (290.0, 0.6, 1.3),
                (554.0, 0.2, 1.0),
                (1319.0, 0.5, 0.9),
            ],
        );
        let i = Interpolator::new(&t, Interpolation::NaturalCubic).unwrap();
        // Sample inside the bounds only where no clamp acts (sigma may clamp at 0 near 264 s).
        let f = |x: f64| i.evaluate(x).alpha_rad;
        let h = 1e-2;
        let d2 = |x: f64| (f(x + h) - 2.0 * f(x) + f(x - h)) / (h * h);
        let d1 = |x: f64| (f(x + h) - f(x - h)) / (2.0 * h);
        assert!(d2(h).abs() < 1e-6, "{}", d2(h));
        assert!(d2(1319.0 - h).abs() < 1e-6);
        for &x in &[264.0, 290.0, 554.0] {
            let l2 = (f(x - 2.0 * h) - 2.0 * f(x - h) + f(x)) / (h * h);
            let r2 = (f(x) - 2.0 * f(x + h) + f(x + 2.0 * h)) / (h * h);
            let scale = 1e-3 + l2.abs();
            assert!(
                (l2 - r2).abs() < 2e-2 * scale + 2e-6,
                "C2 at {x}: {l2} vs {r2}"
            );
            let l1 = (f(x) - f(x - h)) / h;
            let r1 = (f(x + h) - f(x)) / h;
            assert!((l1 - r1).abs() < 1e-4, "C1 at {x}");
            let _ = d1(x);
        }
    }

    /// Cardinal Hermite: the derivative at an interior node is eq. 5.11's tangent
    /// (1 - c)(p_{j+1} - p_{j-1})/(x_{j+1} - x_{j-1}) from both sides. With the misprinted
    /// h10 = t^3 - 2t^2 + 1 the spline would not even pass through the nodes.
    #[test]
    fn cardinal_tangents_match_eq_5_11() {
        let t = table(
            Independent::TimeS,
            &[
                (0.0, 0.1, 0.1),
                (10.0, 0.3, 0.5),
                (40.0, 0.4, 1.5),
                (50.0, 0.1, 0.1),
            ],
        );
        for c in [0.0, 0.5] {
            let i = Interpolator::new(&t, Interpolation::CardinalHermite { tension: c }).unwrap();
            let want = (1.0 - c) * (0.4 - 0.1) / (40.0 - 0.0);
            let h = 1e-5;
            let f = |x: f64| i.evaluate(x).alpha_rad;
            let left = (f(10.0) - f(10.0 - h)) / h;
            let right = (f(10.0 + h) - f(10.0)) / h;
            assert!(
                (left - want).abs() < 1e-6 && (right - want).abs() < 1e-6,
                "{left} {right} {want}"
            );
            assert_eq!(f(10.0), 0.3);
            // End tangent: one-sided (1 - c)(p1 - p0)/h0.
            let end = (f(h) - f(0.0)) / h;
            assert!((end - (1.0 - c) * 0.02).abs() < 1e-6);
        }
        let bad = Interpolation::CardinalHermite { tension: 1.5 };
        assert_eq!(
            Interpolator::new(&t, bad),
            Err(GuidanceError::InvalidConfig)
        );
        let bad = Interpolation::CardinalHermite { tension: f64::NAN };
        assert_eq!(
            Interpolator::new(&t, bad),
            Err(GuidanceError::InvalidConfig)
        );
    }

    /// A bank step followed by a plateau makes the spline overshoot above the step value; with a
    /// step to the bound the overshoot is clamped to the bound.
    #[test]
    fn spline_overshoot_is_clamped_to_bounds() {
        let ninety = core::f64::consts::FRAC_PI_2;
        let t = table(
            Independent::TimeS,
            &[
                (0.0, 0.1, 0.0),
                (10.0, 0.1, 0.0),
                (12.0, 0.1, ninety),
                (30.0, 0.1, ninety),
                (40.0, 0.1, ninety),
            ],
        );
        for kind in [
            Interpolation::NaturalCubic,
            Interpolation::CardinalHermite { tension: 0.0 },
        ] {
            let i = Interpolator::new(&t, kind).unwrap();
            let mut max: f64 = 0.0;
            let mut min: f64 = 1.0;
            for k in 0..=4000 {
                let c = i.evaluate(f64::from(k) * 0.01);
                max = max.max(c.sigma_rad);
                min = min.min(c.sigma_rad);
            }
            assert_eq!(max, ninety, "{kind:?}");
            assert_eq!(min, 0.0, "{kind:?}");
        }
        // Unclamped, the natural spline does overshoot here: the clamp is doing work.
        let wide = AngleBounds {
            sigma_max_rad: 3.0,
            sigma_min_rad: -3.0,
            ..AngleBounds::thesis_default()
        };
        let tw = NodeTable::<f64>::new(Independent::TimeS, t.nodes(), wide).unwrap();
        let i = Interpolator::new(&tw, Interpolation::NaturalCubic).unwrap();
        assert!((0..=4000).any(|k| i.evaluate(f64::from(k) * 0.01).sigma_rad > ninety + 1e-3));
    }
}
