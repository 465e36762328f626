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
