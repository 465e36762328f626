//! Each stage's few lines on the terminal of `propbet run` (without `--verbose`), for the
//! stages whose lines are the run's own: the prediction and the comparison.

use propbet_bemt::PointResult;
use propbet_compare::electric::Electric;
use propbet_pipeline::stages::Compared;
use propbet_qprop::export::{QpropExport, FILE_NAME};
use propbet_settings::spec::PredictSpec;

use crate::answer::ReferenceScore;

/// The prediction: its points (how many did not converge) and where they went, then the
/// exported QPROP file's fidelity (or why there is none).
pub fn predict(points: &[PointResult], spec: &PredictSpec, export: &Result<QpropExport, String>) -> Vec<String> {
    let unconverged = points.iter().filter(|p| p.not_converged > 0).count();
    vec![
        format!(
            "{} operating points at {} speeds{}{}",
            points.len(),
            spec.omegas.len(),
            if unconverged > 0 {
                format!(", {unconverged} with stations that did not converge")
            } else {
                String::new()
            },
            spec.out
                .as_ref()
                .map_or(String::new(), |o| format!(" -> {}", o.display()))
        ),
        match export {
            Ok(x) => format!("{FILE_NAME}: {}", x.fidelity.brief()),
            Err(e) => format!("no QPROP export: {e}"),
        },
    ]
}

/// The comparison: the files and the headline ([`crate::answer::brief`]), the median errors
/// over the points validate scores, and the electrical comparison's sentence.
pub fn compare(c: &Compared, reference: Option<&ReferenceScore>, electric: Option<&Electric>) -> Vec<String> {
    let mut out = crate::answer::brief(&c.sets, &c.metrics, reference);
    let (ct, cp, n) = crate::compare::accuracy(&c.points);
    if n > 0 {
        out.push(format!(
            "median error CT {:.1} %, CP {:.1} % over {n} points below 85 % of the zero-thrust J (as validate scores)",
            100.0 * ct,
            100.0 * cp
        ));
    }
    if let Some(e) = electric {
        out.push(crate::compare::electric_sentence(e));
    }
    out
}
