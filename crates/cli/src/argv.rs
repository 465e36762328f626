//! Each stage's spec as the `propbet` command line that does the same: the one formatter of
//! the "equivalent command" lines the terminal, the run's page and `summary.json` show. Every
//! printed line parses back to the same spec (`every_stage_of_the_shipped_cases_is_a_command_that_parses_back`).

use std::path::Path;

use propbet_api::geometry::scan::{default_stations, ScanOptions, SectionKind};
use propbet_api::measure::RpmSource;
use propbet_api::settings::values::{length_unit_name, list_text, rpm_list_text, scaled_text};
use propbet_api::settings::{drag_factor_or_default, Rotation};
use propbet_api::spec::{
    AirSpec, MeasuredSpec, ModelSpec, PoweredSpec, PredictSpec, ScanSpec, StageSpec, SweepAxis, TableFormat,
    XfoilProcessSpec, XfoilSpec,
};

/// The `propbet` command line of one stage (without the program name).
pub type Argv = Vec<String>;

/// A spec's flags, pushed onto a command line.
trait Flags {
    fn push_argv(&self, v: &mut Argv);
}

fn path(p: &Path) -> String {
    p.display().to_string()
}

fn push(v: &mut Argv, flag: &str, value: impl Into<String>) {
    v.push(flag.to_string());
    v.push(value.into());
}

/// `flag value` where there is a value.
fn opt(v: &mut Argv, flag: &str, value: Option<impl ToString>) {
    if let Some(x) = value {
        push(v, flag, x.to_string());
    }
}

/// `flag` alone where it is on.
fn switch(v: &mut Argv, flag: &str, on: bool) {
    if on {
        v.push(flag.to_string());
    }
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

/// `--rpm` and the sweep's second axis (`static_v0`: a static sweep, `--v 0`, left out).
fn sweep(v: &mut Argv, omegas: &[f64], axis: &SweepAxis, static_v0: bool) {
    push_eq(v, "--rpm", rpm_list_text(omegas));
    match axis {
        SweepAxis::V(x) if static_v0 && x == &[0.0] => {}
        SweepAxis::J(j) => push_eq(v, "--j", list_text(j)),
        SweepAxis::V(x) => push_eq(v, "--v", list_text(x)),
    }
}

/// A table's format, its files and the band (predict's, with or without a motor).
fn table(v: &mut Argv, format: TableFormat, out: Option<&Path>, stations: Option<&Path>, band: bool) {
    if format == TableFormat::Json {
        push(v, "--format", "json");
    }
    opt(v, "--out", out.map(path));
    opt(v, "--out-stations", stations.map(path));
    switch(v, "--band", band);
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
            opt(&mut v, "--units", s.units.map(|u| length_unit_name(u).unwrap_or("m")));
            opt(&mut v, "--airfoil", s.airfoil.as_ref());
            opt(&mut v, "--thickness", s.thickness);
            opt(&mut v, "--station-airfoils", s.station_airfoils.as_deref().map(path));
            opt(&mut v, "--sections-from", s.sections_from.as_deref().map(path));
            opt(&mut v, "--airfoils", s.airfoils.as_deref().map(path));
            sweep(&mut v, &s.omegas, &s.axis, true);
            s.air.push_argv(&mut v);
            s.xfoil.push_argv(&mut v);
            if !s.ncrit_effect.is_empty() {
                push_eq(&mut v, "--ncrit-effect", ncrit_effect_text(&s.ncrit_effect));
            }
            push(&mut v, "--out-prop", path(&s.out_prop));
            opt(&mut v, "--out-polars", s.out_polars.as_deref().map(path));
        }
        StageSpec::Predict(s) => {
            s.model.push_argv(&mut v);
            sweep(&mut v, &s.omegas, &s.axis, false);
            s.air.push_argv(&mut v);
            table(&mut v, s.format, s.out.as_deref(), s.stations.as_deref(), s.band);
        }
        StageSpec::Powered(s) => s.push_argv(&mut v),
        StageSpec::Compare(s) => {
            s.model.push_argv(&mut v);
            s.measured.push_argv(&mut v);
            opt(&mut v, "--per3", s.per3.as_deref().map(path));
            opt(&mut v, "--qprop-output", s.qprop_output.as_deref().map(path));
            opt(&mut v, "--motor", s.motor.as_deref().map(path));
            push(&mut v, "--out", path(&s.out));
        }
        StageSpec::Diagnose(s) => {
            s.model.push_argv(&mut v);
            s.measured.push_argv(&mut v);
            if s.effects != ["all"] {
                push(&mut v, "--effects", s.effects.join(","));
            }
            let not = |x: usize, default: usize| (x != default).then_some(x);
            opt(&mut v, "--folds", not(s.folds, propbet_api::settings::FOLDS.default));
            opt(
                &mut v,
                "--max-steps",
                not(s.max_steps, propbet_api::settings::MAX_STEPS.default),
            );
            let window = propbet_api::compare::metrics::VALIDATION_J_WINDOW;
            opt(&mut v, "--window", (s.window != window).then_some(s.window));
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
        opt(v, "--xfoil-budget", self.budget);
        opt(v, "--xfoil", self.xfoil.as_deref().map(path));
        opt(v, "--cache", self.cache.as_deref().map(path));
        switch(v, "--no-cache", self.no_cache);
        switch(v, "--quiet", self.quiet);
        if self.engine != propbet_api::polar::Engine::default() {
            push(v, "--engine", self.engine.name());
        }
        opt(v, "--neuralfoil-size", self.neuralfoil_size.as_ref());
    }
}

