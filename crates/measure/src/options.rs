//! How a measured file is read.

use crate::reduce::ReduceOptions;
use crate::set::RpmSource;

/// Options of [`crate::read`].
#[derive(Debug, Clone, Default)]
pub struct ReadOptions {
    /// File name (UIUC sweeps carry their RPM in it).
    pub name: Option<String>,
    /// Motor poles: electrical RPM readings are multiplied by 2/poles.
    pub poles: Option<u32>,
    /// Which RPM column of a thrust-stand log to use (default: optical when it reads).
    pub rpm_source: Option<RpmSource>,
    /// Column map for generic CSV (TOML text).
    pub column_map: Option<String>,
    /// Reduction settings.
    pub reduce: ReduceOptions,
}
