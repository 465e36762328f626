//! Values as users write them (flags and case files): number lists and ranges, and quantities
//! with units, converted to SI here, once; and back to text for a stage's command line.

use crate::{Error, Result};

/// `Option` or `Result` → `Result` with an [`Error::Value`]: the flag, the text, and the
/// problem `f` says.
trait OrValue<T> {
    fn or_value(self, flag: &str, text: &str, f: impl FnOnce() -> String) -> Result<T>;
}

impl<T, E> OrValue<T> for std::result::Result<T, E> {
    fn or_value(self, flag: &str, text: &str, f: impl FnOnce() -> String) -> Result<T> {
        self.map_err(|_| Error::value(flag, text, f()))
    }
}

impl<T> OrValue<T> for Option<T> {
    fn or_value(self, flag: &str, text: &str, f: impl FnOnce() -> String) -> Result<T> {
        self.ok_or_else(|| Error::value(flag, text, f()))
    }
}

/// Parses a comma-separated list whose items are numbers, `start:stop:step` (inclusive) or
/// `start:stop/N` (N points).
pub fn parse_list(flag: &str, text: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for item in text.split(',').map(str::trim) {
        if item.is_empty() {
            return Err(Error::value(flag, text, "empty item"));
        }
        let num = |s: &str| -> Result<f64> {
            let v: f64 = s
                .trim()
                .parse()
                .or_value(flag, text, || format!("'{s}' is not a number"))?;
            if !v.is_finite() {
                return Err(Error::value(flag, text, format!("'{s}' is not a finite number")));
            }
            Ok(v)
        };
        if let Some((a, rest)) = item.split_once(':') {
            let start = num(a)?;
            if let Some((b, n)) = rest.split_once('/') {
                let stop = num(b)?;
                let n: usize = n
                    .trim()
                    .parse()
                    .or_value(flag, text, || format!("'{n}' is not a whole number of points"))?;
                if n == 0 || n > 1_000_000 {
                    return Err(Error::value(
                        flag,
                        text,
                        format!("the number of points must be 1..1000000, found {n}"),
                    ));
                }
                if n == 1 {
                    out.push(start);
                } else {
                    out.extend((0..n).map(|i| start + (stop - start) * i as f64 / (n - 1) as f64));
                }
            } else {
                let (b, step) = rest
                    .split_once(':')
                    .or_value(flag, text, || "use start:stop:step or start:stop/N".into())?;
                let stop = num(b)?;
                let step = num(step)?;
                if step <= 0.0 {
                    return Err(Error::value(
                        flag,
                        text,
                        format!("the step must be positive, found {step}"),
                    ));
                }
                let count = ((stop - start) / step + 1e-9).floor();
                if count < 0.0 {
                    return Err(Error::value(flag, text, format!("stop {stop} is below start {start}")));
                }
                if count > 1e6 {
                    return Err(Error::value(flag, text, "more than a million points"));
                }
                out.extend((0..=count as usize).map(|i| start + step * i as f64));
            }
        } else {
            out.push(num(item)?);
        }
    }
    Ok(out)
}

/// Splits `12.5hPa` into (12.5, "hPa").
fn split_unit(text: &str) -> Option<(f64, &str)> {
    let t = text.trim();
    let k = t
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .unwrap_or(t.len());
    // An exponent marker followed by letters is a unit, not an exponent ("5e" never occurs).
    let (num, unit) = t.split_at(k);
    num.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map(|v| (v, unit.trim()))
}

/// A temperature with a unit suffix (`15C`, `288.15K`, `59F`) [K].
pub fn parse_temperature(text: &str) -> Result<f64> {
    let (v, unit) = split_unit(text).or_value("--temp", text, || "not a number with a unit".into())?;
    Ok(match unit {
        "C" | "degC" | "°C" | "ºC" => v + 273.15,
        "K" => v,
        "F" | "degF" | "°F" => (v - 32.0) * 5.0 / 9.0 + 273.15,
        "" => return Err(Error::value("--temp", text, "give a unit: C, K or F (for example 20C)")),
        u => {
            return Err(Error::value(
                "--temp",
                text,
                format!("unknown temperature unit '{u}' (use C, K or F)"),
            ))
        }
    })
}

/// A pressure, Pa unless suffixed (`Pa`, `hPa`, `mbar`, `kPa`, `bar`, `inHg`, `psi`) [Pa].
pub fn parse_pressure(text: &str) -> Result<f64> {
    let (v, unit) = split_unit(text).or_value("--pressure", text, || "not a number".into())?;
    Ok(v * match unit {
        "" | "Pa" => 1.0,
        "hPa" | "mbar" => 100.0,
        "kPa" => 1000.0,
        "bar" => 1e5,
        "inHg" => 3386.389,
        "psi" => 6894.757,
        u => {
            return Err(Error::value(
                "--pressure",
                text,
                format!("unknown pressure unit '{u}' (use Pa, hPa, mbar, kPa, bar, inHg or psi)"),
            ))
        }
    })
}

