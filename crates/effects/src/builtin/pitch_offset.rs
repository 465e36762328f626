//! `pitch-offset`: every blade angle off by the same amount.

use super::*;

/// `pitch-offset`: every blade angle off by the same amount.
#[derive(Debug)]
pub(super) struct PitchOffset(About);

impl PitchOffset {
    pub(super) fn new() -> Self {
        Self(About {
            id: "pitch-offset",
            params: vec![Param::new(
                "deg",
                "deg",
                0.0,
                (-3.0, 3.0),
                0.3,
                "added to every blade angle (physical bounds: +-3 deg, a scan's or a mould's error)",
            )
            .expecting(-2.0, 2.0)],
            hooks: &[Hook::Geometry],
            explanation: "Every blade angle is off by the same amount: a scan aligned to the wrong plane, a \
                 hub that seats the blades at another angle, a mould that differs from the design; or \
                 every section's zero-lift angle is off by as much (a section of other camber than the \
                 polars', XFOIL's lift at small angles and low Re), which acts the same way.",
        })
    }
}

impl Effect for PitchOffset {
    about!();

    fn geometry(&self, p: &[f64], _point: &PointState, g: &mut StationGeom) {
        g.beta += p[0].to_radians();
    }
}
