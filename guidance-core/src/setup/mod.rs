//! Guidance set-up over the PIL link: the host uploads a whole guidance configuration (node
//! table in either independent variable, interpolation, angle bounds, rates, period, initial
//! attitude, E-hat map and, when re-planning is used, its target and configuration:
//! [`replanning`]) as [`SetupItem`]s carried by set-up frames ([`crate::link::Frame::Setup`]);
//! the firmware collects them in a [`SetupBuilder`] and, on [`SetupItem::Commit`], builds its
//! guidance ([`SetupGuidance`]: the stored profile, or [`ReplanningGuidance`]) with the core's
//! own checks ([`NodeTable::new`], [`Guidance::new`], [`EnergyNormalizer::new`],
//! [`ReplanningGuidance::new`]). Every item is answered with a typed status (see
//! `onboard-demo`'s flight application).
//!
//! Payload of a set-up frame: seven `f64` slots, slot 0 the item code (an exact small integer),
//! the rest as listed on each [`SetupItem`] variant (unused slots 0).

use crate::command::Command;
use crate::energy::EnergyNormalizer;
use crate::error::{GuidanceError, NodeTableError};
use crate::guidance::{Guidance, GuidanceConfig, GuidanceOutput, RateLimits};
use crate::interp::Interpolation;
use crate::nav::NavState;
use crate::nodes::{AngleBounds, Independent, Node, NodeTable};
use crate::replan::ReplanningGuidance;
use crate::scalar::{Real, Scalar};

mod error;
pub mod image;
pub mod replanning;

pub use error::SetupError;
use error::small_int;
pub use replanning::{ReplanItem, replan_items};

/// One set-up item (all values SI, radians).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SetupItem {
    /// Code 1: the table's shape. Slots: node count, independent variable (0 E-hat, 1 time),
    /// interpolation (0 linear, 1 natural cubic, 2 cardinal Hermite), Hermite tension \[-\].
    Table {
        /// Number of nodes that follow.
        count: u32,
        /// Independent variable.
        independent: Independent,
        /// Interpolation (tension for Hermite).
        interpolation: Interpolation<f64>,
    },
    /// Code 2: node `index` (from 0). Slots: index, x (E-hat \[-\] or time \[s\]), alpha, sigma
    /// \[rad\].
    Node {
        /// Position in the table.
        index: u32,
        /// The node.
        node: Node<f64>,
    },
    /// Code 3: angle bounds. Slots: alpha min, alpha max, sigma min, sigma max \[rad\].
    Bounds(AngleBounds<f64>),
    /// Code 4: clock and rates. Slots: period \[s\], alpha rate, sigma rate \[rad/s\].
    Config(GuidanceConfig<f64>),
    /// Code 5: attitude before the first tick. Slots: alpha, sigma \[rad\].
    Initial(Command<f64>),
    /// Code 6: the E-hat map. Slots: mu \[m^3/s^2\], planet radius \[m\], entry radius \[m\],
    /// entry speed \[m/s\].
    Energy {
        /// Gravitational parameter \[m^3/s^2\].
        mu_m3_s2: f64,
        /// Planet radius \[m\].
        planet_radius_m: f64,
        /// Entry radius \[m\].
        entry_radius_m: f64,
        /// Entry speed \[m/s\].
        entry_speed_m_s: f64,
    },
    /// Code 7: build guidance from the items received.
    Commit,
    /// Codes 8 to 12: a re-planning item ([`ReplanItem`]).
    Replan(ReplanItem),
}

