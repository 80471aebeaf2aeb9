//! What a campaign's case results depend on, resolved: every input that can change a flight
//! (the `[dispersions]` settings but the number of cases, the scenario's entry, environment,
//! guidance profile, termination and integrator settings, the loaded vehicle, the set-up built
//! from them, the simulator's version) and, as a check on everything else (the code), the
//! nominal flight of each mode. Stored as `<out>/fingerprint.json` before the first case is
//! written; a later run into the same directory reuses its cases only if every field is equal
//! ([`check_and_record`]), so a resumed campaign is the campaign it claims to be.
//!
//! Values are exact text: settings as JSON, the rest as Rust's `Debug` (shortest round-trip
//! floats); a value longer than [`LONG_VALUE`] characters (a vehicle's aerodynamic tables) is
//! kept as its length and FNV-1a 64 digest.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::setup::CampaignSetup;
use super::{CampaignError, CaseResult, DispersionSettings};
use crate::report::{ReportError, write_atomic};
use crate::scenario::{AtmosphereSpec, EnvSpec, Scenario};
use crate::vehicle::Vehicle;
use guidance_core::stack::StackConfig;

pub use super::error::FINGERPRINT_FILE;

/// Version of the fingerprint's layout (a directory of another layout is not resumed).
pub const FORMAT: u32 = 1;

/// Values longer than this (characters) are stored as their length and digest.
pub const LONG_VALUE: usize = 2000;

/// Prefix of the per-mode nominal-flight fields: compared for the modes both runs fly, so a
/// run may add modes to a directory.
const NOMINAL: &str = "nominal.";

/// One input and its value as text.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingerprintField {
    /// Dotted name (`dispersions.seed`, `scenario.tolerances`, `nominal.stored`).
    pub field: String,
    /// The value (exact text, or `"<n> chars, fnv1a64 <hex>"` for a long one).
    pub value: String,
}

/// The resolved inputs of a campaign, in a fixed order (settings first, then scenario,
/// vehicle, version, set-up, nominal flights), so the first difference names the cause.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fingerprint {
    /// Layout version ([`FORMAT`]).
    pub format: u32,
    /// The inputs.
    pub fields: Vec<FingerprintField>,
}

/// A field whose value differs between two fingerprints (values abbreviated around the first
/// differing character; `(absent)` for a field one of them lacks).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FieldChange {
    /// The field.
    pub field: String,
    /// Its value in the stored fingerprint.
    pub old: String,
    /// Its value in this campaign's.
    pub new: String,
}

/// 64-bit FNV-1a of `s` (a change detector, not a cryptographic hash).
fn fnv1a64(s: &str) -> u64 {
    s.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// `s`, or its length and digest if longer than [`LONG_VALUE`].
fn value_text(s: String) -> String {
    let n = s.chars().count();
    if n <= LONG_VALUE {
        s
    } else {
        format!("{n} chars, fnv1a64 {:016x}", fnv1a64(&s))
    }
}

/// The fields of a JSON value, flattened to dotted names below `prefix` (objects recursed,
/// anything else compact JSON).
fn flatten(prefix: &str, v: &serde_json::Value, out: &mut Vec<FingerprintField>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                flatten(&format!("{prefix}.{k}"), x, out);
            }
        }
        other => out.push(FingerprintField {
            field: prefix.to_string(),
            value: value_text(other.to_string()),
        }),
    }
}

/// Builds the field list.
struct Fields(Vec<FingerprintField>);

impl Fields {
    fn debug(&mut self, field: &str, v: &dyn std::fmt::Debug) {
        self.0.push(FingerprintField {
            field: field.to_string(),
            value: value_text(format!("{v:?}")),
        });
    }

