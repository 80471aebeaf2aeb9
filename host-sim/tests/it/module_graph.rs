//! The module graph of a crate, read from its sources: one node per module at every depth
//! (`a/b.rs` and `a/b/mod.rs` are `a::b`, `lib.rs` is `crate`, `main.rs` is `main`), one
//! arrow per module another's non-test code names (`use` trees and inline
//! `crate::`/`super::`/`self::`/child-module paths). Names a facade module re-exports
//! (`pub use sub::X`) are followed to the module that defines them, and a `pub use` is no arrow
//! itself, so a facade does not make a cycle of a child that uses its parent. Test code
//! (`#[cfg(test)]` modules and everything after the first other `#[cfg(test)]` of a file) is
//! not read. Shared by host-sim's `layering` test and the workspace `core_layering` test.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path, `crate` for the crate root (`crate::a::b` is `["a", "b"]`).
type ModPath = Vec<String>;

/// The module graph of one crate.
#[derive(Debug, Default)]
pub struct Graph {
    /// Module -> modules its code names (names as `a::b`, `crate` for the root).
    pub edges: BTreeMap<String, BTreeSet<String>>,
}

#[derive(Debug, PartialEq)]
enum Tok {
    Ident(String),
    Sep, // `::`
    Open,
    Close,
    Comma,
    Semi,
    Star,
    Hash,
    LBracket,
    RBracket,
    Other,
}

