//! The documentation's links resolve: every relative Markdown link (`[text](path)`) of every
//! Markdown file in the repository points at a file or folder that exists, and every
//! repository path to a Markdown document named in the docs, the sources and the examples
//! (`docs/....md`, `CHANGELOG.md`) exists. Also the documentation rule that docs/ and the
//! crates' sources carry no scratch paths or accounts of how the work went.

use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Files under `dir` whose name ends with one of `exts`, skipping build output and VCS data.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if !matches!(
                name.as_str(),
                "target" | ".git" | "node_modules" | ".venv" | "corpus" | "runs"
            ) && !name.starts_with(".venv")
            {
                files(&path, exts, out);
            }
        } else if exts.iter().any(|e| name.ends_with(e)) {
            out.push(path);
        }
    }
}

/// The targets of the inline Markdown links `[text](target)` in `text`.
fn markdown_links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_code_block = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code_block = !in_code_block;
            continue;
        }
        if in_code_block {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else {
                break;
            };
            out.push(after[..end].to_string());
            rest = &after[end..];
        }
    }
    out
}

fn is_external(target: &str) -> bool {
    target.starts_with("http://")
        || target.starts_with("https://")
        || target.starts_with("mailto:")
        || target.starts_with('#')
}

#[test]
fn relative_markdown_links_resolve() {
    let root = repo_root();
    let mut mds = Vec::new();
    files(&root, &[".md"], &mut mds);
    assert!(mds.len() > 10, "found only {} Markdown files", mds.len());
    let mut broken = Vec::new();
    for md in &mds {
        let text = std::fs::read_to_string(md).expect("Markdown file is readable");
        for target in markdown_links(&text) {
            if is_external(&target) {
                continue;
            }
            let path = target.split('#').next().unwrap_or("");
            if path.is_empty() {
                continue;
            }
            let dir = md.parent().expect("a file has a parent");
            if !dir.join(path).exists() {
                broken.push(format!("{}: ({target})", md.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Repository paths of Markdown documents named in `text` (`docs/a/b.md`, `CHANGELOG.md`).
fn named_docs(text: &str) -> Vec<String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/');
    let mut out = Vec::new();
    for (i, _) in text.match_indices("docs/") {
        let before = text[..i].chars().next_back();
        if before.is_some_and(allowed) {
            continue; // part of a longer path (`python/docs/...`) or word
        }
        let tail: String = text[i..].chars().take_while(|&c| allowed(c)).collect();
        let tail = tail.trim_end_matches('.');
        if tail.ends_with(".md") {
            out.push(tail.to_string());
        }
    }
    out
}

#[test]
fn named_documents_exist() {
    let root = repo_root();
    let mut all = Vec::new();
    files(
        &root,
        &[".md", ".rs", ".toml", ".py", ".sh", ".yml"],
        &mut all,
    );
    let mut missing = Vec::new();
    for file in &all {
        if file.ends_with("tests/tests/it/doc_links.rs") {
            continue; // this file's examples name made-up documents
        }
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        for doc in named_docs(&text) {
            if !root.join(&doc).exists() {
                missing.push(format!("{}: {doc}", file.display()));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "documents named but missing:\n{}",
        missing.join("\n")
    );
}

#[test]
fn docs_and_sources_carry_no_work_history() {
    let root = repo_root();
    let mut all = Vec::new();
    files(&root.join("docs"), &[".md"], &mut all);
    for krate in [
        "guidance-core",
        "host-sim",
        "onboard-demo",
        "onboard-spec",
        "xtask",
        "tests",
        "fuzz",
        "python",
    ] {
        files(&root.join(krate).join("src"), &[".rs"], &mut all);
    }
    let phrases = [
        "/tmp/",
        "branch ",
        "this round",
        "previous round",
        "this session",
    ];
    let mut found = Vec::new();
    for file in &all {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        for (n, line) in text.lines().enumerate() {
            for p in phrases {
                if line.contains(p) {
                    found.push(format!("{}:{}: {p:?}", file.display(), n + 1));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "docs/ and the sources state what is true now and how to reproduce it (history goes to \
         CHANGELOG.md):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_link_scanners_find_what_they_look_for() {
    assert_eq!(
        markdown_links("see [a](docs/a.md#x) and [b](https://x.org)\n```\n[c](no)\n```"),
        ["docs/a.md#x", "https://x.org"]
    );
    assert_eq!(
        named_docs("(docs/reference/vinh.md), docs/guides/ and python/docs/x.md, docs/a.md."),
        ["docs/reference/vinh.md", "docs/a.md"]
    );
}
