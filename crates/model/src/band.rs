//! What is uncertain in a prediction, as effects at the two ends of a range: the blade angle
//! (the twist a scan or a file gives, and the sections' zero-lift angle at low Reynolds numbers,
//! which acts the same way), the chord, the sections' drag, and, where the model's tables carry
//! them, the sections' transition: the spread between the default's free transition and the
//! tripped model (the tables at Ncrit 3 tripped at mid-chord and at Ncrit 7, made from
//! NeuralFoil's difference: `propbet_polar::blade::BAND_ENDS`), the model-form source. Each
//! source is solved at both ends and the band is their root-sum-square
//! ([`propbet_compare::band::combine`]). The ranges are calibrated by nested cross-validation
//! over the 35 shared APC props so that the band holds about three quarters of what is measured
//! on props it was not calibrated on (`docs/studies/uncertainty-band.md`).

use propbet_bemt::{Fluid, OperatingPoint};
use propbet_compare::band::PointBand;
use propbet_compare::{AirChoice, ComparedPoint};
use propbet_effects::{parse_spec, Stack};
use propbet_measure::MeasuredSet;

use crate::Model;
use crate::Result;

/// The band's sources in words, as the help and the reports say them: [`BandSpec::default`]'s
/// ranges and the transition's two ends ([`propbet_polar::blade::BAND_ENDS`]; a test holds the
/// words to them).
pub const SOURCES_TEXT: &str = "every blade angle ±0.5°, chord ±6 %, section drag ±20 %, and with tabulated polars \
     2.5 times the sections' spread from Ncrit 3 tripped at mid-chord to Ncrit 7 (free against tripped transition), \
     calibrated to hold three quarters of the measurements on held-out props; a scanned blade's own accuracy \
     added to its angle's and chord's";

/// The half-ranges of the band's sources.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandSpec {
    /// Every blade angle, ± [deg].
    pub angle_deg: f64,
    /// Every chord, ± this fraction.
    pub chord: f64,
    /// Every section's drag, ± this fraction.
    pub drag: f64,
    /// The weight of the sections' transition source: its two ends' moves times this (1: the
    /// ends themselves).
    pub transition: f64,
}

impl Default for BandSpec {
    /// The ranges chosen by nested cross-validation over the 35 shared APC props
    /// (`docs/studies/band_calibration.py`: the narrowest band whose median coverage of CT and
    /// CP on the training props reaches 75 %, each source's stated range times 0-2.5): ±0.5° of
    /// blade angle, ±6 % of chord, ±20 % of drag and 2.5 times the transition's spread. The
    /// stated ranges they scale: ±1° (UIUC's measured twist and APC's design differ by 0.2-1.6°
    /// over r/R 0.6-0.9), ±3 % of chord (the shipped scan against UIUC's table: 2.1 % RMS),
    /// ±20 % of drag (the drag factor's plausible 1.0-1.5 about its 1.25), and the free against
    /// the tripped model. The chord's and the transition's weights are the model's own error,
    /// not a tolerance of the blade: a band of the stated ranges held 64 % of CT.
    fn default() -> Self {
        Self {
            angle_deg: 0.5,
            chord: 0.06,
            drag: 0.2,
            transition: 2.5,
        }
    }
}

impl BandSpec {
    /// The band of a model's prop file ([`BandSpec::for_file`]).
    pub fn for_model(model: &Model) -> Self {
        Self::for_file(&model.loaded.file)
    }

    /// The stated ranges ([`BandSpec::default`]), and where the file says how well its geometry
    /// is known (a scan's own accuracy: `propbet_qprop::GeometryAccuracy`), that added to the
    /// blade angle's and the chord's in root-sum-square: independent errors, the scan's
    /// measurement of its mesh on top of how far any blade's numbers stand from the propeller.
    pub(crate) fn for_file(file: &propbet_qprop::PropFile) -> Self {
        let stated = Self::default();
        match file.accuracy {
            None => stated,
            Some(a) => Self {
                angle_deg: stated.angle_deg.hypot(a.blade_angle_deg),
                chord: stated.chord.hypot(a.chord),
                ..stated
            },
        }
    }

    /// The band's sources in words for a prop file: [`SOURCES_TEXT`], and where the file
    /// carries its geometry's own accuracy, what it is and the ranges it makes.
    pub fn sources_text(file: &propbet_qprop::PropFile) -> String {
        let Some(a) = file.accuracy else {
            return SOURCES_TEXT.to_string();
        };
        let b = Self::for_file(file);
        format!(
            "{SOURCES_TEXT}: here {:.2}° and {:.1} % (the scan's spread of blade angle between blades and \
             twice its section fits' RMS residual), which make ±{:.2}° and ±{:.1} %",
            a.blade_angle_deg,
            100.0 * a.chord,
            b.angle_deg,
            100.0 * b.chord
        )
    }

