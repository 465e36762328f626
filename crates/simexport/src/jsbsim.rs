//! JSBSim's `<propeller>`: C_THRUST(J) and C_POWER(J) at one RPM, the other RPMs as
//! CT_MACH and CP_MACH factors on the helical tip Mach number (FGPropeller's only
//! RPM-dependent tables), and the blade's inertia where none is given.

use std::fmt::Write as _;

use super::*;

/// A curve's factor on the reference curve in column `col` (1: CT, 2: CP): the relative least
/// squares over their shared J range, at the reference's counted points.
fn factor(reference: &Curve, c: &Curve, col: usize) -> f64 {
    let ref_max = reference.rows.iter().map(|r| r[1]).fold(0.0, f64::max);
    let (mut num, mut den) = (0.0, 0.0);
    for r in &c.rows {
        let j = r[0];
        if j < reference.rows[0][0] || j > reference.rows[reference.rows.len() - 1][0] {
            continue;
        }
        if curve_at(reference, j, 1) < COUNTED * ref_max {
            continue;
        }
        let f = r[col] / curve_at(reference, j, col);
        if f.is_finite() && f > 0.0 {
            num += 1.0 / f;
            den += 1.0 / (f * f);
        }
    }
    if den > 0.0 {
        num / den
    } else {
        1.0
    }
}

/// The `<propeller>` element with its header comment `c`: the tables C_THRUST and C_POWER, and
/// CT_MACH and CP_MACH where there are several RPMs.
fn propeller_xml(
    src: &Source,
    ixx: f64,
    c: &str,
    [ct_table, cp_table]: [&[(f64, f64)]; 2],
    mach: Option<[&[(f64, f64)]; 2]>,
) -> String {
    let mut s = format!("<?xml version=\"1.0\"?>\n<!--\n{}-->\n", xml_comment(c));
    let _ = writeln!(s, "<propeller name=\"{}\">", xml_text(&src.name));
    let _ = writeln!(s, "  <ixx unit=\"KG*M2\"> {ixx:.6e} </ixx>");
    let _ = writeln!(s, "  <diameter unit=\"M\"> {:.5} </diameter>", src.diameter);
    let _ = writeln!(s, "  <numblades> {} </numblades>", src.blades.round().max(1.0));
    let _ = writeln!(s, "  <gearratio> 1 </gearratio>");
    let table = |s: &mut String, name: &str, rows: &[(f64, f64)]| {
        let _ = writeln!(s, "  <table name=\"{name}\" type=\"internal\">\n    <tableData>");
        for (x, y) in rows {
            let _ = writeln!(s, "      {x:8.4} {y:10.6}");
        }
        let _ = writeln!(s, "    </tableData>\n  </table>");
    };
    table(&mut s, "C_THRUST", ct_table);
    table(&mut s, "C_POWER", cp_table);
    if let Some([ctm, cpm]) = mach {
        table(&mut s, "CT_MACH", ctm);
        table(&mut s, "CP_MACH", cpm);
    }
    s.push_str("</propeller>\n");
    s
}

