//! The polars stage: each station's section, XFOIL polars at its Reynolds and Mach
//! numbers over the operating points asked (cached), the prop file with QPROP's law fitted
//! to them, and the check that an exported QPROP file keeps the model's prediction.

use super::*;
use propbet_qprop::export::Differences;

// ---------------------------------------------------------------------------------------
// polars

/// A section: a NACA 4-digit name or a coordinate file, optionally scaled to a thickness ratio;
/// with the file's repairs.
pub fn load_airfoil(name: &str, thickness: Option<f64>) -> Result<(Airfoil, Vec<String>)> {
    let (mut foil, notes) = match naca4_from_name(name) {
        Some(r) => {
            let mut foil = r.map_err(|e| Error::about(format!("--airfoil {name}"), e))?;
            foil.normalise();
            (foil, Vec::new())
        }
        // A file of that name first, then propbet's built-in sections (`e63`).
        None => match propbet_model::design::library_airfoil(name).filter(|_| !Path::new(name).is_file()) {
            Some(read) => read?,
            None => read_airfoil(Path::new(name))?,
        },
    };
    if let Some(t) = thickness {
        foil = foil
            .scale_thickness(t)
            .map_err(|e| Error::about(format!("--thickness {}", propbet_units::show(t)), e))?;
    }
    Ok((foil, notes))
}

/// XFOIL and the polar cache, as the spec says.
pub fn polar_engine(p: &XfoilProcessSpec) -> Result<PolarEngine> {
    use propbet_polar::Engine;
    let size = propbet_settings::NEURALFOIL_SIZE;
    let size = size.choose(p.neuralfoil_size.as_deref().unwrap_or(size.default))?;
    let network = || propbet_neuralfoil::Network::shipped(size);
    if p.engine == Engine::NeuralFoil {
        return Ok(PolarEngine::neuralfoil(network()?));
    }
    let exe = match xfoil_runner::find_xfoil(p.xfoil.as_deref(), std::env::var_os("PATH").as_deref()) {
        Ok(exe) => exe,
        // `auto` on a machine without XFOIL (none given, none on PATH): NeuralFoil's polars,
        // which every output then names as such.
        Err(_) if p.engine == Engine::Auto && p.xfoil.is_none() => return Ok(PolarEngine::neuralfoil(network()?)),
        Err(e) => return Err(e.into()),
    };
    let xfoil = xfoil_runner::Xfoil::new(xfoil_runner::XfoilConfig::new(exe))?;
    let cache = if p.no_cache {
        None
    } else {
        match p.cache.clone().or_else(PolarCache::default_dir) {
            Some(dir) => Some(PolarCache::open(&dir)?),
            None => None,
        }
    };
    let mut engine = PolarEngine::new(xfoil, cache);
    if p.engine == Engine::Auto {
        engine = engine.with_neuralfoil(network()?);
    }
    let budget = propbet_settings::XFOIL_BUDGET;
    Ok(engine.with_budget(budget.check(p.budget.unwrap_or(budget.default))?))
}

/// What the polars stage reads: the blade and its sections.
pub struct PolarsInput {
    /// The blade.
    pub geometry: LoadedProp,
    /// One section for every station, or one per input station.
    pub foils: Vec<Airfoil>,
    /// The section at every station (the hint).
    pub foil_name: String,
    /// Notes for the user (repairs, stations without their own section).
    pub notes: Vec<String>,
}

