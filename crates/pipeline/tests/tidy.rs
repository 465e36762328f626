//! The workspace's tidy test (as rust-analyzer's): every invariant of ARCHITECTURE.md that grep
//! or the manifests can see, checked on the source: no file-level import cycle inside a crate,
//! no crate depending on one above it in the data flow, no `unsafe`, processes started and
//! files written only where the architecture says, a solver and analysis crates without file
//! I/O, no unit conversion outside `propbet-units`, pages that load nothing, `anyhow` only in the
//! binary, a `//!` line first in every file, no history in comments, and rooms of a size a
//! person can hold (files up to 700 lines, functions up to 120 outside data tables).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Source without comments and test modules (a file of tests, `#![cfg(test)]`, is all test).
fn code(text: &str) -> String {
    if text.contains("\n#![cfg(test)]") {
        return String::new();
    }
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

/// The module graph of one crate: file → files it imports from. A module's folder
/// (`design/table.rs` beside `design.rs`) is part of the module: its imports are the module's.
fn graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let inner = sources();
    let files: BTreeMap<String, String> = std::fs::read_dir(src)
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "rs").then(|| {
                let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
                let mut text = code(&std::fs::read_to_string(&p).unwrap());
                for (_, t) in inner.iter().filter(|(f, _)| f.starts_with(src.join(&stem))) {
                    text.push('\n');
                    text.push_str(&code(t));
                }
                (stem, text)
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
const RANKS: [(&str, u32); 24] = [
    ("propbet-units", 0),
    ("propbet-plot", 0),
    ("xfoil-runner", 1),
    ("propbet-neuralfoil", 1),
    ("propbet-geometry", 1),
    ("propbet-bemt", 1),
    ("propbet-measure", 1),
    ("propbet-motor", 1),
    ("propbet-qprop", 2),
    ("propbet-atmosphere", 2),
    ("propbet-effects", 2),
    ("propbet-polar", 2),
    ("propbet-compare", 3),
    ("propbet-diagnose", 4),
    ("propbet-settings", 4),
    ("propbet-model", 5),
    ("propbet-pipeline", 6),
    ("propbet-validate", 7),
    ("propbet-simexport", 7),
    ("propbet-report", 8),
    ("propbet-api", 9),
    ("propbet-serve", 10),
    ("propbet-cli", 11),
    ("propbet-python", 12),
];

/// A crate's manifest: its package name and the names of its `[dependencies]`.
fn manifest(dir: &Path) -> (String, Vec<String>) {
    let text = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
    let toml: toml::Table = text.parse().unwrap();
    let name = toml["package"]["name"].as_str().unwrap().to_string();
    let deps = toml
        .get("dependencies")
        .and_then(|d| d.as_table())
        .map(|d| d.keys().cloned().collect())
        .unwrap_or_default();
    (name, deps)
}

#[test]
fn no_crate_depends_on_one_above_it_in_the_data_flow() {
    let rank = |n: &str| RANKS.iter().find(|r| r.0 == n).map(|r| r.1);
    let mut wrong = Vec::new();
    for c in crates() {
        let (name, deps) = manifest(&c);
        let me = rank(&name).unwrap_or_else(|| panic!("{name}: give it a rank in RANKS"));
        for dep in deps {
            if let Some(r) = rank(&dep) {
                if r >= me {
                    wrong.push(format!("{name} (rank {me}) depends on {dep} (rank {r})"));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// One door: the binary reaches every crate below through the typed API (what a user asks
/// for, the commands that run it, the types they hand out) and the workbench's HTTP door over
/// it.
#[test]
fn the_binary_reaches_the_crates_below_through_their_doors_only() {
    let (_, deps) = manifest(&workspace().join("crates/cli"));
    let ours: Vec<&String> = deps
        .iter()
        .filter(|d| RANKS.iter().any(|r| r.0 == d.as_str()) || d.as_str() == "nalgebra")
        .collect();
    assert_eq!(ours, ["propbet-api", "propbet-serve"]);
}

/// Errors are typed in every library crate (`thiserror`); `anyhow` is the binary's alone.
#[test]
fn anyhow_only_in_the_binary() {
    let with: Vec<String> = crates()
        .iter()
        .map(|c| manifest(c))
        .filter(|(_, deps)| deps.iter().any(|d| d == "anyhow"))
        .map(|(name, _)| name)
        .collect();
    assert_eq!(with, ["propbet-cli"]);
}

/// The Rust sources (not tests, nor the `tests.rs` unit-test modules) of the workspace's crates and of `xfoil_runner`, with their paths.
fn sources() -> Vec<(PathBuf, String)> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = crates().into_iter().map(|c| c.join("src")).collect();
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") && p.file_name().is_some_and(|n| n != "tests.rs") {
                let text = std::fs::read_to_string(&p).unwrap();
                out.push((p, text));
            }
        }
    }
    out
}

/// ARCHITECTURE.md's invariants that grep can see: no `unsafe`; the solver prints nothing,
/// reads no file and starts no process; only `xfoil_runner` starts a process (XFOIL, Xvfb); no
/// conversion between rpm, rev/s and rad/s outside `propbet-units` (its factors written out);
/// one median and one quantile (`propbet_units::stats`).
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
        // One median, one quantile (`propbet_units::stats`): every headline number uses the same.
        if rel != "crates/units/src/stats.rs" {
            for pat in ["fn median(", "fn quantile(", "fn percentile("] {
                if code.contains(pat) {
                    broken.push(format!(
                        "{rel}: `{pat}`, a median or quantile outside propbet_units::stats"
                    ));
                }
            }
        }
        // `propbet serve --open` starts the user's browser, and does not wait for it.
        let starts = ["xfoil_runner/", "crates/serve/src/lib.rs"];
        if !starts.iter().any(|w| rel.starts_with(w))
            && (code.contains("Command::new") || code.contains("process::Command"))
        {
            broken.push(format!("{rel}: starts a process outside xfoil_runner"));
        }
        // The solver and the analysis crates compute on what they are given: no file I/O.
        let pure = [
            "units",
            "plot",
            "geometry",
            "bemt",
            "measure",
            "atmosphere",
            "effects",
            "compare",
            "diagnose",
            "report",
        ];
        if pure.iter().any(|c| rel.starts_with(&format!("crates/{c}/"))) {
            for pat in ["std::fs", "fs::", "File::", "OpenOptions", "read_dir"] {
                if code.contains(pat) {
                    broken.push(format!("{rel}: file I/O (`{pat}`) in a crate that computes"));
                }
            }
        }
        // Outputs are written atomically by the API's writers; the polar cache and XFOIL's
        // own run folder are the only other files written.
        let writers = [
            "crates/api/src/files.rs",
            "crates/polar/src/compute.rs",
            "xfoil_runner/",
        ];
        if !writers.iter().any(|w| rel.starts_with(w)) {
            for pat in ["fs::write", "File::create", ".create(true)", ".append(true)"] {
                if code.contains(pat) {
                    broken.push(format!("{rel}: writes a file (`{pat}`) outside the atomic writers"));
                }
            }
        }
        // A page loads nothing: no script, no remote URL, no style sheet from elsewhere.
        if rel.starts_with("crates/report/") || rel.starts_with("crates/plot/") {
            for pat in ["<script", "http://", "https://", "@import", "<link"] {
                if code.contains(pat) {
                    broken.push(format!("{rel}: a page that loads something (`{pat}`)"));
                }
            }
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
    for (rel, text) in rust_files() {
        if !text.starts_with("//!") {
            broken.push(format!("{rel}: no //! line first"));
        }
        for (k, line) in text.lines().enumerate() {
            let Some(at) = line.find("//") else { continue };
            let comment = &line[at..];
            let before = line[..at].trim_end();
            if before.is_empty() || before.ends_with(';') || before.ends_with('{') {
                if let Some(why) = history(comment) {
                    broken.push(format!("{rel}:{}: {why}: {}", k + 1, line.trim()));
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

/// Every Rust file of the repository (sources, tests, benchmarks), as (path from the
/// workspace, text), sorted.
fn rust_files() -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = ["crates", "xfoil_runner", "tests", "benchsuite"]
        .iter()
        .map(|d| workspace().join(d))
        .collect();
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries {
            let p = e.unwrap().path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n != "target") {
                    stack.push(p);
                }
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(workspace()).unwrap().display().to_string();
                out.push((rel, std::fs::read_to_string(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// The longest a source file may be.
const MAX_FILE_LINES: usize = 700;
/// The longest a function may be (from its `fn` line to its closing brace).
const MAX_FN_LINES: usize = 120;

/// Functions allowed over [`MAX_FN_LINES`]: data tables (a list of cases, each a few lines,
/// read one at a time). A function that comes under the limit must leave the list.
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[
    (
        "tests/e2e/campaign.rs",
        "each_item_gets_a_clear_message_and_its_exit_code",
        "data table",
    ),
    (
        "tests/e2e/exit_codes.rs",
        "each_command_and_outcome_gets_the_code_its_help_gives",
        "data table",
    ),
    (
        "tests/e2e/diagnose/refusals.rs",
        "bad_input_gets_clear_messages",
        "data table",
    ),
    (
        "crates/cli/src/lib.rs",
        "specs_with_every_flag_parse_back",
        "data table",
    ),
];

#[test]
fn no_source_file_is_longer_than_700_lines() {
    let long: Vec<String> = rust_files()
        .into_iter()
        .filter(|(_, text)| text.lines().count() > MAX_FILE_LINES)
        .map(|(rel, text)| format!("{rel}: {} lines", text.lines().count()))
        .collect();
    assert!(long.is_empty(), "over {MAX_FILE_LINES} lines:\n{}", long.join("\n"));
}

#[test]
fn no_function_is_longer_than_120_lines_outside_data_tables() {
    // What the measure sees: braces in strings, chars and comments do not count; a lifetime is
    // not a char.
    let sample = "fn a() {\n    let s = \"}}\"; // }\n    let c = '{';\n    /* { */\n}\nfn b<'x>(v: &'x str) -> [&'x str; 1] {\n    [v]\n}\nfn c();\n";
    assert_eq!(
        function_lengths(sample),
        [("a".to_string(), 1, 5), ("b".to_string(), 6, 3)]
    );
    let mut found = Vec::new();
    for (rel, text) in rust_files() {
        for (name, line, n) in function_lengths(&text) {
            if n > MAX_FN_LINES {
                found.push((rel.clone(), name, line, n));
            }
        }
    }
    let listed = |rel: &str, name: &str| LONG_FUNCTIONS.iter().any(|l| l.0 == rel && l.1 == name);
    let new: Vec<String> = found
        .iter()
        .filter(|f| !listed(&f.0, &f.1))
        .map(|f| format!("{}:{}: fn {} is {} lines", f.0, f.2, f.1, f.3))
        .collect();
    assert!(new.is_empty(), "over {MAX_FN_LINES} lines:\n{}", new.join("\n"));
    let gone: Vec<String> = LONG_FUNCTIONS
        .iter()
        .filter(|l| !found.iter().any(|f| f.0 == l.0 && f.1 == l.1))
        .map(|l| format!("{}: fn {}", l.0, l.1))
        .collect();
    assert!(
        gone.is_empty(),
        "within the limit now: take them off LONG_FUNCTIONS:\n{}",
        gone.join("\n")
    );
}

/// The text with every comment and every string and char literal's content blanked (newlines
/// kept), so that braces count.
fn blanked(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let at = |k: usize| c.get(k).copied().unwrap_or('\0');
    let blank = |out: &mut String, ch: char| out.push(if ch == '\n' { '\n' } else { ' ' });
    while i < c.len() {
        if c[i] == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                blank(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            loop {
                if i >= c.len() {
                    break;
                }
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, c[i]);
                    i += 1;
                }
            }
        } else if c[i] == 'r'
            && (at(i + 1) == '"' || (at(i + 1) == '#' && matches!(at(i + 2), '"' | '#')))
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_'))
        {
            // A raw string: r"...", r#"..."#.
            let mut k = i + 1;
            let mut hashes = 0;
            while c.get(k) == Some(&'#') {
                hashes += 1;
                k += 1;
            }
            k += 1;
            let close: String = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let rest: String = c[k..].iter().collect();
            let end = rest
                .find(&close)
                .map_or(c.len(), |e| k + rest[..e].chars().count() + close.len());
            for &ch in &c[i..end] {
                blank(&mut out, ch);
            }
            i = end;
        } else if c[i] == '"' {
            blank(&mut out, c[i]);
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    blank(&mut out, c[i]);
                    i += 1;
                }
                if i < c.len() {
                    blank(&mut out, c[i]);
                    i += 1;
                }
            }
            if i < c.len() {
                blank(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '\'' && (at(i + 1) == '\\' || at(i + 2) == '\'') {
            // A char literal ('x', '\n', '\u{..}'); a lifetime has no closing quote.
            let end = (i + 1..c.len())
                .find(|&k| c[k] == '\'' && (c[k - 1] != '\\' || c[k - 2] == '\\'))
                .unwrap_or(c.len() - 1);
            for &ch in &c[i..=end] {
                blank(&mut out, ch);
            }
            i = end + 1;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Each function of `text` with a body: (name, line of its `fn`, lines to its closing brace).
fn function_lengths(text: &str) -> Vec<(String, usize, usize)> {
    let code = blanked(text);
    let lines: Vec<&str> = code.lines().collect();
    let mut out = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let mut words = line.split_whitespace().peekable();
        let mut name = None;
        while let Some(w) = words.next() {
            match w {
                "pub" | "const" | "async" | "unsafe" | "extern" | "default" => {}
                _ if w.starts_with("pub(") => {}
                "fn" => {
                    name = words
                        .next()
                        .map(|n| n.split(['(', '<']).next().unwrap_or(n).to_string());
                    break;
                }
                _ => break,
            }
        }
        let Some(name) = name else { continue };
        // The body: the first `{` before any `;`, and its matching `}`.
        let (mut depth, mut nested) = (0i32, 0i32);
        let mut end = None;
        'scan: for (j, l) in lines.iter().enumerate().skip(k) {
            for ch in l.chars() {
                match ch {
                    '(' | '[' => nested += 1,
                    ')' | ']' => nested -= 1,
                    ';' if depth == 0 && nested == 0 => break 'scan,
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            end = Some(j);
                            break 'scan;
                        }
                    }
                    _ => {}
                }
            }
        }
        if let Some(j) = end {
            out.push((name, k + 1, j - k + 1));
        }
    }
    out
}
