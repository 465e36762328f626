//! `propbet predict`'s tables, in memory: the sweep (CSV or JSON, with the band when asked)
//! and the per-station table, solved in parallel over a loaded model.

use crate::CommandResult as Result;
use propbet_bemt::PointResult;
use propbet_model::band::BandSpec;
use propbet_model::Model;
use propbet_report::table::columns::Table;
use propbet_report::table::sweep;
use propbet_settings::spec::{PredictSpec, TableFormat};

/// A prediction's tables as `propbet predict` writes them.
pub struct Tables {
    /// The sweep table (CSV or JSON, as the spec asks), in pieces written one after another.
    pub body: Vec<Vec<u8>>,
    /// The per-station table (CSV), when asked for.
    pub stations: Option<Vec<u8>>,
    /// Station solutions that did not converge, and at how many points.
    pub failed: (usize, usize),
}

/// A prediction's tables as columns (the Python package): the sweep table's (with the band's
/// when the spec asks) and, when `stations`, the per-station table's; the same columns as the
/// CSV files, the numbers unrounded. The spec's format and output files are not used.
pub fn columns(spec: &PredictSpec, model: &Model, stations: bool) -> Result<(Table, Option<Table>, (usize, usize))> {
    let (fluid, source) = spec.air.fluid()?;
    let points = propbet_model::solve::operating_points(spec, model.rotor.tip_radius)?;
    let results = propbet_model::solve::sweep(model, &fluid, &points)?;
    let (rho, tip) = (fluid.rho, model.rotor.tip_radius);
    let sweep = if spec.band {
        let band = BandSpec::for_model(model).at_points(model, &fluid, &points, &results)?;
        propbet_report::table::columns::table(sweep::with_band(&results, &band, rho, &source, tip))?
    } else {
        propbet_report::table::columns::table(results.iter().map(|p| sweep::sweep_row(p, rho, &source, tip)))?
    };
    let per_station = stations.then(|| sweep::stations_table(&results)).transpose()?;
    let failed = results.iter().map(|p| p.not_converged).sum();
    let failed_points = results.iter().filter(|p| p.not_converged > 0).count();
    Ok((sweep, per_station, (failed, failed_points)))
}

/// A prediction's tables, in memory: the sweep table as the spec's format says, and the
/// per-station table when `stations`.
pub fn tables(spec: &PredictSpec, model: &Model, stations: bool) -> Result<Tables> {
    let (fluid, fluid_source) = spec.air.fluid()?;
    let points = propbet_model::solve::operating_points(spec, model.rotor.tip_radius)?;
    // Solve and format chunk by chunk in the same parallel task, so the table is written
    // while the data is still in cache; the results themselves are kept only when the output
    // needs them (JSON, the band, the station table).
    let streamed = spec.format == TableFormat::Csv && !spec.band;
    let keep_results = !streamed || stations;
    struct Chunk {
        results: Vec<PointResult>,
        text: Vec<u8>,
        failed: usize,
        failed_points: usize,
    }
    let chunks: Vec<Chunk> = {
        use rayon::prelude::*;
        points
            .par_chunks(propbet_model::solve::CHUNK)
            .enumerate()
            .map(|(k, c)| {
                let r = propbet_model::solve::solve(model, &fluid, c)?;
                Ok(Chunk {
                    text: if streamed {
                        sweep::rows(&r, k == 0, fluid.rho, &fluid_source, model.rotor.tip_radius)
                    } else {
                        Vec::new()
                    },
                    failed: r.iter().map(|p| p.not_converged).sum(),
                    failed_points: r.iter().filter(|p| p.not_converged > 0).count(),
                    results: if keep_results { r } else { Vec::new() },
                })
            })
            .collect::<Result<_>>()?
    };
    let mut results = Vec::with_capacity(if keep_results { points.len() } else { 0 });
    let mut body = Vec::new();
    let (mut failed, mut failed_points) = (0, 0);
    for c in chunks {
        failed += c.failed;
        failed_points += c.failed_points;
        results.extend(c.results);
        body.push(c.text);
    }
    if !streamed {
        // The band needs every point's base solve: written after the whole sweep.
        let band = spec
            .band
            .then(|| BandSpec::for_model(model).at_points(model, &fluid, &points, &results))
            .transpose()?;
        body = vec![match spec.format {
            TableFormat::Csv => sweep::band_rows(
                &results,
                band.as_deref().unwrap_or(&[]),
                fluid.rho,
                &fluid_source,
                model.rotor.tip_radius,
            )?,
            TableFormat::Json => sweep::json_doc(spec, model, &fluid, &fluid_source, &results, band.as_deref())?,
        }];
    }
    Ok(Tables {
        body,
        stations: stations.then(|| sweep::stations_csv(&results)).transpose()?,
        failed: (failed, failed_points),
    })
}

/// A sweep's summary table (CSV; the run's predict stage), with the uncertainty band's
/// columns when the spec asks for them.
pub fn sweep_table(spec: &PredictSpec, model: &Model, points: &[PointResult]) -> Result<Vec<u8>> {
    let (fluid, source) = spec.air.fluid()?;
    Ok(if spec.band {
        let ops = propbet_model::solve::operating_points(spec, model.rotor.tip_radius)?;
        let band = BandSpec::for_model(model).at_points(model, &fluid, &ops, points)?;
        sweep::band_rows(points, &band, fluid.rho, &source, model.rotor.tip_radius)?
    } else {
        sweep::rows(points, true, fluid.rho, &source, model.rotor.tip_radius)
    })
}
