//! How close a prediction of this kind of blade has come, before any measurement: `propbet
//! validate`'s numbers on the shared UIUC props by APC family (E, SF, SP, FF) and over all,
//! written by validate (`families.csv`) and shipped with propbet (`data/validation_families.csv`,
//! copied by `scripts/validation-page.sh` from the same run as the book's validation table).

/// Validate's numbers over one family of props (or all).
#[derive(Debug, Clone, PartialEq)]
pub struct Expected {
    /// `E`, `SF`, `SP`, `FF`, or `all`.
    pub family: String,
    /// Props in it.
    pub props: usize,
    /// Median over its props of each prop's CT median error.
    pub ct_median: f64,
    /// The same for CP.
    pub cp_median: f64,
    /// The 90th percentile over its props of a prop's larger median (CT or CP).
    pub p90: f64,
    /// Its props whose CT or CP median is above 15 %.
    pub above_15: usize,
    /// Median over its props of the share of measured CT inside the uncertainty band.
    pub band_ct_inside: f64,
    /// The same for CP.
    pub band_cp_inside: f64,
    /// Median over its props of the band's median relative half-width of CT.
    pub band_ct_half_width: f64,
}

/// The columns of `families.csv`, in [`Expected`]'s order.
pub(crate) const COLUMNS: [&str; 9] = [
    "family",
    "props",
    "ct_median",
    "cp_median",
    "p90_larger_median",
    "props_above_15",
    "band_ct_inside",
    "band_cp_inside",
    "band_ct_half_width",
];

/// Other makers' lines UIUC measured, by their file names' prefix, in words: validated with a
/// section assumed (no maker publishes theirs), each its own group.
pub const LINES: [(&str, &str); 16] = [
    ("da4002", "UIUC DA4002"),
    ("da4022", "UIUC DA4022"),
    ("da4052", "UIUC DA4052"),
    ("grcp", "Graupner CAM"),
    ("grcsp", "Graupner CAM Slim"),
    ("grsn", "Graupner Super Nylon"),
    ("gwsdd", "GWS Direct Drive"),
    ("gwssf", "GWS Slow Flyer"),
    ("kyosho", "Kyosho"),
    ("ma", "Master Airscrew"),
    ("mae", "Master Airscrew Electric"),
    ("mas", "Master Airscrew Scimitar"),
    ("magf", "Master Airscrew GF"),
    ("mi", "Micro Invent"),
    ("mit", "MIT micro"),
    ("pl", "Plantraco"),
];

/// APC's families, as [`family`] names them.
pub const APC_FAMILIES: [&str; 4] = ["E", "SF", "SP", "FF"];

/// The group of every prop validated with a section assumed.
pub const ASSUMED: &str = "sections assumed";

/// A family's or maker line's name in words.
pub fn family_words(family: &str) -> &'static str {
    match family {
        "E" => "APC Electric",
        "SF" => "APC Slow Flyer",
        "SP" => "APC Sport",
        "FF" => "APC Free Flight",
        ASSUMED => "other makers'",
        f => LINES.iter().find(|l| l.0 == f).map_or("APC", |l| l.1),
    }
}

/// `families.csv`'s text.
pub fn to_csv(e: &[Expected]) -> String {
    let mut s = COLUMNS.join(",") + "\n";
    for x in e {
        s += &format!(
            "{},{},{:.6},{:.6},{:.6},{},{:.6},{:.6},{:.6}\n",
            x.family,
            x.props,
            x.ct_median,
            x.cp_median,
            x.p90,
            x.above_15,
            x.band_ct_inside,
            x.band_cp_inside,
            x.band_ct_half_width
        );
    }
    s
}

/// Reads `families.csv`'s text.
pub(crate) fn from_csv(text: &str) -> Result<Vec<Expected>, String> {
    let mut lines = text.lines();
    if lines.next().map(|h| h.split(',').collect::<Vec<_>>()) != Some(COLUMNS.to_vec()) {
        return Err(format!("not a families table: its header is not {}", COLUMNS.join(",")));
    }
    lines
        .enumerate()
        .map(|(i, l)| {
            let c: Vec<&str> = l.split(',').collect();
            let bad = || format!("line {}: {l:?}", i + 2);
            if c.len() != COLUMNS.len() {
                return Err(bad());
            }
            let f = |k: usize| c[k].parse::<f64>().map_err(|_| bad());
            let n = |k: usize| c[k].parse::<usize>().map_err(|_| bad());
            Ok(Expected {
                family: c[0].to_string(),
                props: n(1)?,
                ct_median: f(2)?,
                cp_median: f(3)?,
                p90: f(4)?,
                above_15: n(5)?,
                band_ct_inside: f(6)?,
                band_cp_inside: f(7)?,
                band_ct_half_width: f(8)?,
            })
        })
        .collect()
}

