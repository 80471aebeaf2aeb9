//! [`BankShape`]: the stored profile's bank magnitude against E-hat, shifted by one offset,
//! as the numerical predictor's control (instead of a constant bank).
//!
//! A constant-bank prediction from a mid-flight state is not what the guidance then flies when
//! the stored profile's bank changes along the flight: HORUS-2B's profile holds 79.6 deg at
//! the heat peak and 59.8 deg after it. With a shape, a prediction flies
//! `|sigma|(E-hat) = clamp(shape(E-hat) + delta)`, the stored profile's magnitude (linear in
//! E-hat between its nodes) plus the offset `delta` that makes it `acos(f)` at the start of the
//! prediction; the solver still searches the vertical fraction `f` at the start (so its
//! bracket, tolerance and monotonicity are unchanged), and a re-plan installs the same offset
//! on every node it replaces ([`crate::replan::ReplanningGuidance::with_bank_shape`]). On the
//! undispersed flight the solved offset is near zero: the stored profile itself.
//!
//! The clamp is the solver's vertical-fraction interval: `|sigma|` in
//! `[acos(f_max), acos(f_min)]` at every state, as the installed nodes are.
//!
//! # Cost
//! Per RK4 stage: E-hat (two divisions), a scan over at most [`SHAPE_CAPACITY`] nodes with one
//! division, one cosine (in `f32` the predictor's single-precision polynomial).

use crate::energy::EnergyNormalizer;
use crate::error::GuidanceError;
use crate::scalar::Real;
use crate::vinh::num::cos_reduced;

/// Most nodes a [`BankShape`] holds (the onboard node table's capacity,
/// [`crate::nodes::DEFAULT_NODE_CAPACITY`]).
pub const SHAPE_CAPACITY: usize = crate::nodes::DEFAULT_NODE_CAPACITY;

/// The stored profile's bank magnitude against E-hat (module docs); the offset a prediction
/// flies is the prediction's own.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BankShape<S> {
    /// E-hat's constants: `1 / (2 mu/R)` \[s^2/m^2\], `R` \[m\], the inverse span \[-\]
    /// ([`EnergyNormalizer::parts`]).
    half_inv_vc2: S,
    planet_radius_m: S,
    inv_span: S,
    /// Node E-hat \[-\], strictly decreasing.
    x: [S; SHAPE_CAPACITY],
    /// Node bank magnitude \[rad\], in `[0, pi]`.
    sigma: [S; SHAPE_CAPACITY],
    len: u8,
    /// `acos(f_max)`, `acos(f_min)` \[rad\]: the bank interval.
    sigma_lo: S,
    sigma_hi: S,
}

impl<S: Real> BankShape<S> {
    /// The shape of `nodes` (`(E-hat [-], bank [rad])`, E-hat strictly decreasing; the sign
    /// of the bank is dropped), E-hat by `energy`, the bank held in `[acos(f_max),
    /// acos(f_min)]` (the solver's vertical-fraction interval).
    ///
    /// # Errors
    /// [`GuidanceError::InvalidConfig`] for no node, more than [`SHAPE_CAPACITY`], a
    /// non-finite value, E-hat not strictly decreasing, or `f_min > f_max` outside `[0, 1]`.
    pub fn new(
        energy: EnergyNormalizer<S>,
        nodes: impl IntoIterator<Item = (S, S)>,
        f_min: S,
        f_max: S,
    ) -> Result<Self, GuidanceError> {
        let bad = GuidanceError::InvalidConfig;
        if !(f_min.is_finite() && f_max.is_finite() && S::ZERO <= f_min && f_min <= f_max)
            || f_max > S::ONE
        {
            return Err(bad);
        }
        let mut x = [S::ZERO; SHAPE_CAPACITY];
        let mut sigma = [S::ZERO; SHAPE_CAPACITY];
        let mut len = 0_usize;
        for (e, s) in nodes {
            let s = s.abs();
            if !(e.is_finite() && s.is_finite()) {
                return Err(bad);
            }
            if let Some(prev) = len.checked_sub(1).and_then(|i| x.get(i))
                && !(e < *prev)
            {
                return Err(bad);
            }
            match (x.get_mut(len), sigma.get_mut(len)) {
                (Some(xs), Some(ss)) => {
                    *xs = e;
                    *ss = s;
                }
                _ => return Err(bad),
            }
            len += 1;
        }
        let len = u8::try_from(len).map_err(|_| bad)?;
        if len == 0 {
            return Err(bad);
        }
        let [vc, radius, inv_span] = energy.parts();
        let half_inv_vc2 = (S::ONE / (vc * vc)).half();
        if !half_inv_vc2.is_finite() {
            return Err(bad);
        }
        Ok(Self {
            half_inv_vc2,
            planet_radius_m: radius,
            inv_span,
            x,
            sigma,
            len,
            sigma_lo: f_max.acos(),
            sigma_hi: f_min.acos(),
        })
    }

