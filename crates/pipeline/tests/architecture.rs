//! Architecture invariants of the whole workspace, checked on the source (as rust-analyzer's
//! tidy tests do): no file-level import cycle inside any crate, and no crate depending on one
//! above it in the data flow.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Source without comments and test modules.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or_default();
    text.lines()
        .map(|l| l.split("//").next().unwrap_or_default())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Identifiers following `prefix` in `text`.
fn after<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    text.match_indices(prefix)
        .map(|(i, _)| {
            let rest = &text[i + prefix.len()..];
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .filter(|s| !s.is_empty())
        .collect()
}

/// Names inside `use crate::{...};` groups (their first path segment).
fn grouped(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (i, _) in text.match_indices("use crate::{") {
        let rest = &text[i + "use crate::{".len()..];
        let Some(end) = rest.find("};") else { continue };
        for part in rest[..end].split(',') {
            let name = part.trim().split("::").next().unwrap_or_default().trim();
            if !name.is_empty() {
                out.push(name.to_string());
            }
        }
    }
    out
}

/// The module graph of one crate: file → files it imports from.
fn graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let files: BTreeMap<String, String> = std::fs::read_dir(src)
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "rs").then(|| {
                let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
                (stem, code(&std::fs::read_to_string(&p).unwrap()))
            })
        })
        .collect();
    let root = if files.contains_key("lib") { "lib" } else { "main" };
    let mods: BTreeSet<&str> = files
        .keys()
        .map(String::as_str)
        .filter(|m| *m != "lib" && *m != "main")
        .collect();
    let rt = &files[root];
    // Items the root defines, and items it re-exports from a module.
    let mut defined = BTreeSet::new();
    for kw in ["struct ", "enum ", "trait ", "fn ", "type ", "const "] {
        for line in rt.lines() {
            let l = line
                .trim_start()
                .trim_start_matches("pub(crate) ")
                .trim_start_matches("pub ");
            if let Some(rest) = l.strip_prefix(kw) {
                defined.insert(after(&format!(" {rest}"), " ")[0].to_string());
            }
        }
    }
    let mut reexported: BTreeMap<String, String> = BTreeMap::new();
    let mut glob = Vec::new();
    for line in rt.lines().map(str::trim) {
        let Some(rest) = line.strip_prefix("pub use ") else {
            continue;
        };
        let Some((m, items)) = rest.split_once("::") else {
            continue;
        };
        if !mods.contains(m) {
            continue;
        }
        if items.starts_with('*') {
            glob.push(m.to_string());
        }
        for it in items
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|s| !s.is_empty())
        {
            reexported.insert(it.to_string(), m.to_string());
        }
    }
    let mut g = BTreeMap::new();
    for (f, text) in &files {
        let mut refs: BTreeSet<String> = after(text, "crate::").into_iter().map(String::from).collect();
        refs.extend(grouped(text));
        if f == root {
            let body: String = text
                .lines()
                .filter(|l| {
                    let t = l.trim_start().trim_start_matches("pub ");
                    !(t.starts_with("mod ") || t.starts_with("use "))
                })
                .collect::<Vec<_>>()
                .join("\n");
            for m in &mods {
                if body.contains(&format!("{m}::")) {
                    refs.insert(m.to_string());
                }
            }
        }
        let mut deps = BTreeSet::new();
        for r in refs {
            if mods.contains(r.as_str()) {
                deps.insert(r);
            } else if defined.contains(&r) {
                deps.insert(root.to_string());
            } else if let Some(m) = reexported.get(&r) {
                deps.insert(m.clone());
            } else {
                deps.extend(glob.iter().cloned());
            }
        }
        deps.remove(f);
        g.insert(f.clone(), deps);
    }
    g
}

fn reaches(g: &BTreeMap<String, BTreeSet<String>>, a: &str, b: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![a.to_string()];
    while let Some(x) = stack.pop() {
        for d in g.get(&x).into_iter().flatten() {
            if d == b {
                return true;
            }
            if seen.insert(d.clone()) {
                stack.push(d.clone());
            }
        }
    }
    false
}

fn crates() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(workspace().join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.push(workspace().join("xfoil_runner"));
    v.sort();
    v
}