impl SetupItem {
    /// The seven payload slots.
    #[must_use]
    pub fn to_slots(&self) -> [f64; 7] {
        match *self {
            SetupItem::Table {
                count,
                independent,
                interpolation,
            } => {
                let ind = match independent {
                    Independent::NormalizedEnergy => 0.0,
                    Independent::TimeS => 1.0,
                };
                let (k, tension) = match interpolation {
                    Interpolation::Linear => (0.0, 0.0),
                    Interpolation::NaturalCubic => (1.0, 0.0),
                    Interpolation::CardinalHermite { tension } => (2.0, tension),
                };
                [1.0, f64::from(count), ind, k, tension, 0.0, 0.0]
            }
            SetupItem::Node { index, node } => [
                2.0,
                f64::from(index),
                node.x,
                node.alpha_rad,
                node.sigma_rad,
                0.0,
                0.0,
            ],
            SetupItem::Bounds(b) => [
                3.0,
                b.alpha_min_rad,
                b.alpha_max_rad,
                b.sigma_min_rad,
                b.sigma_max_rad,
                0.0,
                0.0,
            ],
            SetupItem::Config(c) => [
                4.0,
                c.period_s,
                c.rates.alpha_rad_s,
                c.rates.sigma_rad_s,
                0.0,
                0.0,
                0.0,
            ],
            SetupItem::Initial(c) => [5.0, c.alpha_rad, c.sigma_rad, 0.0, 0.0, 0.0, 0.0],
            SetupItem::Energy {
                mu_m3_s2,
                planet_radius_m,
                entry_radius_m,
                entry_speed_m_s,
            } => [
                6.0,
                mu_m3_s2,
                planet_radius_m,
                entry_radius_m,
                entry_speed_m_s,
                0.0,
                0.0,
            ],
            SetupItem::Commit => [7.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            SetupItem::Replan(r) => r.to_slots(),
        }
    }

    /// The item of seven payload slots.
    ///
    /// # Errors
    /// [`SetupError::BadItem`] for an unknown code, a malformed integer slot, or a payload that
    /// is not the item's canonical encoding (unused slots not +0).
    pub fn from_slots(s: &[f64; 7]) -> Result<Self, SetupError> {
        let item = Self::parse(s)?;
        let canonical = item.to_slots();
        if canonical
            .iter()
            .zip(s)
            .any(|(a, b)| a.to_bits() != b.to_bits())
        {
            return Err(SetupError::BadItem);
        }
        Ok(item)
    }

    fn parse(s: &[f64; 7]) -> Result<Self, SetupError> {
        let [code, a, b, c, d, _, _] = *s;
        Ok(match small_int(code, 12)? {
            1 => SetupItem::Table {
                count: small_int(a, 1 << 16)?,
                independent: match small_int(b, 1)? {
                    0 => Independent::NormalizedEnergy,
                    _ => Independent::TimeS,
                },
                interpolation: match small_int(c, 2)? {
                    0 => Interpolation::Linear,
                    1 => Interpolation::NaturalCubic,
                    _ => Interpolation::CardinalHermite { tension: d },
                },
            },
            2 => SetupItem::Node {
                index: small_int(a, 1 << 16)?,
                node: Node {
                    x: b,
                    alpha_rad: c,
                    sigma_rad: d,
                },
            },
            3 => SetupItem::Bounds(AngleBounds {
                alpha_min_rad: a,
                alpha_max_rad: b,
                sigma_min_rad: c,
                sigma_max_rad: d,
            }),
            4 => SetupItem::Config(GuidanceConfig {
                period_s: a,
                rates: RateLimits {
                    alpha_rad_s: b,
                    sigma_rad_s: c,
                },
            }),
            5 => SetupItem::Initial(Command {
                alpha_rad: a,
                sigma_rad: b,
            }),
            6 => SetupItem::Energy {
                mu_m3_s2: a,
                planet_radius_m: b,
                entry_radius_m: c,
                entry_speed_m_s: d,
            },
            7 => SetupItem::Commit,
            c @ 8..=12 => SetupItem::Replan(ReplanItem::parse(c, s)?),
            _ => return Err(SetupError::BadItem),
        })
    }
}

/// Collects [`SetupItem`]s on the firmware and builds guidance of scalar `S`, capacity `N`.
#[derive(Clone, Debug)]
pub struct SetupBuilder<S, const N: usize> {
    count: Option<usize>,
    independent: Independent,
    interpolation: Interpolation<S>,
    nodes: [Node<S>; N],
    have: [bool; N],
    bounds: Option<AngleBounds<S>>,
    config: Option<GuidanceConfig<S>>,
    initial: Option<Command<S>>,
    energy: Option<EnergyNormalizer<S>>,
    replan: replanning::ReplanParts,
}

impl<S: Scalar, const N: usize> Default for SetupBuilder<S, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const N: usize> SetupBuilder<S, N> {
    /// Nothing received yet.
    #[must_use]
    pub fn new() -> Self {
        let zero = Node {
            x: S::ZERO,
            alpha_rad: S::ZERO,
            sigma_rad: S::ZERO,
        };
        Self {
            count: None,
            independent: Independent::TimeS,
            interpolation: Interpolation::Linear,
            nodes: [zero; N],
            have: [false; N],
            bounds: None,
            config: None,
            initial: None,
            energy: None,
            replan: replanning::ReplanParts::default(),
        }
    }

