//! Drela's cubic spline in derivative form (SPLINE/SEVAL of QPROP and XFOIL).
//!
//! QPROP interpolates chord, twist and every aerodynamic coefficient with this spline, so a
//! solver that must reproduce QPROP digit for digit has to use the same one: nodal slopes from
//! a tridiagonal system with zero third derivative over the two end intervals
//! (`../shared/reference/qprop/FORMULATION.md`, "Discretisation").

/// A cubic spline through `(s_i, x_i)` with slopes chosen as in Drela's `SPLINE`.
#[derive(Debug, Clone, PartialEq)]
pub struct DrelaSpline {
    s: Vec<f64>,
    x: Vec<f64>,
    xs: Vec<f64>,
}

impl DrelaSpline {
    /// Builds the spline. `s` must be strictly increasing and as long as `x` (at least one
    /// point); callers validate user data before this point, so a violation is a bug.
    pub fn new(s: &[f64], x: &[f64]) -> Self {
        assert_eq!(s.len(), x.len(), "spline abscissae and ordinates differ in length");
        assert!(!s.is_empty(), "spline needs at least one point");
        let n = s.len();
        let xs = match n {
            1 => vec![0.0],
            2 => {
                let slope = (x[1] - x[0]) / (s[1] - s[0]);
                vec![slope, slope]
            }
            _ => slopes(s, x),
        };
        Self {
            s: s.to_vec(),
            x: x.to_vec(),
            xs,
        }
    }

    /// Value at `s` (Drela's `SEVAL`); outside the nodes the end cubic is extrapolated.
    pub fn eval(&self, s: f64) -> f64 {
        let n = self.s.len();
        if n == 1 {
            return self.x[0];
        }
        // Interval [i-1, i] with s_{i-1} <= s < s_i, clamped to the end intervals.
        let i = self.s.partition_point(|&si| si <= s).clamp(1, n - 1);
        let ds = self.s[i] - self.s[i - 1];
        let t = (s - self.s[i - 1]) / ds;
        let dx = self.x[i] - self.x[i - 1];
        let cx1 = ds * self.xs[i - 1] - dx;
        let cx2 = ds * self.xs[i] - dx;
        t * self.x[i] + (1.0 - t) * self.x[i - 1] + (t - t * t) * ((1.0 - t) * cx1 - t * cx2)
    }
}

/// Nodal slopes for n >= 3 points: the tridiagonal system of FORMULATION.md solved by the
/// Thomas algorithm (diagonally dominant inside, so no pivoting is needed).
fn slopes(s: &[f64], x: &[f64]) -> Vec<f64> {
    let n = s.len();
    let mut lower = vec![0.0; n];
    let mut diag = vec![0.0; n];
    let mut upper = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    // Zero third derivative over the first interval: x'_1 + x'_2 = 2 dx/ds.
    diag[0] = 1.0;
    upper[0] = 1.0;
    rhs[0] = 2.0 * (x[1] - x[0]) / (s[1] - s[0]);
    for i in 1..n - 1 {
        let dsm = s[i] - s[i - 1];
        let dsp = s[i + 1] - s[i];
        lower[i] = dsp;
        diag[i] = 2.0 * (dsm + dsp);
        upper[i] = dsm;
        rhs[i] = 3.0 * ((x[i + 1] - x[i]) * dsm / dsp + (x[i] - x[i - 1]) * dsp / dsm);
    }
    lower[n - 1] = 1.0;
    diag[n - 1] = 1.0;
    rhs[n - 1] = 2.0 * (x[n - 1] - x[n - 2]) / (s[n - 1] - s[n - 2]);
    // Forward elimination, back substitution.
    for i in 1..n {
        let m = lower[i] / diag[i - 1];
        diag[i] -= m * upper[i - 1];
        rhs[i] -= m * rhs[i - 1];
    }
    let mut xs = vec![0.0; n];
    xs[n - 1] = rhs[n - 1] / diag[n - 1];
    for i in (0..n - 1).rev() {
        xs[i] = (rhs[i] - upper[i] * xs[i + 1]) / diag[i];
    }
    xs
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn check(s: &[f64], x: &[f64], at: f64, expected: f64) {
        let sp = DrelaSpline::new(s, x);
        assert_relative_eq!(sp.eval(at), expected, epsilon = 1e-12);
    }

    #[test]
    fn reproduces_nodes_lines_and_cubics() {
        // A spline passes through its nodes.
        check(&[0.0, 1.0, 3.0, 4.0], &[1.0, -2.0, 5.0, 0.5], 3.0, 5.0);
        // Two points: a straight line.
        check(&[1.0, 3.0], &[2.0, 6.0], 2.5, 5.0);
        // A straight line through many unevenly spaced points stays a line.
        check(&[0.0, 0.3, 1.0, 2.5, 2.6], &[1.0, 1.6, 3.0, 6.0, 6.2], 1.7, 4.4);
        // Zero third derivative at the ends: a parabola is reproduced exactly.
        let s = [0.0, 0.5, 1.2, 2.0, 3.1];
        let x: Vec<f64> = s.iter().map(|v| 2.0 * v * v - v + 3.0).collect();
        check(&s, &x, 0.8, 2.0 * 0.64 - 0.8 + 3.0);
        check(&s, &x, 2.9, 2.0 * 2.9 * 2.9 - 2.9 + 3.0);
    }
}
