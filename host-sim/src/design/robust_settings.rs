//! Guidance settings of the base scenario's stack as decision variables of the robust problem
//! (`[[robust.settings]]`): each names a key of one of the base's layer sections
//! (`guidance.<section>.<key>`, [`LAYER_KEYS`]) and its range in the scenario file's units.
//! A decision's value is written into the base scenario's file model (its TOML text, as
//! [`scenario_to_toml`] prints it) and the whole file resolved again, so the scenario's own
//! range checks ([`parse_scenario`]) check it: one name and one check per setting. An element
//! of a pair-valued key (`limit_scale`) is named `guidance.<section>.limit_scale[0]` or `[1]`,
//! the other element keeping the base's value. A key the
//! base writes as an integer (`every_n_ticks`, `max_reversals`, `solver_steps_per_tick`) takes
//! its gene rounded to the nearest integer.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::DesignError;
use crate::num_fmt::compact;
use crate::scenario::guidance_layers::{CampaignGuidance, LAYER_KEYS};
use crate::scenario::{Scenario, ScenarioError, parse_scenario, scenario_to_toml};

/// One `[[robust.settings]]` entry: a guidance setting of the base's stack as a decision
/// variable.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SettingVariable {
    /// The scenario file's key path, `guidance.<section>.<key>` (`guidance.lateral.
    /// corridor_width_final_deg`, `guidance.replanning.tolerance_km`, ...): a number the
    /// base scenario's stack sets (its section present), or an element of a pair
    /// (`guidance.barrier.limit_scale[0]`).
    pub field: String,
    /// `[lower, upper]` in the scenario file's units, both accepted by the scenario.
    pub range: [f64; 2],
}

/// Where a setting's value goes: `[guidance.<section>] <key>`, or element `element` of that
/// pair; an integer key's value is rounded.
#[derive(Clone, Debug)]
struct SettingKey {
    section: String,
    key: String,
    element: Option<usize>,
    integer: bool,
}

/// `key[i]`: the key and `Some(Some(i))`; `key[...]` with no index 0 or 1: the key and
/// `Some(None)` (refused by the caller); `key`: the key and `None`.
#[allow(clippy::option_option)] // "no element" and "a bad element" differ
fn split_element(key: &str) -> (&str, Option<Option<usize>>) {
    match key.strip_suffix(']').and_then(|k| k.split_once('[')) {
        Some((name, index)) => (name, Some(index.parse::<usize>().ok().filter(|i| *i < 2))),
        None => (key, None),
    }
}

/// The settings checked against a base stack: its file model and where each value goes.
#[derive(Clone, Debug, Default)]
pub struct StackSettings {
    /// The base scenario as its file model (empty when no setting is named).
    table: toml::Table,
    /// Where each setting goes under `[guidance]`.
    keys: Vec<SettingKey>,
    /// The base's value of each setting.
    base: Vec<f64>,
    /// The base scenario's name in errors.
    file: String,
}