/// The numbers shipped with propbet: validate on the 35 shared APC props with the default model.
pub fn shipped() -> Vec<Expected> {
    from_csv(include_str!("../data/validation_families.csv")).expect("the shipped families table reads")
}

/// The UIUC family of a prop name, as APC names the line: `apce_10x5` → `E`, `apcsf` → `SF`,
/// `apcsp` → `SP`, `apcff` → `FF`; other makers: their prefix.
pub fn family(prop: &str) -> String {
    let prefix = prop.split('_').next().unwrap_or(prop);
    match prefix {
        "apce" => "E".into(),
        "apcsf" => "SF".into(),
        "apcsp" => "SP".into(),
        "apcff" => "FF".into(),
        other => other.to_string(),
    }
}

/// The APC family or maker line a file name says, if any: a UIUC name (`apcsf_10x4.7_geom.txt` →
/// `SF`, `gwsdd_9x5_geom.txt` → `gwsdd`) or an
/// APC design or performance file (`10x47SF-PERF.PE0` → `SF`, `10x7-PERF.PE0` → `SP`,
/// `PER3_11x7E.dat` → `E`). Sizes APC gives other letters (MR, C, W, ...) name no family
/// validated here.
pub fn family_of_file(name: &str) -> Option<&'static str> {
    let lower = name.to_ascii_lowercase();
    if lower.contains('_') {
        let f = family(&lower);
        if let Some(f) = APC_FAMILIES
            .into_iter()
            .chain(LINES.iter().map(|l| l.0))
            .find(|x| *x == f)
        {
            return Some(f);
        }
    }
    let stem = lower
        .strip_suffix("-perf.pe0")
        .or_else(|| lower.strip_prefix("per3_").and_then(|s| s.strip_suffix(".dat")))?;
    let (size, kind) = stem.split_at(stem.trim_end_matches(|c: char| c.is_ascii_alphabetic()).len());
    if !size.contains('x') || !size.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    match kind {
        "" => Some("SP"),
        "e" => Some("E"),
        "sf" => Some("SF"),
        _ => None,
    }
}

/// The validated family of the first of `names` (file or folder names: the prop file, the
/// folder it is in, the measured files) that names one, with the shipped table's numbers for
/// it: (median CT error, median CP error, props, the family in words). None where no name says
/// a validated family (a scan, a QPROP file of another maker).
pub fn usual_error<'a>(names: impl IntoIterator<Item = &'a str>) -> Option<(f64, f64, usize, &'static str)> {
    let fam = names.into_iter().find_map(family_of_file)?;
    let table = shipped();
    let e = table.iter().find(|e| e.family == fam)?;
    Some((e.ct_median, e.cp_median, e.props, family_words(fam)))
}

/// The validated group of the prop whose file is `name` (its APC family or maker line), where
/// `table` holds it.
pub fn group_of<'a>(name: Option<&str>, table: &'a [Expected]) -> Option<&'a Expected> {
    let f = family_of_file(name?)?;
    table.iter().find(|e| e.family == f)
}

