//! A blade file's rows as `propbet prop` reads them, in SI.

use propbet_qprop::{PropFile, RadiusReading};

use super::{csv_rows, Error, Num};

/// A prop file's rows in SI: radius, chord, blade angle and the ten QPROP section
/// coefficients of each row (a row's own, or the file's global ones), as a table (CSV).
pub fn csv(file: &PropFile) -> Result<Vec<u8>, Error> {
    let blade = file.to_blade(RadiusReading::Documented);
    let rows = (0..blade.r.len()).map(|i| {
        let c = &blade.coeffs[i];
        StationRow {
            r_m: blade.r[i].into(),
            r_over_tip: (blade.r[i] / blade.tip_radius).into(),
            chord_m: blade.chord[i].into(),
            beta_deg: blade.beta[i].to_degrees().into(),
            cl0: c.cl0.into(),
            cl_a_per_rad: c.cl_a.into(),
            cl_min: c.cl_min.into(),
            cl_max: c.cl_max.into(),
            cd0: c.cd0.into(),
            cd2u: c.cd2u.into(),
            cd2l: c.cd2l.into(),
            cl_cd0: c.clcd0.into(),
            re_ref: c.re_ref.into(),
            re_exp: c.re_exp.into(),
        }
    });
    Ok(csv_rows(rows, true)?)
}

/// A prop file's row in SI.
#[derive(serde::Serialize)]
struct StationRow {
    r_m: Num,
    r_over_tip: Num,
    chord_m: Num,
    beta_deg: Num,
    cl0: Num,
    cl_a_per_rad: Num,
    cl_min: Num,
    cl_max: Num,
    cd0: Num,
    cd2u: Num,
    cd2l: Num,
    cl_cd0: Num,
    re_ref: Num,
    re_exp: Num,
}