    /// The nodes' E-hat \[-\] and bank magnitude \[rad\] (without the offset).
    pub fn nodes(&self) -> impl Iterator<Item = (S, S)> + '_ {
        self.x
            .iter()
            .copied()
            .zip(self.sigma.iter().copied())
            .take(usize::from(self.len))
    }

    /// The stored magnitude at `e_hat` \[rad\]: linear between the nodes, the end nodes'
    /// beyond them.
    #[must_use]
    pub fn sigma_at(&self, e_hat: S) -> S {
        let n = usize::from(self.len).min(SHAPE_CAPACITY);
        let (Some(xs), Some(ss)) = (self.x.get(..n), self.sigma.get(..n)) else {
            return S::ZERO;
        };
        let mut i = 0_usize;
        while i < n {
            let (Some(&x1), Some(&s1)) = (xs.get(i), ss.get(i)) else {
                break;
            };
            if e_hat >= x1 {
                return match (
                    i.checked_sub(1).and_then(|j| xs.get(j)),
                    i.checked_sub(1).and_then(|j| ss.get(j)),
                ) {
                    (Some(&x0), Some(&s0)) => s0 + (s1 - s0) * ((x0 - e_hat) / (x0 - x1)),
                    _ => s1,
                };
            }
            i += 1;
        }
        ss.last().copied().unwrap_or(S::ZERO)
    }

    /// `s` held in the bank interval \[rad\].
    #[must_use]
    pub fn clamp(&self, s: S) -> S {
        s.max(self.sigma_lo).min(self.sigma_hi)
    }

    /// The offset \[rad\] that makes the shape fly the vertical fraction `f` at `e_hat`.
    #[must_use]
    pub fn offset_for(&self, e_hat: S, f: S) -> S {
        f.clamp(-S::ONE, S::ONE).acos() - self.sigma_at(e_hat)
    }

    /// E-hat \[-\] at radius `radius_m` \[m\] and speed `speed_m_s` \[m/s\] (`None` where it is
    /// not computable).
    #[must_use]
    pub fn normalized_energy(&self, radius_m: S, speed_m_s: S) -> Option<S> {
        // `EnergyNormalizer::normalized` with one division instead of three.
        let e = (speed_m_s * speed_m_s * self.half_inv_vc2 + S::ONE
            - self.planet_radius_m / radius_m)
            * self.inv_span;
        (e.is_finite() && radius_m > S::ZERO).then_some(e)
    }

    /// The vertical fraction flown at `radius_m` \[m\], `speed_m_s` \[m/s\] with the offset
    /// `offset_rad` \[rad\]: `cos(clamp(shape(E-hat) + offset))` (`None` where E-hat is not
    /// computable). The offset is the prediction's own ([`BankShape::offset_for`]).
    #[must_use]
    pub fn fraction(&self, radius_m: S, speed_m_s: S, offset_rad: S) -> Option<S> {
        let e = self.normalized_energy(radius_m, speed_m_s)?;
        // The bank is in [0, pi/2]: the single-precision polynomial on f32 (libm's `cosf`
        // works in f64, soft-float on the Cortex-M4F); libm in f64.
        Some(cos_reduced(self.clamp(self.sigma_at(e) + offset_rad)))
    }
}
