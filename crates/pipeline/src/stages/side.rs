//! Propellers side by side on one motor and battery: each at the same hover thrust (its
//! throttle, currents, g/W and endurance) and at full throttle over airspeed (thrust, current,
//! overall efficiency), ranked by g/W at hover.

use propbet_bemt::{Fluid, PointResult};
use propbet_motor::{Drive, Motor, Powered, Supply, SupplyPoint};

use crate::model::Model;
use crate::stages::{powered, PoweredPoint};
use crate::Result;

/// One propeller's operating point on the powertrain: the motor's side, the propeller's, the
/// battery's; or why there is none.
pub type SidePoint = std::result::Result<(Powered, PointResult, SupplyPoint), String>;

/// One propeller's answers.
#[derive(Debug, Clone)]
pub struct SideProp {
    /// Its name (the file's).
    pub name: String,
    /// Diameter [m].
    pub diameter: f64,
    /// At the hover thrust, static.
    pub hover: SidePoint,
    /// At full throttle, at each airspeed (the first static).
    pub full: Vec<(f64, SidePoint)>,
}

impl SideProp {
    /// Grams per watt (of the battery's power) at hover, when it can hover.
    pub fn hover_g_per_w(&self) -> Option<f64> {
        let (p, _, s) = self.hover.as_ref().ok()?;
        (s.battery_power > 0.0).then(|| p.loads.thrust / propbet_units::STANDARD_GRAVITY * 1000.0 / s.battery_power)
    }
}

fn side_point(p: &PoweredPoint) -> SidePoint {
    match (&p.outcome, &p.supply) {
        (Ok((m, r)), Some(Ok(s))) => Ok((*m, r.clone(), *s)),
        (Err(why), _) | (Ok(_), Some(Err(why))) => Err(why.clone()),
        (Ok(_), None) => Err("no battery".into()),
    }
}

/// Each of `props` (name, model) on `motor` and `supply`: hover at `hover_thrust` [N] and full
/// throttle at `speeds` [m/s]; ranked by g/W at hover (those that cannot hover last, in the
/// given order).
pub fn side_by_side(
    props: &[(String, Model)],
    fluid: &Fluid,
    motor: &Motor,
    supply: &Supply,
    hover_thrust: f64,
    speeds: &[f64],
) -> Result<Vec<SideProp>> {
    let mut out = Vec::new();
    for (name, model) in props {
        let hover = powered(
            model,
            fluid,
            motor,
            Some(supply),
            &[Drive::Thrust(hover_thrust)],
            &[0.0],
        )?;
        let full = powered(model, fluid, motor, Some(supply), &[supply.drive(1.0)], speeds)?;
        out.push(SideProp {
            name: name.clone(),
            diameter: model.diameter,
            hover: side_point(&hover[0]),
            full: full.iter().map(|p| (p.v, side_point(p))).collect(),
        });
    }
    out.sort_by(|a, b| match (a.hover_g_per_w(), b.hover_g_per_w()) {
        (Some(x), Some(y)) => y.total_cmp(&x),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => std::cmp::Ordering::Equal,
    });
    Ok(out)
}
