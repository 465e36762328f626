//! Airfoils and their polars for propbet.
//!
//! * [`airfoil`]: coordinate files (Selig, Lednicer), checks, NACA 4-digit, thickness scaling,
//!   blending, repaneling.
//! * [`table`]: polars (XFOIL points at one Re, Mach, Ncrit) and their interpolation.
//! * [`reduce`]: reduction of polars to QPROP's ten coefficients, weighted by the angles the
//!   blade sees, with residuals and a verdict on whether the parametric law fits.
//! * [`tabulated`]: a section model that interpolates the polars themselves, with a post-stall
//!   extension to +-90 deg, usable by the solver instead of the parametric one.
//! * [`compute`]: polars from XFOIL, in parallel, through a content-addressed cache.
//! * [`blade`]: the polars of every station of a blade (`propbet polars`), as JSON.
#![deny(missing_docs)]

pub mod airfoil;
pub mod compute;
pub mod engine;
pub mod neural;
pub mod reduce;
pub mod table;
pub mod tabulated;

pub use airfoil::{naca4, naca4_from_name, Airfoil, AirfoilError, NacaStyle};
pub use compute::{no_progress, Engine, PolarCache, PolarEngine, PolarError, PolarJob, Progress, Source};
pub use reduce::{fit_qprop, AlphaWeights, FitError, QpropFit, DEFAULT_RE_EXP};
pub use table::{Filled, Makers, Polar, PolarPoint};
pub use tabulated::TabulatedAero;
pub use xfoil_runner::SectionSettings;
pub mod blade;
pub use blade::{BladePolars, StationPolars};