/// Reads the polars stage's inputs from the files its spec names.
pub fn polars_input(spec: &PolarsSpec) -> Result<PolarsInput> {
    if spec.station_airfoils.is_none() {
        if let Some(input) = design_input(spec)? {
            return Ok(input);
        }
    } else if spec.sections_from.is_some() {
        conflict!(
            "--sections-from gives every station APC's section; --station-airfoils gives each its own: one of them"
        );
    }
    if spec.sections_from.is_some() {
        conflict!(
            "--sections-from: {} is a QPROP prop file; APC's sections go with a PE0 file, a UIUC geometry table or a blade table",
            spec.geometry.display()
        );
    }
    let geometry = load_prop(&spec.geometry, spec.units)?;
    // Airfoils blended along the blade (`E63@0.25,APC12@0.45`) on a prop file's stations.
    if let Some(a) = spec.airfoil.as_deref().filter(|a| a.contains('@')) {
        let plan = propbet_model::design::SectionPlan::parse(a, "--airfoil")?;
        let blade = geometry.file.to_blade(propbet_qprop::RadiusReading::Documented);
        let radii: Vec<f64> = blade.r.clone();
        let tip = geometry.file.tip_radius(propbet_qprop::RadiusReading::Documented);
        let tcs = vec![spec.thickness; radii.len()];
        let foils = propbet_model::design::plan_sections(&plan, &radii, tip, &tcs, spec.airfoils.as_deref())?;
        let foils = reread(&spec.geometry, foils.iter().map(Airfoil::to_selig).collect())?;
        return Ok(PolarsInput {
            geometry,
            foils,
            foil_name: a.to_string(),
            notes: Vec::new(),
        });
    }
    let (foil, mut notes) = spec_airfoil(spec)?;
    let foils = match &spec.station_airfoils {
        None => vec![foil.clone().expect("spec_airfoil: an airfoil without station sections")],
        Some(dir) => {
            if !dir.is_dir() {
                return Err(Error::value(
                    "--station-airfoils",
                    &dir.display().to_string(),
                    "not a directory",
                ));
            }
            let n = geometry.file.rows.len();
            let texts = (0..n)
                .map(|i| {
                    let path = dir.join(format!("station_{i:02}.dat"));
                    path.exists().then(|| read_text(&path).map(|t| (path, t))).transpose()
                })
                .collect::<Result<Vec<_>>>()?;
            station_foils(dir, texts, foil.as_ref(), &mut notes)?
        }
    };
    Ok(PolarsInput {
        geometry,
        foils,
        foil_name: foil_name(foil.as_ref()),
        notes,
    })
}

/// The polars stage's inputs from a blade file other than QPROP's (APC's PE0, UIUC's table,
/// a blade table): None for a QPROP prop file.
fn design_input(spec: &PolarsSpec) -> Result<Option<PolarsInput>> {
    let plan = spec
        .airfoil
        .as_deref()
        .map(|a| propbet_model::design::SectionPlan::parse(a, "--airfoil"))
        .transpose()?;
    let opts = propbet_model::design::DesignOptions {
        units: spec.units,
        blades: None,
        sections: plan,
        thickness: spec.thickness,
        sections_from: spec.sections_from.clone(),
        airfoils: spec.airfoils.clone(),
    };
    let Some(d) = propbet_model::design::read_design(&spec.geometry, &opts)? else {
        return Ok(None);
    };
    let Some(texts) = d.sections else {
        nothing!(
            "{}: a {} names no sections: give --airfoil (`airfoil` in a case's [polars]), or --sections-from the prop's PE0 file",
            spec.geometry.display(),
            d.format.name()
        );
    };
    let foils = reread(&spec.geometry, texts)?;
    Ok(Some(PolarsInput {
        geometry: d.geometry,
        foils,
        foil_name: d.description,
        notes: Vec::new(),
    }))
}

/// Sections (Selig texts) parsed as the station files `propbet` writes for them would be.
fn reread(geometry: &Path, texts: Vec<String>) -> Result<Vec<Airfoil>> {
    let dir = geometry.parent().unwrap_or(Path::new("."));
    texts
        .iter()
        .enumerate()
        .map(|(i, t)| parse_airfoil(t, &dir.join(format!("station_{i:02}.dat"))).map(|(f, _)| f))
        .collect()
}

