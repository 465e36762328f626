//! Another code's prediction a comparison is drawn beside (`--per3`: APC's; `--qprop-output`:
//! QPROP's), read once and asked for (CT, CP) at each measured point.

use propbet_compare::curves::PerformanceTable;
use propbet_qprop::apc::Per3;
use propbet_qprop::output::QpropOutput;

use super::*;
use propbet_settings::spec::CompareSpec;

/// Another code's prediction a comparison names, read once.
pub struct Reference {
    /// What it is, for legends and the headline ("APC's prediction (PER3_10x7.dat)").
    pub name: String,
    /// What reading it left out, for the terminal (PER3 rows that are not finite or beyond any
    /// propeller's CT, CP or J).
    pub warning: Option<String>,
    table: ReferenceTable,
}

enum ReferenceTable {
    Apc(Per3),
    Qprop(PerformanceTable),
}

impl Reference {
    /// The reference `spec` names, if any (`diameter` [m]: the model's, which turns a QPROP
    /// output's thrust and torque into coefficients); an error names a file that cannot be read.
    pub fn load(spec: &CompareSpec, diameter: f64) -> Result<Option<Reference>> {
        let file_name = |p: &Path| {
            p.file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned())
        };
        Ok(match (&spec.per3, &spec.qprop_output) {
            (Some(p), _) => {
                let per3 = read_per3(p)?;
                let warning = per3.skipped.first().map(|first| {
                    format!(
                        "{}: {} rows of its tables left out (not finite, or beyond any propeller's CT, CP or J), first {first}",
                        p.display(),
                        per3.skipped.len()
                    )
                });
                Some(Reference {
                    name: format!("APC's prediction ({})", file_name(p)),
                    warning,
                    table: ReferenceTable::Apc(per3),
                })
            }
            (None, Some(p)) => Some(Reference {
                name: format!("QPROP's prediction ({})", file_name(p)),
                warning: None,
                table: ReferenceTable::Qprop(qprop_table(&read_qprop_output(p)?, diameter)),
            }),
            (None, None) => None,
        })
    }

    /// (CT, CP) at `rpm` and `j`; None where it has no value.
    pub fn at(&self, rpm: f64, j: f64) -> Option<(f64, f64)> {
        match &self.table {
            ReferenceTable::Apc(p) => p.at(rpm, j),
            ReferenceTable::Qprop(q) => q.at(rpm, j),
        }
    }
}

/// A QPROP output's summary rows as (rpm, J, CT, CP) in propbet's coefficients: from its
/// printed thrust and torque, the output's density and the model's diameter `d` (so that the
/// radius QPROP's own coefficients use does not matter).
fn qprop_table(out: &QpropOutput, d: f64) -> PerformanceTable {
    PerformanceTable::new(out.summary.iter().map(|r| {
        let (v, rpm, thrust, torque) = (r[0].value, r[1].value, r[3].value, r[4].value);
        let omega = propbet_units::rpm_to_omega(rpm);
        let n = propbet_units::rpm_to_rev_per_s(rpm);
        let q = propbet_compare::Quantities::from_forces(thrust, Some(torque), omega, v, out.rho, d);
        [rpm, v / (n * d), q.ct.unwrap_or(f64::NAN), q.cp.unwrap_or(f64::NAN)]
    }))
}
