//! Where an export's points come from: a prediction swept over its spec, or measured files
//! reduced to coefficients; and the exports of a spec, each made before any is written.

use super::{blade_ixx, export, gazebo, Exported, Point, Source, Target, IXX_ASSUMED};
use propbet_model::Model;
use propbet_model::{conflict, out_of_range, Error, Result};
use propbet_settings::spec::{MeasuredSpec, ModelSpec, PredictSpec, SweepAxis};
use propbet_settings::values::{list_text, rpm_list_text, rpm_text};

/// Where the exported points come from.
#[derive(Debug, Clone, PartialEq)]
pub enum ExportFrom {
    /// propbet's prediction over the spec's operating points.
    Prediction(PredictSpec),
    /// Measured files; the prop file's model, where given, for the diameter, the blade count
    /// and the inertia.
    Measured {
        /// The files and how to read them.
        measured: MeasuredSpec,
        /// The prop file's model.
        model: Option<ModelSpec>,
        /// The diameter [m] without a prop file.
        diameter: Option<f64>,
        /// The blade count without a prop file (None: 2).
        blades: Option<f64>,
    },
}

/// What `propbet export` is asked.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSpec {
    /// The points.
    pub from: ExportFrom,
    /// The formats, in [`Target::ALL`]'s order.
    pub targets: Vec<Target>,
    /// Gazebo's fit over this RPM range only.
    pub rpm_range: Option<(f64, f64)>,
    /// The moment of inertia about the shaft [kg m^2] (None: estimated from the prop file).
    pub ixx: Option<f64>,
    /// The propeller's name in the files (None: the prop file's, or the first measured file's).
    pub name: Option<String>,
}

/// What an export says as it goes (for the terminal).
#[derive(Debug, Clone, PartialEq)]
pub enum Said {
    /// A prop file's warning, said as soon as the file is read.
    Warning(String),
    /// Points left out, and why.
    LeftOut(String),
}

/// The model of a prop file, its warnings said; a blade file without coefficients has its
/// polars computed over `points` (the export's operating points).
fn load(
    spec: &ModelSpec,
    points: impl FnOnce() -> Result<(Vec<f64>, propbet_settings::spec::SweepAxis)>,
    say: &dyn Fn(Said),
) -> Result<Model> {
    if spec.design.is_some() {
        let (omegas, axis) = points()?;
        let (model, _) = propbet_pipeline::stages::design_model(spec, omegas, axis, false, &|_, _| {})?
            .ok_or_else(|| propbet_model::Error::Nothing("no design blade".into()))?;
        return Ok(model);
    }
    let model = Model::load(spec, false)?;
    for w in &model.loaded.warnings {
        say(Said::Warning(w.clone()));
    }
    Ok(model)
}

/// The blade's inertia: the one given, or estimated from the prop file's chords.
/// The moments of inertia a propeller can have [kg m^2]: a 1-inch blade's to a 3-metre one's.
const IXX: (f64, f64) = (1e-10, 100.0);

/// The blade counts a propeller can have.
pub const BLADES: std::ops::RangeInclusive<f64> = 1.0..=20.0;

fn inertia(given: Option<f64>, model: Option<&Model>) -> Result<Option<(f64, String)>> {
    if let Some(i) = given {
        if !(i.is_finite() && (IXX.0..=IXX.1).contains(&i)) {
            out_of_range!(
                "--ixx {}: a moment of inertia in kg m^2, from {:e} to {} (a small propeller's is about 1e-5)",
                propbet_units::show(i),
                IXX.0,
                IXX.1
            );
        }
        return Ok(Some((i, "given (--ixx)".into())));
    }
    let Some(m) = model else { return Ok(None) };
    let blade = m.loaded.file.to_blade(propbet_qprop::RadiusReading::Documented);
    let (t_c, density) = IXX_ASSUMED;
    let i = blade_ixx(blade.blades, &blade.r, &blade.chord, t_c, density);
    Ok(Some((
        i,
        format!(
            "estimated from the prop file's chords: {} blades, section area 0.685 t c at t/c {t_c}, \
             {density} kg/m^3 (glass-filled nylon), hub left out; a weighed value belongs here (the ixx option)",
            blade.blades
        ),
    )))
}

