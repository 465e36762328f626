//! Propellers side by side on one motor and battery: each at the same hover thrust (its
//! throttle, currents, g/W and endurance) and at full throttle over airspeed (thrust, current,
//! overall efficiency), ranked by g/W at hover.

use propbet_bemt::{Fluid, PointResult};
use propbet_motor::{Drive, Motor, Powered, Supply, SupplyPoint};

use crate::stages::{powered, PoweredPoint};
use crate::Result;
use propbet_model::Model;

/// One propeller's operating point on the powertrain: the motor's side, the propeller's, the
/// battery's; or why there is none.
pub(crate) type SidePoint = std::result::Result<(Powered, PointResult, SupplyPoint), String>;

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
    /// The g/W at hover at the ends of the prediction's uncertainty band (low, high).
    pub hover_band: Option<(f64, f64)>,
    /// At full throttle, at each airspeed of `full`, the range of thrust, battery current and
    /// overall efficiency over the band's ends (None where the point or an end has no
    /// operating point).
    pub full_band: Vec<Option<FullRange>>,
}

/// The range of a full-throttle point over the prediction's uncertainty band: the propeller's
/// thrust and torque scaled by its band's ends of CT and CP at that point (low CT with high CP,
/// high CT with low CP), and the motor's and battery's operating point found again for each,
/// so that a propeller that takes more torque also turns slower and draws more current.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullRange {
    /// Thrust [N], lowest and highest.
    pub thrust: (f64, f64),
    /// Battery current [A].
    pub battery_amps: (f64, f64),
    /// Overall efficiency, thrust power over battery power [-].
    pub efficiency: (f64, f64),
}

/// Thrust power over the battery's power (0 where the battery gives nothing).
pub fn overall_efficiency(thrust: f64, v: f64, battery_power: f64) -> f64 {
    if battery_power > 0.0 {
        thrust * v / battery_power
    } else {
        0.0
    }
}

/// The full-throttle points' ranges over the band (see [`FullRange`]).
fn full_band(
    model: &Model,
    fluid: &Fluid,
    motor: &Motor,
    supply: &Supply,
    full: &[PoweredPoint],
) -> Result<Vec<Option<FullRange>>> {
    let bands = super::powered::powered_band(model, fluid, full)?;
    let ceiling = crate::stages::omega_ceiling(model, fluid);
    let mut out = vec![None; full.len()];
    for (i, (p, b)) in full.iter().zip(bands).enumerate() {
        let (Ok((_, r)), Some(b)) = (&p.outcome, b) else {
            continue;
        };
        let (Some(ct), Some(cp)) = (r.ct, r.cp) else { continue };
        let mut ends = Vec::new();
        for (kt, kq) in [(b.ct.lo / ct, b.cp.hi / cp), (b.ct.hi / ct, b.cp.lo / cp)] {
            let mut loads = |omega: f64| -> Result<propbet_motor::PropLoads> {
                let at = super::powered::solve_at(model, fluid, p.v, omega)?;
                Ok(propbet_motor::PropLoads {
                    thrust: kt * at.thrust,
                    torque: kq * at.torque,
                })
            };
            let m = match propbet_motor::operate(motor, supply.drive(1.0), ceiling, &mut loads) {
                Ok(m) => m,
                Err(propbet_motor::OperateError::Prop(e)) => return Err(e),
                Err(_) => break,
            };
            let Ok(s) = supply.at(m.volts, m.amps) else { break };
            ends.push((
                m.loads.thrust,
                s.battery_amps,
                overall_efficiency(m.loads.thrust, p.v, s.battery_power),
            ));
        }
        if let [a, b] = ends[..] {
            let span = |x: f64, y: f64| (x.min(y), x.max(y));
            out[i] = Some(FullRange {
                thrust: span(a.0, b.0),
                battery_amps: span(a.1, b.1),
                efficiency: span(a.2, b.2),
            });
        }
    }
    Ok(out)
}

impl SideProp {
    /// Grams per watt (of the battery's power) at hover, when it can hover.
    pub fn hover_g_per_w(&self) -> Option<f64> {
        let (p, _, s) = self.hover.as_ref().ok()?;
        (s.battery_power > 0.0).then(|| p.loads.thrust / propbet_units::STANDARD_GRAVITY * 1000.0 / s.battery_power)
    }
}

/// The hover g/W at the band's ends. At a fixed thrust the shaft power goes as CP / CT^1.5
/// (n = sqrt(T / (CT rho D^4)), P = CP rho n^3 D^5); the motor's efficiency is held, and the
/// corners taken apart (low CT with high CP, high CT with low CP): a conservative range.
fn hover_band(model: &Model, fluid: &Fluid, prop: &SideProp) -> Result<Option<(f64, f64)>> {
    let (Ok((m, r, _)), Some(gpw)) = (&prop.hover, prop.hover_g_per_w()) else {
        return Ok(None);
    };
    let point = propbet_bemt::OperatingPoint { v: 0.0, omega: m.omega };
    let band =
        propbet_model::band::BandSpec::for_model(model).at_points(model, fluid, &[point], std::slice::from_ref(r))?;
    let (Some(b), Some(ct), Some(cp)) = (band.first(), r.ct, r.cp) else {
        return Ok(None);
    };
    let merit = |ct_end: f64, cp_end: f64| (ct_end / ct).powf(1.5) * (cp / cp_end);
    let ends = (gpw * merit(b.ct.lo, b.cp.hi), gpw * merit(b.ct.hi, b.cp.lo));
    Ok((ends.0.is_finite() && ends.1.is_finite() && ends.0 > 0.0).then_some(ends))
}

fn side_point(p: &PoweredPoint) -> SidePoint {
    if let Some(why) = p.problem() {
        return Err(why.to_string());
    }
    match (&p.outcome, &p.supply) {
        (Ok((m, r)), Some(Ok(s))) => Ok((*m, r.clone(), *s)),
        _ => Err("no battery".into()),
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
        let mut prop = SideProp {
            name: name.clone(),
            diameter: model.diameter,
            hover: side_point(&hover[0]),
            full: full.iter().map(|p| (p.v, side_point(p))).collect(),
            hover_band: None,
            full_band: full_band(model, fluid, motor, supply, &full)?,
        };
        prop.hover_band = hover_band(model, fluid, &prop)?;
        out.push(prop);
    }
    out.sort_by(|a, b| match (a.hover_g_per_w(), b.hover_g_per_w()) {
        (Some(x), Some(y)) => y.total_cmp(&x),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => std::cmp::Ordering::Equal,
    });
    Ok(out)
}
