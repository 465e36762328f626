//! `propbet hidden`'s table (hidden.csv) and page (hidden.md): how often the diagnosis found
//! each known effect added to real measurements, and each prop's answers.

use propbet_diagnose::inject::{Finding, Outcome};

/// One row per prop and injection.
pub fn csv(rows: &[(String, Finding)]) -> Result<Vec<u8>, crate::table::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "prop",
        "effect",
        "size",
        "parameter",
        "injected",
        "clean",
        "fitted",
        "ci95",
        "found",
        "tied",
        "outcome",
        "limit",
        "wrong",
        "answers",
        "clean_ladder",
        "ladder",
        "note",
    ])?;
    let num = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:.6}"));
    for (prop, f) in rows {
        w.write_record([
            prop.as_str(),
            f.injection.effect.id(),
            &format!("{}", f.injection.size),
            f.injection.param(),
            &num(Some(f.injected)),
            &num(Some(f.clean)),
            &num(f.fitted),
            &num(f.ci95),
            if f.found { "yes" } else { "no" },
            if f.tied { "yes" } else { "no" },
            f.outcome.name(),
            &num(f.limit),
            &f.wrong.join(" + "),
            &f.answers,
            &f.clean_ladder,
            &f.ladder,
            &f.note,
        ])?;
    }
    Ok(crate::table::bytes(w)?)
}

/// How often each effect was found at each size, then each prop's answers.
pub fn markdown(rows: &[(String, Finding)], skipped: &[(String, String)]) -> String {
    let mut keys: Vec<(&str, f64)> = Vec::new();
    for (_, f) in rows {
        let key = (f.injection.effect.id(), f.injection.size);
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let mut md = String::from(
        "# Hidden effects in real measurements\n\n\
         Each effect added to the measured points at a size (its relative change of the static loads), \
         diagnosed beside the clean measurements. **found**: named alone, and the rise of its parameter over \
         the same ladder refitted to the clean points is the injected one within the 95 % interval; \
         **group**: answered as one of a group of effects the data cannot tell apart that contains it; \
         **below limit**: its injected size is below the detection limit the diagnosis states, and nothing \
         else is named; **missed**: none of these, nothing wrong named; **wrong**: another effect named as \
         physics, neither injected nor in the clean ladder.\n\n\
         | effect | size | found | group | below limit | missed | wrong |\n|---|---|---|---|---|---|---|\n",
    );
    for (effect, size) in &keys {
        let of: Vec<&(String, Finding)> = rows
            .iter()
            .filter(|(_, f)| f.injection.effect.id() == *effect && f.injection.size == *size)
            .collect();
        let count = |o: Outcome| of.iter().filter(|(_, f)| f.outcome == o).count();
        let names = |o: Outcome| -> String {
            let v: Vec<&str> = of
                .iter()
                .filter(|(_, f)| f.outcome == o)
                .map(|(p, _)| p.as_str())
                .collect();
            if v.is_empty() {
                "0".into()
            } else {
                format!("{}: {}", v.len(), v.join(", "))
            }
        };
        md.push_str(&format!(
            "| {effect} | {:+.0} % | {} of {} | {} | {} | {} | {} |\n",
            100.0 * size,
            count(Outcome::Found),
            of.len(),
            count(Outcome::Group),
            count(Outcome::BelowLimit),
            names(Outcome::Missed),
            names(Outcome::Wrong),
        ));
    }
    md.push_str(
        "\n| prop | effect | size | injected | detectable from | clean | fitted ± 95 % | outcome | ladder | its verdict |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for (prop, f) in rows {
        md.push_str(&format!(
            "| {prop} | {} | {:+.0} % | {:.4} | {} | {:.4} | {} | {}{} | {} | {} |\n",
            f.injection.effect.id(),
            100.0 * f.injection.size,
            f.injected,
            f.limit.map_or("–".into(), |l| format!("±{l:.4}")),
            f.clean,
            f.fitted.map_or("–".into(), |v| format!(
                "{v:.4} ± {}",
                f.ci95.map_or("?".into(), |c| format!("{c:.4}"))
            )),
            f.outcome.name(),
            if f.wrong.is_empty() {
                String::new()
            } else {
                format!(" ({} named)", f.wrong.join(", "))
            },
            if f.ladder.is_empty() { "none" } else { &f.ladder },
            if f.answers.is_empty() {
                "nothing named"
            } else {
                &f.answers
            },
        ));
    }
    for (prop, why) in skipped {
        md.push_str(&format!("\nNot diagnosed: {prop}: {why}\n"));
    }
    md
}