/// The spec's airfoil, loaded (and scaled) with its repair notes: None only when the stations
/// have their own sections; an error when neither is given.
pub(crate) fn spec_airfoil(spec: &PolarsSpec) -> Result<(Option<Airfoil>, Vec<String>)> {
    match (&spec.airfoil, &spec.station_airfoils) {
        (Some(a), _) => load_airfoil(a, spec.thickness).map(|(f, n)| (Some(f), n)),
        (None, None) => {
            conflict!("--airfoil: the section of every station (or --station-airfoils, the scanned sections)")
        }
        (None, Some(_)) if spec.thickness.is_some() => {
            conflict!(
                "--thickness scales the --airfoil section; without --airfoil each station keeps its scanned thickness"
            )
        }
        (None, Some(_)) => Ok((None, Vec::new())),
    }
}

/// What the polars' `airfoil` says: the airfoil's name, or that the scan gave every section.
pub(crate) fn foil_name(foil: Option<&Airfoil>) -> String {
    foil.map_or_else(|| "the scanned sections".to_string(), |f| f.name.clone())
}

/// One section per station from the texts of `station_NN.dat` files; a station without its
/// file takes `fallback`, or without one the nearest station's section (the outboard one of
/// two as near). An error when no station has a section and there is no fallback.
pub fn station_foils(
    dir: &Path,
    texts: Vec<Option<(PathBuf, String)>>,
    fallback: Option<&Airfoil>,
    notes: &mut Vec<String>,
) -> Result<Vec<Airfoil>> {
    let mut own: Vec<Option<Airfoil>> = Vec::new();
    for t in texts {
        own.push(match t {
            None => None,
            Some((path, text)) => {
                let (f, repairs) = parse_airfoil(&text, &path)?;
                notes.extend(repairs);
                Some(f)
            }
        });
    }
    let missing: Vec<usize> = (0..own.len()).filter(|&i| own[i].is_none()).collect();
    if missing.is_empty() {
        return Ok(own.into_iter().flatten().collect());
    }
    if let Some(f) = fallback {
        notes.push(format!(
            "{}: no section file for station(s) {missing:?}: {} used there",
            dir.display(),
            f.name
        ));
        return Ok(own.into_iter().map(|o| o.unwrap_or_else(|| f.clone())).collect());
    }
    let have: Vec<usize> = (0..own.len()).filter(|&i| own[i].is_some()).collect();
    if have.is_empty() {
        nothing!(
            "{}: no station has a section file and no airfoil was given for them (`airfoil` in [polars], --airfoil)",
            dir.display()
        );
    }
    let nearest = |i: usize| {
        *have
            .iter()
            .rev()
            .min_by_key(|&&k| k.abs_diff(i))
            .expect("have is not empty")
    };
    let taken: Vec<String> = missing.iter().map(|&i| format!("{i} from {}", nearest(i))).collect();
    notes.push(format!(
        "{}: no section file for station(s) {missing:?}: the nearest station's section used there (station {})",
        dir.display(),
        taken.join(", ")
    ));
    Ok((0..own.len())
        .map(|i| {
            own[i]
                .clone()
                .unwrap_or_else(|| own[nearest(i)].clone().expect("nearest has a section"))
        })
        .collect())
}

/// What the polars stage makes.
pub struct Polars {
    /// The prop file with each station's fitted coefficients (a station without a fit keeps
    /// the geometry's), as the file written for it holds it.
    pub prop: LoadedProp,
    /// Every station's polars and fit.
    pub blade: BladePolars,
    /// How far the exported prop file (QPROP's law) predicts from the tables over the points
    /// the polars cover (None when no station has a polar).
    pub export: Option<ExportCheck>,
    /// The cache could not store what XFOIL computed (read-only, full): the polars were
    /// used, and the next run computes them again.
    pub cache_warning: Option<String>,
}

/// The exported prop file against the tables it was fitted to: relative differences
/// |CT_qprop / CT_tables - 1| (and CP) over the operating points the polars cover where the
/// tables' thrust is at least a quarter of their largest (near zero thrust a ratio says
/// nothing, as in validate's window) and their power positive.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct ExportCheck {
    /// Points compared.
    pub points: usize,
    /// CT's relative differences.
    pub ct: Differences,
    /// CP's relative differences.
    pub cp: Differences,
}

