//! One row of the validation table: the errors before and after calibration, APC's own
//! prediction scored on the same points, and the signatures of the data.

use propbet_compare::expected::family;
use propbet_compare::metrics::{in_window, window_errors, Regimes, StaticRise, ZeroThrustShift, VALIDATION_J_WINDOW};
use propbet_compare::ComparedPoint;
use propbet_diagnose::signature::{rpm_trend_at_fixed_j, RpmTrend};
use propbet_qprop::apc::Pe0;

/// The station solves beyond their polars' Reynolds-number range over `points`, and all their
/// station solves ([`Row::beyond_polars`]).
pub fn beyond_polars(points: &[ComparedPoint]) -> (usize, usize) {
    points
        .iter()
        .fold((0, 0), |(a, b), p| (a + p.beyond_polars.0, b + p.beyond_polars.1))
}

/// One row of the validation table: |pred/meas − 1| of CT and CP below 85 % of each sweep's
/// zero-thrust J, before and after calibration.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Row {
    /// The UIUC name.
    pub prop: String,
    /// Points scored.
    pub points: usize,
    /// Points (of all compared) where the prediction is physically implausible (scored, and
    /// named in the prop's points.csv).
    pub implausible: usize,
    /// Station solves at the compared points whose Reynolds number lies beyond their polars'
    /// (the Re ladder's lowest or highest rung), and all the station solves there: whether the
    /// ladder reaches every station at every operating point.
    pub beyond_polars: (usize, usize),
    /// CT's errors before and after calibration.
    pub ct: BeforeAfter,
    /// CP's errors before and after calibration.
    pub cp: BeforeAfter,
    /// APC's own prediction (PER3) on the same points: CT and CP (median, p90), and the points
    /// it covers; None without `--per3` or its file.
    pub per3: Option<Per3Score>,
    /// The calibration: the effects of the rung of the ladder fitted to all the prop's files
    /// that scores lowest on them (`calibrated/`; the whole ladder is the diagnosis's).
    pub ladder: String,
    /// The rungs each half of the measurements carries to the other, whose predictions are the
    /// "after" columns.
    pub held_out_ladders: [String; 2],
    /// APC's design twist minus UIUC's measured β [deg], the mean over UIUC's stations at
    /// r/R 0.6-0.9 (where most of the thrust is made): what a `pitch-offset` fitted on UIUC's
    /// geometry is to be compared with (docs/studies/geometry-source.md).
    pub twist_gap: f64,
    /// UIUC has a geometry file of the prop; without one the blade is APC's design (PE0) at
    /// UIUC's stations, whatever `--geometry` asks.
    pub uiuc_geometry: bool,
    /// The section assumed for a prop without APC's sections, and why ("sd7037 t/c 0.092 (UIUC
    /// family gwsdd: not an APC propeller)"); None for APC's (PE0).
    pub assumed_section: Option<String>,
    /// The prop's files that did not read (file name, why): left out of every stage.
    pub left_out: Vec<(String, String)>,
    /// The static points' predicted figure of merit over the measured, minus 1 (median;
    /// [`static_figure_of_merit_error`]): the hover efficiency's error, whatever its split
    /// between thrust and power (docs/studies/section-scaling.md: +11 to +19 % on every shared
    /// prop). NaN without static points.
    pub static_fm: f64,
    /// Before calibration, the median signed errors by regime (static, forward flight below and
    /// above half the zero-thrust J: [`propbet_compare::metrics::REGIMES`]): which way and where.
    pub regimes: Regimes,
    /// The static CT's rise from the lowest to the highest static RPM, measured and predicted
    /// ([`static_rise`]); None without a static test spanning 1.3x.
    pub static_rise: Option<StaticRise>,
    /// Before calibration, the CT error's change with RPM at fixed J over the J sweeps' points
    /// in the window ([`forward_rpm_trend`]): the sections' Reynolds-number dependence in
    /// forward flight, where the static rise shows it statically; None where no J bin's RPMs
    /// span 1.3x.
    pub forward_rpm_trend: Option<RpmTrend>,
    /// How the J sweeps' zero-thrust J moves with RPM, measured and predicted
    /// ([`zero_thrust_shift`]): a blade that twists nose-down as it speeds up moves the
    /// measured one down where the sections' Reynolds numbers move the model's up; None with
    /// fewer than two sweeps reaching zero thrust.
    pub zero_thrust_shift: Option<ZeroThrustShift>,
    /// How well the prop's measurements repeat (the relative deviation of one point,
    /// [`propbet_diagnose::Repeatability`]): None without repeated operating points.
    pub repeatability: Option<f64>,
    /// The uncertainty band's coverage of the measured CT and CP over the scored points (the
    /// share inside it) and its median relative half-width ([`band_coverage`]); None where no
    /// point has the quantity.
    pub band: [Option<propbet_compare::band::Coverage>; 2],
}

/// The band's coverage of CT and CP over the points inside the validation window
/// ([`propbet_compare::band::coverage`]; `bands` in the points' order), the band widened by the
/// measurements' repeatability where they repeat a point (`repeatability`, the relative
/// deviation of one point: [`propbet_compare::band::with_repeatability`]).
pub fn band_coverage(
    points: &[ComparedPoint],
    bands: &[propbet_compare::band::PointBand],
    repeatability: Option<f64>,
) -> [Option<propbet_compare::band::Coverage>; 2] {
    let widened = repeatability.map(|r| propbet_compare::band::with_repeatability(bands, points, r));
    let (p, b): (Vec<_>, Vec<_>) = points
        .iter()
        .zip(widened.as_deref().unwrap_or(bands))
        .zip(in_window(points, VALIDATION_J_WINDOW))
        .filter(|(_, inside)| *inside)
        .map(|(pb, _)| pb)
        .unzip();
    propbet_compare::band::coverage(&p, &b)
}

