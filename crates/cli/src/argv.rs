//! Each stage's spec as the `propbet` command line that does the same: the one formatter of
//! the "equivalent command" lines the terminal, the run's page and `summary.json` show. Every
//! printed line parses back to the same spec (`every_stage_of_the_shipped_cases_is_a_command_that_parses_back`).

use std::path::Path;

use propbet_api::geometry::scan::{default_stations, ScanOptions, SectionKind};
use propbet_api::measure::RpmSource;
use propbet_api::settings::values::{length_unit_name, list_text, rpm_list_text, scaled_text};
use propbet_api::settings::{drag_factor_or_default, Rotation};
use propbet_pipeline::spec::{
    AirSpec, MeasuredSpec, ModelSpec, PoweredSpec, PredictSpec, ScanSpec, StageSpec, SweepAxis, TableFormat,
    XfoilProcessSpec, XfoilSpec,
};

/// The `propbet` command line of one stage (without the program name).
pub type Argv = Vec<String>;

/// A spec's flags, pushed onto a command line.
trait Flags {
    fn push_argv(&self, v: &mut Argv);
}

fn path(p: &std::path::Path) -> String {
    p.display().to_string()
}

fn push(v: &mut Argv, flag: &str, value: impl Into<String>) {
    v.push(flag.to_string());
    v.push(value.into());
}

/// `--flag=value`, for values that may begin with a minus sign.
fn push_eq(v: &mut Argv, flag: &str, value: impl AsRef<str>) {
    v.push(format!("{flag}={}", value.as_ref()));
}

/// Degrees as text that reads back to exactly `rad`.
fn deg_text(rad: f64) -> String {
    scaled_text(rad, f64::to_degrees, f64::to_radians)
}

/// Millimetres as text that reads back to exactly `m` [m] (the scan's flags are in mm).
fn mm_text(m: f64) -> String {
    scaled_text(m, |x| x * 1000.0, |x| x / 1000.0)
}

/// Percent as text that reads back to exactly the fraction `f`.
fn percent_text(f: f64) -> String {
    scaled_text(f, |x| 100.0 * x, |x| x / 100.0)
}

fn colour_text(c: &[[u8; 3]]) -> String {
    c.iter()
        .map(|c| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]))
        .collect::<Vec<_>>()
        .join(",")
}

fn vec_text(v: &propbet_api::geometry::Vector3<f64>) -> String {
    format!("{},{},{}", v.x, v.y, v.z)
}

/// The `propbet` command line of one stage (without the program name).
pub fn argv(stage: &StageSpec) -> Argv {
    let subcommand = match stage {
        StageSpec::Powered(_) => "predict",
        _ => stage.name(),
    };
    let mut v = vec![subcommand.to_string()];
    match stage {
        StageSpec::Scan(s) => s.push_argv(&mut v),
        StageSpec::Polars(s) => {
            push(&mut v, "--geometry", path(&s.geometry));
            if let Some(u) = s.units {
                push(&mut v, "--units", length_unit_name(u).unwrap_or("m"));
            }
            if let Some(a) = &s.airfoil {
                push(&mut v, "--airfoil", a.clone());
            }
            if let Some(t) = s.thickness {
                push(&mut v, "--thickness", format!("{t}"));
            }
            if let Some(d) = &s.station_airfoils {
                push(&mut v, "--station-airfoils", path(d));
            }
            if let Some(d) = &s.sections_from {
                push(&mut v, "--sections-from", path(d));
            }
            if let Some(d) = &s.airfoils {
                push(&mut v, "--airfoils", path(d));
            }
            push_eq(&mut v, "--rpm", rpm_list_text(&s.omegas));
            match &s.axis {
                SweepAxis::V(x) if x == &[0.0] => {}
                SweepAxis::J(j) => push_eq(&mut v, "--j", list_text(j)),
                SweepAxis::V(x) => push_eq(&mut v, "--v", list_text(x)),
            }
            s.air.push_argv(&mut v);
            s.xfoil.push_argv(&mut v);
            if !s.ncrit_effect.is_empty() {
                push_eq(&mut v, "--ncrit-effect", ncrit_effect_text(&s.ncrit_effect));
            }
            push(&mut v, "--out-prop", path(&s.out_prop));
            if let Some(p) = &s.out_polars {
                push(&mut v, "--out-polars", path(p));
            }
        }
        StageSpec::Predict(s) => {
            s.model.push_argv(&mut v);
            push_eq(&mut v, "--rpm", rpm_list_text(&s.omegas));
            match &s.axis {
                SweepAxis::J(j) => push_eq(&mut v, "--j", list_text(j)),
                SweepAxis::V(x) => push_eq(&mut v, "--v", list_text(x)),
            }
            s.air.push_argv(&mut v);
            if s.format == TableFormat::Json {
                push(&mut v, "--format", "json");
            }
            if let Some(o) = &s.out {
                push(&mut v, "--out", path(o));
            }
            if let Some(o) = &s.stations {
                push(&mut v, "--out-stations", path(o));
            }
            if s.band {
                v.push("--band".into());
            }
        }
        StageSpec::Powered(s) => s.push_argv(&mut v),
        StageSpec::Compare(s) => {
            s.model.push_argv(&mut v);
            s.measured.push_argv(&mut v);
            if let Some(p) = &s.per3 {
                push(&mut v, "--per3", path(p));
            }
            if let Some(p) = &s.qprop_output {
                push(&mut v, "--qprop-output", path(p));
            }
            if let Some(p) = &s.motor {
                push(&mut v, "--motor", path(p));
            }
            push(&mut v, "--out", path(&s.out));
        }
        StageSpec::Diagnose(s) => {
            s.model.push_argv(&mut v);
            s.measured.push_argv(&mut v);
            if s.effects != ["all"] {
                push(&mut v, "--effects", s.effects.join(","));
            }
            if s.folds != propbet_api::settings::FOLDS.default {
                push(&mut v, "--folds", s.folds.to_string());
            }
            if s.max_steps != propbet_api::settings::MAX_STEPS.default {
                push(&mut v, "--max-steps", s.max_steps.to_string());
            }
            if s.window != propbet_api::compare::metrics::VALIDATION_J_WINDOW {
                push(&mut v, "--window", s.window.to_string());
            }
            push(&mut v, "--out", path(&s.out));
        }
    }
    v
}