impl ExportCheck {
    /// The check in one sentence (terminal and report).
    pub fn sentence(&self) -> String {
        format!(
            "The exported prop file (QPROP's law, for QPROP and other tools) against the tables over the {} operating points the polars cover (thrust at least a quarter of the largest): CT differs by {:.1} % (median), {:.1} % at most; CP by {:.1} %, {:.1} % at most.",
            self.points,
            100.0 * self.ct.median,
            100.0 * self.ct.largest,
            100.0 * self.cp.median,
            100.0 * self.cp.largest
        )
    }

    /// Compares the prop file's QPROP law with the tables at `points`.
    fn new(
        file: &PropFile,
        blade: &BladePolars,
        fluid: &Fluid,
        points: &[OperatingPoint],
    ) -> Result<Option<ExportCheck>> {
        let law = file
            .to_blade(propbet_qprop::RadiusReading::Documented)
            .to_rotor(propbet_bemt::Discretization::default())?;
        let mut tables = law.clone();
        let Ok((r, models)) = blade.models() else {
            return Ok(None);
        };
        propbet_polar::tabulated::apply_to_rotor(&mut tables, &r, &models);
        let opts = propbet_bemt::SolverOptions::default();
        let a = Solver::new(&law, fluid, &opts).solve_many(points);
        let b = Solver::new(&tables, fluid, &opts).solve_many(points);
        let (mut ct, mut cp) = (Vec::new(), Vec::new());
        let ct_max = b.iter().filter_map(|p| p.ct).fold(0.0, f64::max);
        for (x, y) in a.iter().zip(&b) {
            if let (Some(ct_a), Some(ct_b), Some(cp_a), Some(cp_b)) = (x.ct, y.ct, x.cp, y.cp) {
                if ct_b >= 0.25 * ct_max && ct_b > 0.0 && cp_b > 0.0 {
                    ct.push((ct_a / ct_b - 1.0).abs());
                    cp.push((cp_a / cp_b - 1.0).abs());
                }
            }
        }
        Ok(Some(ExportCheck {
            points: ct.len(),
            ct: Differences::of(&ct),
            cp: Differences::of(&cp),
        }))
    }
}

impl Polars {
    /// Nothing to report (exit 0): every station has a fit that describes it where the blade
    /// works, and XFOIL ran without a fault (a crash, a hang, unreadable output).
    pub fn clean(&self) -> bool {
        self.blade
            .stations
            .iter()
            .all(|s| s.fit.as_ref().is_some_and(|f| f.unfit.is_empty()) && s.polars.iter().all(|p| p.faults.is_empty()))
    }

    /// Nothing to report for a model whose section model is the tables themselves (`tables`),
    /// as [`Polars::clean`] for QPROP's law fitted to them: with tables, a station's fit is
    /// only the exported QPROP file's (its fallbacks are notes about that file, its fidelity
    /// measured), and an XFOIL fault that the tables interpolate across is a note; a problem is
    /// a station without a polar, which the tables cannot cover.
    pub(crate) fn clean_for(&self, tables: bool) -> bool {
        if !tables {
            return self.clean();
        }
        self.blade.stations.iter().all(|s| !s.polars.is_empty())
    }
}

