//! A measured file's bytes as text: UTF-8 with or without a byte-order mark, else Windows-1252
//! (a spreadsheet's re-save writes `µ` as the single byte 0xB5), and CR, LF or CRLF line ends
//! all made LF so that every line number counts lines as an editor does.

use crate::set::ReadError;

/// Windows-1252's characters for the bytes 0x80-0x9F (Latin-1 has control codes there; the
/// five bytes Windows-1252 leaves undefined keep them).
const CP1252_HIGH: [char; 32] = [
    '€', '\u{81}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{8d}', 'Ž', '\u{8f}', '\u{90}', '‘', '’',
    '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{9d}', 'ž', 'Ÿ',
];

/// The text of `bytes`, and a note when it was not UTF-8. A byte no text file holds (NUL and
/// the other control bytes but tab, CR and LF) makes it binary: an error naming its offset.
pub fn decode(bytes: &[u8]) -> Result<(String, Option<String>), ReadError> {
    if let Some(at) = bytes
        .iter()
        .position(|&b| b < 0x20 && !matches!(b, b'\t' | b'\r' | b'\n') || b == 0x7f)
    {
        return Err(ReadError::Empty(format!(
            "not a text file: byte {at} is the control byte 0x{:02X} (is it a spreadsheet's .xlsx, not its CSV export?)",
            bytes[at]
        )));
    }
    let (text, note) = match std::str::from_utf8(bytes) {
        Ok(s) => (s.to_string(), None),
        Err(e) => {
            let at = e.valid_up_to();
            let text: String = bytes
                .iter()
                .map(|&b| match b {
                    0x80..=0x9f => CP1252_HIGH[usize::from(b - 0x80)],
                    _ => char::from(b),
                })
                .collect();
            let note = format!(
                "not UTF-8 (byte {at} is 0x{:02X}): read as Windows-1252 / Latin-1, as spreadsheets save it",
                bytes[at]
            );
            (text, Some(note))
        }
    };
    let text = text.strip_prefix('\u{feff}').map(str::to_string).unwrap_or(text);
    Ok((lf(&text), note))
}

/// CRLF and lone CR as LF.
pub fn lf(text: &str) -> String {
    if !text.contains('\r') {
        return text.to_string();
    }
    text.replace("\r\n", "\n").replace('\r', "\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latin1_micro_sign_and_every_line_end() {
        let (t, note) = decode(b"Time (s),ESC signal (\xb5s)\r1,2\r3,4").unwrap();
        assert_eq!(t, "Time (s),ESC signal (µs)\n1,2\n3,4");
        assert!(note.unwrap().contains("byte 21 is 0xB5"));
        let (t, note) = decode("\u{feff}a,b\r\n1,2\r\n".as_bytes()).unwrap();
        assert_eq!((t.as_str(), note), ("a,b\n1,2\n", None));
        assert_eq!(decode(b"\x93q\x94").unwrap().0, "“q”");
        let e = decode(b"PK\x03\x04").unwrap_err().to_string();
        assert!(e.contains("byte 2 is the control byte 0x03"), "{e}");
    }
}