    /// Take one item (not [`SetupItem::Commit`]: see [`SetupBuilder::build`]). Values are
    /// converted to `S` here; the checks run at [`SetupBuilder::build`].
    ///
    /// # Errors
    /// [`SetupError::BadIndex`] for a node outside the announced table,
    /// [`SetupError::Guidance`] for a table larger than `N` or an E-hat map the core rejects.
    pub fn apply(&mut self, item: &SetupItem) -> Result<(), SetupError> {
        let s = S::from_f64;
        match *item {
            SetupItem::Table {
                count,
                independent,
                interpolation,
            } => {
                let count = usize::try_from(count).map_err(|_| SetupError::BadItem)?;
                if count > N {
                    return Err(NodeTableError::TooManyNodes.into());
                }
                self.count = Some(count);
                self.independent = independent;
                self.interpolation = match interpolation {
                    Interpolation::Linear => Interpolation::Linear,
                    Interpolation::NaturalCubic => Interpolation::NaturalCubic,
                    Interpolation::CardinalHermite { tension } => Interpolation::CardinalHermite {
                        tension: s(tension),
                    },
                };
                self.have = [false; N];
            }
            SetupItem::Node { index, node } => {
                let i = usize::try_from(index).map_err(|_| SetupError::BadIndex)?;
                let count = self.count.ok_or(SetupError::BadIndex)?;
                if i >= count {
                    return Err(SetupError::BadIndex);
                }
                let slot = self.nodes.get_mut(i).ok_or(SetupError::BadIndex)?;
                *slot = Node {
                    x: s(node.x),
                    alpha_rad: s(node.alpha_rad),
                    sigma_rad: s(node.sigma_rad),
                };
                if let Some(h) = self.have.get_mut(i) {
                    *h = true;
                }
            }
            SetupItem::Bounds(b) => {
                self.bounds = Some(AngleBounds {
                    alpha_min_rad: s(b.alpha_min_rad),
                    alpha_max_rad: s(b.alpha_max_rad),
                    sigma_min_rad: s(b.sigma_min_rad),
                    sigma_max_rad: s(b.sigma_max_rad),
                });
            }
            SetupItem::Config(c) => {
                self.config = Some(GuidanceConfig {
                    period_s: s(c.period_s),
                    rates: RateLimits {
                        alpha_rad_s: s(c.rates.alpha_rad_s),
                        sigma_rad_s: s(c.rates.sigma_rad_s),
                    },
                });
            }
            SetupItem::Initial(c) => {
                self.initial = Some(Command {
                    alpha_rad: s(c.alpha_rad),
                    sigma_rad: s(c.sigma_rad),
                });
            }
            SetupItem::Energy {
                mu_m3_s2,
                planet_radius_m,
                entry_radius_m,
                entry_speed_m_s,
            } => {
                self.energy = Some(EnergyNormalizer::new(
                    mu_m3_s2,
                    planet_radius_m,
                    entry_radius_m,
                    entry_speed_m_s,
                )?);
            }
            SetupItem::Replan(r) => self.replan.apply(r),
            SetupItem::Commit => return Err(SetupError::BadItem),
        }
        Ok(())
    }

    /// Build the stored-profile guidance from the items received, with the core's checks.
    ///
    /// # Errors
    /// [`SetupError::Incomplete`] if an item or a node is missing; [`SetupError::BadItem`] if
    /// re-planning items were received (use [`SetupBuilder::build_flight`]);
    /// [`SetupError::Guidance`] with the core's error otherwise.
    pub fn build(&self) -> Result<Guidance<S, N>, SetupError> {
        if self.replan != replanning::ReplanParts::default() {
            return Err(SetupError::BadItem);
        }
        let (config, table, initial, energy) = self.parts()?;
        Ok(Guidance::new(
            config,
            table,
            self.interpolation,
            energy,
            initial,
        )?)
    }

    /// Build the guidance the items describe: [`SetupGuidance::Replanning`] (re-planner in the
    /// predictor scalar `P`) if the re-planning items were received, else
    /// [`SetupGuidance::Stored`]; with the core's checks.
    ///
    /// # Errors
    /// [`SetupError::Incomplete`] if an item or a node (or some of the re-planning items) is
    /// missing; [`SetupError::Guidance`] with the core's error otherwise.
    pub fn build_flight<P: Real>(&self) -> Result<SetupGuidance<S, N, P>, SetupError> {
        let (config, table, initial, energy) = self.parts()?;
        Ok(match self.replan.config::<P>()? {
            None => SetupGuidance::Stored(Guidance::new(
                config,
                table,
                self.interpolation,
                energy,
                initial,
            )?),
            Some(r) => SetupGuidance::Replanning(ReplanningGuidance::new(
                config,
                table,
                self.interpolation,
                energy,
                initial,
                r,
            )?),
        })
    }

