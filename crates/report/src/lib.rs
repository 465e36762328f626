//! The pages people read, built from the pipeline's typed artifacts: the answer they lead with
//! ([`answer`]: how close the prediction is, what is missing), one page skeleton
//! ([`page`]: head, font, stylesheet, escaping), the comparison ([`compare`]), the diagnosis
//! ([`diagnose`]), the run ([`run`], holding the other two), the validation table
//! ([`validate`]), the figures of a scan ([`scan`]) and of polars ([`polar`]), and a propeller on its motor
//! ([`powered`]) and props side by side ([`props`]). Pages are strings; the CLI writes them.
#![deny(missing_docs)]

pub mod answer;
pub mod compare;
pub mod diagnose;
pub mod hidden;
pub mod page;
pub mod polar;
pub mod powered;
pub mod props;
pub mod run;
pub mod scan;
pub mod table;
pub mod validate;

/// Markdown that holds no raw HTML: every `<` written as `&lt;` (Markdown renders it as `<`),
/// so that a file name, a label or a tool's output quoted in a summary cannot become a tag.
pub fn md_safe(md: &str) -> String {
    md.replace('<', "&lt;")
}
