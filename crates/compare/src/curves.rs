//! The model's curves beside the measurements: predicted coefficients against J at each RPM
//! group's mean speed, and static loads against RPM, solved at each group's air. Errors of the
//! model (a user formula that fails) are returned, never replaced by empty curves.

use propbet_effects::EffectError;
use rayon::prelude::*;

use crate::metrics::{group_points, sweep_group};
use crate::{predict, ComparedPoint, Quantities, Setup};

/// Intervals per curve (the figures').
pub const SAMPLES: usize = 40;

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

impl Curves {
    /// Every `every`-th sample of each curve, the ends kept where `every` divides the curves'
    /// intervals: the curves [`sampled`] at that many times fewer intervals, without solving
    /// again.
    pub fn thinned(&self, every: usize) -> Curves {
        let every = every.max(1);
        let thin = |c: &Curve| c.iter().step_by(every).copied().collect::<Curve>();
        Curves {
            j_sweeps: self
                .j_sweeps
                .iter()
                .map(|s| s.as_ref().map(|(rpm, c)| (*rpm, thin(c))))
                .collect(),
            statics: self.statics.as_ref().map(thin),
        }
    }
}

fn mean(xs: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n.max(1) as f64
}

/// The curves of `setup` for `points`.
pub fn curves(setup: &Setup, points: &[ComparedPoint]) -> Result<Curves, EffectError> {
    sampled(setup, points, SAMPLES)
}

