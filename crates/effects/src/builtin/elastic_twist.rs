//! `elastic-twist`: the blade's untwist under load, growing with RPM^2 and r/R.

use super::*;

/// Reference RPM of `elastic-twist`'s parameter.
const ELASTIC_REF_RPM: f64 = 10_000.0;

/// `elastic-twist`: the blade's untwist under load, growing with RPM^2 and r/R.
#[derive(Debug)]
pub(super) struct ElasticTwist(About);

impl ElasticTwist {
    pub(super) fn new() -> Self {
        Self(About {
            id: "elastic-twist",
            params: vec![Param::new(
                "k",
                "deg",
                0.0,
                (0.0, 5.0),
                0.5,
                "untwist at the tip at 10,000 rpm (physical bounds: 0-5 deg: a plastic blade's at most; the propeller moment and a cambered section's nose-down moment both flatten it, so a pitch rising with RPM is left to the Reynolds-number effects); -k (rpm/10^4)^2 r/R is added to the blade angle",
            ).expecting(0.0, 2.0)],
            hooks: &[Hook::Geometry],
            explanation: "Thin plastic blades twist under centrifugal and aerodynamic load (the propeller moment \
             flattens them): the pitch falls with RPM^2, most at the tip. Thrust falls short at high RPM.",
        })
    }
}

impl Effect for ElasticTwist {
    about!();

    fn geometry(&self, p: &[f64], point: &PointState, g: &mut StationGeom) {
        let s = point.rpm() / ELASTIC_REF_RPM;
        g.beta -= (p[0] * s * s * g.x).to_radians();
    }
}
