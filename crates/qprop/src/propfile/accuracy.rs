//! How well a prop file's geometry is known, as the tool that measured it says: one comment
//! line QPROP skips (`# geometry accuracy: blade_angle_deg=0.03 chord_fraction=0.02`), which
//! propbet writes for a blade it scanned and reads back for the uncertainty band.

use serde::{Deserialize, Serialize};

use super::ParsePropError;

/// The comment line's opening words.
pub const ACCURACY_PREFIX: &str = "# geometry accuracy:";

/// The geometry's own accuracy, ± about the values in the rows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GeometryAccuracy {
    /// Every blade angle, ± [deg].
    pub blade_angle_deg: f64,
    /// Every chord, ± this fraction.
    pub chord: f64,
}

impl GeometryAccuracy {
    /// The largest blade angle the line may hold [deg]: the band adds it to its own ±0.5° in
    /// root-sum-square and moves every blade angle by the sum, within the ±3° a pitch offset
    /// may take (`pitch-offset`'s bounds); a geometry known worse than this is to be measured
    /// again, not banded.
    pub const MAX_ANGLE_DEG: f64 = 2.5;
    /// The largest chord fraction the line may hold: with the band's own ±6 % in
    /// root-sum-square, within the ±15 % a chord scale may take (`chord-scale`'s bounds).
    pub const MAX_CHORD: f64 = 0.13;

    /// The comment line (no newline), in the key=value form [`parse`] reads.
    pub fn line(&self) -> String {
        format!(
            "{ACCURACY_PREFIX} blade_angle_deg={} chord_fraction={}   (the band adds it to its ranges)",
            self.blade_angle_deg, self.chord
        )
    }
}

/// Whether a raw comment line is meant as an accuracy line: its words, blanks and case aside,
/// open with `#geometryaccuracy` (a variant is then an error of [`parse`], never skipped).
pub(super) fn is_accuracy_line(trimmed: &str) -> bool {
    let squeezed: String = trimmed
        .chars()
        .filter(|c| !c.is_whitespace())
        .take(20)
        .collect::<String>()
        .to_lowercase();
    squeezed.starts_with("#geometryaccuracy")
}

/// Reads the accuracy lines found (line number, text): at most one, both keys, each a finite
/// number from 0 to its maximum.
pub(super) fn parse(found: &[(usize, &str)]) -> Result<Option<GeometryAccuracy>, ParsePropError> {
    let Some(&(line, text)) = found.first() else {
        return Ok(None);
    };
    if let Some(&(again, _)) = found.get(1) {
        return Err(ParsePropError::Invalid {
            line: again,
            message: format!("a second '{ACCURACY_PREFIX}' line (the first is line {line})"),
        });
    }
    let invalid = |message: String| ParsePropError::Invalid { line, message };
    if !text.trim_start().starts_with(ACCURACY_PREFIX) {
        return Err(invalid(format!(
            "'{}' is not written as the accuracy line is ({})",
            excerpt(text.trim()),
            expected()
        )));
    }
    let body = text
        .trim_start()
        .strip_prefix(ACCURACY_PREFIX)
        .and_then(|rest| rest.split('(').next())
        .unwrap_or("");
    let mut angle = None;
    let mut chord = None;
    for token in body.split_whitespace() {
        let (key, value) = token
            .split_once('=')
            .ok_or_else(|| invalid(format!("'{}' is not key=value ({})", excerpt(token), expected())))?;
        let (slot, max) = match key {
            "blade_angle_deg" => (&mut angle, GeometryAccuracy::MAX_ANGLE_DEG),
            "chord_fraction" => (&mut chord, GeometryAccuracy::MAX_CHORD),
            _ => return Err(invalid(format!("unknown key '{}' ({})", excerpt(key), expected()))),
        };
        let v: f64 = value
            .parse()
            .map_err(|_| invalid(format!("{key} = '{}' is not a number", excerpt(value))))?;
        if !(0.0..=max).contains(&v) {
            return Err(invalid(format!("{key} = {value} lies outside 0 to {max}")));
        }
        if slot.is_some() {
            return Err(invalid(format!("{key} given twice: once each ({})", expected())));
        }
        *slot = Some(v);
    }
    match (angle, chord) {
        (Some(a), Some(c)) => Ok(Some(GeometryAccuracy {
            blade_angle_deg: a,
            chord: c,
        })),
        _ => Err(invalid(format!("the accuracy line needs both keys ({})", expected()))),
    }
}

fn expected() -> String {
    format!("expected '{ACCURACY_PREFIX} blade_angle_deg=X chord_fraction=Y'")
}

fn excerpt(s: &str) -> String {
    propbet_bemt::units::excerpt(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_written_reads_back() {
        let a = GeometryAccuracy {
            blade_angle_deg: 0.0312,
            chord: 0.0204,
        };
        let line = a.line();
        let back = parse(&[(7, line.as_str())]).unwrap().unwrap();
        assert_eq!(back, a);
        assert_eq!(parse(&[]).unwrap(), None);
    }

    #[test]
    fn a_bad_accuracy_line_is_an_error_naming_its_line_and_value() {
        let err = |text: &str| parse(&[(5, text)]).unwrap_err().to_string();
        let e = err("# geometry accuracy: blade_angle_deg=nan chord_fraction=0.02");
        assert!(e.starts_with("line 5: blade_angle_deg = nan lies outside"), "{e}");
        let e = err("# geometry accuracy: blade_angle_deg=-1 chord_fraction=0.02");
        assert!(e.contains("blade_angle_deg = -1 lies outside 0 to 2.5"), "{e}");
        let e = err("# geometry accuracy: blade_angle_deg=4 chord_fraction=0.02");
        assert!(e.contains("blade_angle_deg = 4 lies outside 0 to 2.5"), "{e}");
        for variant in [
            "#geometry accuracy: blade_angle_deg=1 chord_fraction=0.02",
            "# Geometry Accuracy: blade_angle_deg=1 chord_fraction=0.02",
        ] {
            assert!(is_accuracy_line(variant), "{variant}");
            let e = err(variant);
            assert!(e.contains("is not written as the accuracy line is"), "{e}");
        }
        assert!(!is_accuracy_line("# geometry of the blade"));
        let e = err("# geometry accuracy: blade_angle_deg=1 blade_angle_deg=2 chord_fraction=0.02");
        assert!(e.contains("blade_angle_deg given twice"), "{e}");
        let e = err("# geometry accuracy: blade_angle_deg=abc chord_fraction=0.02");
        assert!(e.contains("'abc' is not a number"), "{e}");
        let e = err("# geometry accuracy: blade_angle_deg=1");
        assert!(e.contains("needs both keys"), "{e}");
        let e = err("# geometry accuracy: twist=1 chord_fraction=0.02");
        assert!(e.contains("unknown key 'twist'"), "{e}");
        let two = parse(&[
            (3, "# geometry accuracy: blade_angle_deg=1 chord_fraction=0.02"),
            (9, "x"),
        ]);
        assert!(two.unwrap_err().to_string().starts_with("line 9: a second"));
    }
}
