//! Dispersion ellipses of a 2-D sample: the sample mean and covariance, the k-sigma ellipse
//! (the points at Mahalanobis distance k from the mean) and its axes, and the fraction of a
//! bivariate normal inside it (`1 - exp(-k^2 / 2)`: 39.3 %, 86.5 %, 98.9 % for k = 1, 2, 3).

/// Mean and covariance of a 2-D sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gaussian2 {
    /// Mean (x, y).
    pub mean: (f64, f64),
    /// Covariance `[[sxx, sxy], [sxy, syy]]` (sample covariance, divisor n - 1).
    pub cov: [[f64; 2]; 2],
}

/// Axes of an ellipse: semi-axes (major >= minor) and the major axis' angle from +x \[rad\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Semi-major axis (data units).
    pub major: f64,
    /// Semi-minor axis (data units).
    pub minor: f64,
    /// Angle of the major axis from the +x axis, in (-pi/2, pi/2] \[rad\].
    pub angle_rad: f64,
}

impl Gaussian2 {
    /// Mean and sample covariance of the finite points of `pts`; `None` for fewer than 2.
    #[must_use]
    pub fn of(pts: &[(f64, f64)]) -> Option<Self> {
        let v: Vec<(f64, f64)> = pts
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        if v.len() < 2 {
            return None;
        }
        let n = v.len() as f64;
        let mx = v.iter().map(|p| p.0).sum::<f64>() / n;
        let my = v.iter().map(|p| p.1).sum::<f64>() / n;
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for (x, y) in &v {
            let (dx, dy) = (x - mx, y - my);
            sxx += dx * dx;
            sxy += dx * dy;
            syy += dy * dy;
        }
        let d = n - 1.0;
        Some(Self {
            mean: (mx, my),
            cov: [[sxx / d, sxy / d], [sxy / d, syy / d]],
        })
    }

    /// The 1-sigma axes: square roots of the covariance's eigenvalues, the major axis along
    /// the eigenvector of the larger one.
    #[must_use]
    pub fn axes(&self) -> Axes {
        let [[a, b], [_, c]] = self.cov;
        let half_tr = 0.5 * (a + c);
        let disc = (0.25 * (a - c) * (a - c) + b * b).sqrt();
        let l1 = half_tr + disc;
        let l2 = (half_tr - disc).max(0.0);
        let angle_rad = 0.5 * (2.0 * b).atan2(a - c);
        Axes {
            major: l1.max(0.0).sqrt(),
            minor: l2.sqrt(),
            angle_rad,
        }
    }

    /// Squared Mahalanobis distance of `p` from the mean (`None` if the covariance is
    /// singular).
    #[must_use]
    pub fn mahalanobis2(&self, p: (f64, f64)) -> Option<f64> {
        let [[a, b], [_, c]] = self.cov;
        let det = a * c - b * b;
        if !(det.is_finite() && det > 0.0) {
            return None;
        }
        let (dx, dy) = (p.0 - self.mean.0, p.1 - self.mean.1);
        Some((c * dx * dx - 2.0 * b * dx * dy + a * dy * dy) / det)
    }

    /// `n` points (closed: the last is the first) of the `k`-sigma ellipse.
    #[must_use]
    pub fn ellipse(&self, k: f64, n: usize) -> Vec<(f64, f64)> {
        let ax = self.axes();
        let (s, c) = ax.angle_rad.sin_cos();
        let n = n.max(3);
        let mut pts: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                let (u, v) = (k * ax.major * t.cos(), k * ax.minor * t.sin());
                (self.mean.0 + c * u - s * v, self.mean.1 + s * u + c * v)
            })
            .collect();
        if let Some(&first) = pts.first() {
            pts.push(first);
        }
        pts
    }

    /// Fraction of `pts` inside (or on) the `k`-sigma ellipse (`None` if singular or empty).
    #[must_use]
    pub fn fraction_inside(&self, pts: &[(f64, f64)], k: f64) -> Option<f64> {
        if pts.is_empty() {
            return None;
        }
        let mut inside = 0usize;
        for p in pts {
            if self.mahalanobis2(*p)? <= k * k {
                inside += 1;
            }
        }
        Some(inside as f64 / pts.len() as f64)
    }
}

