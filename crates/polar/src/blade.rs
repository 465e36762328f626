//! Polars of a whole blade: one set per input station, at the Reynolds and Mach numbers that
//! station sees at an operating point, with the QPROP fit of each. Written by `propbet polars`
//! as JSON and read back by `propbet predict --polars` for the tabulated section model.

use std::sync::Arc;

use propbet_bemt::SectionAero;
use serde::{Deserialize, Serialize};

use crate::reduce::QpropFit;
use crate::table::Polar;
use crate::tabulated::TabulatedAero;

/// Section models placed at radii [m], ascending.
pub type StationModels = (Vec<f64>, Vec<Arc<dyn SectionAero>>);

/// Format tag of the JSON file.
pub const FORMAT: &str = "propbet-blade-polars-1";

/// Polars of every input station of a blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BladePolars {
    /// Always [`FORMAT`].
    pub format: String,
    /// Where the geometry came from.
    pub geometry: String,
    /// The section used (name).
    pub airfoil: String,
    /// Operating point the Reynolds numbers were taken at: rotation speed [rpm].
    pub rpm: f64,
    /// Operating point: axial speed [m/s].
    pub v: f64,
    /// Air density [kg/m^3], viscosity [Pa s], speed of sound [m/s] used.
    pub air: [f64; 3],
    /// The stations, ascending in radius.
    pub stations: Vec<StationPolars>,
}

/// One input station.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationPolars {
    /// Radius [m].
    pub r: f64,
    /// Chord [m].
    pub chord: f64,
    /// Reynolds number at the operating point [-].
    pub re: f64,
    /// Mach number at the operating point [-].
    pub mach: f64,
    /// Angle of attack at the operating point [deg].
    pub alpha_deg: f64,
    /// Polars computed (the station's Re and its neighbours).
    pub polars: Vec<Polar>,
    /// QPROP fit, when the polars allowed one.
    pub fit: Option<QpropFit>,
    /// What went wrong at this station, if anything.
    pub problem: Option<String>,
}

impl BladePolars {
    /// Reads and checks the JSON text.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let b: BladePolars = serde_json::from_str(text).map_err(|e| format!("not a blade-polars file: {e}"))?;
        if b.format != FORMAT {
            return Err(format!("format {:?}, expected {FORMAT:?}", b.format));
        }
        if b.stations.windows(2).any(|w| w[1].r <= w[0].r) {
            return Err("station radii are not ascending".into());
        }
        Ok(b)
    }

    /// Tabulated section models at the stations that have polars: their radii and models.
    pub fn models(&self) -> Result<StationModels, String> {
        let mut r = Vec::new();
        let mut m: Vec<Arc<dyn SectionAero>> = Vec::new();
        for s in &self.stations {
            if let Some(t) = TabulatedAero::new(&s.polars) {
                r.push(s.r);
                m.push(Arc::new(t));
            }
        }
        if m.is_empty() {
            return Err("no station has a usable polar".into());
        }
        Ok((r, m))
    }
}
