//! The layering rule of host-sim (docs/ARCHITECTURE.md): the library never imports `cli`
//! (only `cli/` itself and `main.rs` may), and `optim/` imports nothing else of host-sim.

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