/// RPMs as a reader takes them in a file's header: a few listed, more as a range.
fn rpms_text(omegas: &[f64]) -> String {
    if omegas.len() <= 6 {
        omegas.iter().map(|&w| rpm_text(w)).collect::<Vec<_>>().join(",")
    } else {
        rpm_list_text(omegas)
    }
}

/// The prediction's points (those that converged at every station).
fn predicted(spec: &PredictSpec, ex: &ExportSpec, say: &dyn Fn(Said)) -> Result<Source> {
    let model = load(&spec.model, || Ok((spec.omegas.clone(), spec.axis.clone())), say)?;
    predicted_by(&model, spec, ex, say)
}

/// The points `model` (loaded, its effects included) predicts over `spec`'s operating points
/// and air (those that converged at every station); `spec.model` names its file and sections.
pub fn predicted_by(model: &Model, spec: &PredictSpec, ex: &ExportSpec, say: &dyn Fn(Said)) -> Result<Source> {
    let (fluid, fluid_source) = spec.air.fluid()?;
    let ops = propbet_model::solve::operating_points(spec, model.rotor.tip_radius)?;
    let results = propbet_model::solve::sweep(model, &fluid, &ops)?;
    let unconverged = results.iter().filter(|p| p.not_converged > 0).count();
    if unconverged > 0 {
        say(Said::LeftOut(format!(
            "{unconverged} operating points did not converge everywhere; they are left out"
        )));
    }
    let points: Vec<Point> = results
        .iter()
        .filter(|p| p.not_converged == 0)
        .filter_map(|p| {
            Some(Point {
                rpm: p.rpm,
                j: p.j?,
                ct: p.ct?,
                cp: p.cp?,
            })
        })
        .collect();
    let m = &spec.model;
    let section = format!(
        "{}, drag factor {}, rotation {}{}",
        m.polars.as_ref().map_or_else(
            || "the prop file's QPROP coefficients".to_string(),
            |p| format!("XFOIL polars {} as tables", p.display())
        ),
        m.drag_factor,
        m.rotation.name(),
        if model.effects.is_empty() {
            String::new()
        } else {
            format!(", effects {}", model.effects.describe())
        }
    );
    let axis = match &spec.axis {
        SweepAxis::J(j) if j.iter().all(|x| *x == 0.0) => "static".to_string(),
        SweepAxis::J(j) => format!("J {}", list_text(j)),
        SweepAxis::V(v) => format!("V {} m/s", list_text(v)),
    };
    Ok(Source {
        points,
        diameter: model.diameter,
        blades: model.rotor.blades,
        ixx: inertia(ex.ixx, Some(model))?,
        origin: format!(
            "propbet's prediction of {} ({section}) at {} rpm, {axis} ({fluid_source}, rho {} kg/m^3)",
            m.prop.display(),
            rpms_text(&spec.omegas),
            fluid.rho
        ),
        name: ex.name.clone().unwrap_or_else(|| model.loaded.file.name.clone()),
        measured: false,
    })
}

