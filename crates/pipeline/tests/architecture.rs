//! ARCHITECTURE.md held to what it promises: a map under 1,500 words whose every named test exists.

use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The Rust files below `dirs` (relative to the workspace), skipping folders named in `skip`.
fn rust_files(dirs: &[&str], skip: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = dirs.iter().map(|d| workspace().join(d)).collect();
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries {
            let p = e.unwrap().path();
            if p.is_dir() {
                if !skip.iter().any(|s| p.file_name().is_some_and(|n| n == *s)) {
                    stack.push(p);
                }
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out
}

/// Every Rust file of the workspace, tests included, with its text.
fn every_rust_file() -> Vec<String> {
    rust_files(&["crates", "tests", "xfoil_runner"], &["target"])
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

/// ARCHITECTURE.md stays a map a person reads in ten minutes, and every test it names as the
/// holder of an invariant exists (a `snake_case_name` in backticks with at least three
/// underscores is a test's name there).
#[test]
fn the_architecture_is_short_and_names_tests_that_exist() {
    let text = std::fs::read_to_string(workspace().join("ARCHITECTURE.md")).unwrap();
    let words = text.split_whitespace().count();
    assert!(words < 1500, "ARCHITECTURE.md has {words} words: at most 1,500");
    let code = every_rust_file().join("\n");
    let mut named = 0;
    for quoted in text.split('`').skip(1).step_by(2) {
        let is_test = quoted.matches('_').count() >= 3
            && quoted
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
        if is_test {
            named += 1;
            assert!(
                code.contains(&format!("fn {quoted}(")),
                "ARCHITECTURE.md names `{quoted}`, which no test is called"
            );
        }
    }
    assert!(
        named >= 15,
        "only {named} tests named: each invariant names the test that holds it"
    );
}

/// The typed doors hold no command line: the api crate and the Python package's modules neither
/// build nor parse argv (but for `execute`, the package's explicit door to a command line), and
/// the package keeps no flag list and builds no flags of its own.
#[test]
fn the_typed_doors_hold_no_command_line() {
    let root = workspace();
    let mut typed: Vec<PathBuf> = ["crates/api/src", "crates/python/src"]
        .iter()
        .flat_map(|d| std::fs::read_dir(root.join(d)).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    typed.sort();
    assert!(typed.len() >= 6, "{typed:?}");
    for p in &typed {
        let text = std::fs::read_to_string(p).unwrap();
        // The Python module's `execute` and `flags`, the doors not yet typed, live in its lib.rs.
        let text = match p.file_name().and_then(|n| n.to_str()) {
            Some("lib.rs") if p.starts_with(root.join("crates/python")) => {
                text.split("fn execute(").next().unwrap_or_default().to_string()
            }
            _ => text,
        };
        for word in ["argv", "parse_args", "try_parse_from", "Vec<String>) -> PyResult<bool>"] {
            assert!(!text.contains(word), "{}: `{word}`", p.display());
        }
    }
    let package = std::fs::read_to_string(root.join("crates/python/python/propbet/__init__.py")).unwrap();
    for name in [
        "_SWITCHES",
        "_pairs",
        "_split_predict",
        "_check_options",
        "_native.flags",
        "case_stages",
        "def _flags",
        "def _sweep",
    ] {
        assert!(!package.contains(name), "the Python package holds `{name}`");
    }
    // The commands' results come back in memory: no file a command wrote is read back.
    for call in ["_read_csv(", "_read_json(", ".read_text()", ".read_bytes()", "open("] {
        assert!(
            !package.contains(call),
            "the Python package reads back a file: `{call}`"
        );
    }
}

/// No command line is built or parsed below the binary: the CLI's argument parser and its one
/// formatter of equivalent commands (`crates/cli/src/argv.rs`) are the only places; the Python
/// package's `execute` is its explicit door to them; examples and benchmarks are programs of
/// their own.
#[test]
fn no_command_line_is_built_or_parsed_below_the_cli() {
    // The binary, and the programs of examples and benchmarks, parse their own.
    let files: Vec<PathBuf> = rust_files(&["crates"], &["cli", "target", "examples", "benches"])
        .into_iter()
        .filter(|p| !p.starts_with(workspace().join("crates/pipeline/tests")))
        .collect();
    for p in &files {
        let text = std::fs::read_to_string(p).unwrap();
        let text = if p.ends_with("crates/python/src/lib.rs") {
            text.split("fn execute(").next().unwrap_or_default().to_string()
        } else {
            text
        };
        for word in [
            "argv",
            "Argv",
            "shell_word",
            "from_flags",
            "parse_args",
            "try_parse_from",
            "env::args",
            "\"--effect {}\"",
        ] {
            assert!(!text.contains(word), "{}: `{word}`", p.display());
        }
    }
    assert!(files.len() > 100, "{} files read", files.len());
}

/// The pipeline is a door, not a warehouse: no module re-exporting the crates below (their
/// types are the API's, `propbet_api::{bemt, qprop, ...}`), no validation harness or simulator
/// export (crates of their own), and its public items held to a ceiling that only goes down.
#[test]
fn the_pipeline_is_a_door_not_a_warehouse() {
    let src = workspace().join("crates/pipeline/src");
    for gone in ["artifacts.rs", "validate.rs", "simexport.rs", "validate", "simexport"] {
        assert!(!src.join(gone).exists(), "crates/pipeline/src/{gone}");
    }
    let mut items = 0;
    for p in rust_files(&["crates/pipeline/src"], &[]) {
        if p.ends_with("tests.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let body = text.split("#[cfg(test)]").next().unwrap_or_default();
        items += body
            .lines()
            .map(str::trim_start)
            .filter(|l| {
                [
                    "fn ", "struct ", "enum ", "mod ", "use ", "type ", "const ", "trait ", "static ",
                ]
                .iter()
                .any(|k| l.starts_with(&format!("pub {k}")))
            })
            .count();
    }
    const CEILING: usize = 95;
    assert!(
        items <= CEILING,
        "the pipeline has {items} pub items, more than {CEILING}"
    );
}

/// One XFOIL request: how a section's polar is asked for (Ncrit, trip, angles, panels,
/// iterations) is `xfoil_runner::SectionSettings`, carried whole from the pipeline's
/// `XfoilSpec` and validate's spec down to XFOIL's script. No other struct below the doors (the
/// case file's keys, the API's request, the command's flags) holds these fields; the Ncrit a
/// computed polar records, NeuralFoil's inputs at one condition, and the transition effect's
/// fitted parameter are not requests.
#[test]
fn one_xfoil_request_below_the_doors() {
    let root = workspace();
    let below = [
        "xfoil_runner/src",
        "crates/polar/src",
        "crates/neuralfoil/src",
        "crates/model/src",
        "crates/pipeline/src",
        "crates/validate/src",
        "crates/effects/src",
    ];
    let not_requests = [
        "crates/pipeline/src/case.rs",
        "crates/polar/src/table.rs",
        "crates/polar/src/neural.rs",
        "crates/neuralfoil/src/lib.rs",
        "crates/effects/src/transition.rs",
    ];
    let mut holders = Vec::new();
    for p in rust_files(&below, &[]) {
        let rel = p.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
        if not_requests.contains(&rel.as_str()) {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        for field in ["pub ncrit:", "pub panels:", "pub max_iter:", "pub iter:", "pub trip:"] {
            if text.contains(field) {
                holders.push(format!("{rel}: `{field}`"));
            }
        }
    }
    holders.sort();
    assert_eq!(
        holders,
        [
            "xfoil_runner/src/run.rs: `pub max_iter:`",
            "xfoil_runner/src/run.rs: `pub ncrit:`",
            "xfoil_runner/src/run.rs: `pub panels:`",
            "xfoil_runner/src/run.rs: `pub trip:`",
        ],
        "the settings a polar is asked with are SectionSettings' alone"
    );
}

/// Ncrit, as a user gives it, is a field of one struct per door: the typed API's
/// `SectionRequest`, which the command line's flags are (every command that makes polars,
/// `validate` and `hidden` too, flattens it) and the Python package fills, and the case file's
/// `[polars]`; below them, of `SectionSettings` alone (`one_xfoil_request_below_the_doors`).
#[test]
fn ncrit_is_a_field_of_one_struct_per_door() {
    let root = workspace();
    let doors = [
        (
            "the command line and the API",
            vec!["crates/cli/src", "crates/api/src", "crates/python/src"],
            "crates/api/src/request.rs",
        ),
        (
            "the case file",
            vec!["crates/pipeline/src/case.rs", "crates/pipeline/src/case"],
            "crates/pipeline/src/case.rs",
        ),
    ];
    for (door, dirs, one) in doors {
        let mut holders = Vec::new();
        let mut files = rust_files(&dirs, &[]);
        files.extend(dirs.iter().map(|d| root.join(d)).filter(|p| p.is_file()));
        for p in files {
            let text = std::fs::read_to_string(&p).unwrap();
            let body = text.split("#[cfg(test)]").next().unwrap_or_default();
            let n = body
                .lines()
                .filter(|l| l.trim_start().starts_with("pub ncrit:"))
                .count();
            let rel = p.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
            holders.extend(std::iter::repeat_n(rel, n));
        }
        assert_eq!(holders, [one], "{door}: Ncrit is a field of one struct");
    }
}

/// The binary parses arguments, talks to the terminal and chooses the exit code: the tables,
/// pages, JSON documents and parallel solves its commands print or write are made below it
/// (`propbet_api::outputs`, `propbet_report::table`), and its files are written through
/// `propbet_api::files`. Its non-test lines are held to a ceiling that only goes down.
#[test]
fn the_binary_parses_prints_and_writes_nothing_it_computes() {
    let mut lines = 0;
    let mut found = Vec::new();
    for p in rust_files(&["crates/cli/src"], &[]) {
        let text = std::fs::read_to_string(&p).unwrap();
        if text.contains("#![cfg(test)]") {
            continue;
        }
        let body = text.split("#[cfg(test)]").next().unwrap_or_default();
        lines += body.lines().count();
        for word in [
            "csv::",
            "csv_rows(",
            "json!(",
            "::build(",
            "par_chunks",
            "par_iter",
            "stages::solve",
            "stages::sweep",
            "solve::solve",
            "solve::sweep",
            "BandSpec",
            "derive(serde::Serialize",
            "textwrap::wrap",
            "std::fs::write",
            "File::create",
        ] {
            if body.contains(word) {
                found.push(format!("{}: `{word}`", p.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "computed or written in the binary:\n{}",
        found.join("\n")
    );
    const CEILING: usize = 2063;
    assert!(
        lines <= CEILING,
        "the binary has {lines} non-test lines, more than {CEILING}"
    );
}

/// The CHANGELOG is by version, as Keep a Changelog has it: `[Unreleased]` first, then each
/// released version with its date, newest first, the workspace's own version among them; its
/// sections are Keep a Changelog's.
#[test]
fn the_changelog_is_by_version_and_names_the_workspaces() {
    let text = std::fs::read_to_string(workspace().join("CHANGELOG.md")).unwrap();
    let manifest = std::fs::read_to_string(workspace().join("Cargo.toml")).unwrap();
    let version = manifest
        .lines()
        .find_map(|l| l.strip_prefix("version = \""))
        .and_then(|v| v.strip_suffix('"'))
        .expect("the workspace's version");
    let sections = ["Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"];
    let mut releases: Vec<(Vec<u32>, String)> = Vec::new();
    let mut headings = 0;
    for line in text.lines() {
        if let Some(h) = line.strip_prefix("### ") {
            assert!(
                sections.contains(&h),
                "CHANGELOG: `### {h}` is not a Keep a Changelog section"
            );
        } else if let Some(h) = line.strip_prefix("## ") {
            headings += 1;
            if headings == 1 {
                assert_eq!(h, "[Unreleased]", "CHANGELOG: the first version heading");
                continue;
            }
            let (v, date) = h
                .strip_prefix('[')
                .and_then(|h| h.split_once("] - "))
                .unwrap_or_else(|| panic!("CHANGELOG: `## {h}` is not `[X.Y.Z] - YYYY-MM-DD`"));
            let parts: Vec<u32> = v.split('.').map(|p| p.parse().expect("a version number")).collect();
            assert!(
                parts.len() == 3 && date.len() == 10 && date.as_bytes()[4] == b'-',
                "CHANGELOG: `## {h}`"
            );
            if let Some((newer, newer_date)) = releases.last() {
                assert!(
                    &parts < newer && date <= newer_date.as_str(),
                    "CHANGELOG: {v} after a newer version"
                );
            }
            releases.push((parts, date.to_string()));
        }
    }
    let named: Vec<String> = releases
        .iter()
        .map(|(p, _)| p.iter().map(u32::to_string).collect::<Vec<_>>().join("."))
        .collect();
    assert!(
        named.iter().any(|v| v == version),
        "the workspace is {version}, which the CHANGELOG does not name: {named:?}"
    );
}