/// Fraction of a bivariate normal distribution inside its `k`-sigma ellipse.
#[must_use]
pub fn normal_fraction_inside(k: f64) -> f64 {
    1.0 - (-0.5 * k * k).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Axes of known covariances: diagonal, and [[2, 1], [1, 2]] (eigenvalues 3 and 1, major
    /// axis at 45 deg); every ellipse point at Mahalanobis distance k.
    #[test]
    fn axes_and_ellipse_of_a_known_covariance() {
        let g = Gaussian2 {
            mean: (1.0, -2.0),
            cov: [[4.0, 0.0], [0.0, 1.0]],
        };
        let ax = g.axes();
        assert!((ax.major - 2.0).abs() < 1e-12 && (ax.minor - 1.0).abs() < 1e-12);
        assert!(ax.angle_rad.abs() < 1e-12);
        let g = Gaussian2 {
            mean: (0.0, 0.0),
            cov: [[2.0, 1.0], [1.0, 2.0]],
        };
        let ax = g.axes();
        assert!((ax.major - 3f64.sqrt()).abs() < 1e-12, "{ax:?}");
        assert!((ax.minor - 1.0).abs() < 1e-12, "{ax:?}");
        assert!((ax.angle_rad - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        for k in [1.0, 2.0, 3.0] {
            let pts = g.ellipse(k, 72);
            assert_eq!(pts.len(), 73);
            assert_eq!(pts.first(), pts.last());
            for p in pts {
                let m = g.mahalanobis2(p).unwrap().sqrt();
                assert!((m - k).abs() < 1e-9, "{m} vs {k}");
            }
            // The major axis' end is at k sqrt(3) along 45 deg.
            let end = g.ellipse(k, 4)[0];
            let r = k * 3f64.sqrt() / 2f64.sqrt();
            assert!(
                (end.0 - r).abs() < 1e-9 && (end.1 - r).abs() < 1e-9,
                "{end:?}"
            );
        }
        assert!((normal_fraction_inside(1.0) - 0.393_469).abs() < 1e-6);
        assert!((normal_fraction_inside(3.0) - 0.988_891).abs() < 1e-6);
    }

    /// Sample mean and covariance (divisor n - 1) of a known sample; singular samples have
    /// no Mahalanobis distance.
    #[test]
    fn sample_covariance() {
        let pts = [
            (1.0, 2.0),
            (3.0, 6.0),
            (5.0, 4.0),
            (7.0, 8.0),
            (f64::NAN, 0.0),
        ];
        let g = Gaussian2::of(&pts).unwrap();
        assert_eq!(g.mean, (4.0, 5.0));
        // dx = -3 -1 1 3, dy = -3 1 -1 3: sxx = 20/3, syy = 20/3, sxy = 16/3.
        let want = [[20.0 / 3.0, 16.0 / 3.0], [16.0 / 3.0, 20.0 / 3.0]];
        for (r, w) in g.cov.iter().zip(want) {
            for (a, b) in r.iter().zip(w) {
                assert!((a - b).abs() < 1e-12, "{:?}", g.cov);
            }
        }
        assert!(Gaussian2::of(&[(1.0, 1.0)]).is_none());
        let line = Gaussian2::of(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)]).unwrap();
        assert!(line.mahalanobis2((0.0, 1.0)).is_none());
        // Of a large seeded normal sample about 39 %, 86 % and 99 % are inside.
        let mut s = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let pts: Vec<(f64, f64)> = (0..20_000)
            .map(|_| {
                let (u, v) = (uniform().max(1e-300), uniform());
                let r = (-2.0 * u.ln()).sqrt();
                let (a, b) = (
                    r * (std::f64::consts::TAU * v).cos(),
                    r * (std::f64::consts::TAU * v).sin(),
                );
                (3.0 * a + 1.0, 0.5 * a + b)
            })
            .collect();
        let g = Gaussian2::of(&pts).unwrap();
        for k in [1.0, 2.0, 3.0] {
            let f = g.fraction_inside(&pts, k).unwrap();
            assert!((f - normal_fraction_inside(k)).abs() < 0.01, "k {k}: {f}");
        }
    }
}
