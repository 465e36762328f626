//! Every command of the user's guide (`docs/guide/*.md`) and of `docs/effects.md` runs as
//! written: each `sh` block's `propbet` commands, in order, from a directory that sees the
//! repository's `props/`, `docs/` and `tests/`.

use super::*;

/// The commands of a page's ```sh blocks, continuation lines joined, comments dropped.
fn commands(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_block = false;
    let mut pending = String::new();
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            in_block = t == "```sh";
            continue;
        }
        if !in_block || t.is_empty() || t.starts_with('#') {
            continue;
        }
        match t.strip_suffix('\\') {
            Some(head) => {
                pending.push_str(head.trim_end());
                pending.push(' ');
            }
            None => {
                pending.push_str(t);
                out.push(std::mem::take(&mut pending));
            }
        }
    }
    out
}

/// The files of `dir` with the extension `ext`, sorted.
fn files_ending(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    files
}

/// The pages whose commands run: the README and every page of the book (`docs/SUMMARY.md`)
/// except the studies, which are records of measurements whose commands take minutes to hours
/// (a whole validation per candidate, a 10-minute fuzzing run) and say when they were run.
fn pages_with_commands() -> Vec<PathBuf> {
    let summary = std::fs::read_to_string(repo().join("docs/SUMMARY.md")).unwrap();
    let mut pages = vec![repo().join("README.md")];
    for line in summary.lines() {
        let Some((_, rest)) = line.split_once("](") else {
            continue;
        };
        let Some((target, _)) = rest.split_once(')') else {
            continue;
        };
        if target.starts_with("studies/") || target == "architecture.md" || target == "changelog.md" {
            continue;
        }
        pages.push(repo().join("docs").join(target));
    }
    pages
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn every_documented_command_runs() {
    // The commands run from `work/`, which sees the repository's props/, docs/ and tests/, with
    // the shared data at `../shared` as the validation page names it.
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("work");
    std::fs::create_dir(&dir).unwrap();
    for d in ["props", "docs", "tests"] {
        std::os::unix::fs::symlink(repo().join(d).canonicalize().unwrap(), dir.join(d)).unwrap();
    }
    std::os::unix::fs::symlink(
        repo().join("../shared").canonicalize().unwrap(),
        root.path().join("shared"),
    )
    .unwrap();
    let bin_dir = Path::new(env!("CARGO_BIN_EXE_propbet")).parent().unwrap().to_path_buf();
    let path = format!("{}:{}", bin_dir.display(), std::env::var("PATH").unwrap_or_default());
    let ci = std::fs::read_to_string(repo().join(".ci/run")).unwrap();
    let mut ran = 0;
    for page in &pages_with_commands() {
        let text = std::fs::read_to_string(page).unwrap();
        for cmd in commands(&text) {
            // The README's set-up and test commands are CI's own steps: .ci/run runs both
            // scripts (this test runs inside the second).
            if cmd.starts_with("scripts/") {
                for script in cmd.split("&&").map(str::trim).filter(|c| c.starts_with("scripts/")) {
                    let name = script.split_whitespace().next().unwrap();
                    assert!(
                        ci.contains(name),
                        "{}: `{cmd}`: .ci/run does not run {name}",
                        page.display()
                    );
                }
                continue;
            }
            assert!(
                cmd.starts_with("propbet "),
                "{}: not a propbet command: {cmd}",
                page.display()
            );
            // Under a terminal (util-linux's `script`), as a person reads it: long sentences are
            // wrapped there (into a pipe each message is one line).
            let o = Command::new("script")
                .args(["-qefc", &cmd, "/dev/null"])
                .env("PATH", &path)
                .env("PROPBET_CACHE_DIR", root.path().join("cache"))
                .current_dir(&dir)
                .output()
                .unwrap();
            // Done (0), or done with problems it reports (1: XFOIL's unconverged angles).
            assert!(
                matches!(o.status.code(), Some(0 | 1)),
                "{}: `{cmd}` exited {:?}: {}",
                page.display(),
                o.status.code(),
                String::from_utf8_lossy(&o.stdout)
            );
            // A terminal a person reads: no line over 160 characters (a table on standard
            // output, CSV or Markdown, is data, not a sentence). `script` gives both streams on
            // standard output.
            let printed = String::from_utf8_lossy(&o.stdout).into_owned();
            for line in printed.split(['\n', '\r']) {
                // A table row is data; an error or a warning is read whole by scripts and the
                // Python package (`output::for_terminal` leaves them so).
                let table_row = line.matches(',').count() >= 4
                    || line.starts_with('|')
                    || line.starts_with("propbet: warning")
                    || line.starts_with("propbet: error");
                assert!(
                    table_row || line.chars().count() <= 160,
                    "{}: `{cmd}` printed a line of {} characters: {line}",
                    page.display(),
                    line.chars().count()
                );
            }
            ran += 1;
        }
    }
    // The pages hold commands (a page that lost its blocks would pass silently).
    assert!(ran >= 30, "only {ran} documented commands found");
    // What the pages promise is there.
    for f in [
        "apc_scan/plots/sections.svg",
        "apc_scan/blades/blade_0.stl",
        "cloud_scan/plots/colour_histogram.svg",
        "pf_compare/report.html",
        "pf_run/report.html",
        "cam_run/report.html",
        "pf_with_effects/metrics.json",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    // Adding the effects the diagnosis names lowers both errors (the guide: thrust 9.2 -> 1.3 %,
    // torque 20 -> 1.2 %).
    let err = |d: &str, q: &str| -> f64 {
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(d).join("metrics.json")).unwrap()).unwrap();
        m["metrics"]["overall"]["metrics"][q]["mean_abs_rel"].as_f64().unwrap()
    };
    let (t0, t1) = (err("pf_compare", "thrust"), err("pf_with_effects", "thrust"));
    let (q0, q1) = (err("pf_compare", "torque"), err("pf_with_effects", "torque"));
    eprintln!("PhotoFoil mean |error| with the effects: thrust {t0:.3} -> {t1:.3}, torque {q0:.3} -> {q1:.3}");
    assert!(
        t1 < 0.25 * t0 && q1 < 0.25 * q0,
        "thrust {t0} -> {t1}, torque {q0} -> {q1}"
    );
}