/// The command line as a shell would take it.
pub fn command(stage: &StageSpec) -> String {
    shell_line(&argv(stage))
}

/// `propbet` and the arguments, each quoted for a POSIX shell where it needs it.
fn shell_line(argv: &[String]) -> String {
    std::iter::once("propbet".to_string())
        .chain(argv.iter().map(|a| shell_word(a)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The final model of a diagnosis as `--effect` arguments.
pub fn effect_args(d: &propbet_api::diagnose::Diagnosis) -> Vec<String> {
    d.final_stack
        .active
        .iter()
        .map(|a| format!("--effect {}", a.describe()))
        .collect()
}

/// `3,9`: the values of `--ncrit-effect` as the command line takes them.
pub fn ncrit_effect_text(v: &[f64]) -> String {
    v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(",")
}

/// The `propbet export` command that writes this prediction for every flight simulator
/// into `out`: the same model, sweep and air.
pub fn export_command(spec: &PredictSpec, out: &Path) -> String {
    let plain = PredictSpec {
        format: TableFormat::Csv,
        out: None,
        stations: None,
        band: false,
        ..spec.clone()
    };
    let mut argv = argv(&StageSpec::Predict(plain));
    argv[0] = "export".into();
    argv.splice(1..1, ["--to".to_string(), "all".to_string()]);
    argv.extend(["-o".to_string(), path(out)]);
    shell_line(&argv)
}

impl Flags for XfoilProcessSpec {
    fn push_argv(&self, v: &mut Argv) {
        if let Some(b) = self.budget {
            push(v, "--xfoil-budget", format!("{b}"));
        }
        if let Some(x) = &self.xfoil {
            push(v, "--xfoil", path(x));
        }
        if let Some(c) = &self.cache {
            push(v, "--cache", path(c));
        }
        if self.no_cache {
            v.push("--no-cache".into());
        }
        if self.quiet {
            v.push("--quiet".into());
        }
        if self.engine != propbet_api::polar::Engine::default() {
            push(v, "--engine", self.engine.name());
        }
        if let Some(s) = &self.neuralfoil_size {
            push(v, "--neuralfoil-size", s.clone());
        }
    }
}

impl Flags for XfoilSpec {
    fn push_argv(&self, v: &mut Argv) {
        self.process.push_argv(v);
        if self.section.ncrit != propbet_api::settings::NCRIT.default {
            push(v, "--ncrit", format!("{}", self.section.ncrit));
        }
        if self.section.trip != propbet_api::settings::default_trip() {
            push(v, "--trip", propbet_api::settings::trip_text(self.section.trip));
        }
        let default =
            propbet_api::settings::values::parse_list("", propbet_api::settings::ALPHA.default).unwrap_or_default();
        if self.section.alphas_deg != default {
            push_eq(v, "--alpha", list_text(&self.section.alphas_deg));
        }
        if let Some(p) = self.section.panels {
            push(v, "--panels", p.to_string());
        }
        if self.section.max_iter != propbet_api::xfoil::DEFAULT_MAX_ITER {
            push(v, "--iter", self.section.max_iter.to_string());
        }
    }
}

impl Flags for AirSpec {
    fn push_argv(&self, v: &mut Argv) {
        if let Some(s) = &self.state {
            push_eq(v, "--temp", format!("{}K", s.temperature));
            push(v, "--pressure", format!("{}", s.pressure));
            if s.relative_humidity != 0.0 {
                push(v, "--humidity", percent_text(s.relative_humidity));
            }
        }
        for (flag, x) in [("--rho", self.rho), ("--mu", self.mu), ("--a", self.a)] {
            if let Some(x) = x {
                push_eq(v, flag, format!("{x}"));
            }
        }
    }
}

impl Flags for ModelSpec {
    fn push_argv(&self, v: &mut Argv) {
        push(v, "--prop", path(&self.prop));
        if self.dbeta != 0.0 {
            push_eq(v, "--dbeta", deg_text(self.dbeta));
        }
        if let Some(u) = self.units {
            push(v, "--units", length_unit_name(u).unwrap_or("m"));
        }
        if self.qprop_compat {
            v.push("--qprop-compat".into());
        }
        if self.no_tip_loss {
            v.push("--no-tip-loss".into());
        }
        if let Some(p) = &self.polars {
            push(v, "--polars", path(p));
        }
        if let Some(d) = &self.design {
            if let Some(a) = &d.airfoil {
                push(v, "--airfoil", a.clone());
            }
            if let Some(p) = &d.sections_from {
                push(v, "--sections-from", path(p));
            }
            if let Some(p) = &d.airfoils {
                push(v, "--airfoils", path(p));
            }
            d.process.push_argv(v);
        }
        if self.rotation != Rotation::or_default(None, self.tabulated()) {
            push(v, "--rotation", self.rotation.name());
        }
        if self.drag_factor != drag_factor_or_default(None, self.tabulated()) {
            push_eq(v, "--drag-factor", format!("{}", self.drag_factor));
        }
        for e in &self.effects {
            push(v, "--effect", e.clone());
        }
        if let Some(p) = &self.user_effects {
            push(v, "--user-effects", path(p));
        }
    }
}

impl Flags for MeasuredSpec {
    fn push_argv(&self, v: &mut Argv) {
        v.push("--measured".into());
        v.extend(self.files.iter().map(|f| path(f)));
        if let Some(p) = self.poles {
            push(v, "--poles", p.to_string());
        }
        if let Some(s) = self.rpm_source {
            push(
                v,
                "--rpm-source",
                match s {
                    RpmSource::Optical => "optical",
                    RpmSource::Electrical => "electrical",
                },
            );
        }
        if let Some(s) = &self.atmosphere {
            push(
                v,
                "--atmosphere",
                format!(
                    "{}K,{},{}",
                    s.temperature,
                    s.pressure,
                    percent_text(s.relative_humidity)
                ),
            );
        }
        if let Some(r) = self.rho {
            push_eq(v, "--rho", format!("{r}"));
        }
        if let Some(c) = &self.columns {
            push(v, "--columns", path(c));
        }
    }
}

impl Flags for ScanSpec {
    fn push_argv(&self, v: &mut Argv) {
        let o = &self.options;
        v.push(path(&self.input));
        push(v, "-o", path(&self.out));
        if let Some(n) = &self.name {
            push(v, "--name", n.clone());
        }
        // The scale: a named unit, or a known length [mm] of one file unit.
        let unit = [("mm", 0.001), ("cm", 0.01), ("m", 1.0), ("in", 0.0254)]
            .into_iter()
            .find(|u| u.1 == o.scale);
        match unit {
            Some(("mm", _)) if !o.scale_given => {}
            Some((name, _)) => push(v, "--units", name),
            None => push_eq(v, "--known-length", format!("0,0,0,1,0,0,{}", mm_text(o.scale))),
        }
        if o.stations != default_stations() {
            push(v, "--stations", list_text(&o.stations));
        }
        if let Some(r) = &self.reference {
            push(v, "--reference", path(r));
        }
        if o.kind == SectionKind::Planar {
            v.push("--planar".into());
        }
        if o.slab != ScanOptions::default().slab {
            push(v, "--slab", mm_text(o.slab));
        }
        if o.slab_points != 400 {
            push(v, "--slab-points", o.slab_points.to_string());
        }
        if !o.blade_colours.is_empty() {
            push(v, "--blade-colour", colour_text(&o.blade_colours));
        }
        if let Some(t) = o.colour_threshold {
            push(v, "--colour-threshold", format!("{t}"));
        }
        if let Some(b) = &o.reference_box {
            let mm = mm_text;
            push(
                v,
                "--box",
                format!("{}x{}x{}", mm(b.dims[0]), mm(b.dims[1]), mm(b.dims[2])),
            );
            push_eq(
                v,
                "--box-offset",
                format!("{},{},{}", mm(b.offset[0]), mm(b.offset[1]), mm(b.offset[2])),
            );
            push(v, "--box-colour", colour_text(&b.colours));
            if !b.seeds.is_empty() {
                push_eq(
                    v,
                    "--box-seeds",
                    b.seeds.iter().map(vec_text).collect::<Vec<_>>().join(";"),
                );
            }
        }
        if let Some((lo, hi)) = &o.crop {
            push_eq(v, "--crop", format!("{},{}", vec_text(lo), vec_text(hi)));
        }
        match o.outliers {
            None => push(v, "--outliers", "off"),
            Some((8, 2.5)) => {}
            Some((n, s)) => push(v, "--outliers", format!("{n},{s}")),
        }
        if let Some(m) = &o.manual {
            push_eq(v, "--root-point", vec_text(&m.root));
            push_eq(v, "--tip-point", vec_text(&m.tip));
            if let Some(c) = &m.origin {
                push_eq(v, "--origin", vec_text(c));
            }
            if m.rotate != [0.0; 3] {
                let r = m.rotate.map(deg_text);
                push_eq(v, "--rotate", format!("{},{},{}", r[0], r[1], r[2]));
            }
        }
    }
}

impl Flags for PoweredSpec {
    fn push_argv(&self, v: &mut Argv) {
        self.model.push_argv(v);
        push(v, "--motor", path(&self.motor));
        let (flag, values) = drive_list(&self.drives);
        push_eq(v, flag, values);
        if let Some(b) = &self.supply {
            push(v, "--battery", b.battery.text());
            push(v, "--esc-ohms", b.esc_ohms.to_string());
        }
        if self.speeds != [0.0] {
            push_eq(v, "--v", list_text(&self.speeds));
        }
        self.air.push_argv(v);
        if self.format == TableFormat::Json {
            push(v, "--format", "json");
        }
        if let Some(o) = &self.out {
            push(v, "--out", path(o));
        }
        if let Some(o) = &self.stations {
            push(v, "--out-stations", path(o));
        }
        if self.band {
            v.push("--band".into());
        }
    }
}

/// The flag of the drivers' kind and their values (a powered spec's drivers are of one kind).
fn drive_list(drives: &[propbet_api::motor::Drive]) -> (&'static str, String) {
    use propbet_api::motor::Drive;
    let flag = match drives.first() {
        Some(Drive::Volts(_)) | None => "--volts",
        Some(Drive::Amps(_)) => "--amps",
        Some(Drive::Thrust(_)) => "--thrust",
        Some(Drive::Omega(_)) => "--rpm",
        Some(Drive::Throttle { .. }) => "--throttle",
    };
    let values: Vec<f64> = drives
        .iter()
        .map(|d| match *d {
            Drive::Volts(x) | Drive::Amps(x) | Drive::Thrust(x) | Drive::Omega(x) => x,
            Drive::Throttle { throttle, .. } => throttle,
        })
        .collect();
    match drives.first() {
        Some(Drive::Omega(_)) => (flag, rpm_list_text(&values)),
        _ => (flag, list_text(&values)),
    }
}

/// One argument quoted for a POSIX shell where it needs it.
fn shell_word(a: &str) -> String {
    if a.is_empty() || a.contains(|c: char| c.is_whitespace() || "'\"$`\\*?;&|<>()#".contains(c)) {
        format!("'{}'", a.replace('\'', "'\\''"))
    } else {
        a.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The equivalent command names the rotation and the drag factor only where they are not
    /// the default.
    #[test]
    fn settings_are_named_only_where_not_the_default() {
        let mut spec = ModelSpec::prop("p.qprop".into());
        spec.polars = Some("polars.json".into());
        spec.rotation = propbet_api::settings::ROTATION.default;
        spec.drag_factor = propbet_api::settings::DRAG_FACTOR.default;
        let mut v = Vec::new();
        spec.push_argv(&mut v);
        assert!(
            !v.iter().any(|a| a == "--rotation" || a.starts_with("--drag-factor")),
            "{v:?}"
        );
        spec.rotation = Rotation::Off;
        spec.drag_factor = 1.0;
        let mut v = Vec::new();
        spec.push_argv(&mut v);
        assert!(v.windows(2).any(|w| w[0] == "--rotation" && w[1] == "off"), "{v:?}");
        assert!(v.iter().any(|a| a == "--drag-factor=1"), "{v:?}");
    }

    #[test]
    fn words_a_shell_would_split_are_quoted() {
        assert_eq!(shell_word("a b"), "'a b'");
        assert_eq!(shell_word("it's"), "'it'\\''s'");
        assert_eq!(shell_word("plain/path.csv"), "plain/path.csv");
        assert_eq!(shell_word(""), "''");
    }
}
