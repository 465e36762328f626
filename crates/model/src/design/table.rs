//! A plain blade table (CSV): a header naming radius, chord and blade angle (with a length
//! unit), then one station per line, optionally each station's thickness ratio and airfoil.

/// A plain table read: (r [m], chord [m], beta [deg]) per station, with each station's
/// airfoil and thickness ratio where the table has them.
pub(super) struct Table {
    pub(super) rows: Vec<(f64, f64, f64)>,
    pub(super) airfoils: Vec<Option<String>>,
    pub(super) thickness: Vec<Option<f64>>,
}

/// The columns of a table's header: radius, chord, blade angle (each index), their length unit
/// [m] when the header says one, and the optional thickness and airfoil columns.
pub(super) struct Columns {
    r: usize,
    chord: usize,
    beta: usize,
    unit: Option<f64>,
    thickness: Option<usize>,
    airfoil: Option<usize>,
}

pub(super) fn table_columns(header: &str) -> std::result::Result<Columns, String> {
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_ascii_lowercase()).collect();
    let base = |s: &str| s.split('(').next().unwrap_or_default().trim().to_string();
    let find = |want: &[&str]| names.iter().position(|n| want.contains(&base(n).as_str()));
    let r = find(&["r", "radius"]).ok_or("no radius column (`r (mm)`, `radius`)")?;
    let chord = find(&["chord", "c"]).ok_or("no chord column (`chord (mm)`)")?;
    let beta = find(&["beta", "blade angle", "twist", "pitch angle"]).ok_or("no blade-angle column (`beta (deg)`)")?;
    let unit_of = |i: usize| -> std::result::Result<Option<f64>, String> {
        match names[i].split_once('(') {
            None => Ok(None),
            Some((_, u)) => {
                let u = u.trim_end_matches(')').trim();
                propbet_settings::values::parse_length_unit(u)
                    .map(Some)
                    .map_err(|_| format!("column `{}`: unit '{u}' is not m, cm, mm or in", names[i]))
            }
        }
    };
    let (ur, uc) = (unit_of(r)?, unit_of(chord)?);
    if ur != uc {
        return Err("the radius and chord columns must have the same unit".into());
    }
    if let Some((_, u)) = names[beta].split_once('(') {
        let u = u.trim_end_matches(')').trim();
        if !matches!(u, "deg" | "degrees" | "°") {
            return Err(format!(
                "column `{}`: the blade angle is in degrees (`deg`)",
                names[beta]
            ));
        }
    }
    Ok(Columns {
        r,
        chord,
        beta,
        unit: ur,
        thickness: find(&["t/c", "thickness", "thickness ratio"]),
        airfoil: find(&["airfoil", "section"]),
    })
}

/// Reads a plain table (header, then one station per line; `#` comments).
pub(super) fn read_table(text: &str, units: Option<f64>) -> std::result::Result<Table, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (_, header) = lines.next().ok_or("empty")?;
    let c = table_columns(header)?;
    let unit = match (c.unit, units) {
        (Some(u), _) | (None, Some(u)) => u,
        (None, None) => {
            return Err(
                "the radius and chord columns name no unit: write `r (mm)`, `chord (mm)`, or give --units".into(),
            )
        }
    };
    let mut t = Table {
        rows: Vec::new(),
        airfoils: Vec::new(),
        thickness: Vec::new(),
    };
    for (i, line) in lines {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        let bad = |m: String| format!("line {}: {m}", i + 1);
        let num = |k: usize, what: &str| -> std::result::Result<f64, String> {
            let s = f.get(k).copied().unwrap_or_default();
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(format!("{what} '{}' is not a number", propbet_units::excerpt(s))))
        };
        let r = num(c.r, "radius")? * unit;
        let chord = num(c.chord, "chord")? * unit;
        let beta = num(c.beta, "blade angle")?;
        if r < 0.0 || chord <= 0.0 || beta.abs() >= 90.0 {
            return Err(bad(format!(
                "r = {}, chord = {}, beta = {beta}: radius at least 0, chord above 0, |beta| below 90 deg",
                propbet_units::show(r),
                propbet_units::show(chord)
            )));
        }
        if let Some(&(last, _, _)) = t.rows.last() {
            if r <= last {
                return Err(bad("the radius must increase from row to row".into()));
            }
        }
        t.rows.push((r, chord, beta));
        t.thickness.push(match c.thickness {
            Some(k) if f.get(k).is_some_and(|s| !s.is_empty()) => {
                let v = propbet_settings::values::parse_fraction(f[k]).map_err(|e| bad(e.to_string()))?;
                if !(v > 0.0 && v < 0.5) {
                    return Err(bad(format!("t/c {v} is not between 0 and 0.5")));
                }
                Some(v)
            }
            _ => None,
        });
        t.airfoils.push(
            c.airfoil
                .and_then(|k| f.get(k))
                .filter(|s| !s.is_empty())
                .map(|s| s.to_string()),
        );
    }
    if t.rows.len() < 2 {
        return Err("fewer than two stations".into());
    }
    Ok(t)
}
