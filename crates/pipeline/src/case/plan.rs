//! A case's plan: each stage's spec from the case file's sections.

use std::path::Path;

use propbet_bemt::units::rpm_to_omega;
use propbet_measure::RpmSource;

use super::{at_key, Case, NumberOrList, RunPlan};
use crate::{Error, Result};
use propbet_settings::scan::ScanSettings;
use propbet_settings::spec::{
    AirSpec, CompareSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PolarsSpec, PoweredSpec, PredictSpec, ScanSpec,
    SweepAxis, TableFormat, XfoilProcessSpec, XfoilSpec,
};
use propbet_settings::values::parse_fraction;
use propbet_settings::values::{parse_atmosphere, parse_length_unit, parse_list};

impl Case {
    /// The scan stage's spec, where the case has a scan: its settings from `[geometry]`'s
    /// keys.
    fn scan_spec(&self, dir: &Path, out: &Path) -> Result<Option<ScanSpec>> {
        let g = &self.geometry;
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        let settings = g.settings.clone();
        let Some(file) = &g.scan else {
            // A prop file takes a unit; a scan's other settings would be read and ignored.
            let scan_only = ScanSettings {
                units: None,
                ..settings
            };
            if scan_only != ScanSettings::default() {
                return Err(at(
                    "[geometry]",
                    Error::Conflict(format!(
                        "{} set a scan's settings, and the case has no scan (`prop` is used as it is)",
                        scan_only.as_keys()
                    )),
                ));
            }
            return Ok(None);
        };
        Ok(Some(ScanSpec {
            input: dir.join(file),
            options: settings.options().map_err(|e| at("[geometry]", e.into()))?,
            reference: g.reference.as_deref().map(|r| dir.join(r)),
            name: Some(self.name.clone()),
            out: out.join("scan"),
        }))
    }

    /// The polars stage's spec, where the case has `[polars]`, and whether its sections are the
    /// scan's.
    fn polars_spec(
        &self,
        dir: &Path,
        out: &Path,
        geometry: &Path,
        units: Option<f64>,
        xfoil: &XfoilProcessSpec,
    ) -> Result<Option<(PolarsSpec, bool)>> {
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        Ok(match &self.polars {
            None => None,
            Some(p) => {
                let airfoil = p.airfoil.as_ref().map(|a| propbet_model::design::resolve_in(a, dir).0);
                let alpha = p.alpha.as_deref().unwrap_or(propbet_settings::ALPHA.default);
                let mut alphas = parse_list("--alpha", alpha).map_err(|e| at("[polars] alpha", e.into()))?;
                alphas.sort_by(f64::total_cmp);
                alphas.dedup();
                // The operating points the polars cover: the sweep's, unless the case says.
                let rpms = match &p.rpm {
                    Some(r) => r.values("--rpm").map_err(|e| at("[polars] rpm", e))?,
                    None => parse_list("--rpm", &self.sweep.rpm).map_err(|e| at("[sweep] rpm", e.into()))?,
                };
                let axis = match (&p.j, &p.v) {
                    (_, Some(v)) => SweepAxis::V(v.values("--v").map_err(|e| at("[polars] v", e))?),
                    (Some(j), None) => SweepAxis::J(parse_list("--j", j).map_err(|e| at("[polars] j", e.into()))?),
                    (None, None) => {
                        SweepAxis::J(parse_list("--j", &self.sweep.j).map_err(|e| at("[sweep] j", e.into()))?)
                    }
                };
                let thickness = p
                    .thickness
                    .as_deref()
                    .map(parse_fraction)
                    .transpose()
                    .map_err(|e| at("[polars] thickness", e.into()))?;
                let sections = p.sections.as_deref().unwrap_or("airfoil");
                let scanned = sections == "scan";
                let g = &self.geometry;
                // With `pe0` beside `prop`, the blade is the prop's and the sections APC's.
                let sections_from = match (&g.prop, &g.pe0) {
                    (Some(_), Some(pe0)) if sections == "design" => Some(f(pe0)),
                    _ => None,
                };
                let airfoil = if sections == "design" { None } else { airfoil };
                Some((
                    PolarsSpec {
                        geometry: geometry.to_path_buf(),
                        units,
                        airfoil,
                        thickness,
                        station_airfoils: scanned.then(|| out.join("scan/airfoils")),
                        sections_from,
                        airfoils: None,
                        omegas: rpms.into_iter().map(rpm_to_omega).collect(),
                        axis,
                        air: AirSpec::default(),
                        xfoil: XfoilSpec {
                            process: XfoilProcessSpec {
                                engine: p
                                    .engine
                                    .as_deref()
                                    .and_then(propbet_polar::Engine::parse)
                                    .unwrap_or(xfoil.engine),
                                neuralfoil_size: p.neuralfoil_size.clone().or_else(|| xfoil.neuralfoil_size.clone()),
                                ..xfoil.clone()
                            },
                            section: xfoil_runner::SectionSettings {
                                ncrit: p.ncrit.unwrap_or(propbet_settings::NCRIT.default),
                                trip: match &p.trip {
                                    None => propbet_settings::default_trip(),
                                    Some(NumberOrList::Number(x)) => {
                                        propbet_settings::values::parse_trip(&x.to_string())
                                            .map_err(|e| at("[polars] trip", e.into()))?
                                    }
                                    Some(NumberOrList::List(t)) => propbet_settings::values::parse_trip(t)
                                        .map_err(|e| at("[polars] trip", e.into()))?,
                                },
                                ..xfoil_runner::SectionSettings::new(alphas)
                            },
                        },
                        ncrit_effect: match &p.ncrit_effect {
                            None => Vec::new(),
                            Some(n) => n
                                .values("--ncrit-effect")
                                .and_then(|v| {
                                    Ok(propbet_settings::check_ncrit_effect(
                                        &v,
                                        p.ncrit.unwrap_or(propbet_settings::NCRIT.default),
                                    )?)
                                })
                                .map_err(|e| at("[polars] ncrit_effect", e))?,
                        },
                        out_prop: out.join("polars/prop.qprop"),
                        out_polars: Some(out.join("polars/polars.json")),
                    },
                    scanned,
                ))
            }
        })
    }

