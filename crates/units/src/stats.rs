//! The median and the quantiles every headline number is made of, defined once.
//!
//! A quantile is the linear interpolation between the order statistics (Hyndman and Fan's
//! type 7, NumPy's and R's default): with the n samples sorted, the q-quantile lies at rank
//! h = q (n − 1) counted from 0, between the samples at ⌊h⌋ and ⌈h⌉. The median is the
//! 0.5-quantile: the middle sample, or the mean of the two middle ones.

/// The `q`-quantile of `v` (0 ≤ q ≤ 1; linear between order statistics); NaN for no samples.
/// NaNs sort last ([`f64::total_cmp`]): drop them first where they are not data.
pub fn quantile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let h = (v.len() - 1) as f64 * q.clamp(0.0, 1.0);
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    if lo == hi {
        v[lo]
    } else {
        v[lo] + (h - lo as f64) * (v[hi] - v[lo])
    }
}

/// The median of `v`: the middle sample, or the mean of the two middle ones; NaN for none.
pub fn median(v: Vec<f64>) -> f64 {
    quantile(v, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_is_the_middle_or_the_mean_of_the_two_middles() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(vec![7.0]), 7.0);
        assert!(median(vec![]).is_nan());
    }

    #[test]
    fn quantiles_interpolate_between_order_statistics_as_numpy_does() {
        // numpy.quantile([1, 2, 3, 4, 10], [0, 0.25, 0.9, 1]) = [1, 2, 7.6, 10].
        let v = vec![10.0, 1.0, 4.0, 2.0, 3.0];
        assert_eq!(quantile(v.clone(), 0.0), 1.0);
        assert_eq!(quantile(v.clone(), 0.25), 2.0);
        assert!((quantile(v.clone(), 0.9) - 7.6).abs() < 1e-12);
        assert_eq!(quantile(v, 1.0), 10.0);
    }
}