/// Relative humidity in percent (`45%` or `45`) or as a fraction below 1 with no suffix is
/// ambiguous, so a bare number is read as percent [-, 0..1].
pub fn parse_humidity(text: &str) -> Result<f64> {
    let (v, unit) = split_unit(text).or_value("--humidity", text, || "not a number".into())?;
    match unit {
        "" | "%" => Ok(v / 100.0),
        u => Err(Error::value(
            "--humidity",
            text,
            format!("unknown unit '{u}' (give percent, for example 45%)"),
        )),
    }
}

/// Forced transition as `--trip` and `[polars] trip` give it: `free` (or 1, the trailing edge)
/// for free transition by Ncrit alone, else the chord fraction in (0, 1) where transition is
/// forced on both surfaces at the latest.
pub fn parse_trip(text: &str) -> Result<Option<f64>> {
    let t = text.trim();
    if t == "free" {
        return Ok(None);
    }
    let trip = crate::TRIP;
    match t.parse::<f64>() {
        // At the trailing edge: no forcing, free transition.
        Ok(x) if trip.check(x).is_ok() => Ok(Some(x).filter(|x| *x < 1.0)),
        // The value as written (`nan`, not Rust's `NaN`).
        _ => Err(trip
            .bad(propbet_bemt::units::excerpt(t), trip.allowed_meaning().to_string())
            .into()),
    }
}

/// A length unit for prop-file radii and chords: metres per unit.
pub fn parse_length_unit(text: &str) -> Result<f64> {
    Ok(match text {
        "m" => 1.0,
        "cm" => 0.01,
        "mm" => 0.001,
        "in" | "inch" => 0.0254,
        u => return Err(Error::value("--units", u, "unknown length unit (use m, cm, mm or in)")),
    })
}

/// A length with its unit (`10in`, `254mm`, `2.54e-1m`) [m], for the flag `flag`: a bare
/// number is refused (metres or inches, only the unit can say).
pub fn parse_length(flag: &str, text: &str) -> Result<f64> {
    let (v, unit) =
        split_unit(text).or_value(flag, text, || "not a number with its unit, like 10in or 0.254m".into())?;
    if unit.is_empty() {
        return Err(Error::value(
            flag,
            text,
            "give its unit: m, cm, mm or in (for example 10in or 0.254m)",
        ));
    }
    let scale = parse_length_unit(unit).map_err(|_| {
        Error::value(
            flag,
            text,
            format!("unknown length unit '{unit}' (use m, cm, mm or in)"),
        )
    })?;
    Ok(v * scale)
}

/// The name of a length unit of [`parse_length_unit`] from its metres per unit.
pub fn length_unit_name(metres: f64) -> Option<&'static str> {
    [("m", 1.0), ("cm", 0.01), ("mm", 0.001), ("in", 0.0254)]
        .into_iter()
        .find(|u| u.1 == metres)
        .map(|u| u.0)
}

/// `T,P,RH` split into its three parts, a bare temperature given its unit (°C).
pub(crate) fn split_atmosphere(text: &str) -> Result<[String; 3]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(Error::value(
            "--atmosphere",
            text,
            "give temperature, pressure and humidity, for example 22,1009hPa,40",
        ));
    }
    let t = if parts[0].parse::<f64>().is_ok() {
        format!("{}C", parts[0])
    } else {
        parts[0].to_string()
    };
    Ok([t, parts[1].to_string(), parts[2].to_string()])
}

/// `T,P,RH` with optional units (temperature °C unless suffixed K or F; pressure Pa unless
/// suffixed; humidity %).
pub fn parse_atmosphere(text: &str) -> Result<propbet_atmosphere::AirState> {
    let [t, p, rh] = split_atmosphere(text)?;
    propbet_atmosphere::AirState::new(parse_temperature(&t)?, parse_pressure(&p)?, parse_humidity(&rh)?)
        .map_err(|e| Error::value("--atmosphere", text, e))
}

/// The shortest decimal text of a value in the user's unit that converts back to exactly
/// `si` (`from_user(text) == si`): 5000 rpm prints as `5000`, not `5000.000000000001`.
pub fn scaled_text(si: f64, to_user: impl Fn(f64) -> f64, from_user: impl Fn(f64) -> f64) -> String {
    let user = to_user(si);
    for digits in 1..=17 {
        let text = format!("{:.*e}", digits - 1, user);
        if let Ok(v) = text.parse::<f64>() {
            if from_user(v) == si {
                return format!("{v}");
            }
        }
    }
    format!("{user}")
}

/// A list as [`parse_list`] reads it back exactly: `start:stop:step` where that gives the
/// same numbers, else the numbers separated by commas.
pub fn list_text(v: &[f64]) -> String {
    if v.len() >= 3 {
        // The numbers as a user would write them (0.7, not 0.7000000000000001) first.
        let short = |x: f64| format!("{x:.9e}").parse::<f64>().unwrap_or(x);
        let (first, last, step) = (v[0], v[v.len() - 1], v[1] - v[0]);
        for stop in [short(last), last] {
            let points = format!("{first}:{stop}/{}", v.len());
            if parse_list("", &points).is_ok_and(|r| r == v) {
                // The step form where it reads as plainly (0:0.7:0.025), else N points.
                let step_form = format!("{first}:{stop}:{}", short(step));
                if parse_list("", &step_form).is_ok_and(|r| r == v) {
                    return step_form;
                }
                return points;
            }
        }
        for (stop, step) in [
            (short(last), short(step)),
            (last, short(step)),
            (short(last), step),
            (last, step),
        ] {
            let range = format!("{first}:{stop}:{step}");
            if parse_list("", &range).is_ok_and(|r| r == v) {
                return range;
            }
        }
    }
    v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(",")
}

