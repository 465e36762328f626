//! The points of a comparison as `points.csv`: each measured point (its file, lines, samples,
//! scatter) beside its prediction.

use propbet_compare::ComparedPoint;

use super::{csv_rows, Num};

/// A row of points.csv.
#[derive(serde::Serialize)]
struct PointRow {
    file: String,
    label: String,
    line_first: usize,
    line_last: usize,
    samples_rpm: usize,
    samples_thrust: Option<usize>,
    samples_torque: Option<usize>,
    rpm: Num,
    rpm_sd: Num,
    v_m_s: Num,
    j: Num,
    rho: Num,
    thrust_n: Num,
    thrust_sd: Num,
    thrust_pred: Num,
    torque_nm: Num,
    torque_sd: Num,
    torque_pred: Num,
    power_w: Num,
    power_pred: Num,
    ct: Num,
    ct_sd: Num,
    ct_pred: Num,
    cp: Num,
    cp_sd: Num,
    cp_pred: Num,
    eta: Num,
    eta_pred: Num,
    re75: Num,
    mach_tip: Num,
    scored: u8,
    model_flags: String,
}

/// points.csv of a comparison: one row per measured point with its prediction (`files`: the
/// measured files' names, by index).
pub fn csv(files: &[String], pts: &[ComparedPoint]) -> Result<Vec<u8>, csv::Error> {
    csv_rows(
        pts.iter().map(|p| PointRow {
            file: files[p.file].clone(),
            label: p.label.clone(),
            line_first: p.lines.0,
            line_last: p.lines.1,
            samples_rpm: p.samples.rpm,
            samples_thrust: p.samples.thrust,
            samples_torque: p.samples.torque,
            rpm: p.rpm.into(),
            rpm_sd: p.rpm_sd.into(),
            v_m_s: p.v.into(),
            j: p.j.into(),
            rho: p.air.fluid.rho.into(),
            thrust_n: p.measured.thrust.into(),
            thrust_sd: p.measured_sd.thrust.into(),
            thrust_pred: p.predicted.thrust.into(),
            torque_nm: p.measured.torque.into(),
            torque_sd: p.measured_sd.torque.into(),
            torque_pred: p.predicted.torque.into(),
            power_w: p.measured.power.into(),
            power_pred: p.predicted.power.into(),
            ct: p.measured.ct.into(),
            ct_sd: p.measured_sd.ct.into(),
            ct_pred: p.predicted.ct.into(),
            cp: p.measured.cp.into(),
            cp_sd: p.measured_sd.cp.into(),
            cp_pred: p.predicted.cp.into(),
            eta: p.measured.eta.into(),
            eta_pred: p.predicted.eta.into(),
            re75: p.re75.into(),
            mach_tip: p.mach_tip.into(),
            scored: u8::from(p.scored()),
            model_flags: p.model_flags.join("; "),
        }),
        true,
    )
}
