//! Validate's numbers by APC family and over all props ([`summarise`]), the rows of
//! `families.csv` that propbet ships as what to expect before any measurement
//! ([`propbet_pipeline::expected`]).

use propbet_compare::expected::Expected;
use propbet_units::stats::{median, quantile};

use crate::{family_groups, line_groups, Row};

/// The APC families' numbers (those with two or more props), other makers' lines' (with a
/// section assumed) and all of those together, and `all` over the rows of APC's sections.
pub fn summarise(rows: &[Row]) -> Vec<Expected> {
    let mut out: Vec<Expected> = family_groups(rows)
        .into_iter()
        .chain(line_groups(rows))
        .map(|(f, m)| over(f, &m))
        .collect();
    let apc: Vec<&Row> = rows.iter().filter(|r| r.assumed_section.is_none()).collect();
    if !apc.is_empty() {
        out.push(over("all".into(), &apc));
    }
    out
}

fn over(family: String, rows: &[&Row]) -> Expected {
    let med = |f: &dyn Fn(&Row) -> f64| median(rows.iter().map(|r| f(r)).filter(|x| x.is_finite()).collect());
    let larger: Vec<f64> = rows
        .iter()
        .map(|r| r.ct.before.median.max(r.cp.before.median))
        .collect();
    let band = |k: usize, f: &dyn Fn(&propbet_compare::band::Coverage) -> f64| {
        med(&|r: &Row| r.band[k].as_ref().map_or(f64::NAN, f))
    };
    Expected {
        family,
        props: rows.len(),
        ct_median: med(&|r| r.ct.before.median),
        cp_median: med(&|r| r.cp.before.median),
        p90: quantile(larger.clone(), 0.9),
        above_15: larger.iter().filter(|x| **x > 0.15).count(),
        band_ct_inside: band(0, &|c| c.inside),
        band_cp_inside: band(1, &|c| c.inside),
        band_ct_half_width: band(0, &|c| c.half_width),
    }
}