impl StackSettings {
    /// Check `settings` against the base `stack` (named `file` in errors): each names a number
    /// of the stack's layer sections once, with a finite range whose ends the scenario accepts.
    ///
    /// # Errors
    /// [`DesignError::Robust`] naming `robust.settings[i].field` or `.range` and the value.
    pub fn new(
        stack: &Scenario,
        settings: &[SettingVariable],
        file: &str,
    ) -> Result<Self, DesignError> {
        if settings.is_empty() {
            return Ok(Self::default());
        }
        let bad = |field: String, value: String, reason: String| DesignError::Robust {
            field,
            value,
            reason,
        };
        let table: toml::Table = toml::from_str(&scenario_to_toml(stack)).map_err(|e| {
            bad(
                "problem.base".into(),
                file.into(),
                format!("its printed file model does not parse again: {e}"),
            )
        })?;
        let sections = ["lateral", "replanning", "estimator", "barrier"];
        let mut out = Self {
            file: file.to_string(),
            ..Self::default()
        };
        for (i, s) in settings.iter().enumerate() {
            let name = format!("robust.settings[{i}].field");
            let parts: Vec<&str> = s.field.split('.').collect();
            let known = match parts.as_slice() {
                ["guidance", section, key] => {
                    let (key, element) = split_element(key);
                    LAYER_KEYS
                        .iter()
                        .any(|(_, sec, k)| sec == section && *k == key)
                        .then_some((*section, key, element))
                }
                _ => None,
            };
            let Some((section, key, element)) = known else {
                return Err(bad(
                    name,
                    format!("{:?}", s.field),
                    "not a guidance layer setting: name a key of the scenario file's \
                     [guidance.lateral], [guidance.replanning], [guidance.estimator] or \
                     [guidance.barrier] as guidance.<section>.<key> (an element of a pair \
                     as guidance.<section>.<key>[0] or [1])"
                        .into(),
                ));
            };
            if let Some(j) = settings[..i].iter().position(|o| o.field == s.field) {
                return Err(bad(
                    name,
                    format!("{:?}", s.field),
                    format!("named twice (also robust.settings[{j}].field)"),
                ));
            }
            let value = table
                .get("guidance")
                .and_then(|g| g.get(section))
                .and_then(|t| t.get(key));
            // An element of a pair: the base must write the pair and have that element.
            let value = match (element, value) {
                (None, v) => v,
                (Some(e), Some(toml::Value::Array(a))) if e.is_some_and(|e| e < a.len()) => {
                    e.and_then(|e| a.get(e))
                }
                (Some(_), Some(v)) => {
                    return Err(bad(
                        name,
                        format!("{:?}", s.field),
                        format!(
                            "not an element of the base scenario's {key} ({file}: {key} = {v}): \
                             name [0] or [1] of a pair"
                        ),
                    ));
                }
                (Some(_), None) => None,
            };
            let (base, integer) = match value {
                None => {
                    let on = sections.iter().any(|sec| {
                        *sec == section && table.get("guidance").and_then(|g| g.get(sec)).is_some()
                    });
                    let why = if on {
                        format!("the base scenario ({file}) does not set it (an optional key)")
                    } else {
                        format!(
                            "the base scenario's stack ({file}) has no [guidance.{section}] \
                             layer"
                        )
                    };
                    return Err(bad(name, format!("{:?}", s.field), why));
                }
                Some(toml::Value::Float(v)) => (*v, false),
                #[allow(clippy::cast_precision_loss)] // scenario integers are small
                Some(toml::Value::Integer(v)) => (*v as f64, true),
                Some(v) => {
                    return Err(bad(
                        name,
                        format!("{:?}", s.field),
                        format!(
                            "not a number in the base scenario ({file}: {key} = {v}): only a \
                             single number, or an element of a pair as {key}[0] or {key}[1], \
                             can be a decision variable"
                        ),
                    ));
                }
            };
            out.keys.push(SettingKey {
                section: section.to_string(),
                key: key.to_string(),
                element: element.flatten(),
                integer,
            });
            out.base.push(base);
        }
        out.table = table;
        for (i, s) in settings.iter().enumerate() {
            let name = format!("robust.settings[{i}].range");
            let [lo, hi] = s.range;
            let shown = format!("[{}, {}]", compact(lo), compact(hi));
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(bad(
                    name,
                    shown,
                    "give finite [lower, upper] with lower < upper".into(),
                ));
            }
            for v in [lo, hi] {
                let mut values = out.base.clone();
                values[i] = v;
                if let Err(e) = out.resolve(&values) {
                    return Err(bad(
                        name,
                        shown,
                        format!(
                            "{} = {} is refused by the scenario: {e}",
                            s.field,
                            compact(v)
                        ),
                    ));
                }
            }
        }
        Ok(out)
    }

    /// How many settings.
    #[must_use]
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// The base scenario's value of each setting (file units).
    #[must_use]
    pub fn base_values(&self) -> &[f64] {
        &self.base
    }

    /// The layer settings of the base with `values` written in (one per setting, file units;
    /// an integer key's rounded), resolved by the scenario's own parser.
    ///
    /// # Errors
    /// [`ScenarioError`] from the scenario's checks, naming the base file and the key.
    pub fn resolve(&self, values: &[f64]) -> Result<CampaignGuidance, ScenarioError> {
        let mut t = self.table.clone();
        for (k, v) in self.keys.iter().zip(values) {
            let value = if k.integer {
                #[allow(clippy::cast_possible_truncation)] // checked by the scenario's range
                toml::Value::Integer(v.round() as i64)
            } else {
                toml::Value::Float(*v)
            };
            if let Some(toml::Value::Table(g)) = t.get_mut("guidance")
                && let Some(toml::Value::Table(sec)) = g.get_mut(k.section.as_str())
            {
                match (k.element, sec.get_mut(k.key.as_str())) {
                    (Some(e), Some(toml::Value::Array(a))) => {
                        if let Some(slot) = a.get_mut(e) {
                            *slot = value;
                        }
                    }
                    _ => {
                        sec.insert(k.key.clone(), value);
                    }
                }
            }
        }
        let text = toml::to_string(&t).map_err(|e| ScenarioError::Field {
            file: self.file.clone(),
            field: "guidance".into(),
            value: String::new(),
            reason: format!("cannot write the file model: {e}"),
        })?;
        let sc = parse_scenario(&text, &self.file, Path::new("."))?;
        sc.layers
            .map(|l| l.settings)
            .ok_or_else(|| ScenarioError::Field {
                file: self.file.clone(),
                field: "guidance".into(),
                value: String::new(),
                reason: "the layers are gone".into(),
            })
    }
}
