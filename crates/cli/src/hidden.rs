//! `propbet hidden`: known effects added to real measurements (validate's props and files), and
//! how often the diagnosis finds them with their size.

use anyhow::Result;
use clap::Args;
use propbet_api::diagnose::inject::{Finding, Injection};
use propbet_validate::{hidden_prop, sections_for, PropSections};

use crate::polar::Bar;
use crate::validate::ValidateArgs;
use propbet_api::files::write_atomic;

/// Arguments of `propbet hidden`.
#[derive(Debug, Args)]
pub struct HiddenArgs {
    /// The props, their files and the model, as `propbet validate` takes them.
    #[command(flatten)]
    pub validate: ValidateArgs,
    /// The effects added to the measurements, each at every size.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "thrust-tare,torque-tare,rpm-scale,density"
    )]
    pub inject: Vec<String>,
    /// Sizes: each effect's relative change of the static loads (0.05: 5 %).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0.03,0.05,0.1",
        allow_negative_numbers = true
    )]
    pub sizes: Vec<f64>,
}

/// Runs `propbet hidden`.
pub fn run(a: &HiddenArgs) -> Result<bool> {
    let mut injections = Vec::new();
    for e in &a.inject {
        for &s in &a.sizes {
            injections.push(Injection::new(e.trim(), s).map_err(|why| anyhow::anyhow!("--inject/--sizes: {why}"))?);
        }
    }
    let (spec, props, generic) = crate::validate::spec(&a.validate)?;
    let lock = propbet_api::files::claim_folder(&spec.out, "propbet hidden")?;
    let (quiet, engine) = (a.validate.xfoil.quiet, spec.xfoil.process.engine);
    let mut rows: Vec<(String, Finding)> = Vec::new();
    let mut skipped = Vec::new();
    for (k, prop) in props.iter().enumerate() {
        let sections = match sections_for(&spec, prop, generic.as_ref()) {
            PropSections::Use(s) => s,
            PropSections::NotValidated(why) => {
                skipped.push((prop.clone(), why));
                continue;
            }
        };
        eprintln!("propbet hidden [{}/{}] {prop}", k + 1, props.len());
        let bar = Bar::new(quiet, engine);
        match hidden_prop(&spec, prop, &sections, &injections, &move |d, t| bar.tick(d, t)) {
            Ok(found) => rows.extend(found.into_iter().map(|f| (prop.clone(), f))),
            Err(e) => skipped.push((prop.clone(), format!("{e:#}"))),
        }
    }
    if rows.is_empty() {
        anyhow::bail!("no prop could be diagnosed: {skipped:?}");
    }
    let md = summary(&rows, &skipped);
    write_atomic(&spec.out.join("hidden.csv"), &[csv(&rows)?], &[])?;
    write_atomic(&spec.out.join("hidden.md"), &[md.as_bytes()], &[])?;
    lock.finish()?;
    crate::output::print_page(&md);
    Ok(skipped.is_empty())
}

/// One row per prop and injection.
fn csv(rows: &[(String, Finding)]) -> Result<Vec<u8>> {
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
    Ok(w.into_inner()?)
}

/// How often each effect was found at each size, then each prop's answers.
fn summary(rows: &[(String, Finding)], skipped: &[(String, String)]) -> String {
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