#[test]
fn the_command_extractor_joins_continuations() {
    let page = "text\n```sh\n# comment\npropbet a \\\n  --b c\n\npropbet d\n```\n```\npropbet not_sh\n```\n";
    assert_eq!(
        commands(page),
        vec!["propbet a --b c".to_string(), "propbet d".to_string()]
    );
}

/// Every picture the guide shows is in the repository (scripts/screenshots.sh makes them).
#[test]
fn the_guides_pictures_exist() {
    let mut seen = 0;
    for e in std::fs::read_dir(repo().join("docs/guide")).unwrap() {
        let page = e.unwrap().path();
        if page.extension().and_then(|x| x.to_str()) != Some("md") {
            continue;
        }
        let text = std::fs::read_to_string(&page).unwrap();
        for link in text.split("](").skip(1).filter_map(|t| t.split(')').next()) {
            if link.ends_with(".png") {
                let f = repo().join("docs/guide").join(link);
                assert!(
                    f.metadata().is_ok_and(|m| m.len() > 10_000),
                    "{}: {link} missing",
                    page.display()
                );
                seen += 1;
            }
        }
    }
    assert!(seen >= 3, "the guide shows the report ({seen} pictures)");
}

#[test]
fn every_documented_user_effects_file_reads() {
    // docs/user_effects.toml and the studies' effects (docs/studies/*.toml), which their
    // commands pass to diagnose and validate: each lists its effects.
    let mut files = vec![repo().join("docs/user_effects.toml")];
    let studies = files_ending(&repo().join("docs/studies"), "toml");
    assert!(studies.len() >= 2, "{studies:?}");
    files.extend(studies);
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let o = run(&["effects", "--user-effects", f.to_str().unwrap()], &repo());
        assert!(o.status.success(), "{}: {}", f.display(), stderr(&o));
        let listed = String::from_utf8_lossy(&o.stdout).into_owned();
        for id in text.lines().filter_map(|l| l.trim().strip_prefix("id = \"")) {
            let id = id.trim_end_matches('"');
            assert!(listed.contains(id), "{}: {id} not listed", f.display());
        }
    }
}

