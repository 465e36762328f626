//! Measured files as `compare` reads them, as two tables: the points and the rows dropped.

use propbet_settings::spec::MeasuredSpec;

use crate::CommandResult as Result;

/// Measured files read as `compare` reads them (each file on its own, a refused one in the
/// dropped table): a table of the points (CSV, one row per point, every file's in order) and
/// one of the rows dropped (CSV).
pub fn tables(spec: &MeasuredSpec) -> Result<(Vec<u8>, Vec<u8>)> {
    let batch = propbet_pipeline::stages::load_batch(spec)?;
    Ok((
        propbet_report::table::measured::points(&batch.names, &batch.sets)?,
        propbet_report::table::measured::dropped(&batch.names, &batch.sets, &batch.refused)?,
    ))
}
