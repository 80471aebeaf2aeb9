//! The reference documents generated from the code are current: docs/reference/cli.md is the
//! `--help` of every command (clap); the generated blocks of docs/reference/scenario.md are
//! the annotated scenario template (`--print-scenario`). Regenerate with
//! `UPDATE_DOCS=1 cargo test -p host-sim --test it doc_reference`.

use std::path::{Path, PathBuf};

use clap::CommandFactory;

fn doc_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("docs")
        .join("reference")
        .join(name)
}

/// Compare `generated` with the stored document, or write it when `UPDATE_DOCS` is set.
fn check_or_update(name: &str, generated: &str) {
    let path = doc_path(name);
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, generated).expect("the document is writable");
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        stored == generated,
        "{} is stale: regenerate it with `UPDATE_DOCS=1 cargo test -p host-sim --test it \
         doc_reference`",
        path.display()
    );
}

fn cli_markdown() -> String {
    let mut root = host_sim::cli::Cli::command().term_width(100);
    let mut out = String::from(
        "# Command line\n\nThe `--help` of `host-sim` and of each of its commands, generated from the \
         code (`UPDATE_DOCS=1 cargo test -p host-sim --test it doc_reference`; the test fails \
         when this file is stale). Run them with `cargo run --release -p host-sim -- COMMAND \
         ARGS`. Step-by-step use: docs/guides/.\n\n## host-sim\n\n```text\n",
    );
    out.push_str(root.render_long_help().to_string().trim_end());
    out.push_str("\n```\n");
    subcommands_markdown(&mut root, "host-sim", &mut out);
    out
}

/// The `--help` of each subcommand of `command` (named `path`), and of theirs (`optimize`'s
/// algorithms, without their `help` subcommand), in order.
fn subcommands_markdown(command: &mut clap::Command, path: &str, out: &mut String) {
    let names: Vec<String> = command
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .filter(|n| path == "host-sim" || n != "help")
        .collect();
    for name in names {
        let Some(sub) = command.find_subcommand_mut(&name) else {
            continue;
        };
        let path = format!("{path} {name}");
        let mut sub = sub.clone().bin_name(&path);
        out.push_str(&format!("\n## {path}\n\n```text\n"));
        out.push_str(sub.render_long_help().to_string().trim_end());
        out.push_str("\n```\n");
        subcommands_markdown(&mut sub, &path, out);
    }
}

#[test]
fn cli_reference_is_current() {
    check_or_update("cli.md", &cli_markdown());
}

/// `doc` with the block between `<!-- generated: NAME -->` and the next
/// `<!-- end generated -->` replaced by `content` in a TOML code block.
fn with_generated(doc: &str, name: &str, content: &str) -> String {
    let start = format!("<!-- generated: {name} -->\n");
    let end = "<!-- end generated -->";
    let Some(a) = doc.find(&start).map(|i| i + start.len()) else {
        panic!(
            "docs/reference/scenario.md has no `{}` marker",
            start.trim()
        );
    };
    let b = a + doc[a..]
        .find(end)
        .expect("an end marker after each generated block");
    format!("{}```toml\n{content}```\n{}", &doc[..a], &doc[b..])
}

#[test]
fn scenario_reference_is_current() {
    use host_sim::scenario::{Scenario, read_scenario, scenario_to_toml};
    let stored = std::fs::read_to_string(doc_path("scenario.md")).expect("scenario.md");
    let template = scenario_to_toml(&Scenario::default());
    let example = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("examples")
        .join("srm-glide-replanning.toml");
    let replanning = scenario_to_toml(&read_scenario(&example).expect("the example reads"));
    let section = &replanning[replanning
        .find("[guidance.lateral]")
        .expect("the example has guidance layers")..];
    let doc = with_generated(&stored, "print-scenario", &template);
    let doc = with_generated(&doc, "print-scenario-replanning", section);
    check_or_update("scenario.md", &doc);
}
