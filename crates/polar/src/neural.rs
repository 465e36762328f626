//! Polars from NeuralFoil's networks (`propbet-neuralfoil`): the section's Kulfan parameters
//! fitted to its coordinates, the network at every angle of the job, at Mach 0 (the tables
//! apply Prandtl-Glauert from each polar's own Mach, so a NeuralFoil polar is corrected to the
//! operating Mach as an XFOIL polar is); and an XFOIL polar's unconverged angles filled from
//! them (the `auto` engine). Every point NeuralFoil makes is listed in the polar
//! (`Polar::neuralfoil`) with the network's confidence.

use propbet_neuralfoil::{cst, Condition, Network};

use crate::airfoil::Airfoil;
use crate::table::{Filled, Polar, PolarPoint};

/// The section and the condition of a polar (a `PolarJob`'s, without XFOIL's settings).
#[derive(Debug, Clone, Copy)]
pub struct Section<'a> {
    /// The section.
    pub airfoil: &'a Airfoil,
    /// Chord Reynolds number.
    pub re: f64,
    /// Transition amplification ratio.
    pub ncrit: f64,
    /// Forced transition x/c on both surfaces (None: free).
    pub trip: Option<f64>,
}

/// Why NeuralFoil cannot take a section (the airfoil's or the Kulfan fit's words).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct NeuralError(pub String);

/// NeuralFoil's points of `job` at `alphas_deg`, with their confidence.
fn points(job: &Section<'_>, net: &Network, alphas_deg: &[f64]) -> Result<Vec<(PolarPoint, f64)>, NeuralError> {
    job.airfoil
        .check(&job.airfoil.name)
        .map_err(|e| NeuralError(e.to_string()))?;
    let fit = cst::fit(&job.airfoil.points).map_err(|e| NeuralError(e.to_string()))?;
    // The network's angle is the fitted section's: its chord line turned by the normalisation.
    let shifted: Vec<f64> = alphas_deg.iter().map(|a| a + fit.normalization.rotation_deg).collect();
    let xtr = job.trip.unwrap_or(1.0);
    let aero = net.polar(
        &fit.kulfan,
        &shifted,
        &Condition {
            alpha_deg: 0.0,
            re: job.re,
            ncrit: job.ncrit,
            xtr_upper: xtr,
            xtr_lower: xtr,
        },
    );
    Ok(alphas_deg
        .iter()
        .zip(aero)
        .map(|(&alpha_deg, a)| {
            (
                PolarPoint {
                    alpha_deg,
                    cl: a.cl,
                    cd: a.cd,
                    // NeuralFoil gives no pressure drag apart.
                    cdp: 0.0,
                    cm: a.cm,
                    xtr_top: a.top_xtr,
                    xtr_bottom: a.bot_xtr,
                },
                a.confidence,
            )
        })
        .collect())
}

/// The job's polar from NeuralFoil alone.
pub fn polar(job: &Section<'_>, alphas_deg: &[f64], net: &Network) -> Result<Polar, NeuralError> {
    let pts = points(job, net, alphas_deg)?;
    Ok(Polar {
        re: job.re,
        mach: 0.0,
        ncrit: job.ncrit,
        trip: job.trip,
        neuralfoil: pts
            .iter()
            .map(|(p, c)| Filled {
                alpha_deg: p.alpha_deg,
                confidence: *c,
            })
            .collect(),
        points: pts.into_iter().map(|(p, _)| p).collect(),
        unconverged_deg: Vec::new(),
        hysteresis: Vec::new(),
        faults: Vec::new(),
    })
}

/// An XFOIL polar with its unconverged angles made by NeuralFoil (at the XFOIL polar's Mach:
/// the network has none, and a few angles at one Mach are not worth a polar of their own).
pub fn fill(mut polar: Polar, job: &Section<'_>, net: &Network) -> Result<Polar, NeuralError> {
    if polar.unconverged_deg.is_empty() {
        return Ok(polar);
    }
    let missing = std::mem::take(&mut polar.unconverged_deg);
    for (p, confidence) in points(job, net, &missing)? {
        polar.neuralfoil.push(Filled {
            alpha_deg: p.alpha_deg,
            confidence,
        });
        polar.points.push(p);
    }
    polar.points.sort_by(|a, b| a.alpha_deg.total_cmp(&b.alpha_deg));
    Ok(polar)
}