    /// The scenario's inputs to a flight (its name is not one; the vehicle is taken as
    /// loaded, not by the path it came from, nor a tabulated atmosphere's file name).
    fn scenario(&mut self, sc: &Scenario) {
        // Exhaustive: a field added to the scenario must be placed here.
        let Scenario {
            name: _,
            vehicle: _,
            environment,
            entry,
            guidance,
            termination,
            tolerances,
            output_interval_s,
            interface_altitude_m,
            g_rate_window_s,
            nose_radius_m,
            layers,
        } = sc;
        let EnvSpec {
            planet,
            atmosphere,
            gravity,
            rotating,
            heat_flux,
        } = environment;
        self.debug("scenario.environment.planet", planet);
        match atmosphere {
            AtmosphereSpec::Table(t) => self.debug("scenario.environment.atmosphere", &t.model),
            other => self.debug("scenario.environment.atmosphere", other),
        }
        self.debug("scenario.environment.gravity", gravity);
        self.debug("scenario.environment.rotating", rotating);
        self.debug("scenario.environment.heat_flux", heat_flux);
        self.debug("scenario.entry", entry);
        self.debug("scenario.guidance", guidance);
        self.debug("scenario.termination", termination);
        self.debug("scenario.tolerances", tolerances);
        self.debug("scenario.output_interval_s", output_interval_s);
        self.debug("scenario.interface_altitude_m", interface_altitude_m);
        self.debug("scenario.g_rate_window_s", g_rate_window_s);
        self.debug("scenario.nose_radius_m", nose_radius_m);
        self.debug("scenario.layers", layers);
    }

    /// The vehicle as loaded (its name is not an input).
    fn vehicle(&mut self, v: &Vehicle) {
        let Vehicle {
            name: _,
            mass_kg,
            reference_area_m2,
            nose_radius_m,
            limits,
            aero,
        } = v;
        self.debug("vehicle.mass_kg", mass_kg);
        self.debug("vehicle.reference_area_m2", reference_area_m2);
        self.debug("vehicle.nose_radius_m", nose_radius_m);
        self.debug("vehicle.limits", limits);
        self.debug("vehicle.aero", aero);
    }

    /// What the set-up derived (terminal interface, target, profile, lateral and re-planner
    /// settings): a check on the nominal flights and the code that built them.
    fn setup(&mut self, s: &CampaignSetup) {
        let CampaignSetup {
            scenario: _,
            file: _,
            interface_energy_j_kg,
            interface_speed_m_s,
            interface,
            floor_altitude_m,
            planet_radius_m,
            target_downrange_rad,
            stack,
            guidance,
        } = s;
        self.debug("setup.interface_energy_j_kg", interface_energy_j_kg);
        self.debug("setup.interface_speed_m_s", interface_speed_m_s);
        self.debug("setup.interface", interface);
        self.debug("setup.floor_altitude_m", floor_altitude_m);
        self.debug("setup.planet_radius_m", planet_radius_m);
        self.debug("setup.target_downrange_rad", target_downrange_rad);
        self.debug("setup.guidance", guidance);
        let StackConfig {
            profile,
            replan,
            lateral,
            estimator,
            barrier,
            target,
        } = stack;
        self.debug("setup.stack.profile", profile);
        self.debug("setup.stack.replan", replan);
        self.debug("setup.stack.lateral", lateral);
        self.debug("setup.stack.estimator", estimator);
        self.debug("setup.stack.barrier", barrier);
        self.debug("setup.stack.target", target);
    }
}

impl Fingerprint {
    /// The fingerprint of a campaign of `setup` and `settings` whose nominal flights (one per
    /// mode flown) are `nominal`.
    ///
    /// # Errors
    /// [`CampaignError::Scenario`] if the vehicle cannot be loaded; [`CampaignError::Report`]
    /// if the settings cannot be serialised.
    pub fn of(
        setup: &CampaignSetup,
        settings: &DispersionSettings,
        nominal: &[CaseResult],
    ) -> Result<Self, CampaignError> {
        let mut f = Fields(Vec::new());
        let mut s = serde_json::to_value(settings).map_err(ReportError::from)?;
        // The number of cases is no input of a case: a run may extend a campaign.
        if let Some(m) = s.as_object_mut() {
            m.remove("cases");
        }
        flatten("dispersions", &s, &mut f.0);
        f.scenario(&setup.scenario);
        let vehicle = setup
            .scenario
            .load_vehicle()
            .map_err(|e| CampaignError::Scenario {
                file: setup.file.clone(),
                source: Box::new(e),
            })?;
        f.vehicle(&vehicle);
        f.debug("host_sim.version", &env!("CARGO_PKG_VERSION"));
        f.setup(setup);
        for c in nominal {
            let json = serde_json::to_string(c).map_err(ReportError::from)?;
            f.0.push(FingerprintField {
                field: format!("{NOMINAL}{}", c.mode.name()),
                value: value_text(json),
            });
        }
        Ok(Self {
            format: FORMAT,
            fields: f.0,
        })
    }

