//! Unit tests of `reduce.rs`.

use super::*;

#[test]
fn coefficients_outside_physics_are_clamped_and_named() {
    let mut c = QpropCoefficients {
        cl0: 1.3,
        cl_a: 17.27,
        cl_min: -0.3,
        cl_max: 1.2,
        cd0: 0.03,
        cd2u: 5000.0,
        cd2l: 0.07,
        clcd0: 0.3,
        re_ref: 15849.0,
        re_exp: -0.09,
    };
    let said = bound(&mut c);
    assert_eq!((c.cl0, c.cl_a, c.cd2u), (1.0, 7.5, 1.0));
    assert_eq!(said.len(), 3, "{said:?}");
    assert!(
        said[1].starts_with("CL_a 17.27") && said[1].contains("fallback"),
        "{said:?}"
    );
    // Inside the bounds nothing changes.
    let before = c;
    assert!(bound(&mut c).is_empty() && c == before);
}

/// A polar made from QPROP's own law (plus a stall) must come back exactly.
fn synthetic(re: f64, c: &QpropCoefficients) -> Polar {
    Polar::from_law(re, -6, 16, |alpha| {
        let lin = c.cl0 + c.cl_a * alpha.to_radians();
        let cl = if alpha > 11.0 { lin - 0.15 * (alpha - 11.0) } else { lin };
        (cl, c.cd_profile(cl) * c.re_factor(re))
    })
}

const TRUTH: QpropCoefficients = QpropCoefficients {
    cl0: 0.45,
    cl_a: 5.8,
    cl_min: -0.3,
    cl_max: 1.4,
    cd0: 0.012,
    cd2u: 0.02,
    cd2l: 0.035,
    clcd0: 0.55,
    re_ref: 1e5,
    re_exp: -0.4,
};

#[test]
fn qprop_law_is_recovered() {
    let truth = TRUTH;
    let polars = [synthetic(5e4, &truth), synthetic(1e5, &truth), synthetic(2e5, &truth)];
    let fit = fit_qprop(&polars, 1e5, &AlphaWeights::Uniform, -0.5).unwrap();
    let c = fit.coeffs;
    assert!((c.cl0 - 0.45).abs() < 1e-9 && (c.cl_a - 5.8).abs() < 1e-9, "{c:?}");
    assert!((c.cd0 - 0.012).abs() < 1e-5, "{c:?}");
    assert!((c.clcd0 - 0.55).abs() < 0.02, "{c:?}");
    assert!((c.cd2u - 0.02).abs() < 2e-3 && (c.cd2l - 0.035).abs() < 3e-3, "{c:?}");
    assert!((c.re_exp + 0.4).abs() < 1e-6, "{c:?}");
    assert!(fit.re_exp_fitted);
    assert_eq!(fit.linear_range_deg, [-6.0, 11.0]);
    assert!(fit.unfit.is_empty(), "{:?}", fit.unfit);
    assert!(fit.cd_max_rel_error < 0.01);
}

#[test]
fn working_outside_the_linear_range_is_called_unfit() {
    let truth = TRUTH;
    let w = AlphaWeights::Around {
        alphas_deg: vec![14.0],
        sigma_deg: 2.0,
    };
    let fit = fit_qprop(&[synthetic(1e5, &truth)], 1e5, &w, -0.5).unwrap();
    assert!(
        fit.unfit.iter().any(|u| u.contains("outside the linear range")),
        "{:?}",
        fit.unfit
    );
    assert!(!fit.re_exp_fitted);
    assert_eq!(fit.coeffs.re_exp, -0.5);
}

#[test]
fn too_few_points_is_an_error() {
    let mut p = synthetic(
        1e5,
        &QpropCoefficients::from_array([0.4, 6.0, -0.3, 1.2, 0.01, 0.02, 0.02, 0.5, 1e5, -0.5]),
    );
    p.points.truncate(2);
    assert!(matches!(
        fit_qprop(&[p], 1e5, &AlphaWeights::Uniform, -0.5),
        Err(FitError::TooFewPoints { .. })
    ));
    assert!(matches!(
        fit_qprop(&[], 1e5, &AlphaWeights::Uniform, -0.5),
        Err(FitError::NoPolar)
    ));
}
