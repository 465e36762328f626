//! Every flag of every command that a declared setting names (`propbet_api::settings`)
//! takes its help, default and names from the declaration; every declared setting is some
//! command's flag; every declared case key is a key of the case file whose line carries that
//! flag ([`crate::case_keys`]).
#![cfg(test)]

use clap::CommandFactory;
use propbet_api::settings::{self, About};

/// Every argument of every command and subcommand, with the command's path.
fn arguments(cmd: &clap::Command, path: &str, out: &mut Vec<(String, clap::Arg)>) {
    for a in cmd.get_arguments() {
        out.push((path.to_string(), a.clone()));
    }
    for sub in cmd.get_subcommands() {
        arguments(sub, &format!("{path} {}", sub.get_name()), out);
    }
}

fn declared(flag: &str) -> Option<About> {
    settings::all().into_iter().find(|s| s.flag == flag)
}

#[test]
fn every_flag_of_a_declared_setting_is_the_declaration() {
    let mut args = Vec::new();
    arguments(&crate::Cli::command(), "propbet", &mut args);
    let mut wrong = Vec::new();
    for (cmd, a) in &args {
        let Some(flag) = a.get_long() else { continue };
        let Some(s) = declared(flag) else { continue };
        let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
        if help != s.help {
            wrong.push(format!("{cmd} --{flag}: help {help:?}, declared {:?}", s.help));
        }
        let defaults: Vec<String> = a
            .get_default_values()
            .iter()
            .map(|d| d.to_string_lossy().into_owned())
            .collect();
        if !defaults.is_empty() && defaults != [s.default.clone()] {
            wrong.push(format!(
                "{cmd} --{flag}: default {defaults:?}, declared {:?}",
                s.default
            ));
        }
        let names: Vec<String> = a
            .get_possible_values()
            .iter()
            .map(|p| p.get_name().to_string())
            .collect();
        if !names.is_empty() && names != s.names {
            wrong.push(format!("{cmd} --{flag}: values {names:?}, declared {:?}", s.names));
        }
    }
    assert!(
        wrong.is_empty(),
        "flags that differ from their declaration:\n{}",
        wrong.join("\n")
    );
    for s in settings::all() {
        assert!(
            args.iter().any(|(_, a)| a.get_long() == Some(s.flag)),
            "--{} is declared but no command takes it",
            s.flag
        );
    }
}

#[test]
fn every_declared_case_key_is_a_case_key_that_carries_its_flag() {
    for s in settings::all().into_iter().filter(|s| !s.key.is_empty()) {
        let (section, key) = s.key.trim_start_matches('[').split_once("] ").unwrap();
        let listed = crate::case_keys::KEYS
            .iter()
            .find(|k| k.0 == section && k.1 == key)
            .unwrap_or_else(|| panic!("{} is declared but is not a case key", s.key));
        // The key's stage line names the flag, or what the stage's command spells it as: the
        // air state as --temp, --pressure and --humidity; QPROP's law as the fitted --prop.
        let spelled = [("atmosphere", "--temp"), ("section-model", "--prop")]
            .iter()
            .find(|(f, _)| *f == s.flag)
            .map_or(format!("--{}", s.flag), |(_, as_)| as_.to_string());
        assert!(
            listed.4.contains(&spelled),
            "{}: the case key's command line carries {:?}, not --{}",
            s.key,
            listed.4,
            s.flag
        );
    }
}

/// The book's table of settings, as the declarations make it.
fn settings_table() -> String {
    let cell = |s: &str| s.replace('|', "\\|");
    let mut t = String::from("| flag | case key | default | values | what it is |\n|---|---|---|---|---|\n");
    for s in settings::all() {
        let key = if s.key.is_empty() {
            "—".to_string()
        } else {
            format!("`{}`", s.key)
        };
        let default = if s.default.is_empty() {
            "—".to_string()
        } else {
            format!("`{}`", s.default)
        };
        let values = if !s.names.is_empty() {
            s.names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
        } else if !s.range.is_empty() {
            cell(s.range)
        } else {
            "—".to_string()
        };
        t.push_str(&format!(
            "| `--{}` | {key} | {default} | {values} | {} |\n",
            s.flag,
            cell(s.help)
        ));
    }
    t
}

/// `docs/settings.md` holds the table the declarations make: the book cannot drift from them.
#[test]
fn the_book_lists_every_setting_as_declared() {
    let page = std::fs::read_to_string(crate::tests::repo().join("docs/settings.md")).unwrap();
    let table = settings_table();
    assert!(
        page.contains(&table),
        "docs/settings.md's table differs from the declarations; the table they make:\n{table}"
    );
}

/// Every default a page of the book (and the README) states for a setting, next to its case key
/// (`trip = 0.5 (default "free")`) or its flag (`--ncrit ... (default 5)`), is the declared one:
/// a page cannot keep an old default after the code changed it.
#[test]
fn every_default_the_book_states_is_the_declared_one() {
    let root = crate::tests::repo();
    let mut pages: Vec<std::path::PathBuf> = vec![root.join("README.md")];
    let mut dirs = vec![root.join("docs")];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "md") {
                pages.push(p);
            }
        }
    }
    let mut checked = 0;
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        for (n, line) in text.lines().enumerate() {
            for s in settings::all().iter().filter(|s| !s.default.is_empty()) {
                let key = s.key.rsplit(' ').next().unwrap_or_default();
                let flag = format!("--{}", s.flag);
                for name in [key, flag.as_str()].into_iter().filter(|k| !k.is_empty()) {
                    // `name ... (default V)` within a few words of the name, on one line.
                    let Some(at) = line
                        .find(&format!("{name} "))
                        .or_else(|| line.find(&format!("{name} =")))
                    else {
                        continue;
                    };
                    let rest = &line[at + name.len()..];
                    let Some(d) = rest.find("(default ") else { continue };
                    if d > 24 || rest[..d].contains(',') {
                        continue;
                    }
                    let value = rest[d + "(default ".len()..]
                        .split([')', ';', ','])
                        .next()
                        .unwrap_or_default()
                        .trim()
                        .trim_matches(['"', '`']);
                    assert_eq!(
                        value,
                        s.default,
                        "{}:{}: `{name}` says its default is {value}, the declaration {}: {line}",
                        page.display(),
                        n + 1,
                        s.default
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 1, "no stated default found: the test reads nothing");
}
