//! Numbers as propbet's tables print them: 7 significant digits, trailing zeros dropped, an
//! empty cell for a number not given ([`push_num`], [`Num`]), and the number a written text
//! says ([`written`]); rows of these as CSV ([`csv_rows`]).

const POW10: [f64; 65] = [
    1e-32, 1e-31, 1e-30, 1e-29, 1e-28, 1e-27, 1e-26, 1e-25, 1e-24, 1e-23, 1e-22, 1e-21, 1e-20, 1e-19, 1e-18, 1e-17,
    1e-16, 1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1,
    1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21,
    1e22, 1e23, 1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31, 1e32,
];

/// A number as propbet's tables print it: 7 significant digits ([`push_num`]), an empty cell
/// for `None` and for a value that is not finite. Table rows are structs of these, written by
/// `csv` + serde ([`csv_rows`]), so a header cannot drift from its values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub Option<f64>);

impl From<f64> for Num {
    fn from(v: f64) -> Self {
        Num(Some(v))
    }
}

impl From<Option<f64>> for Num {
    fn from(v: Option<f64>) -> Self {
        Num(v)
    }
}

impl serde::Serialize for Num {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        if !s.is_human_readable() {
            // The number the text says, for tables handed over as columns (`columns`): none
            // where the text would be an empty cell.
            return match self.0.and_then(written) {
                Some(v) => s.serialize_f64(v),
                None => s.serialize_none(),
            };
        }
        // One buffer per thread: a 20,000-row table has 340,000 cells.
        thread_local! {
            static BUF: std::cell::RefCell<Vec<u8>> = std::cell::RefCell::new(Vec::with_capacity(32));
        }
        BUF.with(|b| {
            let mut b = b.borrow_mut();
            b.clear();
            push_num(&mut b, self.0);
            s.serialize_str(std::str::from_utf8(&b).unwrap_or_default())
        })
    }
}

/// Rows as CSV, with the header from the row type's field names when `header`.
pub fn csv_rows<T: serde::Serialize>(rows: impl IntoIterator<Item = T>, header: bool) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::WriterBuilder::new().has_headers(header).from_writer(Vec::new());
    for r in rows {
        w.serialize(r)?;
    }
    bytes(w)
}

/// The bytes a CSV writer over memory wrote, once it is flushed.
pub fn bytes(w: csv::Writer<Vec<u8>>) -> Result<Vec<u8>, csv::Error> {
    w.into_inner().map_err(|e| e.into_error().into())
}

/// Significant digits written by [`push_num`].
const DIGITS: i32 = 7;

fn pow10(e: i32) -> f64 {
    if (-32..=32).contains(&e) {
        POW10[(e + 32) as usize]
    } else {
        10f64.powi(e)
    }
}

/// `a` (positive, normal, within 1e-290..1e290) as 7 decimal digits `m` and the exponent of
/// the first: a = m × 10^(e10 − 6), rounded.
fn decimal(a: f64) -> (u32, i32) {
    // Decimal exponent from the binary one, then corrected against the table.
    let e2 = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut e10 = (e2 as f64 * std::f64::consts::LOG10_2).floor() as i32;
    if a >= pow10(e10 + 1) {
        e10 += 1;
    } else if a < pow10(e10) {
        e10 -= 1;
    }
    let scaled = if DIGITS - 1 - e10 >= 0 {
        a * pow10(DIGITS - 1 - e10)
    } else {
        a / pow10(e10 - DIGITS + 1)
    };
    let mut m = scaled.round() as u32;
    if m >= 10_000_000 {
        m = (m + 5) / 10;
        e10 += 1;
    }
    (m, e10)
}

/// `v` as [`push_num`] writes it, read back: the number of the written digits (None where the
/// cell is empty). Computed without the text where the decimal power is exact (10^0 to
/// 10^22), so one division or product of exact numbers rounds it as reading the text does.
pub fn written(v: f64) -> Option<f64> {
    if !v.is_finite() {
        return None;
    }
    let a = v.abs();
    if a == 0.0 {
        return Some(0.0);
    }
    if (1e-15..1e22).contains(&a) {
        let (m, e10) = decimal(a);
        let k = DIGITS - 1 - e10;
        let r = if k >= 0 {
            m as f64 / pow10(k)
        } else {
            m as f64 * pow10(-k)
        };
        return Some(r.copysign(v));
    }
    let mut b = Vec::new();
    push_num(&mut b, Some(v));
    std::str::from_utf8(&b).ok().and_then(|t| t.parse().ok())
}