/// JSBSim's `<propeller>`: C_THRUST and C_POWER against J at a reference RPM, and the other
/// RPMs as CT_MACH and CP_MACH factors on the helical tip Mach number.
pub fn jsbsim(src: &Source) -> Result<Exported> {
    check(src)?;
    let Some((ixx, ixx_how)) = src.ixx.clone() else {
        unsuited!(
            "JSBSim's propeller needs its moment of inertia: give --prop (estimated from the blade's chords) \
             or --ixx (kg m^2)"
        );
    };
    let cs = curves(src);
    if cs.is_empty() {
        return Err(too_few_curves(src, "JSBSim's C_THRUST(J) and C_POWER(J)"));
    }
    // The reference: the curve reaching the largest J (ties: the middle RPM).
    let span = |c: &Curve| c.rows[c.rows.len() - 1][0] - c.rows[0][0];
    let best = cs.iter().map(span).fold(0.0, f64::max);
    let candidates: Vec<&Curve> = cs.iter().filter(|c| span(c) >= best - 1e-9).collect();
    let reference = candidates[candidates.len() / 2].clone();
    let d = src.diameter;
    let tip_mach = |rpm: f64, j: f64| {
        std::f64::consts::PI * rpm_to_rev_per_s(rpm) * d * (1.0 + (j / std::f64::consts::PI).powi(2)).sqrt() / SOUND
    };
    let mut mach: Vec<(f64, f64, f64)> = cs
        .iter()
        .map(|c| (tip_mach(c.rpm, 0.0), factor(&reference, c, 1), factor(&reference, c, 2)))
        .collect();
    mach.sort_by(|a, b| a.0.total_cmp(&b.0));
    mach.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-6);
    let ct_table: Vec<(f64, f64)> = reference.rows.iter().map(|r| (r[0], r[1])).collect();
    let cp_table: Vec<(f64, f64)> = reference.rows.iter().map(|r| (r[0], r[2])).collect();
    let ctm: Vec<(f64, f64)> = mach.iter().map(|m| (m.0, m.1)).collect();
    let cpm: Vec<(f64, f64)> = mach.iter().map(|m| (m.0, m.2)).collect();
    let with_mach = mach.len() > 1;
    let model = |p: &Point| {
        let m = tip_mach(p.rpm, p.j);
        let (ft, fp) = if with_mach {
            (lookup(&ctm, m), lookup(&cpm, m))
        } else {
            (1.0, 1.0)
        };
        (lookup(&ct_table, p.j) * ft, lookup(&cp_table, p.j) * fp)
    };
    let pts = counted(&src.points);
    let pairs: Vec<(f64, f64, f64, f64)> = pts
        .iter()
        .map(|p| {
            let (ct, cp) = model(p);
            (ct, p.ct, cp, p.cp)
        })
        .collect();
    let fit = fit_of(&pairs);
    let mut c = header(src, "JSBSim propeller", &fit, "  ");
    let _ = writeln!(
        c,
        "  C_THRUST and C_POWER: the {:.0} rpm curve{}.\n  {}\n  ixx: {}.",
        reference.rpm,
        if src.measured {
            format!(" ({SMOOTHING})")
        } else {
            String::new()
        },
        if with_mach {
            format!(
                "CT_MACH and CP_MACH: the other RPMs ({}) as factors on those tables, placed at each RPM's \
                 static tip Mach number (speed of sound {SOUND} m/s); between RPMs JSBSim interpolates, beyond \
                 them it holds the end factor. The RPM dependence is mostly a Reynolds-number effect, carried \
                 here by the only RPM-dependent tables JSBSim's format has.",
                cs.iter()
                    .map(|c| format!("{:.0}", c.rpm))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        } else {
            "One RPM only: no CT_MACH or CP_MACH table; JSBSim uses these coefficients at every RPM.".into()
        },
        ixx_how
    );
    let s = propeller_xml(src, ixx, &c, [&ct_table, &cp_table], with_mach.then_some([&ctm, &cpm]));
    let file = format!("{}.xml", file_stem(&src.name));
    Ok(Exported {
        target: Target::Jsbsim,
        files: vec![(file, s)],
        fit,
        values: format!(
            "C_THRUST/C_POWER at {:.0} rpm, {} rows; {} RPMs in CT_MACH/CP_MACH; ixx {ixx:.3e} kg m^2",
            reference.rpm,
            ct_table.len(),
            if with_mach { mach.len() } else { 0 }
        ),
    })
}

/// The blade's moment of inertia about the shaft, estimated from its chords: B times the
/// integral of (material density x section area x r^2), the section area 0.685 t c (a NACA
/// 4-digit section's) at a thickness `t_c` of the chord. Radii and chords in metres.
pub fn blade_ixx(blades: f64, r: &[f64], chord: &[f64], t_c: f64, density: f64) -> f64 {
    let f = |k: usize| density * 0.685 * t_c * chord[k] * chord[k] * r[k] * r[k];
    let mut sum = 0.0;
    for k in 1..r.len().min(chord.len()) {
        sum += 0.5 * (f(k - 1) + f(k)) * (r[k] - r[k - 1]);
    }
    blades * sum
}

/// What [`blade_ixx`] assumes, for the files.
pub const IXX_ASSUMED: (f64, f64) = (0.10, 1200.0);
