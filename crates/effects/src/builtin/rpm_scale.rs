//! `rpm-scale`: the true RPM over the logged one.

use super::*;

/// `rpm-scale`: the true RPM over the logged one.
#[derive(Debug)]
pub(super) struct RpmScale(About);

impl RpmScale {
    pub(super) fn new() -> Self {
        Self(About {
            id: "rpm-scale",
            params: vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.85, 1.2),
                0.02,
                "true RPM / logged RPM (a wrong pole count: poles used / true poles; physical bounds 0.85-1.2 hold 12/14 and 14/12)",
            )
            .known(
                Evidence::OpticalRpm,
                OPTICAL_RPM_SCALE,
                "an optical RPM sensor: no pole count to get wrong",
            )],
            hooks: &[Hook::Measurement],
            explanation: "The RPM sensor is off by a constant factor: an electrical-RPM reading divided by the wrong \
             pole count, a reflective tape counted twice. Thrust and torque errors go as factor^2 at \
             every point.",
        })
    }
}

impl Effect for RpmScale {
    about!();

    fn measurement(&self, p: &[f64], point: &mut PointState) {
        point.omega *= p[0];
    }
}
