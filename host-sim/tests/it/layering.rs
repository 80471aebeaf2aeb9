//! The layering rule of host-sim (docs/ARCHITECTURE.md): the library never imports `cli`
//! (only `cli/` itself and `main.rs` may), `optim/` imports nothing else of host-sim, and the
//! module graph at every depth (`crate::a::b`, `cli/` included, read by
//! [`crate::module_graph`]) has no import cycle (none is listed in [`ALLOWED_CYCLES`]).

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Code lines of a file (comment lines dropped, so docs may name `cli`).
fn code_lines(p: &Path) -> Vec<(usize, String)> {
    std::fs::read_to_string(p)
        .unwrap()
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with("//"))
        .map(|(i, l)| (i + 1, l.to_string()))
        .collect()
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// A line that names the `cli` module as a path (`crate::cli`, `host_sim::cli`, `super::cli`,
/// `cli::...`).
fn names_cli(line: &str) -> bool {
    [
        "crate::cli",
        "host_sim::cli",
        "super::cli",
        "use cli",
        " cli::",
        "(cli::",
    ]
    .iter()
    .any(|n| {
        let ident = |c: char| c.is_alphanumeric() || c == '_';
        line.match_indices(n)
            .any(|(i, _)| !line[i + n.len()..].starts_with(ident))
    })
}

#[test]
fn library_never_imports_cli() {
    let root = src();
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    assert!(
        files.len() > 20,
        "source tree not found at {}",
        root.display()
    );
    let mut bad = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&root).unwrap();
        if rel.starts_with("cli") || rel == Path::new("main.rs") {
            continue;
        }
        for (n, l) in code_lines(f) {
            if names_cli(&l) {
                bad.push(format!("{}:{n}: {}", rel.display(), l.trim()));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "library modules import `cli`:\n{}",
        bad.join("\n")
    );
}

#[test]
fn optim_imports_nothing_else_of_host_sim() {
    let root = src().join("optim");
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    assert!(!files.is_empty(), "optim/ not found");
    let mut bad = Vec::new();
    for f in &files {
        for (n, l) in code_lines(f) {
            let mut rest = l.as_str();
            while let Some(i) = rest.find("crate::") {
                if !rest[i..].starts_with("crate::optim") {
                    bad.push(format!("{}:{n}: {}", f.display(), l.trim()));
                    break;
                }
                rest = &rest[i + 7..];
            }
            if l.contains("host_sim::") || l.contains("super::super") {
                bad.push(format!("{}:{n}: {}", f.display(), l.trim()));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "optim/ imports other host-sim modules:\n{}",
        bad.join("\n")
    );
}

/// The checker itself: it sees the imports it must reject.
#[test]
fn layering_checker_detects_imports() {
    assert!(names_cli("use crate::cli::run;"));
    assert!(names_cli("    let x = host_sim::cli::Cli::parse();"));
    assert!(!names_cli("use crate::client::Thing;"));
    assert!(!names_cli("let clip = 3;"));
}

/// Import cycles that are allowed, each as the set of modules it joins and why it cannot be
/// broken. None is: the list stays (empty) so that a new cycle, or one that grew, fails the
/// test, and an entry that no longer matches a cycle fails it too.
const ALLOWED_CYCLES: &[(&[&str], &str)] = &[];

#[test]
fn module_graph_has_no_cycles_beyond_the_allow_list() {
    let g = crate::module_graph::graph(&src(), &["host_sim"]);
    for m in [
        "cli::optimize_cmd",
        "optim::algorithms::moead",
        "campaign::flight",
    ] {
        assert!(
            g.edges.contains_key(m),
            "module {m} not found: {:?}",
            g.edges.keys()
        );
    }
    assert!(g.edges.len() > 100, "{} modules", g.edges.len());
    let bad = g.cycle_mismatches(ALLOWED_CYCLES);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The graph reader itself: it follows `use` trees, `super::`, child paths and re-exports,
/// skips test code, and a cycle that is not allowed is reported.
#[test]
fn module_graph_reader_sees_cycles_at_depth() {
    let g = crate::module_graph::graph_of_texts(&[
        ("lib.rs", "mod a;\nmod b;\npub use a::Thing;\n"),
        (
            "a/mod.rs",
            "mod x;\nmod y;\npub use y::Thing;\nuse crate::{b::{self, Z}};\n\
             #[cfg(test)]\nmod tests;\n",
        ),
        (
            "a/x.rs",
            "use super::y::Y; // crate::b\nfn f() { let s = \"crate::b\"; }\n",
        ),
        (
            "a/y.rs",
            "pub struct Y; fn g() { super::x::f(); mycrate::Thing::new(); }\n",
        ),
        ("a/tests.rs", "use crate::b::Z;\n"),
        (
            "b.rs",
            "pub struct Z;\nfn h() { crate::Thing::new(); }\n#[cfg(test)]\nuse crate::a::x;\n",
        ),
    ]);
    let set = |v: &[&str]| {
        v.iter()
            .map(|s| s.to_string())
            .collect::<std::collections::BTreeSet<_>>()
    };
    assert_eq!(g.edges["a"], set(&["b"]));
    assert_eq!(g.edges["a::x"], set(&["a::y"]));
    // `mycrate::Thing` goes through the root's and a's re-exports to a::y itself.
    assert_eq!(g.edges["a::y"], set(&["a::x"]));
    assert_eq!(g.edges["b"], set(&["a::y"]));
    assert!(!g.edges.contains_key("a::tests"), "{:?}", g.edges);
    assert_eq!(g.cycles(), vec![set(&["a::x", "a::y"])]);
    let bad = g.cycle_mismatches(&[(&["a", "b"], "stale")]);
    assert_eq!(bad.len(), 2, "{bad:?}");
    assert!(
        g.cycle_mismatches(&[(&["a::x", "a::y"], "known")])
            .is_empty()
    );
}