/// Runs the polars stage: XFOIL on the rungs of the Re ladder covering every station's Re and
/// Mach over the spec's operating points, each station reduced to QPROP's coefficients.
pub fn polars(spec: &PolarsSpec, input: &PolarsInput, engine: &PolarEngine, progress: &Progress<'_>) -> Result<Polars> {
    let (fluid, _) = spec.air.fluid()?;
    let tip = input.geometry.file.tip_radius(propbet_qprop::RadiusReading::Documented);
    let points = grid(&spec.omegas, &spec.axis, tip)?;
    if points.is_empty() {
        nothing!("--rpm / --j / --v: no operating point for the polars to cover");
    }
    if let Some(p) = points.iter().find(|p| p.omega <= 0.0) {
        out_of_range!(
            "--rpm: {} must be positive",
            propbet_settings::values::rpm_text(p.omega)
        );
    }
    if let Some(p) = points.iter().find(|p| p.v < 0.0) {
        out_of_range!("--v / --j: {} m/s; the polars cover propeller states, V >= 0", p.v);
    }
    spec.xfoil.check()?;
    let ncrit_effect = propbet_settings::check_ncrit_effect(&spec.ncrit_effect, spec.xfoil.section.ncrit)?;
    let blade = input.geometry.file.to_blade(propbet_qprop::RadiusReading::Documented);
    let settings = XfoilSettings {
        section: spec.xfoil.section(BLADE_PANELS),
        ncrit_effect,
    };
    let job = BladeJob {
        blade: &blade,
        geometry: spec.geometry.display().to_string(),
        foils: &input.foils,
        points: &points,
        fluid,
        settings: &settings,
    };
    let b = compute_blade(&job, engine, progress).map_err(|e| Error::input(&spec.geometry, e))?;
    let mut file = input.geometry.file.clone();
    for (i, s) in b.stations.iter().enumerate() {
        if let Some(f) = &s.fit {
            file.set_station_coeffs(i, &f.coeffs);
        }
    }
    file.name = format!(
        "{} / {} polars for {:.0}-{:.0} rpm, {:.1}-{:.1} m/s",
        file.name, input.foil_name, b.rpm[0], b.rpm[1], b.v[0], b.v[1]
    );
    let prop = as_written(&file, &spec.out_prop)?;
    let export = ExportCheck::new(&prop.file, &b, &fluid, &points)?;
    let cache_warning = engine.cache_error().map(|e| {
        format!("{e}: the cache could not store the polars XFOIL computed; they were used, and the next run computes them again")
    });
    Ok(Polars {
        prop,
        blade: b,
        export,
        cache_warning,
    })
}

/// A model whose prop file is a blade file other than QPROP's: the blade's polars computed over
/// the operating points `omegas` x `axis` (the polars stage with its defaults, in memory), and
/// the model with them as its section tables, as `propbet run` models such a blade. None for a
/// QPROP prop file (read as it is, by [`Model::load`]).
pub fn design_model(
    spec: &propbet_settings::spec::ModelSpec,
    omegas: Vec<f64>,
    axis: propbet_settings::spec::SweepAxis,
    keep_stations: bool,
    progress: &propbet_polar::Progress<'_>,
) -> Result<Option<(propbet_model::Model, Polars)>> {
    let Some(design) = &spec.design else {
        return Ok(None);
    };
    if spec.polars.is_some() {
        return Err(Error::Conflict(format!(
            "--polars: {} is a blade file without sections' coefficients; its polars are computed (leave out --polars)",
            spec.prop.display()
        )));
    }
    let pspec = propbet_settings::spec::PolarsSpec {
        geometry: spec.prop.clone(),
        units: spec.units,
        airfoil: design.airfoil.clone(),
        thickness: None,
        station_airfoils: None,
        sections_from: design.sections_from.clone(),
        airfoils: design.airfoils.clone(),
        omegas,
        axis,
        air: propbet_settings::spec::AirSpec::default(),
        xfoil: propbet_settings::spec::XfoilSpec {
            process: design.process.clone(),
            section: xfoil_runner::SectionSettings {
                ncrit: propbet_settings::NCRIT.default,
                trip: propbet_settings::default_trip(),
                ..xfoil_runner::SectionSettings::new(propbet_settings::values::parse_list(
                    "--alpha",
                    propbet_settings::ALPHA.default,
                )?)
            },
        },
        ncrit_effect: Vec::new(),
        out_prop: spec.prop.with_extension("polars.qprop"),
        out_polars: None,
    };
    let input = polars_input(&pspec)?;
    let engine = polar_engine(&design.process)?;
    let polars = polars(&pspec, &input, &engine, progress)?;
    let mspec = propbet_settings::spec::ModelSpec {
        units: None,
        polars: Some(spec.prop.with_extension("polars.json")),
        ..spec.clone()
    };
    let model = propbet_model::Model::from_parts(&mspec, polars.prop.clone(), Some(&polars.blade), keep_stations)?;
    Ok(Some((model, polars)))
}
