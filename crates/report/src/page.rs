//! One page skeleton for every report: the document head with the font embedded once and one
//! stylesheet, the escaping function, and number formats. No script, no URL: a page opens
//! from disk anywhere.

/// The stylesheet of every page.
pub const CSS: &str = "body{font-family:PropbetSans,sans-serif;margin:2em auto;max-width:1500px;color:#222;padding:0 1em}\
h1{font-size:1.6em;margin-bottom:.2em}h2{border-bottom:2px solid #0072b2;padding-bottom:.2em;margin-top:2em}\
table{border-collapse:collapse;margin:.5em 0 1.5em;font-size:.9em;display:block;overflow-x:auto;max-width:100%}td,th{border:1px solid #ccc;padding:.25em .6em;text-align:right}\
th{background:#eef4fa}td:first-child,th:first-child{text-align:left}\
.cards{display:flex;gap:1em;flex-wrap:wrap}.card{border:1px solid #ccc;border-radius:6px;padding:.8em 1.2em;min-width:11em}\
.card b{display:block;font-size:1.6em;color:#0072b2}.warn{background:#fff4e0;border-left:4px solid #e69f00;padding:.6em 1em}\
.note{color:#555}figure{margin:1em 0}figure svg{max-width:100%;height:auto}code{background:#f4f4f4;padding:0 .3em}\
tr.flagged td{color:#999}tr.sig td{background:#eef7ee}nav a{margin-right:1em}\
section{border-top:2px solid #888;margin-top:2em}svg{max-width:100%;height:auto}\
td.num{white-space:nowrap}td.cmd,td.text,th.text{text-align:left}td.text,th.text{min-width:14em}td.cmd code{white-space:normal;overflow-wrap:anywhere;font-size:.85em}\
p,li{overflow-wrap:anywhere}pre{overflow-x:auto}\
section#answer,section#outputs{border-top:none;margin-top:0}section#answer h2,section#outputs h2{margin-top:.6em}\
table.headline,table.steps{margin:.3em 0 .6em}p.verdict{font-weight:bold}tr.calibration td{background:#fff4e0}\
section#outputs ul{margin:.2em 0}section#answer p{margin:.4em 0}";

/// A whole page: `title`, extra CSS (empty for none), and the body's markup.
pub fn page(title: &str, extra_css: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title>\n<style>{}\n{CSS}\n{extra_css}\nsvg text{{font-family:{},sans-serif}}</style></head><body>\n{body}</body></html>\n",
        esc(title),
        propbet_plot::font_face_css(),
        propbet_plot::FONT_FAMILY,
    )
}

/// A page's body placed one level down in another page: its h1 becomes an h2, and so on.
/// Only for bodies made by this crate (their headings carry no attributes).
pub fn nest(body: &str) -> String {
    let mut s = body.to_string();
    for level in (1..=5).rev() {
        s = s
            .replace(&format!("<h{level}>"), &format!("<h{}>", level + 1))
            .replace(&format!("</h{level}>"), &format!("</h{}>", level + 1));
    }
    s
}

/// HTML-escapes text.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `x` with 4 significant digits.
pub fn sig(x: f64) -> String {
    if !x.is_finite() {
        return "–".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let e = x.abs().log10().floor() as i32;
    if (-4..6).contains(&e) {
        format!("{:.*}", (3 - e).max(0) as usize, x)
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pages_are_self_contained_and_escaped() {
        let p = page("a <b>", "", "<h1>x</h1>");
        assert!(p.contains("<title>a &lt;b&gt;</title>") && p.contains("@font-face"));
        assert_eq!(p.matches("@font-face").count(), 1);
        assert!(!p.contains("url(http") && !p.contains("<script"));
        assert_eq!(nest("<h1>a</h1><h2>b</h2>"), "<h2>a</h2><h3>b</h3>");
        assert_eq!(sig(1234.5678), "1235");
        assert_eq!(sig(0.012345), "0.01235");
    }
}

/// Messages grouped by kind (their words, numbers left out), in order of kind: each kind once,
/// with how many messages it holds and the first as example. How propbet tells about a problem
/// that repeats (at many stations, rows or points): once, with a count.
pub fn group_alike(messages: impl IntoIterator<Item = String>) -> Vec<(usize, String)> {
    let mut kinds: std::collections::BTreeMap<String, (usize, String)> = std::collections::BTreeMap::new();
    for m in messages {
        let kind: String = m
            .chars()
            .filter(|c| !(c.is_ascii_digit() || *c == '.' || *c == '-'))
            .collect();
        kinds.entry(kind).or_insert((0, m)).0 += 1;
    }
    kinds.into_values().collect()
}

#[cfg(test)]
mod group_tests {
    #[test]
    fn alike_messages_are_counted_once() {
        let g = super::group_alike(
            ["CL_a 9.1 is outside 3..7.5", "CL_a 8.2 is outside 3..7.5", "no polar"].map(String::from),
        );
        assert_eq!(
            g,
            vec![
                (2, "CL_a 9.1 is outside 3..7.5".to_string()),
                (1, "no polar".to_string())
            ]
        );
    }
}