/// What to expect of a prediction of the prop whose file is `name` (None: a scan, a table),
/// in one sentence, from `table` (the shipped one: [`shipped`]).
pub fn sentence(name: Option<&str>, table: &[Expected]) -> Option<String> {
    let all = table.iter().find(|e| e.family == "all")?;
    let fam = name
        .and_then(family_of_file)
        .and_then(|f| table.iter().find(|e| e.family == f));
    let pct = |x: f64| format!("{:.1} %", 100.0 * x);
    let worst = table
        .iter()
        .filter(|e| APC_FAMILIES.contains(&e.family.as_str()))
        .max_by(|a, b| a.ct_median.max(a.cp_median).total_cmp(&b.ct_median.max(b.cp_median)));
    let band = |e: &Expected| {
        format!(
            "its uncertainty band held {} of the measured CT (±{}) and {} of the CP",
            pct(e.band_ct_inside),
            pct(e.band_ct_half_width),
            pct(e.band_cp_inside)
        )
    };
    let assumed = |e: &Expected| {
        if LINES.iter().any(|l| l.0 == e.family) {
            " with a section assumed (no maker's section data)"
        } else {
            ""
        }
    };
    Some(match fam {
        Some(e) => format!(
            "Expected accuracy: on the {} {} props propbet is validated on (UIUC's wind tunnel){}, the default \
             model's median error was {} in CT and {} in CP ({} of them above 15 %; over all {} APC props {} / {}); \
             {}.",
            e.props,
            family_words(&e.family),
            assumed(e),
            pct(e.ct_median),
            pct(e.cp_median),
            e.above_15,
            all.props,
            pct(all.ct_median),
            pct(all.cp_median),
            band(e)
        ),
        None => format!(
            "Expected accuracy: no prop of this maker line is in propbet's validation. On the {} APC props it is \
             validated on (UIUC's wind tunnel), the default \
             model's median error was {} in CT and {} in CP, {} of them above 15 %{}; {}.{}",
            all.props,
            pct(all.ct_median),
            pct(all.cp_median),
            all.above_15,
            worst
                .map(|w| format!(
                    " (the worst family, {}: {} / {})",
                    family_words(&w.family),
                    pct(w.ct_median),
                    pct(w.cp_median)
                ))
                .unwrap_or_default(),
            band(all),
            table
                .iter()
                .find(|e| e.family == ASSUMED)
                .map(|o| format!(
                    " On the {} props of other makers, a section assumed: {} / {}.",
                    o.props,
                    pct(o.ct_median),
                    pct(o.cp_median)
                ))
                .unwrap_or_default()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_say_their_family() {
        for (name, f) in [
            ("apcsf_10x4.7_geom.txt", Some("SF")),
            ("APCE_11x7_static.txt", Some("E")),
            ("10x47SF-PERF.PE0", Some("SF")),
            ("10x7-PERF.PE0", Some("SP")),
            ("18x12E-PERF.PE0", Some("E")),
            ("PER3_11x7E.dat", Some("E")),
            ("5x45MR-PERF.PE0", None),
            ("apcsf_10x4.7.stl", Some("SF")),
            ("blade.stl", None),
            ("x-PERF.PE0", None),
            ("gwsdd_9x5_geom.txt", Some("gwsdd")),
            ("MA_9x4_static_0740rd.txt", Some("ma")),
            ("xyz_9x4_geom.txt", None),
        ] {
            assert_eq!(family_of_file(name), f, "{name}");
        }
    }

    #[test]
    fn the_shipped_table_reads_and_names_every_family() {
        let t = shipped();
        let fams: Vec<&str> = t.iter().map(|e| e.family.as_str()).collect();
        assert_eq!(fams[..3], ["E", "SF", "SP"]);
        assert_eq!(fams[fams.len() - 2..], [ASSUMED, "all"]);
        // Every other group a maker line of its own.
        assert!(
            fams[3..fams.len() - 2].iter().all(|f| LINES.iter().any(|l| l.0 == *f)),
            "{fams:?}"
        );
        let props = |f: &dyn Fn(&str) -> bool| t.iter().filter(|e| f(&e.family)).map(|e| e.props).sum::<usize>();
        let all = t.last().unwrap();
        // APC's families and the one Free Flight prop; the lines of two props or more, within all assumed.
        assert_eq!(all.props, props(&|f| ["E", "SF", "SP"].contains(&f)) + 1);
        assert!(props(&|f| LINES.iter().any(|l| l.0 == f)) <= t[fams.len() - 2].props);
        for e in &t {
            assert!(e.ct_median > 0.0 && e.ct_median < 0.5 && e.band_ct_inside > 0.0 && e.band_ct_inside <= 1.0);
        }
        // Round trip.
        assert_eq!(from_csv(&to_csv(&t)).unwrap(), t);
        assert!(from_csv("family,props\nE,3\n").unwrap_err().contains("header"));
        assert!(from_csv(&format!("{}\nE,x,1,1,1,1,1,1,1\n", COLUMNS.join(",")))
            .unwrap_err()
            .contains("line 2"));
    }

    /// The shipped table and the book's validation table come from one validate run
    /// (`scripts/validation-page.sh`): each family's and all props' medians are the table's.
    #[test]
    fn the_shipped_table_is_the_books_validation_table() {
        let page =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/validation-table.md")).unwrap();
        for e in shipped() {
            let label = match e.family.as_str() {
                "all" => "**all (median over props)**".to_string(),
                f => format!("**{f} (median of {})**", e.props),
            };
            let row = page
                .lines()
                .find(|l| l.starts_with(&format!("| {label} |")))
                .unwrap_or_else(|| panic!("{label} not in the validation table"));
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            // | label | | points | CT median | CT p90 | CP median | ...
            let pct = |x: f64| format!("{:.1} %", 100.0 * x);
            assert_eq!(
                (cells[4], cells[6]),
                (pct(e.ct_median).as_str(), pct(e.cp_median).as_str()),
                "{row}"
            );
        }
    }

    #[test]
    fn the_sentence_names_the_family_or_all() {
        let t = shipped();
        let sp = sentence(Some("10x7-PERF.PE0"), &t).unwrap();
        assert!(
            sp.contains("APC Sport props") && sp.contains("uncertainty band held"),
            "{sp}"
        );
        let scan = sentence(None, &t).unwrap();
        assert!(scan.contains("the worst family, APC Slow Flyer"), "{scan}");
        assert!(
            scan.starts_with("Expected accuracy: no prop of this maker line is in propbet's validation"),
            "{scan}"
        );
        assert!(sentence(None, &[]).is_none());
        // A maker line the table holds: its own numbers, and that its section was assumed.
        let mut with_line = t.clone();
        with_line.insert(
            0,
            Expected {
                family: "gwsdd".into(),
                props: 6,
                ct_median: 0.12,
                cp_median: 0.2,
                ..t[0].clone()
            },
        );
        let gws = sentence(Some("gwsdd_9x5_geom.txt"), &with_line).unwrap();
        assert!(
            gws.contains("on the 6 GWS Direct Drive props")
                && gws.contains("with a section assumed")
                && gws.contains("12.0 % in CT and 20.0 % in CP"),
            "{gws}"
        );
        // One the table does not hold (one prop is no group): told so.
        let unseen = sentence(Some("mit_4.3x3.5_geom.txt"), &t).unwrap();
        assert!(unseen.contains("no prop of this maker line"), "{unseen}");
    }

    /// The headline accuracy on the README and the validation page is the book's validation
    /// table's (itself the shipped table's, above): every page quoting it is checked here, and a
    /// new validate run that moves it fails until the pages say the new numbers.
    #[test]
    fn the_pages_quote_the_validation_tables_numbers() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
        let read = |p: &str| {
            std::fs::read_to_string(format!("{root}/{p}"))
                .unwrap()
                .replace('\n', " ")
        };
        let table = read("docs/validation-table.md");
        let row = |label: &str| -> Vec<String> {
            let at = table.find(&format!("| **{label}")).unwrap_or_else(|| panic!("{label}"));
            let line = table[at..].split(" | **").next().unwrap_or_default();
            line.split('|')
                .map(|c| c.trim().trim_end_matches(" %").to_string())
                .collect()
        };
        // | label | | points | CT median | CT p90 | CP median | CP p90 | APC CT | p90 | APC CP | ...
        let all = row("all (median over props)");
        let sf = row("SF (median of");
        let (ct, cp, apc_ct, apc_cp) = (&all[4], &all[6], &all[8], &all[10]);
        let readme = read("README.md");
        let validation = read("docs/validation.md");
        for (page, text, quote) in [
            (
                "README.md",
                &readme,
                format!("**{ct} % in CT and {cp} % in CP, against {apc_ct} % and {apc_cp} % for APC's own"),
            ),
            ("README.md", &readme, format!("family (median {} / {} %)", sf[4], sf[6])),
            (
                "docs/validation.md",
                &validation,
                format!("| {ct} % | {cp} % | {apc_ct} / {apc_cp} % (its "),
            ),
            (
                "docs/validation.md",
                &validation,
                format!("| {ct} / {cp} % on the 55 APC props of today's table (APC's own code on the same points {apc_ct} / {apc_cp} %)"),
            ),
        ] {
            assert!(text.contains(&quote), "{page} does not say `{quote}`");
        }
    }
}
