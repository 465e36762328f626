//! Every key a case file takes gives the spec its command-line flag gives: a case with the key
//! set plans stages whose command lines carry the flag and parse back to the same specs; a key
//! without a flag says why. The list is checked against the case file's sections, so a key
//! added without its flag (or a flag that drops it) fails here.
#![cfg(test)]

use std::path::Path;

use crate::tests::{check, repo};

/// (section, key, the line that sets it, the stage that takes it, what its command line then
/// carries). An empty stage: a key with no flag, and why.
pub(crate) const KEYS: &[(&str, &str, &str, &str, &str)] = &[
    (
        "",
        "name",
        "name = \"K\"",
        "",
        "the report's title, not a stage's input",
    ),
    (
        "",
        "description",
        "description = \"D\"",
        "",
        "the report's text, not a stage's input",
    ),
    (
        "",
        "blades",
        "blades = 2",
        "",
        "the run page's blade count, checked against the scan's",
    ),
    (
        "",
        "effects",
        "effects = [\"pitch-offset:deg=-0.8\"]",
        "predict",
        "--effect pitch-offset:deg=-0.8",
    ),
    (
        "geometry",
        "scan",
        "scan = \"{case}/../apcsf_10x4.7/apcsf_10x4.7.stl\"",
        "scan",
        "apcsf_10x4.7.stl",
    ),
    (
        "geometry",
        "prop",
        "",
        "",
        "without a scan: the prop file the polars and the model read (cam6x3 cases)",
    ),
    (
        "geometry",
        "pe0",
        "",
        "",
        "without a scan: APC's design file, the polars stage's --geometry (beside `prop`, its --sections-from); props/apcsp_10x7",
    ),
    ("geometry", "units", "units = \"mm\"", "scan", "--units mm"),
    ("geometry", "stations", "stations = \"0.3:0.9/7\"", "scan", "--stations"),
    (
        "geometry",
        "reference",
        "reference = \"{case}/apcsf_10x4.7_geom.txt\"",
        "scan",
        "--reference",
    ),
    ("geometry", "planar", "planar = true", "scan", "--planar"),
    ("geometry", "slab", "slab = 0.5", "scan", "--slab 0.5"),
    (
        "geometry",
        "slab_points",
        "slab_points = 100",
        "scan",
        "--slab-points 100",
    ),
    (
        "geometry",
        "blade_colour",
        "blade_colour = \"orange\"",
        "scan",
        "--blade-colour '#e6640a'",
    ),
    (
        "geometry",
        "colour_threshold",
        "colour_threshold = 40",
        "scan",
        "--colour-threshold 40",
    ),
    (
        "geometry",
        "box",
        "box = \"50.8x48.26x50.8\"",
        "scan",
        "--box 50.8x48.26x50.8",
    ),
    (
        "geometry",
        "box_offset",
        "box = \"50x50x50\"\nbox_offset = \"0,0,-30\"",
        "scan",
        "--box-offset=0,0,-30",
    ),
    (
        "geometry",
        "box_colour",
        "box = \"50x50x50\"\nbox_colour = \"grey\"",
        "scan",
        "--box-colour '#c8c8c8'",
    ),
    (
        "geometry",
        "box_seeds",
        "box = \"50x50x50\"\nbox_seeds = \"1,2,3;4,5,6\"",
        "scan",
        "--box-seeds=1,2,3;4,5,6",
    ),
    (
        "geometry",
        "crop",
        "crop = \"-80,-200,-200,200,200,200\"",
        "scan",
        "--crop=-80,-200,-200,200,200,200",
    ),
    ("geometry", "outliers", "outliers = \"off\"", "scan", "--outliers off"),
    (
        "geometry",
        "root_point",
        "root_point = \"0,10,0\"\ntip_point = \"0,120,0\"",
        "scan",
        "--root-point=0,10,0 --tip-point=0,120,0",
    ),
    (
        "geometry",
        "tip_point",
        "root_point = \"0,10,0\"\ntip_point = \"0,127,0\"",
        "scan",
        "--tip-point=0,127,0",
    ),
    (
        "geometry",
        "origin",
        "root_point = \"0,10,0\"\ntip_point = \"0,120,0\"\norigin = \"0,0,1\"",
        "scan",
        "--origin=0,0,1",
    ),
    (
        "geometry",
        "rotate",
        "root_point = \"0,10,0\"\ntip_point = \"0,120,0\"\nrotate = \"0,0,5\"",
        "scan",
        "--rotate=0,0,5",
    ),
    (
        "geometry",
        "known_length",
        "known_length = \"0,0,0,0,10,0,20\"",
        "scan",
        "--known-length=0,0,0,1,0,0,2",
    ),
    (
        "polars",
        "sections",
        "sections = \"scan\"",
        "polars",
        "--station-airfoils",
    ),
    (
        "polars",
        "airfoil",
        "airfoil = \"naca4412\"",
        "polars",
        "--airfoil naca4412",
    ),
    ("polars", "thickness", "thickness = \"0.1\"", "polars", "--thickness"),
    ("polars", "rpm", "rpm = \"3000,5000\"", "polars", "--rpm=3000,5000"),
    ("polars", "j", "j = \"0:0.5:0.1\"", "polars", "--j"),
    ("polars", "v", "v = \"0:10:5\"", "polars", "--v"),
    ("polars", "ncrit", "ncrit = 7", "polars", "--ncrit 7"),
    (
        "polars",
        "ncrit_effect",
        "ncrit_effect = \"3,9\"",
        "polars",
        "--ncrit-effect",
    ),
    ("polars", "trip", "trip = 0.25", "polars", "--trip 0.25"),
    ("polars", "engine", "engine = \"auto\"", "polars", "--engine auto"),
    (
        "polars",
        "neuralfoil_size",
        "neuralfoil_size = \"large\"",
        "polars",
        "--neuralfoil-size large",
    ),
    ("polars", "alpha", "alpha = \"-4:12:1\"", "polars", "--alpha"),
    ("polars", "model", "model = \"qprop\"", "predict", "--prop"),
    ("polars", "rotation", "rotation = \"off\"", "predict", "--rotation off"),
    (
        "polars",
        "drag_factor",
        "drag_factor = 1.1",
        "predict",
        "--drag-factor=1.1",
    ),
    ("sweep", "rpm", "rpm = \"4500\"", "predict", "--rpm=4500"),
    ("sweep", "j", "j = \"0:0.5:0.25\"", "predict", "--j"),
    (
        "measured",
        "files",
        "files = [\"{case}/uiuc/apcsf_10x4.7_kt0836_4014.txt\"]",
        "compare",
        "kt0836",
    ),
    ("measured", "poles", "poles = 14", "compare", "--poles 14"),
    (
        "measured",
        "rpm_source",
        "rpm_source = \"electrical\"",
        "compare",
        "--rpm-source electrical",
    ),
    (
        "measured",
        "columns",
        "columns = \"{repo}/tests/data/bad_inputs/colmap_same_column.toml\"",
        "compare",
        "--columns",
    ),
    ("measured", "folds", "folds = 3", "diagnose", "--folds 3"),
    ("measured", "max_steps", "max_steps = 2", "diagnose", "--max-steps 2"),
    (
        "measured",
        "per3",
        "per3 = \"{case}/PER3_10x47SF.dat\"",
        "compare",
        "--per3",
    ),
    (
        "measured",
        "user_effects",
        "user_effects = \"{repo}/docs/studies/re-zero-lift.toml\"",
        "diagnose",
        "--user-effects",
    ),
    (
        "atmosphere",
        "air",
        "air = \"20C,1000hPa,50%\"",
        "predict",
        "--temp=293.15K --pressure 100000 --humidity 50",
    ),
    ("atmosphere", "rho", "rho = 1.2", "predict", "--rho=1.2"),
    (
        "motor",
        "file",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"",
        "compare",
        "--motor",
    ),
    (
        "motor",
        "volts",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = \"6,7\"",
        "motor",
        "--volts=6,7",
    ),
    (
        "motor",
        "amps",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"\namps = \"3,4\"",
        "motor",
        "--amps=3,4",
    ),
    (
        "motor",
        "thrust",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"\nthrust = 1.5",
        "motor",
        "--thrust=1.5",
    ),
    (
        "motor",
        "throttle",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"\nthrottle = \"0.5,1\"\n\n[battery]\ncells = 2",
        "motor",
        "--throttle=0.5,1",
    ),
    (
        "motor",
        "v",
        "file = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7\nv = \"0,5\"",
        "motor",
        "--v=0,5",
    ),
    (
        "battery",
        "cells",
        "cells = 3\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "--battery 3S,",
    ),
    (
        "battery",
        "capacity_mah",
        "cells = 3\ncapacity_mah = 2200\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        ",2.2Ah,",
    ),
    (
        "battery",
        "cell_volts",
        "cells = 3\ncell_volts = 3.8\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "V=3.8",
    ),
    (
        "battery",
        "cell_ohms",
        "cells = 3\ncell_ohms = 0.004\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "R=0.004",
    ),
    (
        "battery",
        "cutoff_volts",
        "cells = 3\ncutoff_volts = 3.2\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "cutoff=3.2",
    ),
    (
        "battery",
        "usable",
        "cells = 3\nusable = 0.7\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "usable=0.7",
    ),
    (
        "esc",
        "ohms",
        "ohms = 0.01\n\n[battery]\ncells = 3\n\n[motor]\nfile = \"{repo}/props/motors/s400-6v-dd.motor\"\nvolts = 7",
        "motor",
        "--esc-ohms 0.01",
    ),
];