/// The CT error's (predicted / measured − 1) change with RPM at fixed J over the J sweeps'
/// points inside the validation window ([`propbet_diagnose::signature::rpm_trend_at_fixed_j`]:
/// the median over J bins of the slope against ln RPM, over the range the bins typically span).
pub fn forward_rpm_trend(points: &[ComparedPoint], window: f64) -> Option<RpmTrend> {
    let ok = |x: Option<f64>| x.filter(|v| v.is_finite() && *v > 0.0);
    let pts: Vec<(f64, f64, i64, f64)> = points
        .iter()
        .zip(in_window(points, window))
        .filter(|(p, inside)| *inside && !p.is_static() && p.rpm.is_finite() && p.rpm > 0.0)
        .filter_map(|(p, _)| {
            Some((
                p.j,
                p.rpm,
                0,
                p.predicted.ct.filter(|c| c.is_finite())? / ok(p.measured.ct)? - 1.0,
            ))
        })
        .collect();
    rpm_trend_at_fixed_j(&pts)
}

/// Mean of APC's design twist minus the measured β [deg] over the stations of `table` within
/// [`propbet_compare::metrics::TWIST_GAP_SPAN`] (NaN if none is).
pub fn twist_gap(table: &[propbet_measure::uiuc::GeometryRow], pe0: &Pe0, big_r: f64) -> f64 {
    let stations: Vec<(f64, f64)> = table.iter().map(|row| (row.r_r, row.beta.to_degrees())).collect();
    propbet_compare::metrics::twist_gap(&stations, |r_r| pe0.twist_at(r_r * big_r))
}

/// The ladder of one fold as the command line gives it ("none" without an effect).
pub(super) fn ladder_text(effects: &[String]) -> String {
    if effects.is_empty() {
        "none".into()
    } else {
        effects.join(" + ")
    }
}

/// The median and 90th percentile of errors: the table's two numbers per quantity.
pub(super) fn median_p90(v: &[f64]) -> Spread {
    Spread {
        median: propbet_units::stats::median(v.to_vec()),
        p90: propbet_units::stats::quantile(v.to_vec(), 0.9),
    }
}

/// How large a set of errors is: their median and 90th percentile (|pred/meas - 1|).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Spread {
    /// The median.
    pub median: f64,
    /// The 90th percentile.
    pub p90: f64,
}

/// A quantity's errors before calibration and after it (the held-out predictions).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BeforeAfter {
    /// Before.
    pub before: Spread,
    /// After.
    pub after: Spread,
}

/// APC's PER3 prediction scored as propbet's is.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Per3Score {
    /// Points scored (those inside the PER3 file's RPM and J range).
    pub points: usize,
    /// CT's errors.
    pub ct: Spread,
    /// CP's errors.
    pub cp: Spread,
}

/// Other makers' lines (their props predicted with a section assumed) with two or more props,
/// then all such props together ([`propbet_compare::expected::ASSUMED`]).
pub fn line_groups(rows: &[Row]) -> Vec<(String, Vec<&Row>)> {
    let assumed: Vec<&Row> = rows.iter().filter(|r| r.assumed_section.is_some()).collect();
    let mut out = by_family(&assumed);
    if assumed.len() >= 2 {
        out.push((propbet_compare::expected::ASSUMED.to_string(), assumed));
    }
    out
}

/// The rows of APC's sections (a row whose section was assumed left out, as from validate's
/// medians) grouped by [`family`], in name order, the families of two or more props only.
pub fn family_groups(rows: &[Row]) -> Vec<(String, Vec<&Row>)> {
    let apc: Vec<&Row> = rows.iter().filter(|r| r.assumed_section.is_none()).collect();
    by_family(&apc)
}

/// `rows` grouped by [`family`], in name order, the groups of two or more rows only.
fn by_family<'a>(rows: &[&'a Row]) -> Vec<(String, Vec<&'a Row>)> {
    let mut families: Vec<String> = rows.iter().map(|r| family(&r.prop)).collect();
    families.sort();
    families.dedup();
    families
        .into_iter()
        .map(|f| {
            let members: Vec<&Row> = rows.iter().copied().filter(|r| family(&r.prop) == f).collect();
            (f, members)
        })
        .filter(|(_, members)| members.len() >= 2)
        .collect()
}

/// Scores APC's PER3 prediction on the compared points: each point's predicted CT and CP
/// replaced by PER3's at its RPM and J (points outside PER3's range left out), then the same
/// window and errors as propbet's.
pub fn per3_score(per3: &propbet_qprop::apc::Per3, points: &[propbet_compare::ComparedPoint]) -> Per3Score {
    let replaced: Vec<propbet_compare::ComparedPoint> = points
        .iter()
        .map(|p| {
            let mut q = p.clone();
            let at = per3.at(p.rpm, p.j);
            q.predicted.ct = at.map(|x| x.0);
            q.predicted.cp = at.map(|x| x.1);
            q
        })
        .collect();
    let (ct, cp) = window_errors(&replaced, VALIDATION_J_WINDOW);
    Per3Score {
        points: ct.len(),
        ct: median_p90(&ct),
        cp: median_p90(&cp),
    }
}
