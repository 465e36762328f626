//! Each stage's spec as the `propbet` command line that does the same ([`StageSpec::argv`]),
//! and the `propbet export` command for a prediction.

use super::*;

/// One stage of the data flow.
#[derive(Debug, Clone, PartialEq)]
pub enum StageSpec {
    /// Geometry from a scan.
    Scan(ScanSpec),
    /// XFOIL polars of every station.
    Polars(PolarsSpec),
    /// Sweeps.
    Predict(PredictSpec),
    /// The propeller on its motor.
    Powered(PoweredSpec),
    /// Measured against predicted.
    Compare(CompareSpec),
    /// What is missing.
    Diagnose(DiagnoseSpec),
}

impl StageSpec {
    /// The stage's name (the subcommand).
    pub fn name(&self) -> &'static str {
        match self {
            StageSpec::Scan(_) => "scan",
            StageSpec::Polars(_) => "polars",
            StageSpec::Predict(_) => "predict",
            StageSpec::Powered(_) => "motor",
            StageSpec::Compare(_) => "compare",
            StageSpec::Diagnose(_) => "diagnose",
        }
    }

    /// The equivalent `propbet` command line (without the program name).
    pub fn argv(&self) -> Argv {
        let subcommand = match self {
            StageSpec::Powered(_) => "predict",
            _ => self.name(),
        };
        let mut v = vec![subcommand.to_string()];
        match self {
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
                if s.folds != crate::settings::FOLDS.default {
                    push(&mut v, "--folds", s.folds.to_string());
                }
                if s.max_steps != crate::settings::MAX_STEPS.default {
                    push(&mut v, "--max-steps", s.max_steps.to_string());
                }
                if s.window != propbet_compare::metrics::VALIDATION_J_WINDOW {
                    push(&mut v, "--window", s.window.to_string());
                }
                push(&mut v, "--out", path(&s.out));
            }
        }
        v
    }

    /// The command line as a shell would take it.
    pub fn command(&self) -> String {
        std::iter::once("propbet".to_string())
            .chain(self.argv().iter().map(|a| shell_word(a)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

impl PredictSpec {
    /// The `propbet export` command that writes this prediction for every flight simulator
    /// into `out`: the same model, sweep and air.
    pub fn export_command(&self, out: &Path) -> String {
        let plain = PredictSpec {
            format: TableFormat::Csv,
            out: None,
            stations: None,
            band: false,
            ..self.clone()
        };
        let mut argv = StageSpec::Predict(plain).argv();
        argv[0] = "export".into();
        argv.splice(1..1, ["--to".to_string(), "all".to_string()]);
        argv.extend(["-o".to_string(), path(out)]);
        std::iter::once("propbet".to_string())
            .chain(argv.iter().map(|a| shell_word(a)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

impl PoweredSpec {
    /// The flags of `propbet predict --motor` that give this spec.
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
fn drive_list(drives: &[propbet_motor::Drive]) -> (&'static str, String) {
    use propbet_motor::Drive;
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
pub(crate) fn shell_word(a: &str) -> String {
    if a.is_empty() || a.contains(|c: char| c.is_whitespace() || "'\"$`\\*?;&|<>()#".contains(c)) {
        format!("'{}'", a.replace('\'', "'\\''"))
    } else {
        a.to_string()
    }
}