    /// Each source's weight, in [`BandSpec::names`]' order: 1 for the effects (their range is
    /// their spec's), [`BandSpec::transition`] for the sections' transition.
    pub(crate) fn weights(&self) -> [f64; 4] {
        [1.0, 1.0, 1.0, self.transition]
    }

    /// Each source's name and its two ends as effect specs.
    pub(crate) fn sources(&self) -> Vec<(&'static str, [String; 2])> {
        let (a, c, d) = (self.angle_deg, self.chord, self.drag);
        vec![
            (
                "blade angle",
                [format!("pitch-offset:deg={}", -a), format!("pitch-offset:deg={a}")],
            ),
            (
                "chord",
                [
                    format!("chord-scale:factor={}", 1.0 - c),
                    format!("chord-scale:factor={}", 1.0 + c),
                ],
            ),
            (
                "section drag",
                [
                    format!("drag-scale:factor={}", 1.0 - d),
                    format!("drag-scale:factor={}", 1.0 + d),
                ],
            ),
        ]
    }

    /// `solve` with the model's effects and each source's two ends added, source by source.
    fn at_both_ends<T, E>(
        &self,
        model: &Model,
        solve: impl Fn(Stack) -> std::result::Result<T, E>,
    ) -> Result<Vec<[T; 2]>>
    where
        crate::Error: From<E>,
    {
        let with = |spec: &str| -> Result<Stack> {
            let mut s = model.effects.clone();
            s.active.push(model.registry.resolve(&parse_spec(spec)?)?);
            Ok(s)
        };
        let mut solved: Vec<[T; 2]> = self
            .sources()
            .iter()
            .map(|(_, [lo, hi])| Ok([solve(with(lo)?)?, solve(with(hi)?)?]))
            .collect::<Result<_>>()?;
        // The sections' transition: the tables at the band's two ends, where the model's
        // tables carry them (`Model::band_sections`).
        if let Some(effect) = &model.band_sections {
            let at = |ncrit: f64| {
                let mut s = model.effects.clone();
                s.active.push(propbet_effects::Active {
                    effect: effect.clone(),
                    values: vec![ncrit],
                });
                s
            };
            let [lo, hi] = propbet_polar::blade::BAND_NCRIT;
            solved.push([solve(at(lo))?, solve(at(hi))?]);
        }
        Ok(solved)
    }