/// Tokens of Rust source, comments, strings and char literals dropped.
fn tokens(text: &str) -> Vec<Tok> {
    let c: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && c.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if ch == 'r'
            && matches!(c.get(i + 1), Some('"') | Some('#'))
            && (i == 0 || !is_ident(c[i - 1]))
        {
            // raw string r"..." / r#"..."#
            let mut j = i + 1;
            let mut hashes = 0;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if c.get(j) != Some(&'"') {
                out.push(Tok::Ident("r".into()));
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= c.len() {
                    break;
                }
                if c[j] == '"' && (0..hashes).all(|k| c.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            i = j;
            out.push(Tok::Other);
        } else if ch == '"' {
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push(Tok::Other);
        } else if ch == '\'' {
            // char literal or lifetime
            if c.get(i + 1) == Some(&'\\') {
                i += 2;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if c.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                i += 1;
                while i < c.len() && is_ident(c[i]) {
                    i += 1;
                }
            }
            out.push(Tok::Other);
        } else if is_ident(ch) {
            let s = i;
            while i < c.len() && is_ident(c[i]) {
                i += 1;
            }
            out.push(Tok::Ident(c[s..i].iter().collect()));
        } else {
            i += 1;
            out.push(match ch {
                ':' if c.get(i) == Some(&':') => {
                    i += 1;
                    Tok::Sep
                }
                '{' => Tok::Open,
                '}' => Tok::Close,
                ',' => Tok::Comma,
                ';' => Tok::Semi,
                '*' => Tok::Star,
                '#' => Tok::Hash,
                '[' => Tok::LBracket,
                ']' => Tok::RBracket,
                c if c.is_whitespace() => continue,
                _ => Tok::Other,
            });
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// A parsed `use` leaf: its path and the name it binds (`None` for a glob).
type UseLeaf = (Vec<String>, Option<String>);

/// Parses a use tree starting at `t[*i]` under `prefix`, leaves appended to `out`.
fn use_tree(t: &[Tok], i: &mut usize, prefix: Vec<String>, out: &mut Vec<UseLeaf>) {
    let mut path = prefix;
    loop {
        match t.get(*i) {
            Some(Tok::Sep) => *i += 1,
            Some(Tok::Ident(s)) if s == "as" => {
                *i += 1;
                if let Some(Tok::Ident(a)) = t.get(*i) {
                    *i += 1;
                    let a = a.clone();
                    out.push((path, Some(a)));
                    return;
                }
            }
            Some(Tok::Ident(s)) => {
                *i += 1;
                if s == "self" && !path.is_empty() {
                    let name = path.last().cloned();
                    if !matches!(t.get(*i), Some(Tok::Ident(a)) if a == "as") {
                        out.push((path, name));
                        return;
                    }
                    continue;
                }
                path.push(s.clone());
            }
            Some(Tok::Star) => {
                *i += 1;
                out.push((path, None));
                return;
            }
            Some(Tok::Open) => {
                *i += 1;
                loop {
                    match t.get(*i) {
                        None => return,
                        Some(Tok::Close) => {
                            *i += 1;
                            return;
                        }
                        Some(Tok::Comma) => *i += 1,
                        _ => use_tree(t, i, path.clone(), out),
                    }
                }
            }
            _ => {
                if !path.is_empty() {
                    let name = path.last().cloned();
                    out.push((path, name));
                }
                return;
            }
        }
    }
}

/// What one file says: its `use` leaves (with `pub`-ness) and inline paths.
#[derive(Debug, Default)]
struct FileRefs {
    /// (is `pub use`, leaf).
    uses: Vec<(bool, UseLeaf)>,
    /// Inline paths `a::b::c` (at least one `::`).
    paths: Vec<Vec<String>>,
    /// Child modules declared under `#[cfg(test)]`.
    test_children: BTreeSet<String>,
}

fn file_refs(text: &str) -> FileRefs {
    let t = tokens(text);
    let mut r = FileRefs::default();
    let mut i = 0;
    while i < t.len() {
        // `#[cfg(test)]`: a test child module is skipped, anything else ends the file.
        if t[i] == Tok::Hash
            && matches!(t.get(i + 2), Some(Tok::Ident(s)) if s == "cfg")
            && matches!(t.get(i + 4), Some(Tok::Ident(s)) if s == "test")
            && t.get(i + 6) == Some(&Tok::RBracket)
        {
            let mut j = i + 7; // past `]`
            while t.get(j) == Some(&Tok::Hash) {
                // further attributes: skip to the matching `]`
                let mut depth = 0;
                j += 1;
                while j < t.len() {
                    match t[j] {
                        Tok::LBracket => depth += 1,
                        Tok::RBracket => depth -= 1,
                        _ => {}
                    }
                    j += 1;
                    if depth == 0 {
                        break;
                    }
                }
            }
            if let (Some(Tok::Ident(m)), Some(Tok::Ident(name)), Some(Tok::Semi)) =
                (t.get(j), t.get(j + 1), t.get(j + 2))
                && m == "mod"
            {
                r.test_children.insert(name.clone());
                i = j + 3;
                continue;
            }
            break;
        }
        match &t[i] {
            Tok::Ident(s) if s == "use" => {
                let is_pub = i > 0
                    && (matches!(&t[i - 1], Tok::Ident(p) if p == "pub")
                        || (t[i - 1] == Tok::Other
                            && (i >= 3)
                            && t[..i - 1]
                                .iter()
                                .rev()
                                .take(4)
                                .any(|x| matches!(x, Tok::Ident(p) if p == "pub"))));
                i += 1;
                let mut leaves = Vec::new();
                use_tree(&t, &mut i, Vec::new(), &mut leaves);
                r.uses.extend(leaves.into_iter().map(|l| (is_pub, l)));
            }
            Tok::Ident(s) if i == 0 || t[i - 1] != Tok::Sep => {
                let mut p = vec![s.clone()];
                let mut j = i + 1;
                while t.get(j) == Some(&Tok::Sep) {
                    match t.get(j + 1) {
                        Some(Tok::Ident(n)) => {
                            p.push(n.clone());
                            j += 2;
                        }
                        _ => break,
                    }
                }
                if p.len() > 1 {
                    r.paths.push(p);
                }
                i = j;
            }
            _ => i += 1,
        }
    }
    r
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("source directory is readable") {
        let p = e.expect("directory entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Module path of a source file relative to `src`.
fn module_of(src: &Path, file: &Path) -> ModPath {
    let rel = file.strip_prefix(src).expect("file under src");
    let mut segs: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    let last = segs.pop().expect("a file name");
    let stem = last.strip_suffix(".rs").unwrap_or(&last).to_string();
    match stem.as_str() {
        "mod" => {}
        "lib" if segs.is_empty() => {}
        _ => segs.push(stem),
    }
    segs
}

/// Display name of a module path.
pub fn name(m: &[String]) -> String {
    if m.is_empty() {
        "crate".into()
    } else {
        m.join("::")
    }
}

struct Crate {
    modules: BTreeSet<ModPath>,
    /// Re-exports: module -> bound name -> absolute path (unresolved).
    reexports: BTreeMap<ModPath, BTreeMap<String, ModPath>>,
}

impl Crate {
    /// Absolute path of `p` named in module `m`, `None` for an external crate or a local name.
    fn absolute(&self, m: &ModPath, p: &[String], crate_names: &[&str]) -> Option<ModPath> {
        let first = p.first()?;
        let mut base: ModPath;
        let mut rest = p;
        if first == "crate" || crate_names.contains(&first.as_str()) {
            base = Vec::new();
            rest = &rest[1..];
        } else if first == "self" {
            base = m.clone();
            rest = &rest[1..];
        } else if first == "super" {
            base = m.clone();
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
        } else {
            let mut child = m.clone();
            child.push(first.clone());
            if !self.modules.contains(&child) {
                return None;
            }
            base = m.clone();
        }
        base.extend(rest.iter().cloned());
        Some(base)
    }

    /// The module that defines the item at absolute path `p` (following re-exports).
    fn target(&self, p: &[String], depth: usize) -> ModPath {
        let mut k = p.len();
        while k > 0 && !self.modules.contains(&p[..k]) {
            k -= 1;
        }
        let m = p[..k].to_vec();
        if depth < 8
            && let Some(item) = p.get(k)
            && let Some(src) = self.reexports.get(&m).and_then(|r| r.get(item))
        {
            let mut full = src.clone();
            full.extend(p[k + 1..].iter().cloned());
            return self.target(&full, depth + 1);
        }
        m
    }
}

/// The module graph of the crate whose sources are under `src`; `crate_names` are the names
/// its own code may use for itself (`host_sim` in main.rs).
pub fn graph(src: &Path, crate_names: &[&str]) -> Graph {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let parsed: Vec<(ModPath, FileRefs)> = files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).expect("source is readable");
            (module_of(src, f), file_refs(&text))
        })
        .collect();
    // Test modules (and everything below them) are not part of the graph.
    let mut test_mods: Vec<ModPath> = Vec::new();
    for (m, r) in &parsed {
        for c in &r.test_children {
            let mut t = m.clone();
            t.push(c.clone());
            test_mods.push(t);
        }
    }
    let parsed: Vec<(ModPath, FileRefs)> = parsed
        .into_iter()
        .filter(|(m, _)| !test_mods.iter().any(|t| m.starts_with(t)))
        .collect();
    let mut krate = Crate {
        modules: parsed.iter().map(|(m, _)| m.clone()).collect(),
        reexports: BTreeMap::new(),
    };
    for (m, r) in &parsed {
        for (is_pub, (p, bound)) in &r.uses {
            if let (true, Some(b), Some(abs)) = (is_pub, bound, krate.absolute(m, p, crate_names)) {
                krate
                    .reexports
                    .entry(m.clone())
                    .or_default()
                    .insert(b.clone(), abs);
            }
        }
    }
    let mut g = Graph::default();
    for (m, r) in &parsed {
        let mut out = BTreeSet::new();
        let private_uses = r.uses.iter().filter(|(p, _)| !p).map(|(_, (p, _))| p);
        for p in private_uses.chain(r.paths.iter()) {
            if let Some(abs) = krate.absolute(m, p, crate_names) {
                let t = krate.target(&abs, 0);
                if &t != m {
                    out.insert(name(&t));
                }
            }
        }
        g.edges.entry(name(m)).or_default().extend(out);
    }
    g
}

impl Graph {
    /// The cycles of this graph checked against an allow-list of `(modules, reason)`: a
    /// message for every cycle not in it and for every entry that no longer matches a cycle
    /// (so the list can only shrink). Empty when they agree.
    pub fn cycle_mismatches(&self, allowed: &[(&[&str], &str)]) -> Vec<String> {
        let found = self.cycles();
        let allowed: Vec<BTreeSet<String>> = allowed
            .iter()
            .map(|(m, _)| m.iter().map(|s| s.to_string()).collect())
            .collect();
        let mut bad = Vec::new();
        for c in &found {
            if !allowed.contains(c) {
                bad.push(format!(
                    "import cycle not in the allow-list: {:?} ({})",
                    c,
                    self.witness(c)
                ));
            }
        }
        for a in &allowed {
            if !found.contains(a) {
                bad.push(format!(
                    "allow-listed cycle is gone or changed: {a:?}; remove or update its entry"
                ));
            }
        }
        bad
    }

    /// Modules reachable from `m` (not counting `m` unless on a cycle).
    fn reach(&self, m: &str) -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut todo = vec![m.to_string()];
        while let Some(x) = todo.pop() {
            for y in self.edges.get(&x).into_iter().flatten() {
                if seen.insert(y.clone()) {
                    todo.push(y.clone());
                }
            }
        }
        seen
    }

    /// The import cycles: strongly connected sets of two or more modules.
    pub fn cycles(&self) -> Vec<BTreeSet<String>> {
        let reach: BTreeMap<&String, BTreeSet<String>> =
            self.edges.keys().map(|m| (m, self.reach(m))).collect();
        let mut out: Vec<BTreeSet<String>> = Vec::new();
        for (m, r) in &reach {
            if !r.contains(*m) || out.iter().any(|c| c.contains(*m)) {
                continue;
            }
            let scc: BTreeSet<String> = r
                .iter()
                .filter(|x| reach.get(x).is_some_and(|rx| rx.contains(*m)))
                .cloned()
                .collect();
            out.push(scc);
        }
        out
    }

    /// One arrow path `a -> ... -> a` through the modules of `scc` (for messages).
    pub fn witness(&self, scc: &BTreeSet<String>) -> String {
        let start = scc.iter().next().cloned().unwrap_or_default();
        let mut path = vec![start.clone()];
        let mut seen = BTreeSet::new();
        while let Some(here) = path.last().cloned() {
            let next = self.edges[&here]
                .iter()
                .filter(|n| scc.contains(*n))
                .find(|n| *n == &start || !seen.contains(*n))
                .cloned();
            match next {
                Some(n) if n == start => {
                    path.push(n);
                    break;
                }
                Some(n) => {
                    seen.insert(n.clone());
                    path.push(n);
                }
                None => break,
            }
        }
        path.join(" -> ")
    }
}

/// Graph of source text given as (file path under src, text) pairs, for the checker's own test.
pub fn graph_of_texts(files: &[(&str, &str)]) -> Graph {
    let dir = std::env::temp_dir().join(format!(
        "module-graph-{}-{}",
        std::process::id(),
        files.len()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    for (p, t) in files {
        let f = dir.join(p);
        std::fs::create_dir_all(f.parent().expect("a parent")).expect("temp dir");
        std::fs::write(&f, t).expect("temp file");
    }
    let g = graph(&dir, &["mycrate"]);
    let _ = std::fs::remove_dir_all(&dir);
    g
}