/// The case every key is set in: the default case's scan, polars, sweep and measurements.
fn base(repo: &Path) -> String {
    let case = repo.join("props/apcsf_10x4.7").display().to_string();
    format!(
        "name = \"settings\"\n\n[geometry]\nscan = \"{case}/apcsf_10x4.7.stl\"\n#geometry\n\n[polars]\nsections = \"airfoil\"\nairfoil = \"{case}/../airfoils/e63.dat\"\n#polars\n\n[sweep]\nrpm = \"4000,5000\"\nj = \"0:0.6:0.1\"\n#sweep\n\n[measured]\nfiles = [\"{case}/uiuc/apcsf_10x4.7_static_kt0835.txt\"]\n#measured\n\n[atmosphere]\n#atmosphere\n"
    )
}

/// The base case with `line` in `section` (replacing the base's own line for the key).
fn with(base: &str, section: &str, key: &str, line: &str) -> String {
    let mut out = Vec::new();
    // The section a line is in: "" before the first header, the top level.
    let mut current = String::new();
    for l in base.lines() {
        if let Some(s) = l.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
            current = s.to_string();
        }
        let sets_key = l.split('=').next().is_some_and(|k| k.trim() == key);
        if sets_key && current == section {
            continue;
        }
        out.push(if l == format!("#{section}") { line } else { l }.to_string());
    }
    if section.is_empty() {
        out.insert(0, line.to_string());
    } else if !base.contains(&format!("#{section}")) {
        // A section the base case has not (one whose keys are all required).
        out.push(format!("\n[{section}]\n{line}"));
    }
    out.join("\n") + "\n"
}