/// Appends `v` with 7 significant digits (the solver's accuracy: its Newton exit,
/// |d psi| < 1e-6 as QPROP's, leaves ~1e-7 relative error; QPROP prints 4), trailing zeros dropped, in plain notation from 1e-5 to
/// 1e16 and exponent notation outside; an empty cell for `None`. Hand-written because it runs
/// for every cell of a 20,000-row table and `format!` with a precision is several times slower.
pub fn push_num(buf: &mut Vec<u8>, v: Option<f64>) {
    let Some(v) = v else { return };
    if v == 0.0 {
        buf.push(b'0');
        return;
    }
    if !v.is_finite() {
        // No value: an empty cell, never `NaN` or `inf` in a table a user reads on.
        return;
    }
    let a = v.abs();
    if !(1e-290..1e290).contains(&a) {
        // Beyond the power table (and subnormal numbers, whose binary exponent is not their
        // decimal one): the standard formatter, 7 significant digits.
        let e = format!("{v:.6e}");
        let (m, exp) = e.split_once('e').unwrap_or((&e, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        buf.extend_from_slice(format!("{m}e{exp}").as_bytes());
        return;
    }
    let (mut m, e10) = decimal(a);
    let mut digits = [0u8; DIGITS as usize];
    for d in digits.iter_mut().rev() {
        *d = b'0' + (m % 10) as u8;
        m /= 10;
    }
    let nd = (DIGITS as usize - digits.iter().rev().take_while(|&&d| d == b'0').count()).max(1);
    let digits = &digits[..nd];
    let mut out = [0u8; 40];
    let mut n = 0;
    let mut put = |bytes: &[u8]| {
        out[n..n + bytes.len()].copy_from_slice(bytes);
        n += bytes.len();
    };
    if v < 0.0 {
        put(b"-");
    }
    if (-5..16).contains(&e10) {
        if e10 >= 0 {
            let int_len = e10 as usize + 1;
            if nd <= int_len {
                put(digits);
                put(&b"0000000000000000"[..int_len - nd]);
            } else {
                put(&digits[..int_len]);
                put(b".");
                put(&digits[int_len..]);
            }
        } else {
            put(b"0.");
            put(&b"0000"[..(-e10 - 1) as usize]);
            put(digits);
        }
    } else {
        put(&digits[..1]);
        if nd > 1 {
            put(b".");
            put(&digits[1..]);
        }
        put(b"e");
        put(e10.to_string().as_bytes());
    }
    buf.extend_from_slice(&out[..n]);
}

/// A number as propbet's tables write it, as text (7 significant digits; empty when it is not
/// finite).
pub fn text(v: f64) -> String {
    let mut b = Vec::new();
    push_num(&mut b, Some(v));
    String::from_utf8(b).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number a table hands over as a column is the number its text says, over every
    /// magnitude and at the halfway digits where rounding could differ.
    #[test]
    fn the_written_number_is_the_texts() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut values = vec![
            4000.0,
            0.05,
            0.1 + 0.2,
            1.0 / 3.0,
            2.5e-7,
            9_999_999.5,
            1e-300,
            5e300,
            -0.15,
        ];
        for _ in 0..200_000 {
            let mantissa = (next() % 100_000_000) as f64 / 1e7;
            let exp = (next() % 70) as i32 - 35;
            values.push(mantissa * 10f64.powi(exp));
            // Halfway between two 7-digit numbers, as near as a double gets.
            values.push(((next() % 9_000_000 + 1_000_000) as f64 + 0.5) * 10f64.powi(exp - 6));
        }
        for v in values {
            let mut b = Vec::new();
            push_num(&mut b, Some(v));
            let text: f64 = std::str::from_utf8(&b).unwrap().parse().unwrap();
            assert_eq!(
                written(v),
                Some(text),
                "{v:e} written as {}",
                std::str::from_utf8(&b).unwrap()
            );
        }
        assert_eq!(written(f64::NAN), None);
        assert_eq!(written(f64::INFINITY), None);
    }

    fn check(v: f64, expected: &str) {
        let mut s = Vec::new();
        push_num(&mut s, Some(v));
        assert_eq!(String::from_utf8(s).unwrap(), expected, "{v:e}");
    }

    #[test]
    fn seven_significant_digits() {
        check(6000.000000000001, "6000");
        check(0.19999999999999998, "0.2");
        check(2.0319999976781014, "2.032");
        check(0.123456749, "0.1234567");
        check(-1.5e-7, "-1.5e-7");
        check(0.0, "0");
        check(9.99999999, "10");
        check(123456789012345.0, "123456800000000");
        check(0.00012345678901, "0.0001234568");
        check(1.5e22, "1.5e22");
        check(-0.5, "-0.5");
        // Subnormal and extreme values keep their value (once printed as 0e-308).
        check(1e-310, "1e-310");
        check(-1.2345678e-305, "-1.234568e-305");
        check(1e300, "1e300");
        let mut s = Vec::new();
        push_num(&mut s, None);
        assert!(s.is_empty());
    }

    proptest::proptest! {
        #[test]
        fn reads_back_as_ten_digit_rounding(m in -1.0..1.0f64, e in -40i32..40) {
            let v = m * 10f64.powi(e);
            let mut s = Vec::new();
            push_num(&mut s, Some(v));
            let s = String::from_utf8(s).unwrap();
            let back: f64 = s.parse().unwrap();
            proptest::prop_assert!((back - v).abs() <= 5.000001e-7 * v.abs(), "{} -> {}", v, s);
        }
    }
}