#[test]
fn no_file_level_import_cycle_in_any_crate() {
    let mut cycles = Vec::new();
    for c in crates() {
        let g = graph(&c.join("src"));
        let names: Vec<&String> = g.keys().collect();
        for (i, a) in names.iter().enumerate() {
            for b in &names[i + 1..] {
                if reaches(&g, a, b) && reaches(&g, b, a) {
                    cycles.push(format!("{}: {a}.rs <-> {b}.rs", c.display()));
                }
            }
        }
    }
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

/// The data flow, bottom up: a crate may depend only on crates of a lower rank.
const RANKS: [(&str, u32); 15] = [
    ("propbet-units", 0),
    ("propbet-plot", 0),
    ("xfoil-runner", 1),
    ("propbet-geometry", 1),
    ("propbet-bemt", 1),
    ("propbet-measure", 1),
    ("propbet-qprop", 2),
    ("propbet-atmosphere", 2),
    ("propbet-effects", 2),
    ("propbet-polar", 2),
    ("propbet-compare", 3),
    ("propbet-diagnose", 4),
    ("propbet-pipeline", 5),
    ("propbet-report", 6),
    ("propbet-cli", 7),
];

#[test]
fn no_crate_depends_on_one_above_it_in_the_data_flow() {
    let rank = |n: &str| RANKS.iter().find(|r| r.0 == n).map(|r| r.1);
    let mut wrong = Vec::new();
    for c in crates() {
        let toml = std::fs::read_to_string(c.join("Cargo.toml")).unwrap();
        let name = toml
            .lines()
            .find_map(|l| l.strip_prefix("name = "))
            .unwrap()
            .trim_matches('"')
            .to_string();
        let me = rank(&name).unwrap_or_else(|| panic!("{name}: give it a rank in RANKS"));
        let deps = toml.split("[dependencies]").nth(1).unwrap_or_default();
        let deps = deps.split("\n[").next().unwrap_or_default();
        for line in deps.lines() {
            let dep = line.split(['.', ' ', '=']).next().unwrap_or_default();
            if let Some(r) = rank(dep) {
                if r >= me {
                    wrong.push(format!("{name} (rank {me}) depends on {dep} (rank {r})"));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The Rust sources (not tests) of the workspace's crates and of `xfoil_runner`, with their paths.
fn sources() -> Vec<(PathBuf, String)> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = crates().into_iter().map(|c| c.join("src")).collect();
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let text = std::fs::read_to_string(&p).unwrap();
                out.push((p, text));
            }
        }
    }
    out
}

/// ARCHITECTURE.md's invariants that grep can see: no `unsafe`; the solver prints nothing,
/// reads no file and starts no process; only `xfoil_runner` starts a process (XFOIL, Xvfb); no
/// conversion between rpm, rev/s and rad/s outside `propbet-units` (its factors written out).
#[test]
fn the_invariants_grep_can_see_hold() {
    let mut broken = Vec::new();
    for (path, text) in sources() {
        let code = code(&text);
        let rel = path.strip_prefix(workspace()).unwrap().display().to_string();
        if code.contains("unsafe ") || code.contains("unsafe{") {
            broken.push(format!("{rel}: unsafe"));
        }
        if rel.starts_with("crates/bemt/") {
            for pat in ["println!", "eprintln!", "std::fs::", "File::open", "Command::new"] {
                if code.contains(pat) {
                    broken.push(format!("{rel}: the solver uses {pat}"));
                }
            }
        }
        if !rel.starts_with("crates/units/") {
            for pat in ["PI / 30", "30.0 / PI", "/ (2.0 * PI)", "/ 60.0", "* 60.0"] {
                if code.contains(pat) {
                    broken.push(format!(
                        "{rel}: `{pat}`, a conversion of rpm or rev/s outside propbet-units"
                    ));
                }
            }
        }
        if !rel.starts_with("xfoil_runner/") && (code.contains("Command::new") || code.contains("process::Command")) {
            broken.push(format!("{rel}: starts a process outside xfoil_runner"));
        }
    }
    assert!(broken.is_empty(), "{broken:#?}");
}

/// Every Rust file of the repository (sources and tests) opens with a `//!` line, and no comment
/// holds a date or an issue number: history is the CHANGELOG's and the commits'.
#[test]
fn every_file_says_what_it_is_and_no_comment_holds_history() {
    // What the check sees, and what it lets pass.
    assert_eq!(history("// bounds until 2026-11-23 were"), Some("a date"));
    assert_eq!(history("/// (Issue 17, item 5)"), Some("an issue number"));
    assert_eq!(history("// issues #4"), Some("an issue number"));
    assert_eq!(history("// a file named StepsTest_2022-01-18_1538.csv"), None);
    assert_eq!(history("// J sweeps at 2000-6000 rpm; the issue is drag"), None);
    let mut broken = Vec::new();
    let mut stack = vec![
        workspace().join("crates"),
        workspace().join("xfoil_runner"),
        workspace().join("tests"),
    ];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries {
            let p = e.unwrap().path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n != "target") {
                    stack.push(p);
                }
                continue;
            }
            if p.extension().is_none_or(|x| x != "rs") {
                continue;
            }
            let text = std::fs::read_to_string(&p).unwrap();
            let rel = p.strip_prefix(workspace()).unwrap().display().to_string();
            if !text.starts_with("//!") {
                broken.push(format!("{rel}: no //! line first"));
            }
            for (k, line) in text.lines().enumerate() {
                let Some(at) = line.find("//") else { continue };
                let comment = &line[at..];
                if line[..at].trim().is_empty()
                    || line[..at].trim_end().ends_with(';')
                    || line[..at].trim_end().ends_with('{')
                {
                    if let Some(why) = history(comment) {
                        broken.push(format!("{rel}:{}: {why}: {}", k + 1, line.trim()));
                    }
                }
            }
        }
    }
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

/// A date (YYYY-MM-DD, not inside a name) or an issue number in a comment.
fn history(comment: &str) -> Option<&'static str> {
    let b = comment.as_bytes();
    for i in 0..b.len().saturating_sub(9) {
        let digits = |r: std::ops::Range<usize>| r.clone().all(|k| b[k].is_ascii_digit());
        if b[i] == b'2'
            && b[i + 1] == b'0'
            && digits(i..i + 4)
            && b[i + 4] == b'-'
            && digits(i + 5..i + 7)
            && b[i + 7] == b'-'
            && digits(i + 8..i + 10)
        {
            let month = (b[i + 5] - b'0') * 10 + (b[i + 6] - b'0');
            let before = if i > 0 { b[i - 1] } else { b' ' };
            if (1..=12).contains(&month) && !before.is_ascii_alphanumeric() && before != b'_' {
                return Some("a date");
            }
        }
    }
    let lower = comment.to_lowercase();
    let mut rest = lower.as_str();
    while let Some(at) = rest.find("issue") {
        let after = rest[at + 5..]
            .trim_start_matches('s')
            .trim_start_matches(' ')
            .trim_start_matches('#');
        if after.starts_with(|c: char| c.is_ascii_digit()) {
            return Some("an issue number");
        }
        rest = &rest[at + 5..];
    }
    None
}