/// The book builds with mdBook, and every link of its pages (and of the README) reaches a file:
/// the relative `href`s of the built HTML, fragments dropped, and the README's Markdown links.
#[test]
fn the_book_builds_and_its_links_resolve() {
    let out = tempfile::tempdir().unwrap();
    let o = Command::new("mdbook")
        .args(["build", "docs", "-d"])
        .arg(out.path())
        .current_dir(repo())
        .output()
        .expect("mdbook is installed by scripts/setup.sh");
    assert!(o.status.success(), "mdbook build: {}", stderr(&o));
    // mdBook only warns of an include it cannot find: a warning is a broken page here.
    let log = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr(&o));
    assert!(!log.contains("WARN") && !log.contains("ERROR"), "mdbook build: {log}");
    let mut broken = Vec::new();
    let mut checked = 0;
    let mut stack = vec![out.path().to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            if p.extension().is_none_or(|x| x != "html") {
                continue;
            }
            let html = std::fs::read_to_string(&p).unwrap();
            for part in html.split("href=\"").skip(1) {
                let target = part.split('"').next().unwrap();
                let file = target.split('#').next().unwrap();
                if file.is_empty() || file.contains("://") || file.starts_with("mailto:") {
                    continue;
                }
                checked += 1;
                if !p.parent().unwrap().join(file).exists() {
                    broken.push(format!("{}: {target}", p.strip_prefix(out.path()).unwrap().display()));
                }
            }
        }
    }
    assert!(checked > 100, "only {checked} links found");
    // The README's own links, relative to the repository.
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    for part in readme.split("](").skip(1) {
        let target = part.split(')').next().unwrap();
        if target.contains("://") {
            continue;
        }
        if !repo().join(target.split('#').next().unwrap()).exists() {
            broken.push(format!("README.md: {target}"));
        }
    }
    assert!(broken.is_empty(), "broken links: {broken:#?}");
}

/// The README is a user's page: at most 200 lines, none over 200 characters, no dates and no
/// issue numbers (history is the CHANGELOG's).
#[test]
fn the_readme_is_short() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let lines: Vec<&str> = readme.lines().collect();
    assert!(lines.len() <= 200, "{} lines", lines.len());
    for (i, l) in lines.iter().enumerate() {
        assert!(
            l.chars().count() <= 200,
            "line {}: {} characters",
            i + 1,
            l.chars().count()
        );
        // A date stands alone (a file name that holds one, `StepsTest_2022-01-18_1538.csv`, is
        // no date of the project's history).
        let b = l.as_bytes();
        let alone = |c: Option<&u8>| c.is_none_or(|c| !c.is_ascii_alphanumeric() && *c != b'_');
        let date = (0..b.len().saturating_sub(9)).any(|i| {
            let w = &b[i..i + 10];
            w[4] == b'-'
                && w[7] == b'-'
                && w.iter()
                    .enumerate()
                    .all(|(k, c)| k == 4 || k == 7 || c.is_ascii_digit())
                && alone(i.checked_sub(1).map(|j| &b[j]))
                && alone(b.get(i + 10))
        });
        assert!(!date, "line {}: a date: {l}", i + 1);
        assert!(
            !l.to_lowercase().contains("issue "),
            "line {}: an issue number: {l}",
            i + 1
        );
    }
}

/// Every shipped polars file reads with its prop file (a format change leaves none behind):
/// `props/*/NAME.polars.json` beside `NAME.qprop`.
#[test]
fn the_shipped_polars_files_read() {
    let mut n = 0;
    for case in std::fs::read_dir(repo().join("props")).unwrap() {
        for f in std::fs::read_dir(case.unwrap().path()).unwrap() {
            let p = f.unwrap().path();
            let Some(name) = p.file_name().and_then(|s| s.to_str()) else {
                continue;
            };
            let Some(stem) = name.strip_suffix(".polars.json") else {
                continue;
            };
            let prop = p.with_file_name(format!("{stem}.qprop"));
            let o = bin()
                .args(["predict", "--prop"])
                .arg(&prop)
                .arg("--polars")
                .arg(&p)
                .args(["--rpm", "5000", "--j", "0,0.3"])
                .output()
                .unwrap();
            assert!(o.status.success(), "{}: {}", p.display(), stderr(&o));
            n += 1;
        }
    }
    assert!(n >= 1, "no shipped polars file found");
}
