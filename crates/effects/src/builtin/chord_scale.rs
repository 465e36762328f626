//! `chord-scale`: every chord times a factor.

use super::*;

/// `chord-scale`: every chord times a factor.
#[derive(Debug)]
pub(super) struct ChordScale(About);

impl ChordScale {
    pub(super) fn new() -> Self {
        Self(About {
            id: "chord-scale",
            params: vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.85, 1.15),
                0.05,
                "multiplies every chord (physical bounds: +-15 %, a scan's scale or a production run)",
            )
            .expecting(0.93, 1.07)],
            hooks: &[Hook::Geometry],
            explanation: "The blades are wider or narrower than the geometry says (scan scale, a different \
                 production run): thrust and torque change nearly in proportion, less at high load.",
        })
    }
}

impl Effect for ChordScale {
    about!();

    fn geometry(&self, p: &[f64], _point: &PointState, g: &mut StationGeom) {
        g.chord *= p[0];
    }
}