/// The keys of each section of `case.rs`'s structs (and of the scan's settings, which are
/// `[geometry]` keys), as (section, key): each field, renamed where serde renames it.
fn case_file_keys(repo: &Path) -> Vec<(String, String)> {
    let case = std::fs::read_to_string(repo.join("crates/pipeline/src/case.rs")).unwrap();
    let scan = std::fs::read_to_string(repo.join("crates/settings/src/scan.rs")).unwrap();
    let sections = [
        (&case, "Case", ""),
        (&case, "GeometrySection", "geometry"),
        (&scan, "ScanSettings", "geometry"),
        (&case, "PolarSection", "polars"),
        (&case, "SweepSection", "sweep"),
        (&case, "MeasuredSection", "measured"),
        (&case, "AtmosphereSection", "atmosphere"),
        (&case, "MotorSection", "motor"),
        (&case, "BatterySection", "battery"),
        (&case, "EscSection", "esc"),
    ];
    // Fields that are not keys: the sections themselves at the top level, and [geometry]'s
    // `settings` (whose keys are listed from their own struct).
    let sections_names = [
        "geometry",
        "polars",
        "sweep",
        "measured",
        "atmosphere",
        "motor",
        "battery",
        "esc",
    ];
    let mut out = Vec::new();
    for (text, name, section) in sections {
        let start = text
            .find(&format!("pub struct {name} {{"))
            .or_else(|| text.find(&format!("pub(crate) struct {name} {{")))
            .unwrap_or_else(|| panic!("struct {name}"));
        let body = &text[start..start + text[start..].find("\n}").unwrap()];
        let mut rename = None;
        for l in body.lines().skip(1) {
            if let Some(r) = l.trim().strip_prefix("#[serde(rename = \"") {
                rename = r.split('"').next().map(str::to_string);
            }
            let Some(rest) = l
                .trim()
                .strip_prefix("pub ")
                .or_else(|| l.trim().strip_prefix("pub(crate) "))
            else {
                continue;
            };
            let field = rest.split(':').next().unwrap().to_string();
            let key = rename.take().unwrap_or(field);
            let is_key = if section.is_empty() {
                !sections_names.contains(&key.as_str())
            } else {
                key != "settings"
            };
            if is_key {
                out.push((section.to_string(), key));
            }
        }
    }
    out
}