/// Rotation speeds [rad/s] as the rpm list a flag takes, read back exactly: each speed as the
/// shortest rpm text that converts back to it ([`scaled_text`]), the list as [`list_text`]
/// writes it (which reads back to exactly those numbers).
pub fn rpm_list_text(omegas: &[f64]) -> String {
    let rpm: Vec<f64> = omegas
        .iter()
        .map(|&w| rpm_text(w).parse().unwrap_or(f64::NAN))
        .collect();
    list_text(&rpm)
}

/// Revolutions per minute of `omega` [rad/s], as text that reads back exactly.
pub fn rpm_text(omega: f64) -> String {
    use propbet_bemt::units::{omega_to_rpm, rpm_to_omega};
    scaled_text(omega, omega_to_rpm, rpm_to_omega)
}

/// A thickness ratio written as `0.06` or `6%`.
pub fn parse_fraction(text: &str) -> crate::Result<f64> {
    let t = text.trim();
    let (num, scale) = match t.strip_suffix('%') {
        Some(n) => (n, 0.01),
        None => (t, 1.0),
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| crate::Error::value("--thickness", t, "not a number (a fraction as 0.06 or 6%)"))?;
    Ok(v * scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str, expected: &[f64]) {
        let got = parse_list("--x", text).unwrap();
        assert_eq!(got.len(), expected.len(), "{text}: {got:?}");
        for (g, e) in got.iter().zip(expected) {
            assert!((g - e).abs() < 1e-12, "{text}: {got:?}");
        }
    }

    #[test]
    fn lists_and_ranges() {
        check("4000,6000", &[4000.0, 6000.0]);
        check("0:0.2:0.05", &[0.0, 0.05, 0.1, 0.15, 0.2]);
        check("0:20/3", &[0.0, 10.0, 20.0]);
        check("1, 2:3:1", &[1.0, 2.0, 3.0]);
        assert_eq!(parse_list("--j", "0:0.8:0.05").unwrap().len(), 17);
        for bad in ["", "a", "1,,2", "0:1:0", "1:0:0.1", "0:1/0", "nan", "0:1"] {
            assert!(parse_list("--x", bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn lists_print_back_exactly() {
        assert_eq!(list_text(&parse_list("", "0.2:0.96/20").unwrap()), "0.2:0.96/20");
        for text in [
            "0:0.7:0.025",
            "4000,5000,6000",
            "0:20/7",
            "1,2,5",
            "-8:16:1",
            "0.15:0.97/25",
        ] {
            let v = parse_list("--x", text).unwrap();
            let back = list_text(&v);
            assert_eq!(parse_list("--x", &back).unwrap(), v, "{text} -> {back}");
        }
        assert_eq!(list_text(&parse_list("", "0:0.7:0.025").unwrap()), "0:0.7:0.025");
        let w: Vec<f64> = [4000.0, 5000.0, 6000.0].map(propbet_bemt::units::rpm_to_omega).to_vec();
        assert_eq!(rpm_list_text(&w), "4000:6000:1000");
        assert_eq!(scaled_text(0.4, |x| 100.0 * x, |x| x / 100.0), "40");
        assert_eq!(length_unit_name(0.0254), Some("in"));
    }

    #[test]
    fn units() {
        assert!((parse_temperature("15C").unwrap() - 288.15).abs() < 1e-12);
        assert!((parse_temperature("59F").unwrap() - 288.15).abs() < 1e-9);
        assert!(parse_temperature("15").is_err());
        assert!(parse_temperature("15Q")
            .unwrap_err()
            .to_string()
            .contains("unknown temperature unit 'Q'"));
        assert_eq!(parse_pressure("1013.25hPa").unwrap(), 101325.0);
        assert_eq!(parse_pressure("101325").unwrap(), 101325.0);
        assert!(parse_pressure("1atm").is_err());
        assert_eq!(parse_humidity("50%").unwrap(), 0.5);
        assert_eq!(parse_length_unit("in").unwrap(), 0.0254);
        assert!(parse_length_unit("furlong").is_err());
        assert!((parse_length("--diameter", "2.54e-1m").unwrap() - 0.254).abs() < 1e-15);
        assert_eq!(parse_length("--diameter", "10in").unwrap(), 0.254);
        let e = parse_length("--diameter", "6").unwrap_err().to_string();
        assert!(e.starts_with("--diameter '6': give its unit"), "{e}");
        let e = parse_length("--diameter", "6furlong").unwrap_err().to_string();
        assert!(
            e.starts_with("--diameter '6furlong': unknown length unit 'furlong'"),
            "{e}"
        );
    }
}