    /// The compare and diagnose stages' specs, where the case has `[measured]`.
    fn compare_specs(
        &self,
        dir: &Path,
        out: &Path,
        model: ModelSpec,
        state: Option<propbet_atmosphere::AirState>,
    ) -> Result<Option<(CompareSpec, DiagnoseSpec)>> {
        let a = &self.atmosphere;
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        Ok(match &self.measured {
            None => None,
            Some(m) => {
                let rpm_source = match m.rpm_source.as_deref() {
                    None => None,
                    Some(x) => match propbet_settings::RPM_SOURCE
                        .choose(x)
                        .map_err(|e| at("[measured] rpm_source", e.into()))?
                    {
                        "optical" => Some(RpmSource::Optical),
                        _ => Some(RpmSource::Electrical),
                    },
                };
                // A user-effects file that does not read stops the run before its first stage.
                let user_effects = m.user_effects.as_deref().map(f);
                propbet_model::effect_registry(user_effects.as_deref())
                    .map_err(|e| at("[measured] user_effects", e))?;
                let measured = MeasuredSpec {
                    files: m.files.iter().map(|x| f(x)).collect(),
                    poles: m.poles,
                    rpm_source,
                    atmosphere: state,
                    rho: a.rho,
                    columns: m.columns.as_deref().map(f),
                };
                Some((
                    CompareSpec {
                        model: model.clone(),
                        measured: measured.clone(),
                        per3: m.per3.as_deref().map(f),
                        qprop_output: None,
                        motor: self.motor.as_ref().map(|m| f(&m.file)),
                        out: out.join("compare"),
                    },
                    DiagnoseSpec {
                        model: ModelSpec { user_effects, ..model },
                        measured,
                        effects: vec!["all".into()],
                        folds: propbet_settings::FOLDS
                            .check(m.folds.unwrap_or(propbet_settings::FOLDS.default))
                            .map_err(|e| at("[measured] folds", e.into()))?,
                        max_steps: m.max_steps.unwrap_or(propbet_settings::MAX_STEPS.default),
                        window: propbet_compare::metrics::VALIDATION_J_WINDOW,
                        out: out.join("diagnose"),
                    },
                ))
            }
        })
    }

