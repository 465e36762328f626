//! `density`: the true air density over the assumed one.

use super::*;

/// `density`: the true air density over the assumed one.
#[derive(Debug)]
pub(super) struct Density(About);

impl Density {
    pub(super) fn new() -> Self {
        Self(About {
            id: "density",
            params: vec![Param::new(
                "ratio",
                "-",
                1.0,
                (0.75, 1.2),
                0.02,
                "true density / assumed density (physical bounds: 0.75-1.2, 2,500 m at 40 C to sea level at -30 C against ISA)",
            )
            .expecting(0.9, 1.1)
            .known(
                Evidence::LabAir,
                LAB_DENSITY_RATIO,
                "coefficients the lab reduced with the density it measured",
            )],
            hooks: &[Hook::Measurement],
            explanation: "The air was not what the model assumed (temperature, altitude, humidity): thrust and \
             torque scale together at every point. Where the files log temperature, pressure and \
             humidity the comparison already uses them; the ratio is what remains. Coefficients a \
             lab reduced with its measured air (UIUC's files) bound it to +-2 % in diagnose.",
        })
    }
}

impl Effect for Density {
    about!();

    fn measurement(&self, p: &[f64], point: &mut PointState) {
        point.fluid.rho *= p[0];
    }
}
