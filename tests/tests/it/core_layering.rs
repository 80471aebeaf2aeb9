//! guidance-core's modules form a layered graph: no module, at any depth (`vinh::predict`,
//! `replan::numerical::dynamics`), imports, directly or through others, a module that imports
//! it back (no cycle is listed in [`ALLOWED_CYCLES`]). Checked on the source text by
//! host-sim's module-graph reader (`crate::module_graph`, shared with host-sim's layering
//! test), so a new cycle fails here rather than in review.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::module_graph::{Graph, graph};

fn core_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("guidance-core")
        .join("src")
}

/// Import cycles of guidance-core that are allowed, each as the set of modules it joins and
/// why. None is: the list stays (empty) so that a new cycle fails the test, and an entry added
/// here must say why the cycle cannot be broken (a stale entry fails too).
const ALLOWED_CYCLES: &[(&[&str], &str)] = &[];

#[test]
fn guidance_core_modules_have_no_import_cycles_beyond_the_allow_list() {
    let g = graph(&core_src(), &["guidance_core"]);
    for m in ["guidance", "command", "vinh::predict", "vinh::validity"] {
        assert!(
            g.edges.contains_key(m),
            "module {m} not found: {:?}",
            g.edges.keys()
        );
    }
    let bad = g.cycle_mismatches(ALLOWED_CYCLES);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Whether any module under `from` (itself or below) imports a module under `to`.
fn imports_under(g: &Graph, from: &str, to: &str) -> Vec<String> {
    let under = |m: &str, top: &str| m == top || m.starts_with(&format!("{top}::"));
    g.edges
        .iter()
        .filter(|(m, _)| under(m, from))
        .flat_map(|(m, refs)| {
            refs.iter()
                .filter(|r| under(r, to))
                .map(move |r| format!("{m} -> {r}"))
        })
        .collect()
}

/// The stages of the guidance path below `guidance` do not reach up into it.
#[test]
fn interp_and_rate_do_not_import_guidance() {
    let g = graph(&core_src(), &["guidance_core"]);
    for m in ["interp", "rate", "command", "nodes"] {
        assert!(g.edges.contains_key(m), "module {m} exists");
        let bad = imports_under(&g, m, "guidance");
        assert!(bad.is_empty(), "{m} imports guidance: {bad:?}");
    }
}

/// The checker finds a sub-module cycle like the `vinh::predict` <-> `vinh::validity` one it
/// replaced (so the test above can fail).
#[test]
fn cycle_checker_detects_a_sub_module_cycle() {
    let g = crate::module_graph::graph_of_texts(&[
        ("lib.rs", "pub mod vinh;\n"),
        (
            "vinh/mod.rs",
            "mod predict;\nmod validity;\npub use predict::Prediction;\n",
        ),
        (
            "vinh/predict.rs",
            "use super::validity::Validity;\npub struct Prediction;\n",
        ),
        (
            "vinh/validity.rs",
            "pub struct Validity;\nfn f(_: &super::Prediction) {}\n",
        ),
    ]);
    let want: BTreeSet<String> = ["vinh::predict", "vinh::validity"].map(String::from).into();
    assert_eq!(g.cycles(), vec![want]);
}