    /// The checked table and the other items every guidance needs.
    #[allow(clippy::type_complexity)]
    fn parts(
        &self,
    ) -> Result<
        (
            GuidanceConfig<S>,
            NodeTable<S, N>,
            Command<S>,
            EnergyNormalizer<S>,
        ),
        SetupError,
    > {
        let count = self.count.ok_or(SetupError::Incomplete)?;
        let have = self.have.get(..count).ok_or(SetupError::Incomplete)?;
        if have.iter().any(|h| !h) {
            return Err(SetupError::Incomplete);
        }
        let nodes = self.nodes.get(..count).ok_or(SetupError::Incomplete)?;
        let (Some(bounds), Some(config), Some(initial), Some(energy)) =
            (self.bounds, self.config, self.initial, self.energy)
        else {
            return Err(SetupError::Incomplete);
        };
        let table = NodeTable::new(self.independent, nodes, bounds)?;
        Ok((config, table, initial, energy))
    }
}

/// Guidance built from a set-up: the stored profile, or the stored profile with onboard
/// re-planning (guidance scalar `S`, node capacity `N`, predictor scalar `P`).
#[derive(Clone, Debug, PartialEq)]
// The firmware holds exactly one of these for the whole run, statically: no allocation.
#[allow(clippy::large_enum_variant)]
pub enum SetupGuidance<S, const N: usize, P> {
    /// [`Guidance`] flying the uploaded table.
    Stored(Guidance<S, N>),
    /// [`ReplanningGuidance`] re-planning the uploaded table.
    Replanning(ReplanningGuidance<S, N, P>),
}

impl<S: Scalar, const N: usize, P: Real> SetupGuidance<S, N, P> {
    /// The guidance flying the table (held command, ramp, clock, rates).
    #[must_use]
    pub fn guidance(&self) -> &Guidance<S, N> {
        match self {
            SetupGuidance::Stored(g) => g,
            SetupGuidance::Replanning(r) => r.guidance(),
        }
    }

    /// One navigation sample ([`Guidance::update`], or [`ReplanningGuidance::update`]).
    ///
    /// # Errors
    /// As the guidance's own update.
    pub fn update(&mut self, nav: &NavState<S>) -> Result<GuidanceOutput<S>, GuidanceError> {
        match self {
            SetupGuidance::Stored(g) => g.update(nav),
            SetupGuidance::Replanning(r) => r.update(nav).map(|o| o.guidance),
        }
    }
}

/// The set-up items of a guidance configuration, in the order the host sends them (table,
/// nodes, bounds, config, initial attitude, E-hat map, the re-planning items if `replanning`
/// is given, commit). `energy` is (mu \[m^3/s^2\], planet radius \[m\], entry radius \[m\],
/// entry speed \[m/s\]).
pub fn items<'a, const N: usize>(
    table: &'a NodeTable<f64, N>,
    interpolation: Interpolation<f64>,
    config: GuidanceConfig<f64>,
    initial: Command<f64>,
    energy: (f64, f64, f64, f64),
    replanning: Option<&crate::replan::ReplanningConfig<f64>>,
) -> impl Iterator<Item = SetupItem> + 'a {
    let count = u32::try_from(table.len()).unwrap_or(u32::MAX);
    let head = [SetupItem::Table {
        count,
        independent: table.independent(),
        interpolation,
    }];
    let nodes = table
        .nodes()
        .iter()
        .zip(0u32..)
        .map(|(n, index)| SetupItem::Node { index, node: *n });
    let tail = [
        SetupItem::Bounds(table.bounds()),
        SetupItem::Config(config),
        SetupItem::Initial(initial),
        SetupItem::Energy {
            mu_m3_s2: energy.0,
            planet_radius_m: energy.1,
            entry_radius_m: energy.2,
            entry_speed_m_s: energy.3,
        },
    ];
    let replan = replanning
        .map(replan_items)
        .into_iter()
        .flatten()
        .map(SetupItem::Replan);
    head.into_iter()
        .chain(nodes)
        .chain(tail)
        .chain(replan)
        .chain([SetupItem::Commit])
}
