//! guidance-core's modules form a layered graph: no module imports, directly or through
//! others, a module that imports it back. Checked on the source text (`crate::<module>` paths
//! outside `#[cfg(test)]` code), so a new cycle fails here rather than in review.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn core_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("guidance-core")
        .join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("guidance-core/src is readable") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Top-level module a source file belongs to (`vinh/skip.rs` -> `vinh`), `None` for lib.rs.
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (name != "lib").then(|| name.to_string())
}

/// `crate::<module>` references of the non-test, non-comment code of `text`.
fn references(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let code = line.trim_start();
        if code.starts_with("#[cfg(test)]") {
            break; // unit tests sit at the end of each file
        }
        if code.starts_with("//") {
            continue;
        }
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

/// The module graph: module -> modules it references.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = core_src();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let Some(m) = module_of(&src, f) else {
            continue;
        };
        let text = std::fs::read_to_string(f).expect("source is readable");
        let refs = g.entry(m.clone()).or_default();
        refs.extend(references(&text).into_iter().filter(|r| *r != m));
    }
    g
}

/// A cycle through `start`, if any (depth-first search).
fn cycle_from(
    g: &BTreeMap<String, BTreeSet<String>>,
    start: &str,
    path: &mut Vec<String>,
) -> Option<Vec<String>> {
    let here = path.last()?.clone();
    for next in g.get(&here).into_iter().flatten() {
        if next == start {
            let mut c = path.clone();
            c.push(next.clone());
            return Some(c);
        }
        if !path.contains(next) {
            path.push(next.clone());
            if let Some(c) = cycle_from(g, start, path) {
                return Some(c);
            }
            path.pop();
        }
    }
    None
}

#[test]
fn guidance_core_modules_have_no_import_cycles() {
    let g = graph();
    assert!(
        g.contains_key("guidance") && g.contains_key("command"),
        "{g:?}"
    );
    for m in g.keys() {
        let mut path = vec![m.clone()];
        if let Some(c) = cycle_from(&g, m, &mut path) {
            panic!("import cycle in guidance-core: {}", c.join(" -> "));
        }
    }
}

/// The stages of the guidance path below `guidance` do not reach up into it.
#[test]
fn interp_and_rate_do_not_import_guidance() {
    let g = graph();
    for m in ["interp", "rate", "command", "nodes"] {
        let refs = g.get(m).expect("module exists");
        assert!(!refs.contains("guidance"), "{m} imports guidance: {refs:?}");
    }
}

/// The checker itself finds a cycle when there is one (so the test above can fail).
#[test]
fn cycle_checker_detects_a_cycle() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    g.entry("c".into()).or_default().insert("a".into());
    let mut path = vec!["a".to_string()];
    assert_eq!(
        cycle_from(&g, "a", &mut path),
        Some(vec!["a".into(), "b".into(), "c".into(), "a".into()])
    );
    assert_eq!(
        references("use crate::guidance::Command;\n// crate::x\n#[cfg(test)]\nuse crate::y;"),
        BTreeSet::from(["guidance".to_string()])
    );
}
