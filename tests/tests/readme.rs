//! The READMEs' code blocks are all tested: a Rust block runs as a doctest of `mechgen` (whose
//! crate docs are the workspace README), so none may be `ignore`d, `no_run` or hidden as
//! `text`; the other blocks are shell commands (`sh`). A block with no language would be Rust
//! to rustdoc but plain text to a reader, so it must say which it is.

use std::path::Path;

/// The info string of every fenced code block in `markdown`, with its line.
fn fences(markdown: &str) -> Vec<(usize, String)> {
    let mut open = false;
    let mut found = Vec::new();
    for (number, line) in markdown.lines().enumerate() {
        let Some(info) = line.trim_start().strip_prefix("```") else {
            continue;
        };
        if !open {
            found.push((number + 1, info.trim().to_owned()));
        }
        open = !open;
    }
    assert!(!open, "an unclosed code block");
    found
}

fn check(readme: &str, rust_allowed: bool) -> usize {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(readme);
    let text = std::fs::read_to_string(&path).unwrap();
    let blocks = fences(&text);
    for (line, info) in &blocks {
        let allowed = info == "sh" || (rust_allowed && info == "rust");
        assert!(
            allowed,
            "{readme}:{line}: a code block marked `{info}`: Rust blocks must be plain `rust` \
             (a doctest), the others `sh`"
        );
    }
    blocks.iter().filter(|(_, info)| info == "rust").count()
}

#[test]
fn every_rust_block_of_the_workspace_readme_is_a_doctest() {
    // The usage example, the nalgebra conversions, the shipped mechanisms.
    assert_eq!(check("README.md", true), 3);
}

#[test]
fn the_other_crates_readmes_hold_no_rust_block_that_no_doctest_runs() {
    check("mechanisms/README.md", false);
    check("mechgen-macros/README.md", false);
}
