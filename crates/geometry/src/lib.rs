//! Propeller geometry from scans.
//!
//! - [`mesh`]: triangle meshes, STL read (ASCII and binary) and binary write.
//! - [`align`]: the propeller frame from a mesh (rotation axis from the surface inertia tensor,
//!   hub centre, blade axis, thrust direction).
//! - [`section`]: cylindrical sections (r = const) of a mesh, split by blade; chord and blade
//!   angle on the unrolled cylinder.
//! - [`synth`]: blade definition → mesh (NACA 4-digit sections stacked on a pitch axis).
//!
//! **Propeller frame**: rotation axis z, thrust towards +z, blade 0 along +x, blades turning
//! towards +theta; the leading edge is at +theta and higher z. Millimetres inside this crate's
//! mesh types unless said otherwise (scans come in mm); results in SI.
#![deny(missing_docs)]

pub mod align;
pub mod boxfit;
pub mod cloud;
pub mod fit;
pub mod mesh;
pub mod scan;
pub mod section;
pub mod synth;

pub use mesh::{Mesh, MeshError};