/// The measured points as coefficients at their own air (points flagged unsteady or
/// implausible left out).
fn measured(
    (measured, model_spec, diameter, blades): (&MeasuredSpec, &Option<ModelSpec>, Option<f64>, Option<f64>),
    ex: &ExportSpec,
    say: &dyn Fn(Said),
) -> Result<Source> {
    use propbet_measure::{Loads, Speed};
    if let Some(b) = blades.filter(|b| !(b.fract() == 0.0 && BLADES.contains(b))) {
        out_of_range!(
            "--blades {}: a propeller has a whole number of blades, from {} to {}",
            propbet_units::show(b),
            BLADES.start(),
            BLADES.end()
        );
    }
    let model = model_spec
        .as_ref()
        .map(|s| {
            load(
                s,
                || propbet_pipeline::stages::cover(measured).map(|(o, j)| (o, propbet_settings::spec::SweepAxis::J(j))),
                say,
            )
        })
        .transpose()?;
    let diameter = match (&model, diameter) {
        (Some(m), _) => m.diameter,
        (None, Some(d)) => d,
        (None, None) => conflict!(
            "the measurements' propeller diameter is needed for its coefficients: give --diameter (like 10in) or --prop"
        ),
    };
    // Every file, read once; one that does not read stops the export.
    let batch = propbet_pipeline::stages::load_batch(measured)?;
    if let Some(r) = batch.refused.first() {
        return Err(Error::input(std::path::Path::new(&r.file), r.reason.clone()));
    }
    let (air, sets) = (batch.air, &batch.sets);
    let mut points = Vec::new();
    let mut flagged = 0;
    for (name, set) in batch.names.iter().zip(sets) {
        if !set.has_torque {
            return Err(Error::input(
                std::path::Path::new(name),
                "no torque or power measured; every export needs the torque (momentConstant, CP)",
            ));
        }
        for p in &set.points {
            if !p.flags.is_empty() {
                flagged += 1;
                continue;
            }
            let rho = propbet_compare::point_air(p, &air).fluid.rho;
            let omega = p.omega.mean;
            let n = propbet_units::omega_to_rev_per_s(omega);
            let j = match p.speed {
                Speed::Airspeed(v) => v.mean / (n * diameter),
                Speed::AdvanceRatio(j) => j,
            };
            let (ct, cp) = match p.loads {
                Loads::Coefficients { ct, cp } => (ct, cp),
                Loads::Forces { thrust, torque } => {
                    let q = propbet_compare::Quantities::from_forces(
                        thrust.mean,
                        torque.map(|q| q.mean),
                        omega,
                        j * n * diameter,
                        rho,
                        diameter,
                    );
                    match (q.ct, q.cp) {
                        (Some(ct), Some(cp)) => (ct, cp),
                        _ => continue,
                    }
                }
            };
            points.push(Point {
                rpm: p.rpm(),
                j,
                ct,
                cp,
            });
        }
    }
    if flagged > 0 {
        say(Said::LeftOut(format!(
            "{flagged} measured points flagged as unsteady or implausible are left out"
        )));
    }
    let first = measured.files[0]
        .file_stem()
        .map_or_else(|| "propeller".to_string(), |s| s.to_string_lossy().into_owned());
    Ok(Source {
        points,
        diameter,
        blades: model.as_ref().map_or(blades.unwrap_or(2.0), |m| m.rotor.blades),
        ixx: inertia(ex.ixx, model.as_ref())?,
        origin: format!(
            "measurements {} ({} points, diameter {:.4} m{})",
            measured
                .files
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            sets.iter().map(|s| s.points.len()).sum::<usize>(),
            diameter,
            if model.is_some() { " from the prop file" } else { "" }
        ),
        name: ex
            .name
            .clone()
            .or_else(|| model.as_ref().map(|m| m.loaded.file.name.clone()))
            .unwrap_or(first),
        measured: true,
    })
}

/// The points of a spec, as the exports take them; `say` hears the prop file's warnings and
/// the points left out as they come.
pub fn source(spec: &ExportSpec, say: &dyn Fn(Said)) -> Result<Source> {
    match &spec.from {
        ExportFrom::Prediction(p) => predicted(p, spec, say),
        ExportFrom::Measured {
            measured: m,
            model,
            diameter,
            blades,
        } => measured((m, model, *diameter, *blades), spec, say),
    }
}

/// Every export of a spec, each made before any is written: one the data cannot support
/// stops them all.
pub fn exports(spec: &ExportSpec, say: &dyn Fn(Said)) -> Result<Vec<Exported>> {
    exports_of(&source(spec, say)?, spec)
}

/// Every export `spec` names of the points `src`, each made before any is written.
pub fn exports_of(src: &Source, spec: &ExportSpec) -> Result<Vec<Exported>> {
    spec.targets
        .iter()
        .map(|&t| match t {
            Target::Gazebo => gazebo(src, spec.rpm_range),
            t => export(t, src),
        })
        .collect()
}
