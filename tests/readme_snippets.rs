//! The C, JavaScript, Python and firmware snippets in the README are excerpts of
//! code that CI compiles and runs. Each fenced block after a
//! `<!-- snippet: PATH -->` marker must appear in PATH: every non-blank line,
//! in order (comparing trimmed lines; lines containing `...` stand for code
//! left out).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use std::path::Path;

#[test]
fn readme_snippets_are_excerpts_of_compiled_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let mut checked = 0;
    let mut lines = readme.lines();
    while let Some(line) = lines.next() {
        let Some(path) = line
            .trim()
            .strip_prefix("<!-- snippet: ")
            .and_then(|r| r.strip_suffix(" -->"))
        else {
            continue;
        };
        let fence = lines.next().unwrap();
        assert!(fence.starts_with("```"), "snippet {path}: no code fence");
        let block: Vec<&str> = lines
            .by_ref()
            .take_while(|l| !l.starts_with("```"))
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.contains("..."))
            .collect();
        let source = std::fs::read_to_string(root.join(path)).unwrap();
        let mut src = source.lines().map(str::trim);
        for want in &block {
            assert!(
                src.any(|l| l == *want),
                "README snippet from {path}: line not found (in order): {want}"
            );
        }
        checked += 1;
    }
    assert_eq!(
        checked, 4,
        "expected the firmware, C, JS and Python snippets"
    );
}
