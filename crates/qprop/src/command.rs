//! QPROP's command-line sequence syntax (`io.f` `PPARSE`), so that runs of QPROP can be
//! reproduced point for point: `P`, `P1,P2` (5 points), `P1,P2,dP`, `P1,P2/N`.

/// The values of a QPROP sequence argument, as QPROP steps through them
/// (`P = P1 + (P2 - P1)/(N - 1) * (i - 1)`). `None` when the text is not a sequence.
pub fn qprop_sequence(arg: &str) -> Option<Vec<f64>> {
    let num = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let (p1, p2, n) = if let Some((a, rest)) = arg.split_once(',') {
        let p1 = num(a)?;
        if let Some((b, n)) = rest.split_once('/') {
            let p2 = num(b)?;
            let n = num(n)?;
            (p1, p2, (n.abs() + 0.01) as usize)
        } else if let Some((b, d)) = rest.split_once(',') {
            let p2 = num(b)?;
            let d = num(d)?;
            (p1, p2, (((p2 - p1) / d).abs() + 1.49) as usize)
        } else {
            let p2 = num(rest)?;
            (p1, p2, if p1 == p2 { 1 } else { 5 })
        }
    } else {
        let p = num(arg)?;
        (p, p, 1)
    };
    let step = (p2 - p1) / (n.max(2) - 1) as f64;
    Some((0..n).map(|i| p1 + step * i as f64).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequences() {
        assert_eq!(qprop_sequence("5"), Some(vec![5.0]));
        assert_eq!(qprop_sequence("0,16/17").unwrap().len(), 17);
        assert_eq!(qprop_sequence("-4,4,2"), Some(vec![-4.0, -2.0, 0.0, 2.0, 4.0]));
        assert_eq!(qprop_sequence("1,2"), Some(vec![1.0, 1.25, 1.5, 1.75, 2.0]));
        assert_eq!(qprop_sequence("3000,12000/10").unwrap()[9], 12000.0);
        assert_eq!(qprop_sequence("x"), None);
    }
}
