//! `propbet compare-props`' outputs: report.html, props.csv and the figure.

use crate::CommandResult as Result;
use propbet_pipeline::stages::SideProp;
use propbet_report::props::Setup;

use crate::files::Outputs;

/// The outputs of propellers side by side on one motor and supply.
pub fn outputs(props: &[SideProp], setup: &Setup) -> Result<Outputs> {
    let fig = propbet_report::props::figure(props);
    let html = propbet_report::props::html(props, setup, &fig)?;
    let mut files = Outputs::default();
    files.figure("plots/props", &fig)?;
    files.add(
        "props.csv",
        propbet_report::table::props::csv(props, setup.hover_thrust)?,
    );
    files.add("report.html", html.as_bytes());
    Ok(files)
}