    /// The sources' names in the order [`BandSpec::at_compared_by_source`] gives their ends:
    /// [`BandSpec::sources`], then the sections' transition where the model's tables carry it.
    pub(crate) fn names(&self, model: &Model) -> Vec<&'static str> {
        let mut n: Vec<&'static str> = self.sources().into_iter().map(|(name, _)| name).collect();
        if model.band_sections.is_some() {
            n.push("sections' transition");
        }
        n
    }

    /// The band at a comparison's points, and its sources by name with the points predicted at
    /// their two ends (validate's `band_sources.csv`).
    #[allow(clippy::type_complexity)]
    pub fn with_sources(
        &self,
        model: &Model,
        air: AirChoice,
        sets: &[MeasuredSet],
        points: &[ComparedPoint],
    ) -> Result<(Vec<PointBand>, Vec<(&'static str, [Vec<ComparedPoint>; 2])>)> {
        let ends = self.at_compared_by_source(model, air, sets)?;
        let bands = propbet_compare::band::of_points(points, &ends, &self.weights());
        Ok((bands, self.names(model).into_iter().zip(ends).collect()))
    }

    /// The compared points predicted at each source's two ends, in [`BandSpec::names`]' order.
    pub(crate) fn at_compared_by_source(
        &self,
        model: &Model,
        air: AirChoice,
        sets: &[MeasuredSet],
    ) -> Result<Vec<[Vec<ComparedPoint>; 2]>> {
        self.at_both_ends(model, |s| {
            propbet_compare::compare(&crate::solve::setup(model, air, s), sets)
        })
    }

    /// The band along a comparison's model curves (`base`: the model's own,
    /// [`propbet_compare::curves::curves`] of `points`, or those curves `thinned`: the ends are
    /// solved at the same samples).
    pub fn along_curves(
        &self,
        model: &Model,
        air: AirChoice,
        points: &[ComparedPoint],
        base: &propbet_compare::curves::Curves,
    ) -> Result<propbet_compare::band::BandCurves> {
        let samples = base
            .j_sweeps
            .iter()
            .flatten()
            .map(|(_, c)| c.len())
            .chain(base.statics.iter().map(Vec::len))
            .next()
            .map_or(propbet_compare::curves::SAMPLES, |n| n.saturating_sub(1));
        let variants = self.at_both_ends(model, |s| {
            propbet_compare::curves::sampled(&crate::solve::setup(model, air, s), points, samples)
        })?;
        Ok(propbet_compare::band::of_curves(base, &variants, &self.weights()))
    }

    /// The band of CT, CP and efficiency at sweep points (`base`: the model's own solve of
    /// `points`).
    pub fn at_points(
        &self,
        model: &Model,
        fluid: &Fluid,
        points: &[OperatingPoint],
        base: &[propbet_bemt::PointResult],
    ) -> Result<Vec<PointBand>> {
        let solved = self.at_both_ends(model, |s| crate::solve::sweep_with(model, &s, fluid, points))?;
        Ok(propbet_compare::band::of_rows(
            base,
            &solved,
            &self.weights(),
            [|p| p.ct, |p| p.cp, |p| Some(p.eta)],
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// QPROP's example prop (shipped in `props/cam6x3`) at 6000 rpm over its J range.
    fn cam6x3() -> (Model, Fluid, Vec<OperatingPoint>) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../props/cam6x3/cam6x3.qprop");
        let model = Model::load(&propbet_settings::spec::ModelSpec::prop(path), false).unwrap();
        let omega = 6000.0 * std::f64::consts::PI / 30.0;
        let j: Vec<f64> = (0..6).map(|k| 0.1 * k as f64).collect();
        let points = propbet_bemt::grid_omega_j(&[omega], &j, model.rotor.tip_radius);
        (model, Fluid::default(), points)
    }

    /// The words the help and the reports use for the band are its sources' ranges.
    #[test]
    fn the_sources_text_says_the_default_ranges() {
        let d = BandSpec::default();
        let [(early, trip), (late, late_trip)] = propbet_polar::blade::BAND_ENDS;
        for words in [
            format!("blade angle ±{}°", d.angle_deg),
            format!("chord ±{} %", 100.0 * d.chord),
            format!("drag ±{} %", 100.0 * d.drag),
            format!(
                "{} times the sections' spread from Ncrit {early} tripped at mid-chord to Ncrit {late}",
                d.transition
            ),
        ] {
            assert!(SOURCES_TEXT.contains(&words), "{words}: {SOURCES_TEXT}");
        }
        assert_eq!((trip, late_trip), (Some(0.5), None));
    }

    #[test]
    fn the_band_holds_the_prediction_and_widens_with_each_source() {
        let (model, fluid, points) = cam6x3();
        let base = crate::solve::sweep(&model, &fluid, &points).unwrap();
        let band = |spec: BandSpec| spec.at_points(&model, &fluid, &points, &base).unwrap();
        let full = band(BandSpec::default());
        let angle_only = band(BandSpec {
            chord: 0.0,
            drag: 0.0,
            ..BandSpec::default()
        });
        let none = band(BandSpec {
            angle_deg: 0.0,
            chord: 0.0,
            drag: 0.0,
            transition: 0.0,
        });
        for (i, p) in base.iter().enumerate() {
            let ct = p.ct.unwrap();
            assert!(
                full[i].ct.contains(ct) && full[i].cp.contains(p.cp.unwrap()),
                "{i}: {:?}",
                full[i]
            );
            // A degree of blade angle moves CT by several per cent; the other sources add to it.
            let w = angle_only[i].ct.relative_half_width(ct);
            assert!(w > 0.02, "{i}: {w}");
            assert!(full[i].ct.relative_half_width(ct) > w, "{i}");
            // No source, no band.
            assert!((none[i].ct.hi - none[i].ct.lo).abs() < 1e-12 * ct, "{i}: {:?}", none[i]);
        }
        // Thrust rises with the blade angle: the high end of the angle is the band's top.
        let raised = crate::solve::sweep_with(
            &model,
            &{
                let mut s = model.effects.clone();
                s.active.push(
                    model
                        .registry
                        .resolve(&parse_spec(&format!("pitch-offset:deg={}", BandSpec::default().angle_deg)).unwrap())
                        .unwrap(),
                );
                s
            },
            &fluid,
            &points,
        )
        .unwrap();
        assert!((raised[0].ct.unwrap() - angle_only[0].ct.hi).abs() < 1e-12);
    }
}