impl Flags for XfoilSpec {
    fn push_argv(&self, v: &mut Argv) {
        self.process.push_argv(v);
        let s = &self.section;
        opt(
            v,
            "--ncrit",
            (s.ncrit != propbet_api::settings::NCRIT.default).then_some(s.ncrit),
        );
        if s.trip != propbet_api::settings::default_trip() {
            push(v, "--trip", propbet_api::settings::trip_text(s.trip));
        }
        let default =
            propbet_api::settings::values::parse_list("", propbet_api::settings::ALPHA.default).unwrap_or_default();
        if s.alphas_deg != default {
            push_eq(v, "--alpha", list_text(&s.alphas_deg));
        }
        opt(v, "--panels", s.panels);
        let default_iter = propbet_api::xfoil::DEFAULT_MAX_ITER;
        opt(v, "--iter", (s.max_iter != default_iter).then_some(s.max_iter));
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
        opt(v, "--units", self.units.map(|u| length_unit_name(u).unwrap_or("m")));
        switch(v, "--qprop-compat", self.qprop_compat);
        switch(v, "--no-tip-loss", self.no_tip_loss);
        opt(v, "--polars", self.polars.as_deref().map(path));
        if let Some(d) = &self.design {
            opt(v, "--airfoil", d.airfoil.as_ref());
            opt(v, "--sections-from", d.sections_from.as_deref().map(path));
            opt(v, "--airfoils", d.airfoils.as_deref().map(path));
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
        opt(v, "--user-effects", self.user_effects.as_deref().map(path));
    }
}

impl Flags for MeasuredSpec {
    fn push_argv(&self, v: &mut Argv) {
        v.push("--measured".into());
        v.extend(self.files.iter().map(|f| path(f)));
        opt(v, "--poles", self.poles);
        let source = self.rpm_source.map(|s| match s {
            RpmSource::Optical => "optical",
            RpmSource::Electrical => "electrical",
        });
        opt(v, "--rpm-source", source);
        let air = self.atmosphere.as_ref().map(|s| {
            format!(
                "{}K,{},{}",
                s.temperature,
                s.pressure,
                percent_text(s.relative_humidity)
            )
        });
        opt(v, "--atmosphere", air);
        if let Some(r) = self.rho {
            push_eq(v, "--rho", format!("{r}"));
        }
        opt(v, "--columns", self.columns.as_deref().map(path));
    }
}

impl Flags for ScanSpec {
    fn push_argv(&self, v: &mut Argv) {
        let o = &self.options;
        v.push(path(&self.input));
        push(v, "-o", path(&self.out));
        opt(v, "--name", self.name.as_ref());
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
        opt(v, "--reference", self.reference.as_deref().map(path));
        switch(v, "--planar", o.kind == SectionKind::Planar);
        opt(
            v,
            "--slab",
            (o.slab != ScanOptions::default().slab).then(|| mm_text(o.slab)),
        );
        opt(v, "--slab-points", (o.slab_points != 400).then_some(o.slab_points));
        if !o.blade_colours.is_empty() {
            push(v, "--blade-colour", colour_text(&o.blade_colours));
        }
        opt(v, "--colour-threshold", o.colour_threshold);
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
        table(v, self.format, self.out.as_deref(), self.stations.as_deref(), self.band);
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