/// [`curves`] with `samples` intervals per curve (a band drawn on fewer points than its curve).
pub fn sampled(setup: &Setup, points: &[ComparedPoint], samples: usize) -> Result<Curves, EffectError> {
    let samples = samples.max(1);
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
        let curve = (0..=samples)
            .into_par_iter()
            .map(|i| {
                let j = jmax * i as f64 / samples as f64;
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
            (0..=samples)
                .into_par_iter()
                .map(|i| {
                    let rpm = (0.9 * lo) + (1.1 * hi - 0.9 * lo) * i as f64 / samples as f64;
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

/// `reference`'s quantities at `rpm` and `j` (speed `v` [m/s]) in air of density `rho`, for a
/// propeller of diameter `diameter`: its CT and CP made thrust and torque.
fn reference_at(reference: Reference<'_>, rpm: f64, j: f64, v: f64, rho: f64, diameter: f64) -> Option<Quantities> {
    let (ct, cp) = reference(rpm, j)?;
    let omega = propbet_units::rpm_to_omega(rpm);
    let s = propbet_units::Scales::new(rho, propbet_units::omega_to_rev_per_s(omega), diameter);
    Some(Quantities::from_forces(
        ct * s.thrust,
        Some(cp * s.power / omega),
        omega,
        v,
        rho,
        diameter,
    ))
}

/// The compared points with `reference`'s prediction in place of the model's (all quantities
/// None where the reference has no value), to be scored by [`crate::metrics::metrics`] on the
/// same points, window and measure as the model.
pub fn with_reference(points: &[ComparedPoint], reference: Reference<'_>, diameter: f64) -> Vec<ComparedPoint> {
    points
        .iter()
        .map(|p| ComparedPoint {
            predicted: reference_at(reference, p.rpm, p.j, p.v, p.air.fluid.rho, diameter).unwrap_or_default(),
            ..p.clone()
        })
        .collect()
}

/// A reference's curves on the model's abscissae: (J, quantities) at each sweep's speed and
/// (rpm, quantities) static at `rho_static`, None where the reference has no value.
pub fn reference_curves(curves: &Curves, reference: Reference<'_>, diameter: f64, rho_static: f64) -> Curves {
    let at = |rpm: f64, j: f64, rho: f64| {
        let v = j * propbet_units::rpm_to_rev_per_s(rpm) * diameter;
        reference_at(reference, rpm, j, v, rho, diameter)
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

/// Another code's predictions as a table to interpolate (a QPROP output's summary rows): rows
/// of (rpm, J, CT, CP) grouped by speed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PerformanceTable {
    /// (rpm, rows of (J, CT, CP) ascending in J), ascending in rpm.
    groups: Vec<(f64, Vec<[f64; 3]>)>,
}

impl PerformanceTable {
    /// The table of `rows` (rpm, J, CT, CP); rows within 0.5 % of a speed share its group,
    /// non-finite rows are left out.
    pub fn new(rows: impl IntoIterator<Item = [f64; 4]>) -> PerformanceTable {
        let mut rows: Vec<[f64; 4]> = rows
            .into_iter()
            .filter(|r| r.iter().all(|x| x.is_finite()) && r[0] > 0.0)
            .collect();
        rows.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        let mut groups: Vec<(f64, Vec<[f64; 3]>)> = Vec::new();
        for r in rows {
            match groups.last_mut() {
                Some((rpm, g)) if (r[0] / *rpm - 1.0).abs() <= 0.005 => g.push([r[1], r[2], r[3]]),
                _ => groups.push((r[0], vec![[r[1], r[2], r[3]]])),
            }
        }
        PerformanceTable { groups }
    }

    /// (CT, CP) of one speed's rows at `j`: linear in J inside their range; a single row only
    /// at its own J (within 0.005).
    fn in_group(rows: &[[f64; 3]], j: f64) -> Option<(f64, f64)> {
        if let [r] = rows {
            return ((r[0] - j).abs() <= 0.005).then_some((r[1], r[2]));
        }
        let (first, last) = (rows.first()?, rows.last()?);
        if j < first[0] - 1e-9 || j > last[0] + 1e-9 {
            return None;
        }
        let k = rows.partition_point(|r| r[0] <= j).clamp(1, rows.len() - 1);
        let (a, b) = (rows[k - 1], rows[k]);
        let t = if b[0] > a[0] {
            ((j - a[0]) / (b[0] - a[0])).clamp(0.0, 1.0)
        } else {
            0.0
        };
        Some((a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])))
    }

    /// (CT, CP) at `rpm` and `j`: within a speed's rows, linear in J; between two speeds that
    /// both have a value, linear in rpm; within 2 % of the nearest speed outside them, that
    /// speed's value; None elsewhere.
    pub fn at(&self, rpm: f64, j: f64) -> Option<(f64, f64)> {
        let g = &self.groups;
        let (first, last) = (g.first()?, g.last()?);
        if rpm <= first.0 {
            return ((first.0 / rpm - 1.0) <= 0.02)
                .then(|| Self::in_group(&first.1, j))
                .flatten();
        }
        if rpm >= last.0 {
            return ((rpm / last.0 - 1.0) <= 0.02)
                .then(|| Self::in_group(&last.1, j))
                .flatten();
        }
        let k = g.partition_point(|x| x.0 <= rpm).clamp(1, g.len() - 1);
        let (lo, hi) = (&g[k - 1], &g[k]);
        match (Self::in_group(&lo.1, j), Self::in_group(&hi.1, j)) {
            (Some(p), Some(q)) => {
                let t = (rpm - lo.0) / (hi.0 - lo.0);
                Some((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)))
            }
            (Some(p), None) if rpm / lo.0 - 1.0 <= 0.02 => Some(p),
            (None, Some(q)) if 1.0 - rpm / hi.0 <= 0.02 => Some(q),
            _ => None,
        }
    }
}

#[cfg(test)]
mod table_tests {
    use super::PerformanceTable;

    #[test]
    fn a_table_interpolates_in_j_and_rpm_and_says_none_outside() {
        let t = PerformanceTable::new([
            [4000.0, 0.0, 0.10, 0.05],
            [4000.0, 0.4, 0.06, 0.04],
            [6000.0, 0.0, 0.12, 0.06],
            [6000.0, 0.4, 0.08, 0.05],
            [8000.0, 0.0, 0.13, 0.07],
        ]);
        let (ct, cp) = t.at(4000.0, 0.2).unwrap();
        assert!((ct - 0.08).abs() < 1e-12 && (cp - 0.045).abs() < 1e-12);
        let (ct, _) = t.at(5000.0, 0.2).unwrap();
        assert!((ct - 0.09).abs() < 1e-12);
        // A single row (a static point) only at its own J; between 6000 and 8000 at J = 0.
        assert!((t.at(7000.0, 0.0).unwrap().0 - 0.125).abs() < 1e-12);
        assert_eq!(t.at(7000.0, 0.2), None);
        // Outside the J range, or more than 2 % beyond the speeds.
        assert_eq!(t.at(4000.0, 0.5), None);
        assert_eq!(t.at(3000.0, 0.0), None);
        assert!(t.at(3950.0, 0.0).is_some());
        assert!(PerformanceTable::new([]).at(4000.0, 0.0).is_none());
    }
}