    /// The powered table's spec, where `[motor]` names a driver: the sweep's model and air on
    /// the motor, with `[battery]` and `[esc]` in front of it.
    fn powered_spec(&self, dir: &Path, out: &Path, model: &ModelSpec, air: &AirSpec) -> Result<Option<PoweredSpec>> {
        use propbet_motor::{Battery, DriveRule, Driver, Supply};
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        let Some(m) = &self.motor else {
            if self.battery.is_some() || self.esc.is_some() {
                return Err(at(
                    "[battery]",
                    Error::Conflict("a battery or an ESC needs the motor they drive ([motor] file)".into()),
                ));
            }
            return Ok(None);
        };
        let supply = match (&self.battery, &self.esc) {
            (None, Some(_)) => {
                return Err(at(
                    "[esc]",
                    Error::Conflict("an ESC needs the battery in front of it ([battery] cells)".into()),
                ))
            }
            (None, None) => None,
            (Some(b), esc) => {
                let lipo = propbet_motor::power::LIPO;
                let battery = Battery {
                    cells: b.cells,
                    cell_volts: b.cell_volts.unwrap_or(lipo.cell_volts),
                    cell_ohms: b.cell_ohms.unwrap_or(lipo.cell_ohms),
                    capacity_ah: b.capacity_mah.map_or(0.0, |c| c / 1000.0),
                    cutoff_volts: b.cutoff_volts.unwrap_or(lipo.cutoff_volts),
                    usable: b.usable.unwrap_or(lipo.usable),
                };
                battery
                    .check()
                    .map_err(|e| at("[battery]", Error::Range(e.to_string())))?;
                let esc_ohms = esc.as_ref().map_or(propbet_motor::power::ESC_OHMS, |e| e.ohms);
                if !(0.0..10.0).contains(&esc_ohms) {
                    return Err(at(
                        "[esc] ohms",
                        Error::Range(format!("{esc_ohms}: a resistance from 0 to 10 ohm")),
                    ));
                }
                Some(Supply { battery, esc_ohms })
            }
        };
        let given: Vec<(&str, &NumberOrList)> = [
            ("volts", &m.volts),
            ("amps", &m.amps),
            ("thrust", &m.thrust),
            ("throttle", &m.throttle),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.as_ref().map(|v| (k, v)))
        .collect();
        let (key, values) = match given[..] {
            [] => return Ok(None),
            [(k, v)] => (k, v),
            _ => {
                return Err(at(
                    "[motor]",
                    Error::Conflict(
                        "volts, amps, thrust, throttle: give one of them (what sets the operating point)".into(),
                    ),
                ))
            }
        };
        let key_name = format!("[motor] {key}");
        let list = values.values(&format!("--{key}")).map_err(|e| at(&key_name, e))?;
        let driver = match key {
            "volts" => Driver::Volts,
            "amps" => Driver::Amps,
            "thrust" => Driver::Thrust,
            _ => Driver::Throttle,
        };
        let drives = propbet_motor::drives(driver, list, supply.as_ref()).map_err(|rule| {
            at(
                &key_name,
                match rule {
                    DriveRule::ThrottleWithoutBattery => {
                        Error::Conflict("a throttle needs the battery ([battery] cells)".into())
                    }
                    DriveRule::ThrottleOutside(bad) => Error::Range(format!("{bad}: a throttle is between 0 and 1")),
                },
            )
        })?;
        let speeds = match &m.v {
            None => vec![0.0],
            Some(v) => v.values("--v").map_err(|e| at("[motor] v", e))?,
        };
        Ok(Some(PoweredSpec {
            model: model.clone(),
            motor: dir.join(&m.file),
            drives,
            supply,
            speeds,
            air: *air,
            format: TableFormat::Csv,
            out: Some(out.join("predict/powered.csv")),
            stations: None,
            band: true,
        }))
    }

