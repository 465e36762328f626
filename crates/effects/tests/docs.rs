//! The book's page of the built-in effects (`docs/builtin-effects.md`) is generated from
//! `builtin::all()`: each effect's id, hooks, explanation and parameters as the code declares
//! them. The page in the repository must be that text; `PROPBET_WRITE_DOCS=1 cargo test -p
//! propbet-effects --test docs` writes it after a change to an effect.

use std::fmt::Write as _;
use std::path::PathBuf;

use propbet_effects::{builtin, fmt_value, Param};

fn page() -> String {
    let mut s = String::from(
        "# Built-in effects\n\n\
         The physical effects `propbet diagnose` tries, each acting through one hook of the model \
         ([Effects](effects.md): the hooks, and how to write your own). This page is generated from the \
         code (`crates/effects/src/builtin/`, one file per effect) by `crates/effects/tests/docs.rs`, \
         which fails when the two differ.\n\n\
         | effect | hooks | parameters |\n|---|---|---|\n",
    );
    let effects = builtin::all();
    for e in effects {
        let hooks: Vec<String> = e.hooks().iter().map(|h| format!("{h:?}").to_lowercase()).collect();
        let params: Vec<String> = e.params().iter().map(|p| format!("`{}`", p.name)).collect();
        let id = e.id();
        writeln!(s, "| [`{id}`](#{id}) | {} | {} |", hooks.join(", "), params.join(", ")).unwrap();
    }
    for e in effects {
        writeln!(s, "\n## {}\n\n{}\n", e.id(), e.explanation()).unwrap();
        s.push_str("| parameter | unit | neutral | bounds | physically expected | meaning |\n");
        s.push_str("|---|---|---|---|---|---|\n");
        for p in e.params() {
            writeln!(s, "{}", row(p)).unwrap();
        }
        for p in e.params() {
            if let Some(k) = &p.known {
                let (lo, hi) = k.bounds;
                writeln!(
                    s,
                    "\n`{}` is bounded to {} to {} when the measured files show it ({}).",
                    p.name,
                    fmt_value(lo),
                    fmt_value(hi),
                    k.why
                )
                .unwrap();
            }
        }
        let starts = e.extra_starts();
        if !starts.is_empty() {
            let v: Vec<String> = starts
                .iter()
                .map(|x| x.iter().map(|v| fmt_value(*v)).collect::<Vec<_>>().join(", "))
                .map(|x| format!("({x})"))
                .collect();
            writeln!(s, "\nThe fit also starts from {}.", v.join(", ")).unwrap();
        }
    }
    s
}

fn row(p: &Param) -> String {
    let neutral = p.neutral.map_or("none".to_string(), fmt_value);
    let expected = p.expected.map_or("the bounds".to_string(), |(lo, hi)| {
        format!("{} to {}", fmt_value(lo), fmt_value(hi))
    });
    format!(
        "| `{}` | {} | {} | {} to {} | {} | {} |",
        p.name,
        p.unit,
        neutral,
        fmt_value(p.lower),
        fmt_value(p.upper),
        expected,
        p.doc.replace('|', "\\|")
    )
}

#[test]
fn the_books_page_of_builtin_effects_is_generated_from_the_code() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/builtin-effects.md");
    let want = page();
    if std::env::var_os("PROPBET_WRITE_DOCS").is_some() {
        std::fs::write(&path, &want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "{} differs from the effects' code: run `PROPBET_WRITE_DOCS=1 cargo test -p propbet-effects --test docs`",
        path.display()
    );
    // Every effect has its section, and the page names every effect the code has.
    for id in builtin::ids() {
        assert!(have.contains(&format!("\n## {id}\n")), "{id}");
    }
    assert_eq!(builtin::ids().len(), 15);
}
