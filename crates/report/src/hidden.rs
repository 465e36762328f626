//! `propbet hidden`'s table (hidden.csv) and page (hidden.md): how often the diagnosis found
//! each known effect added to real measurements, and each prop's answers.

use propbet_diagnose::inject::Finding;

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
         diagnosed beside the clean measurements: found when the ladder holds it and the rise of its \
         parameter over the same ladder refitted to the clean points is the injected one within the \
         95 % interval; tied when the diagnosis names it beside its one answer as explaining the data as \
         well.\n\n\
         | effect | size | found | tied | missed |\n|---|---|---|---|---|\n",
    );
    for (effect, size) in &keys {
        let of: Vec<&(String, Finding)> = rows
            .iter()
            .filter(|(_, f)| f.injection.effect.id() == *effect && f.injection.size == *size)
            .collect();
        let found = of.iter().filter(|(_, f)| f.found).count();
        let tied = of.iter().filter(|(_, f)| f.tied).count();
        let missed: Vec<&str> = of
            .iter()
            .filter(|(_, f)| !f.found && !f.tied)
            .map(|(p, _)| p.as_str())
            .collect();
        md.push_str(&format!(
            "| {effect} | {:+.0} % | {found} of {} | {tied} | {} |\n",
            100.0 * size,
            of.len(),
            missed.join(", ")
        ));
    }
    md.push_str("\n| prop | effect | size | injected | clean | fitted ± 95 % | found | ladder |\n|---|---|---|---|---|---|---|---|\n");
    for (prop, f) in rows {
        md.push_str(&format!(
            "| {prop} | {} | {:+.0} % | {:.4} | {:.4} | {} | {} | {} |\n",
            f.injection.effect.id(),
            100.0 * f.injection.size,
            f.injected,
            f.clean,
            f.fitted.map_or("–".into(), |v| format!(
                "{v:.4} ± {}",
                f.ci95.map_or("?".into(), |c| format!("{c:.4}"))
            )),
            if f.found {
                "yes"
            } else if f.tied {
                "tied"
            } else {
                "no"
            },
            if f.ladder.is_empty() { "none" } else { &f.ladder },
        ));
    }
    for (prop, why) in skipped {
        md.push_str(&format!("\nNot diagnosed: {prop}: {why}\n"));
    }
    md
}
