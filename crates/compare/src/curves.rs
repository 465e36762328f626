//! The model's curves beside the measurements: predicted coefficients against J at each RPM
//! group's mean speed, and static loads against RPM, solved at each group's air. Errors of the
//! model (a user formula that fails) are returned, never replaced by empty curves.

use propbet_effects::EffectError;

use crate::metrics::{group_points, sweep_group};
use crate::{predict, ComparedPoint, Quantities, Setup};

/// Points per curve.
const SAMPLES: usize = 40;

/// A predicted curve: (x, predicted quantities) pairs.
pub type Curve = Vec<(f64, Quantities)>;

/// Predicted curves for the comparison's figures.
#[derive(Debug, Clone, Default)]
pub struct Curves {
    /// Per sweep, in the order of [`group_points`] by [`sweep_group`]: the group's mean speed
    /// [rpm, a label] and (J, predicted quantities) from 0 to 1.08 of its largest J; None for a
    /// group of static points only.
    pub j_sweeps: Vec<Option<(f64, Curve)>>,
    /// Static: (speed [rpm], predicted quantities) from 0.9 of the slowest to 1.1 of the fastest
    /// static point; None without static points.
    pub statics: Option<Curve>,
}

fn mean(xs: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n.max(1) as f64
}

/// The curves of `setup` for `points`.
pub fn curves(setup: &Setup, points: &[ComparedPoint]) -> Result<Curves, EffectError> {
    let mut j_sweeps = Vec::new();
    for (_, pts) in group_points(points, sweep_group) {
        if pts.iter().all(|p| p.is_static()) {
            j_sweeps.push(None);
            continue;
        }
        let rpm = mean(pts.iter().map(|p| p.rpm));
        let fluid = pts[0].air.fluid;
        let jmax = pts.iter().map(|p| p.j).fold(0.0, f64::max) * 1.08;
        let omega = propbet_units::rpm_to_omega(rpm);
        let n = propbet_units::omega_to_rev_per_s(omega);
        let curve = (0..=SAMPLES)
            .map(|i| {
                let j = jmax * i as f64 / SAMPLES as f64;
                Ok((j, predict(setup, omega, j * n * setup.diameter, &fluid)?.0))
            })
            .collect::<Result<_, EffectError>>()?;
        j_sweeps.push(Some((rpm, curve)));
    }
    let stat: Vec<&ComparedPoint> = points.iter().filter(|p| p.is_static()).collect();
    let statics = if stat.is_empty() {
        None
    } else {
        let (lo, hi) = stat
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.rpm), b.max(p.rpm)));
        let fluid = stat[0].air.fluid;
        Some(
            (0..=SAMPLES)
                .map(|i| {
                    let rpm = (0.9 * lo) + (1.1 * hi - 0.9 * lo) * i as f64 / SAMPLES as f64;
                    Ok((rpm, predict(setup, propbet_units::rpm_to_omega(rpm), 0.0, &fluid)?.0))
                })
                .collect::<Result<_, EffectError>>()?,
        )
    };
    Ok(Curves { j_sweeps, statics })
}

/// Another prediction to draw and score beside propbet's (APC's PER3 tables, a QPROP run):
/// (CT, CP) at (rpm, J), None where it has no value.
pub type Reference<'a> = &'a dyn Fn(f64, f64) -> Option<(f64, f64)>;

/// The compared points with `reference`'s prediction in place of the model's (all quantities
/// None where the reference has no value), to be scored by [`crate::metrics::metrics`] on the
/// same points, window and measure as the model.
pub fn with_reference(points: &[ComparedPoint], reference: Reference<'_>, diameter: f64) -> Vec<ComparedPoint> {
    points
        .iter()
        .map(|p| {
            let omega = propbet_units::rpm_to_omega(p.rpm);
            let predicted = match reference(p.rpm, p.j) {
                Some((ct, cp)) => {
                    let s =
                        propbet_units::Scales::new(p.air.fluid.rho, propbet_units::omega_to_rev_per_s(omega), diameter);
                    Quantities::from_forces(
                        ct * s.thrust,
                        Some(cp * s.power / omega),
                        omega,
                        p.v,
                        p.air.fluid.rho,
                        diameter,
                    )
                }
                None => Quantities::default(),
            };
            ComparedPoint { predicted, ..p.clone() }
        })
        .collect()
}

/// A reference's curves on the model's abscissae: (J, quantities) at each sweep's speed and
/// (rpm, quantities) static at `rho_static`, None where the reference has no value.
pub fn reference_curves(curves: &Curves, reference: Reference<'_>, diameter: f64, rho_static: f64) -> Curves {
    let at = |rpm: f64, j: f64, rho: f64| {
        let (ct, cp) = reference(rpm, j)?;
        let omega = propbet_units::rpm_to_omega(rpm);
        let n = propbet_units::omega_to_rev_per_s(omega);
        let s = propbet_units::Scales::new(rho, n, diameter);
        Some(Quantities::from_forces(
            ct * s.thrust,
            Some(cp * s.power / omega),
            omega,
            j * n * diameter,
            rho,
            diameter,
        ))
    };
    Curves {
        j_sweeps: curves
            .j_sweeps
            .iter()
            .map(|s| {
                s.as_ref().map(|(rpm, c)| {
                    (
                        *rpm,
                        c.iter()
                            .filter_map(|(j, _)| Some((*j, at(*rpm, *j, rho_static)?)))
                            .collect(),
                    )
                })
            })
            .collect(),
        statics: curves.statics.as_ref().map(|c| {
            c.iter()
                .filter_map(|(r, _)| Some((*r, at(*r, 0.0, rho_static)?)))
                .collect()
        }),
    }
}