    fn get(&self, field: &str) -> Option<&str> {
        self.fields
            .iter()
            .find(|f| f.field == field)
            .map(|f| f.value.as_str())
    }

    /// The first field (in this fingerprint's order, then `old`'s) whose value differs from
    /// the stored `old`; a nominal flight of a mode only one of them flew is no difference.
    #[must_use]
    pub fn first_difference(&self, old: &Self) -> Option<FieldChange> {
        const ABSENT: &str = "(absent)";
        if self.format != old.format {
            return Some(FieldChange {
                field: "format".into(),
                old: old.format.to_string(),
                new: self.format.to_string(),
            });
        }
        let change = |field: &str, o: &str, n: &str| {
            let (old, new) = abbreviate(o, n);
            FieldChange {
                field: field.to_string(),
                old,
                new,
            }
        };
        for f in &self.fields {
            match old.get(&f.field) {
                Some(o) if o == f.value => {}
                Some(o) => return Some(change(&f.field, o, &f.value)),
                None if f.field.starts_with(NOMINAL) => {}
                None => return Some(change(&f.field, ABSENT, &f.value)),
            }
        }
        old.fields
            .iter()
            .find(|o| !o.field.starts_with(NOMINAL) && self.get(&o.field).is_none())
            .map(|o| change(&o.field, &o.value, ABSENT))
    }

    /// This fingerprint with the nominal flights of the modes only `old` has (after a run
    /// that flew fewer modes, the directory still holds their cases).
    #[must_use]
    pub fn merged_with(&self, old: &Self) -> Self {
        let mut m = self.clone();
        for o in &old.fields {
            if o.field.starts_with(NOMINAL) && self.get(&o.field).is_none() {
                m.fields.push(o.clone());
            }
        }
        m
    }
}

/// Characters shown either side of the first difference.
const CONTEXT: usize = 40;

/// Both values cut to a window around their first differing character (`...` where cut).
fn abbreviate(a: &str, b: &str) -> (String, String) {
    let first = a
        .chars()
        .zip(b.chars())
        .position(|(x, y)| x != y)
        .unwrap_or_else(|| a.chars().count().min(b.chars().count()));
    let start = first.saturating_sub(CONTEXT);
    let cut = |s: &str| {
        let n = s.chars().count();
        let end = (first + CONTEXT).min(n);
        let mut t: String = s
            .chars()
            .skip(start)
            .take(end.saturating_sub(start))
            .collect();
        if start > 0 {
            t.insert_str(0, "...");
        }
        if end < n {
            t.push_str("...");
        }
        t
    };
    (cut(a), cut(b))
}

/// True if `dir/cases/<mode>/` holds any case file.
fn holds_cases(dir: &Path) -> bool {
    let Ok(modes) = std::fs::read_dir(dir.join("cases")) else {
        return false;
    };
    modes.flatten().any(|m| {
        std::fs::read_dir(m.path()).is_ok_and(|files| {
            files
                .flatten()
                .any(|f| f.path().extension().is_some_and(|e| e == "json"))
        })
    })
}

