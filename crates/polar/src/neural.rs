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

/// Reynolds numbers NeuralFoil is trusted over: its networks learned from XFOIL runs inside
/// them, and answer outside only by extrapolation.
pub const TRUSTED_RE: [f64; 2] = [1e3, 1e8];
/// The largest angle of attack [deg] NeuralFoil is trusted at (beyond stall its training runs
/// thin out, and XFOIL's own answers there are unreliable).
pub const TRUSTED_ALPHA_DEG: f64 = 25.0;
/// The confidence a point outside [`TRUSTED_RE`] or [`TRUSTED_ALPHA_DEG`] gets at most: it is
/// listed as uncertain whatever the network says.
pub const OUTSIDE_CONFIDENCE: f64 = 0.1;

/// The thickest trailing edge NeuralFoil takes [chords]: its training sections' Kulfan
/// trailing-edge thickness is 0.004 ± 0.007 (the scaling file's mean and deviation); a
/// thicker one is a shape it never saw.
pub const MAX_TE_THICKNESS: f64 = 0.03;
/// The largest miss of the Kulfan fit [chords] NeuralFoil is asked about: beyond it the network
/// would answer for another section (the shared airfoils miss by at most 0.0024).
pub const MAX_SHAPE_ERROR: f64 = 0.01;

/// The network's confidence, capped outside the trusted ranges.
fn trusted(confidence: f64, re: f64, alpha_deg: f64) -> f64 {
    let inside = (TRUSTED_RE[0]..=TRUSTED_RE[1]).contains(&re) && alpha_deg.abs() <= TRUSTED_ALPHA_DEG;
    if inside {
        confidence
    } else {
        confidence.min(OUTSIDE_CONFIDENCE)
    }
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
    if fit.kulfan.te_thickness > MAX_TE_THICKNESS {
        return Err(NeuralError(format!(
            "a blunt trailing edge {:.3} chords thick (NeuralFoil learned sections up to {MAX_TE_THICKNESS})",
            fit.kulfan.te_thickness
        )));
    }
    if fit.max > MAX_SHAPE_ERROR {
        return Err(NeuralError(format!(
            "its Kulfan fit misses the contour by up to {:.4} chords (more than {MAX_SHAPE_ERROR}): a shape NeuralFoil's 18 parameters cannot represent",
            fit.max
        )));
    }
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
                trusted(a.confidence, job.re, alpha_deg),
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
        not_filled: None,
    })
}

/// An XFOIL polar with its unconverged angles made by NeuralFoil (at the XFOIL polar's Mach:
/// the network has none, and a few angles at one Mach are not worth a polar of their own).
/// A section NeuralFoil cannot take leaves the polar as XFOIL made it, saying why in
/// `not_filled`.
pub fn fill(mut polar: Polar, job: &Section<'_>, net: &Network) -> Polar {
    if polar.unconverged_deg.is_empty() {
        return polar;
    }
    match points(job, net, &polar.unconverged_deg) {
        Ok(made) => {
            polar.unconverged_deg.clear();
            for (p, confidence) in made {
                polar.neuralfoil.push(Filled {
                    alpha_deg: p.alpha_deg,
                    confidence,
                });
                polar.points.push(p);
            }
            polar.points.sort_by(|a, b| a.alpha_deg.total_cmp(&b.alpha_deg));
        }
        Err(e) => polar.not_filled = Some(format!("NeuralFoil cannot take this section: {}", e.0)),
    }
    polar
}
