//! Whether measurements can be of the propeller they are compared with: the check `compare`
//! warns with and `diagnose` refuses on. A measured thrust a median 3 times the prediction
//! or a third of it is beyond what any effect of the diagnosis explains (the largest, a
//! chord or pitch error, moves thrust by tens of per cent): a wrong prop file, diameter,
//! unit, RPM column or pole count.

/// How far the measured thrust may lie from the prediction (median ratio, either way).
pub const THRUST_RATIO: f64 = 3.0;

/// Why measurements cannot be of the propeller.
#[derive(Debug, Clone, PartialEq)]
pub enum Mismatch {
    /// At more than half the points the model gives no thrust where some was measured:
    /// `(count, of n, index of the first)`.
    NoThrust(usize, usize, usize),
    /// The median of measured over predicted thrust, where both are positive.
    Ratio(f64),
}

impl Mismatch {
    /// The sentence for a person, ending with what to check.
    pub fn message(&self) -> String {
        match self {
            Mismatch::NoThrust(k, n, _) => format!(
                "the measurements do not overlap the propeller's operating range: at {k} of {n} points the model \
                 gives no thrust where the stand measured some. Wrong prop file, diameter or airspeed units?"
            ),
            Mismatch::Ratio(r) => format!(
                "the measurements do not overlap the propeller's operating range: measured thrust is a median {r:.2} \
                 times the prediction, beyond what any effect explains. Wrong prop file, units, RPM column or pole count?"
            ),
        }
    }
}

/// Checks pairs of (measured, predicted) thrust [N] of one comparison.
pub fn mismatch(thrusts: &[(f64, f64)]) -> Option<Mismatch> {
    let n = thrusts.len();
    let outside: Vec<usize> = (0..n).filter(|&i| thrusts[i].1 <= 0.0 && thrusts[i].0 > 0.0).collect();
    if 2 * outside.len() > n {
        return Some(Mismatch::NoThrust(outside.len(), n, outside[0]));
    }
    let mut ratios: Vec<f64> = thrusts
        .iter()
        .filter(|(m, p)| *m > 0.0 && *p > 0.0)
        .map(|(m, p)| m / p)
        .filter(|r| r.is_finite())
        .collect();
    ratios.sort_by(f64::total_cmp);
    let med = *ratios.get(ratios.len() / 2)?;
    (!(1.0 / THRUST_RATIO..=THRUST_RATIO).contains(&med)).then_some(Mismatch::Ratio(med))
}

/// [`mismatch`] over compared points (every point, scored or not: a wrong prop shows in all).
pub fn of_points(points: &[crate::ComparedPoint]) -> Option<Mismatch> {
    let pairs: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| Some((p.measured.thrust?, p.predicted.thrust?)))
        .collect();
    mismatch(&pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_right_prop_passes_and_a_wrong_one_is_named() {
        let right = [(1.0, 1.1), (2.0, 1.8), (3.0, 3.3)];
        assert_eq!(mismatch(&right), None);
        // A 5-inch prop's prediction against a 2-inch log: measured 1/14 of it.
        let small: Vec<(f64, f64)> = right.iter().map(|(m, p)| (m / 14.0, *p)).collect();
        let Some(Mismatch::Ratio(r)) = mismatch(&small) else {
            panic!("{:?}", mismatch(&small))
        };
        assert!((r - 1.0 / 14.0 * 3.0 / 3.3).abs() < 0.01, "{r}");
        assert!(Mismatch::Ratio(r)
            .message()
            .contains("median 0.06 times the prediction"));
        let none = [(1.0, 0.0), (2.0, -0.1), (3.0, 3.0)];
        assert_eq!(mismatch(&none), Some(Mismatch::NoThrust(2, 3, 0)));
        assert_eq!(mismatch(&[]), None);
    }
}
