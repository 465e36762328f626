//! An uncertainty band from the model's own response to what is uncertain: each source is
//! solved at its low and its high end, and the band's two sides are the root-sum-square over
//! the sources of how far each moves the value up and down (the sources taken as independent;
//! a source that moves the value the same way at both ends counts once, its larger move).

use crate::{ComparedPoint, Quantities};

/// The low and high ends of a band around one value.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Bounds {
    /// Low end.
    pub lo: f64,
    /// High end.
    pub hi: f64,
}

impl Bounds {
    /// True when `x` is inside (the ends included).
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lo && x <= self.hi
    }

    /// Half the band's width relative to `centre` (NaN where the centre is zero).
    pub fn relative_half_width(&self, centre: f64) -> f64 {
        0.5 * (self.hi - self.lo) / centre.abs()
    }
}

/// The band around each of `base` from `variants`: one pair of value lists per source (its low
/// and its high end, each as long as `base`), each source's moves times its weight (`weights`,
/// in the sources' order; 1 where it ends). A NaN variant value (a point a source's solve
/// cannot give) leaves that source out of the point's band.
pub fn combine(base: &[f64], variants: &[[Vec<f64>; 2]], weights: &[f64]) -> Vec<Bounds> {
    base.iter()
        .enumerate()
        .map(|(i, &b)| {
            let (mut up, mut down) = (0.0f64, 0.0f64);
            for (k, [lo, hi]) in variants.iter().enumerate() {
                let w = weights.get(k).copied().unwrap_or(1.0);
                let d = [w * (lo[i] - b), w * (hi[i] - b)];
                let u = d.iter().filter(|x| x.is_finite()).fold(0.0f64, |a, &x| a.max(x));
                let w = d.iter().filter(|x| x.is_finite()).fold(0.0f64, |a, &x| a.max(-x));
                up += u * u;
                down += w * w;
            }
            Bounds {
                lo: b - down.sqrt(),
                hi: b + up.sqrt(),
            }
        })
        .collect()
}

/// The bands of CT, CP and efficiency of each of `base`'s rows from the same rows solved at
/// each source's two ends (`variants`: one pair per source, each as long as `base`), the three
/// quantities read from a row by `values` (None where unknown), each source weighted by
/// `weights` ([`combine`]).
pub fn of_rows<R, V: AsRef<[R]>>(
    base: &[R],
    variants: &[[V; 2]],
    weights: &[f64],
    values: [fn(&R) -> Option<f64>; 3],
) -> Vec<PointBand> {
    let [ct, cp, eta] = values.map(|f| {
        let read = |rows: &[R]| -> Vec<f64> { rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect() };
        let v: Vec<[Vec<f64>; 2]> = variants
            .iter()
            .map(|[a, b]| [read(a.as_ref()), read(b.as_ref())])
            .collect();
        combine(&read(base), &v, weights)
    });
    (0..base.len())
        .map(|i| PointBand {
            ct: ct[i],
            cp: cp[i],
            eta: eta[i],
        })
        .collect()
}

/// The bands of CT, CP and efficiency at compared points, from the same points predicted at
/// each source's two ends (`variants`: one pair of comparisons per source, in the points'
/// order).
pub fn of_points(base: &[ComparedPoint], variants: &[[Vec<ComparedPoint>; 2]], weights: &[f64]) -> Vec<PointBand> {
    of_rows(
        base,
        variants,
        weights,
        [|p| p.predicted.ct, |p| p.predicted.cp, |p| p.predicted.eta],
    )
}

/// A band along a model curve: (x, the band there), x as the curve's (J or RPM).
pub type BandCurve = Vec<(f64, PointBand)>;

/// The band along each of a comparison's model curves ([`crate::curves::Curves`]).
#[derive(Debug, Clone, Default)]
pub struct BandCurves {
    /// Per J sweep, as the curves' `j_sweeps`.
    pub j_sweeps: Vec<Option<BandCurve>>,
    /// Along the static curve.
    pub statics: Option<BandCurve>,
}

/// The band along `base`'s curves from the same curves solved at each source's two ends (the
/// same x grid: the curves' grid comes from the compared points, not from the model).
pub fn of_curves(base: &crate::curves::Curves, variants: &[[crate::curves::Curves; 2]], weights: &[f64]) -> BandCurves {
    use crate::curves::{Curve, Curves};
    let along = |c: &Curve, pick: &dyn Fn(&Curves) -> Option<&Curve>| -> BandCurve {
        let (v, w): (Vec<[&Curve; 2]>, Vec<f64>) = variants
            .iter()
            .enumerate()
            .filter_map(|(k, [a, b])| Some(([pick(a)?, pick(b)?], weights.get(k).copied().unwrap_or(1.0))))
            .filter(|([a, b], _)| a.len() == c.len() && b.len() == c.len())
            .unzip();
        let bands = of_rows(c, &v, &w, [|(_, q)| q.ct, |(_, q)| q.cp, |(_, q)| q.eta]);
        c.iter().map(|(x, _)| *x).zip(bands).collect()
    };
    BandCurves {
        j_sweeps: base
            .j_sweeps
            .iter()
            .enumerate()
            .map(|(k, s)| {
                s.as_ref()
                    .map(|(_, c)| along(c, &|v| v.j_sweeps.get(k)?.as_ref().map(|s| &s.1)))
            })
            .collect(),
        statics: base.statics.as_ref().map(|c| along(c, &|v| v.statics.as_ref())),
    }
}