/// Make `dir` safe to resume into with `fp`: if it holds a fingerprint, it must equal `fp`
/// (but for the nominal flights of modes only one of them flew; the stored one gains `fp`'s);
/// if it holds case results without one, it is refused; otherwise `fp` is written (atomically)
/// before any case.
///
/// # Errors
/// [`CampaignError::ResumeMismatch`] naming the directory and the first differing field with
/// its old and new value; [`CampaignError::ResumeUnverified`] for case results without a
/// fingerprint; [`CampaignError::FingerprintFile`] for an unreadable one;
/// [`CampaignError::Report`] for an I/O error.
pub fn check_and_record(dir: &Path, fp: &Fingerprint) -> Result<(), CampaignError> {
    let path = dir.join(FINGERPRINT_FILE);
    let io = |path: PathBuf| move |source| ReportError::Io { path, source };
    let stored = match std::fs::read_to_string(&path) {
        Ok(text) => Some(
            serde_json::from_str::<Fingerprint>(&text).map_err(|source| {
                CampaignError::FingerprintFile {
                    path: path.clone(),
                    source,
                }
            })?,
        ),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => return Err(io(path.clone())(e).into()),
    };
    let record = match stored {
        Some(old) => {
            if let Some(c) = fp.first_difference(&old) {
                return Err(CampaignError::ResumeMismatch {
                    dir: dir.to_path_buf(),
                    field: c.field,
                    old: c.old,
                    new: c.new,
                });
            }
            let merged = fp.merged_with(&old);
            (merged != old).then_some(merged)
        }
        None if holds_cases(dir) => {
            return Err(CampaignError::ResumeUnverified {
                dir: dir.to_path_buf(),
            });
        }
        None => Some(fp.clone()),
    };
    if let Some(f) = record {
        std::fs::create_dir_all(dir).map_err(io(dir.to_path_buf()))?;
        let json = serde_json::to_vec_pretty(&f).map_err(ReportError::from)?;
        write_atomic(&path, &json)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fp(fields: &[(&str, &str)]) -> Fingerprint {
        Fingerprint {
            format: FORMAT,
            fields: fields
                .iter()
                .map(|(f, v)| FingerprintField {
                    field: (*f).into(),
                    value: (*v).into(),
                })
                .collect(),
        }
    }

    #[test]
    fn the_first_difference_is_named_with_both_values() {
        let old = fp(&[("dispersions.seed", "7"), ("scenario.entry", "E")]);
        let new = fp(&[("dispersions.seed", "8"), ("scenario.entry", "F")]);
        assert_eq!(
            new.first_difference(&old),
            Some(FieldChange {
                field: "dispersions.seed".into(),
                old: "7".into(),
                new: "8".into()
            })
        );
        assert_eq!(old.first_difference(&old), None);
        // A field only one of them has is a difference, but for nominal flights of a mode.
        let more = fp(&[
            ("dispersions.seed", "7"),
            ("scenario.entry", "E"),
            ("x", "1"),
        ]);
        assert_eq!(
            more.first_difference(&old).map(|c| c.old),
            Some("(absent)".into())
        );
        assert_eq!(
            old.first_difference(&more).map(|c| c.new),
            Some("(absent)".into())
        );
        let a = fp(&[("dispersions.seed", "7"), ("nominal.stored", "A")]);
        let b = fp(&[("dispersions.seed", "7"), ("nominal.replan-reversals", "B")]);
        assert_eq!(a.first_difference(&b), None);
        let merged = a.merged_with(&b);
        assert_eq!(merged.fields.len(), 3);
        let c = fp(&[("dispersions.seed", "7"), ("nominal.stored", "C")]);
        assert_eq!(
            c.first_difference(&merged).map(|c| c.field),
            Some("nominal.stored".into())
        );
    }

    #[test]
    fn long_values_are_cut_around_the_first_difference() {
        let a = format!("{}1{}", "x".repeat(100), "y".repeat(100));
        let b = format!("{}2{}", "x".repeat(100), "y".repeat(100));
        let (o, n) = abbreviate(&a, &b);
        assert_eq!(o, format!("...{}1{}...", "x".repeat(40), "y".repeat(39)));
        assert_eq!(n, format!("...{}2{}...", "x".repeat(40), "y".repeat(39)));
        assert_eq!(abbreviate("7", "8"), ("7".into(), "8".into()));
        assert_eq!(abbreviate("ab", "abc"), ("ab".into(), "abc".into()));
        let long = "z".repeat(LONG_VALUE + 1);
        assert!(
            value_text(long.clone()).starts_with(&format!("{} chars, fnv1a64 ", LONG_VALUE + 1))
        );
        assert_ne!(value_text(long), value_text("z".repeat(LONG_VALUE + 2)));
    }
}