/// Every key of the case file's sections is in [`KEYS`], with its flag or why it has none.
#[test]
fn every_case_key_is_listed_with_its_flag() {
    let listed: Vec<(String, String)> = KEYS.iter().map(|k| (k.0.to_string(), k.1.to_string())).collect();
    let mut missing = Vec::new();
    for k in case_file_keys(&repo()) {
        if !listed.contains(&k) {
            missing.push(format!("[{}] {}", k.0, k.1));
        }
    }
    assert!(missing.is_empty(), "case keys without their flag in KEYS: {missing:?}");
}

/// Each key set in a case changes the stage that takes it (nothing a user writes is dropped),
/// that stage's command line carries the key's flag, and every stage's command line parses back
/// to the same spec.
#[test]
fn each_case_key_and_its_flag_give_the_same_spec() {
    let repo = repo();
    let case = repo.join("props/apcsf_10x4.7").display().to_string();
    let base = base(&repo);
    let xfoil = propbet_api::ProcessRequest {
        quiet: true,
        engine: Some("xfoil".into()),
        ..Default::default()
    };
    let plan_of = |text: &str| {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("case.toml"), text).unwrap();
        propbet_api::case::plan(dir.path(), Path::new("out"), &xfoil.spec().unwrap())
    };
    let base_stages = plan_of(&base).unwrap().stages();
    let mut failures = Vec::new();
    for &(section, key, line, stage, carries) in KEYS {
        if stage.is_empty() {
            assert!(!carries.is_empty(), "{key}: say why it has no flag");
            continue;
        }
        let line = line
            .replace("{case}", &case)
            .replace("{repo}", &repo.display().to_string());
        let text = with(&base, section, key, &line);
        let plan = match plan_of(&text) {
            Ok(p) => p,
            Err(e) => {
                failures.push(format!("[{section}] {key}: the case does not plan: {e:#}\n{text}"));
                continue;
            }
        };
        let stages = plan.stages();
        let Some(spec) = stages.iter().find(|s| s.name() == stage) else {
            failures.push(format!("[{section}] {key}: no {stage} stage"));
            continue;
        };
        let command = crate::argv::command(spec);
        if !command.contains(carries) {
            failures.push(format!(
                "[{section}] {key}: the {stage} command does not carry `{carries}`: {command}"
            ));
        }
        // Nothing written is dropped: the key changes the stage it belongs to.
        if base_stages.iter().any(|b| b == spec) {
            failures.push(format!(
                "[{section}] {key}: the {stage} stage is the base case's: the key was dropped"
            ));
        }
        // The flag gives back the same spec.
        for s in &stages {
            check(s);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