/// `bands` at `points` widened by the measurements' repeatability: `rel` (one repeated
/// point's relative deviation) at two standard deviations of each predicted value, added to
/// each side in root-sum-square.
pub fn with_repeatability(bands: &[PointBand], points: &[ComparedPoint], rel: f64) -> Vec<PointBand> {
    let widen = |b: Bounds, c: Option<f64>| {
        let Some(c) = c.filter(|c| c.is_finite()) else {
            return b;
        };
        let m = 2.0 * rel * c.abs();
        let side = |d: f64| (d * d + m * m).sqrt();
        Bounds {
            lo: c - side(c - b.lo),
            hi: c + side(b.hi - c),
        }
    };
    bands
        .iter()
        .zip(points)
        .map(|(b, p)| PointBand {
            ct: widen(b.ct, p.predicted.ct),
            cp: widen(b.cp, p.predicted.cp),
            eta: widen(b.eta, p.predicted.eta),
        })
        .collect()
}

/// The band of one point.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PointBand {
    /// Thrust coefficient.
    pub ct: Bounds,
    /// Power coefficient.
    pub cp: Bounds,
    /// Efficiency.
    pub eta: Bounds,
}

/// How a band fits the measurements: the share of measured values inside it and its median
/// relative half-width, over the points given.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Coverage {
    /// Points counted.
    pub n: usize,
    /// Share of the measured values inside the band.
    pub inside: f64,
    /// Median of the band's half-width over the predicted value.
    pub half_width: f64,
}

/// The coverage of CT's and CP's bands over `points` (those with a measured value).
pub fn coverage(points: &[&ComparedPoint], bands: &[&PointBand]) -> [Option<Coverage>; 2] {
    let one = |m: fn(&Quantities) -> Option<f64>, b: fn(&PointBand) -> Bounds| {
        let mut inside = 0;
        let mut widths = Vec::new();
        for (p, band) in points.iter().zip(bands) {
            let (Some(x), Some(c)) = (m(&p.measured), m(&p.predicted)) else {
                continue;
            };
            let w = b(band).relative_half_width(c);
            if !w.is_finite() {
                continue;
            }
            inside += usize::from(b(band).contains(x));
            widths.push(w);
        }
        let n = widths.len();
        (n > 0).then(|| Coverage {
            n,
            inside: inside as f64 / n as f64,
            half_width: propbet_units::stats::median(widths),
        })
    };
    [one(|q| q.ct, |b| b.ct), one(|q| q.cp, |b| b.cp)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_side_is_the_root_sum_square_of_the_sources_moves_that_way() {
        // Source 1 moves the value -3 / +4, source 2 +1 at both ends (counted once), source 3
        // cannot be solved at its low end.
        let base = [10.0];
        let v = [
            [vec![7.0], vec![14.0]],
            [vec![11.0], vec![10.5]],
            [vec![f64::NAN], vec![8.0]],
        ];
        let b = combine(&base, &v, &[])[0];
        assert!((b.hi - (10.0 + (16.0f64 + 1.0).sqrt())).abs() < 1e-12, "{b:?}");
        assert!((b.lo - (10.0 - (9.0f64 + 4.0).sqrt())).abs() < 1e-12, "{b:?}");
        assert!(b.contains(10.0) && !b.contains(14.2) && b.contains(b.lo));
        assert!((b.relative_half_width(10.0) - 0.5 * (b.hi - b.lo) / 10.0).abs() < 1e-15);
        assert_eq!(combine(&base, &[], &[])[0], Bounds { lo: 10.0, hi: 10.0 });
        // A weight multiplies its source's moves: source 1 at twice its ends.
        let w = combine(&base, &v[..1], &[2.0])[0];
        assert!((w.hi - 18.0).abs() < 1e-12 && (w.lo - 4.0).abs() < 1e-12, "{w:?}");
    }

    #[test]
    fn repeatability_widens_each_side_about_the_prediction() {
        let mut p = ComparedPoint::default();
        p.predicted.ct = Some(0.1);
        let b = Bounds { lo: 0.097, hi: 0.104 };
        let band = PointBand { ct: b, cp: b, eta: b };
        // 1 % repeatability: 2 % of 0.1 = 0.002 added in root-sum-square to 0.003 and 0.004.
        let w = with_repeatability(&[band], &[p], 0.01)[0].ct;
        assert!(
            (0.1 - w.lo - (0.003f64.powi(2) + 0.002f64.powi(2)).sqrt()).abs() < 1e-12,
            "{w:?}"
        );
        assert!(
            (w.hi - 0.1 - (0.004f64.powi(2) + 0.002f64.powi(2)).sqrt()).abs() < 1e-12,
            "{w:?}"
        );
    }
}