    /// The plan of stages: each stage's spec, reading from `dir` and writing under `out`.
    pub fn plan(&self, dir: &Path, out: &Path, xfoil: &XfoilProcessSpec) -> Result<RunPlan> {
        let g = &self.geometry;
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        let units = match (&g.prop, &g.settings.units) {
            (Some(_), Some(u)) => Some(parse_length_unit(u).map_err(|e| at("[geometry] units", e.into()))?),
            _ => None,
        };
        let scan = self.scan_spec(dir, out)?;
        let geometry = match &g.scan {
            Some(_) => out.join("scan/prop.qprop"),
            None => f(g.prop.as_deref().or(g.pe0.as_deref()).unwrap_or_default()),
        };
        let polars = self.polars_spec(dir, out, &geometry, units, xfoil)?;
        // The fitted prop file is in metres; a case's own prop file keeps its units. With
        // tables, the polars are the section model (the prop file gives the blade).
        let (prop, model_units) = match &polars {
            Some(_) => (out.join("polars/prop.qprop"), None),
            None => (geometry, units),
        };
        let tables = self.polars.as_ref().is_some_and(|p| p.model == "tables");
        let rotation = self
            .polars
            .as_ref()
            .and_then(|p| p.rotation.as_deref())
            .map(propbet_settings::Rotation::parse)
            .transpose()
            .map_err(|e| at("[polars] rotation", e.into()))?;
        let model = ModelSpec {
            units: model_units,
            polars: tables.then(|| out.join("polars/polars.json")),
            rotation: propbet_settings::Rotation::or_default(rotation, tables),
            drag_factor: propbet_settings::drag_factor_or_default(
                self.polars.as_ref().and_then(|p| p.drag_factor),
                tables,
            ),
            effects: self.effects.clone(),
            ..ModelSpec::prop(prop)
        };
        // The effects are checked against the built-ins before any stage runs.
        let registry = propbet_model::effect_registry(None).map_err(|e| at("effects", e))?;
        propbet_model::stack_of(&registry, &self.effects, "effects").map_err(|e| Error::input(&case_file, e))?;
        let a = &self.atmosphere;
        // Checked with the case, before any stage runs (a NaN would otherwise reach predict).
        if let Some(r) = a.rho {
            propbet_units::air::check("[atmosphere] rho", r, &propbet_units::air::DENSITY, "kg/m^3")
                .map_err(|e| at("[atmosphere] rho", Error::Range(e)))?;
        }
        let state = a
            .air
            .as_deref()
            .map(parse_atmosphere)
            .transpose()
            .map_err(|e| at("[atmosphere] air", e.into()))?;
        let rpms = parse_list("--rpm", &self.sweep.rpm).map_err(|e| at("[sweep] rpm", e.into()))?;
        let js = parse_list("--j", &self.sweep.j).map_err(|e| at("[sweep] j", e.into()))?;
        let predict = PredictSpec {
            model: model.clone(),
            omegas: rpms.into_iter().map(rpm_to_omega).collect(),
            axis: SweepAxis::J(js),
            air: AirSpec {
                rho: a.rho,
                state,
                ..AirSpec::default()
            },
            format: TableFormat::Csv,
            out: Some(out.join("predict/sweep.csv")),
            stations: None,
            band: true,
        };
        let powered = self.powered_spec(dir, out, &model, &predict.air)?;
        let compare = self.compare_specs(dir, out, model, state)?;
        Ok(RunPlan {
            name: self.name.clone(),
            description: self.description.clone(),
            dir: dir.to_path_buf(),
            out: out.to_path_buf(),
            blades: self.blades,
            scan,
            polars,
            predict,
            powered,
            compare,
            expected: propbet_compare::expected::sentence(
                g.pe0
                    .as_deref()
                    .or(g.prop.as_deref())
                    .and_then(|p| Path::new(p).file_name()?.to_str()),
                &propbet_compare::expected::shipped(),
            ),
        })
    }
}
