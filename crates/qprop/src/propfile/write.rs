//! Writing a prop file as QPROP reads it: numbers in fields QPROP's reader takes.

use super::*;

/// Shortest text that reads back as exactly `v` (Rust's shortest round-trip form, in plain or
/// exponent notation, whichever is shorter; Fortran list-directed input reads both).
fn num(v: f64) -> String {
    let plain = format!("{v}");
    let exp = format!("{v:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

pub(super) fn join(vals: &[f64]) -> String {
    vals.iter().map(|&v| num(v)).collect::<Vec<_>>().join(" ")
}

/// Note that QPROP 1.22 reads R on line 2 unscaled; with Rfac != 1 the file means R in r units.
pub fn write_prop(file: &PropFile) -> String {
    let mut out = String::new();
    // One line: a newline or other control character in a name would break the file.
    let name: String = file
        .name
        .replace('!', "|")
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let name = if name.trim().is_empty() {
        "propeller".to_string()
    } else {
        name
    };
    // QPROP reads 128 characters of the line: a longer name is cut, with "..." where it was.
    let mut name = name.trim().to_string();
    if name.len() > QPROP_LINE_MAX - 1 {
        let mut end = QPROP_LINE_MAX - 4;
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        name.truncate(end);
        name.push_str("...");
    }
    // A leading blank keeps a name starting with # from being read as a comment.
    out.push_str(&format!(" {name}\n\n"));
    let mut l2 = vec![file.blades];
    l2.extend(file.radius);
    out.push_str(&format!(" {}   ! Nblades [R]\n\n", join(&l2)));
    let g = &file.global;
    out.push_str(&format!(" {}   ! CL0 CL_a\n", join(&g[0..2])));
    out.push_str(&format!(" {}   ! CLmin CLmax\n\n", join(&g[2..4])));
    out.push_str(&format!(" {}   ! CD0 CD2u CD2l CLCD0\n", join(&g[4..8])));
    out.push_str(&format!(" {}   ! REref REexp\n\n", join(&g[8..10])));
    out.push_str(&format!(" {}   ! Rfac Cfac Bfac\n", join(&file.scale)));
    out.push_str(&format!(" {}   ! Radd Cadd Badd\n\n", join(&file.offset)));
    if let Some(a) = &file.accuracy {
        out.push_str(&a.line());
        out.push_str("\n\n");
    }
    out.push_str("#  r  chord  beta  [CL0 CL_a CLmin CLmax CD0 CD2u CD2l CLCD0 REref REexp]\n");
    for row in &file.rows {
        let mut vals = vec![row.r, row.chord, row.beta];
        vals.extend(&row.coeffs);
        let mut line = format!(" {}", join(&vals));
        for digits in (4..=9).rev() {
            if line.len() <= QPROP_LINE_MAX - 2 {
                break;
            }
            let rounded: Vec<f64> = vals
                .iter()
                .map(|v| format!("{v:.*e}", digits - 1).parse().unwrap_or(*v))
                .collect();
            line = format!(" {}", join(&rounded));
        }
        out.push_str(&line);
        out.push('\n');
    }
    out
}
