//! The built-in effects, by id:
//!
//! | id | hook | parameters |
//! |---|---|---|
//! | `tip-loss` | inflow | `strength` (1 = the baseline's Prandtl factor, 0 = none) |
//! | `hub-loss` | inflow | `strength` (0 = none, 1 = Prandtl's hub factor at the blade root) |
//! | `re-scaling` | section drag | `dexp`: change of the drag's Reynolds exponent |
//! | `drag-scale` | section drag | `factor`: every section's drag times it |
//! | `re-lift` | section lift | `n`: lift times (Re/1e5)^n |
//! | `compressibility` | section lift and drag | `mcrit` (drag-rise Mach), `pg` (Prandtl-Glauert exponent) |
//! | `stall-delay` | section lift | `a` (Snel's rotational augmentation, 3 in Snel) |
//! | `post-stall` | section lift and drag | `cd_max` (Viterna's flat-plate drag) |
//! | `elastic-twist` | geometry | `k`: tip untwist [deg] at 10,000 rpm, growing with rpm^2 and r/R |
//! | `pitch-offset` | geometry | `deg` |
//! | `chord-scale` | geometry | `factor` |
//! | `density` | measurement | `ratio` (true/assumed density) |
//! | `rpm-scale` | measurement | `factor` (true/logged RPM) |
//! | `thrust-tare` | loads | `k`: blockage area over disc area, times the slipstream dynamic pressure |
//! | `torque-tare` | loads | `q0` [N m], `q1` [N m s/rad]: Q0 + Q1 omega |

use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};

use propbet_bemt::aero::{attached_lift, augment_lift, snel_fraction};
use propbet_bemt::{DragInput, LiftEval, PointResult, QpropAirfoil, Rotor, SectionAero, SolverOptions};

use crate::{Effect, EffectError, Evidence, Hook, Loads, Param, PointState, SectionCtx, StationGeom};

/// Reference RPM of `elastic-twist`'s parameter.
pub const ELASTIC_REF_RPM: f64 = 10_000.0;
/// QPROP's drag-rise Mach number (qprop.f `MCRIT0`), the baseline of `compressibility`.
const MCRIT0: f64 = propbet_bemt::aero::QPROP_MCRIT;
/// Reference Reynolds number of `re-scaling` for sections that are not QPROP's model.
pub const RE_SCALING_REF: f64 = 1e5;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    TipLoss,
    HubLoss,
    ReScaling,
    DragScale,
    ReLift,
    Compressibility,
    StallDelay,
    PostStall,
    ElasticTwist,
    PitchOffset,
    ChordScale,
    Density,
    RpmScale,
    ThrustTare,
    TorqueTare,
}

/// Bounds of the RPM scale when every file's RPM is optical (the wide bounds hold the
/// pole-count ratios of an electrical reading, 12/14 and 14/12). An optical tachometer times
/// pulses against a quartz clock: a handheld one is specified to ±0.02 % of the reading ± 1
/// count (Ono Sokki HT-5500's data sheet), so ±1 % is fifty times that and still not a
/// miscount, which would be a factor of 2 (two reflections a turn). The bounds were once ±3 %
/// with no source; validate's held-out columns with each are in `README.md` (Validation on
/// real propellers).
pub const OPTICAL_RPM_SCALE: (f64, f64) = (0.99, 1.01);

/// Bounds of the density ratio when every file gives coefficients (UIUC's CT and CP): the lab
/// reduced its loads with the density it measured, so the ratio is only that measurement's
/// error. Density from a barometer and a thermometer (ideal gas) is good to a few tenths of a
/// percent (1 hPa is 0.1 %, 1 K 0.35 %); humidity left out makes dry-air density up to about
/// 1 % high at 30 C and 60 % RH (moist air's gas constant): ±2 % holds both with room. The
/// wide bounds (0.75-1.2) are those of a stand log whose air nobody wrote down.
pub const LAB_DENSITY_RATIO: (f64, f64) = (0.98, 1.02);

/// A built-in effect.
#[derive(Debug)]
pub struct Builtin {
    kind: Kind,
    id: &'static str,
    params: Vec<Param>,
    hooks: &'static [Hook],
    explanation: &'static str,
}

fn make(kind: Kind) -> Builtin {
    use Hook::*;
    let (id, params, hooks, explanation): (&str, Vec<Param>, &'static [Hook], &str) = match kind {
        Kind::TipLoss => (
            "tip-loss",
            vec![Param::new(
                "strength",
                "-",
                1.0,
                (0.0, 4.0),
                0.2,
                "divides the tip-loss exponent: 1 = Prandtl (the baseline), 0 = no tip loss",
            ).expecting(0.7, 1.5)],
            &[Inflow],
            "Near the tip air flows round from the pressure to the suction side and the blade loses lift; \
             Prandtl's factor models it for a helical wake. Measured loads above the model near its limit of \
             small blade counts, or below it with wide tips, show a different strength.",
        ),
        Kind::HubLoss => (
            "hub-loss",
            vec![Param::new(
                "strength",
                "-",
                0.0,
                (0.0, 10.0),
                0.2,
                "0 = no hub loss (the baseline), 1 = Prandtl's hub factor",
            ).expecting(0.0, 1.5)],
            &[Inflow],
            "At the blade root the hub and the spinner shed a vortex like the tip does, and the inner \
             sections carry less load than strip theory gives.",
        ),
        Kind::ReScaling => (
            "re-scaling",
            vec![Param::new(
                "dexp",
                "-",
                0.0,
                (-1.5, 1.5),
                0.1,
                "added to the drag's Reynolds-number exponent: cd * (Re/REref)^dexp",
            ).expecting(-0.5, 0.5)],
            &[Section],
            "At the Reynolds numbers of small propellers (20k-100k) laminar separation bubbles make the \
             section drag depend on Re more strongly than the polar's exponent says: torque errors that change \
             with RPM at a fixed advance ratio.",
        ),
        Kind::DragScale => (
            "drag-scale",
            vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.5, 2.5),
                0.1,
                "multiplies every section's drag (physical bounds: 0.5-2.5: XFOIL's or a wind tunnel's low-Re drag against a real blade's, rough or smooth)",
            ).expecting(0.8, 1.4)],
            &[Section],
            "The sections' profile drag is not the polars': surface roughness (a printed or scanned blade, \
             paint, mould lines), a finite trailing edge, unsteady laminar bubbles and three-dimensional flow \
             that 2-D polars do not hold. Torque (and the hover efficiency) off at every RPM and J alike, thrust \
             barely.",
        ),
        Kind::ReLift => (
            "re-lift",
            vec![Param::new(
                "n",
                "-",
                0.0,
                (-0.4, 0.4),
                0.02,
                "section lift times (Re/1e5)^n (physical bounds: +-0.4, lift halving or doubling over a decade at most)",
            ).expecting(-0.2, 0.2)],
            &[Section],
            "At 20k-100k the sections' lift depends on Reynolds number (laminar separation and bubbles \
             thin as Re grows) more or less than the polars say: thrust errors that change with RPM at a fixed \
             advance ratio, torque following through the induced power.",
        ),
        Kind::Compressibility => (
            "compressibility",
            vec![
                Param {
                    start: 0.6,
                    ..Param::new(
                        "mcrit",
                        "-",
                        MCRIT0,
                        (0.2, 0.95),
                        0.05,
                        "drag-rise Mach number: cd + 10 (M - mcrit)^3 above it (baseline 0.70)",
                    ).expecting(0.5, 0.9)
                },
                Param::new(
                    "pg",
                    "-",
                    1.0,
                    (0.0, 4.0),
                    0.3,
                    "Prandtl-Glauert exponent: cl / (1 - M^2)^(pg/2) (baseline 1)",
                ).expecting(0.5, 2.0),
            ],
            &[Section],
            "Near the tip the local Mach number reaches 0.3-0.6: lift grows by the Prandtl-Glauert factor \
             (Karman-Tsien: faster), and the drag rises steeply once shocks form above the critical Mach \
             number. The error grows with tip Mach, i.e. with RPM at any advance ratio.",
        ),
        Kind::StallDelay => (
            "stall-delay",
            vec![Param::new(
                "a",
                "-",
                0.0,
                (0.0, 12.0),
                0.5,
                "Snel's coefficient: cl + a (c/r)^2 (cl_attached - cl) where the section lifts less than its attached-flow line (Snel: 3)",
            ).expecting(0.0, 6.0)],
            &[Section],
            "Rotation delays stall near the root: centrifugal pumping thins the boundary layer and \
             the inner sections keep lifting beyond the 2-D stall angle (Snel et al. 1994). Visible at low \
             advance ratio, where the inner sections stall.",
        ),
        Kind::PostStall => (
            "post-stall",
            vec![Param {
                neutral: None,
                start: 1.2,
                ..Param::new(
                    "cd_max",
                    "-",
                    1.2,
                    (0.3, 2.5),
                    0.1,
                    "Viterna's flat-plate drag at 90 deg (1.11 + 0.018 AR)",
                ).expecting(1.0, 2.0)
            }],
            &[Section],
            "Beyond stall the section behaves like a flat plate: Viterna and Corrigan's lift and drag \
             replace the model's cosine roll-off. Visible only where sections stall (static thrust, low J).",
        ),
        Kind::ElasticTwist => (
            "elastic-twist",
            vec![Param::new(
                "k",
                "deg",
                0.0,
                (0.0, 5.0),
                0.5,
                "untwist at the tip at 10,000 rpm (physical bounds: 0-5 deg: a plastic blade's at most; the propeller moment and a cambered section's nose-down moment both flatten it, so a pitch rising with RPM is left to the Reynolds-number effects); -k (rpm/10^4)^2 r/R is added to the blade angle",
            ).expecting(0.0, 2.0)],
            &[Geometry],
            "Thin plastic blades twist under centrifugal and aerodynamic load (the propeller moment \
             flattens them): the pitch falls with RPM^2, most at the tip. Thrust falls short at high RPM.",
        ),
        Kind::PitchOffset => (
            "pitch-offset",
            vec![Param::new(
                "deg",
                "deg",
                0.0,
                (-3.0, 3.0),
                0.3,
                "added to every blade angle (physical bounds: +-3 deg, a scan's or a mould's error)",
            ).expecting(-2.0, 2.0)],
            &[Geometry],
            "Every blade angle is off by the same amount: a scan aligned to the wrong plane, a \
             hub that seats the blades at another angle, a mould that differs from the design; or \
             every section's zero-lift angle is off by as much (a section of other camber than the \
             polars', XFOIL's lift at small angles and low Re), which acts the same way.",
        ),
        Kind::ChordScale => (
            "chord-scale",
            vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.85, 1.15),
                0.05,
                "multiplies every chord (physical bounds: +-15 %, a scan's scale or a production run)",
            ).expecting(0.93, 1.07)],
            &[Geometry],
            "The blades are wider or narrower than the geometry says (scan scale, a different \
             production run): thrust and torque change nearly in proportion, less at high load.",
        ),
        Kind::Density => (
            "density",
            vec![Param::new(
                "ratio",
                "-",
                1.0,
                (0.75, 1.2),
                0.02,
                "true density / assumed density (physical bounds: 0.75-1.2, 2,500 m at 40 C to sea level at -30 C against ISA)",
            )
            .expecting(0.9, 1.1)
            .known(
                Evidence::LabAir,
                LAB_DENSITY_RATIO,
                "coefficients the lab reduced with the density it measured",
            )],
            &[Measurement],
            "The air was not what the model assumed (temperature, altitude, humidity): thrust and \
             torque scale together at every point. Where the files log temperature, pressure and \
             humidity the comparison already uses them; the ratio is what remains. Coefficients a \
             lab reduced with its measured air (UIUC's files) bound it to +-2 % in diagnose.",
        ),
        Kind::RpmScale => (
            "rpm-scale",
            vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.85, 1.2),
                0.02,
                "true RPM / logged RPM (a wrong pole count: poles used / true poles; physical bounds 0.85-1.2 hold 12/14 and 14/12)",
            )
            .known(
                Evidence::OpticalRpm,
                OPTICAL_RPM_SCALE,
                "an optical RPM sensor: no pole count to get wrong",
            )],
            &[Measurement],
            "The RPM sensor is off by a constant factor: an electrical-RPM reading divided by the wrong \
             pole count, a reflective tape counted twice. Thrust and torque errors go as factor^2 at \
             every point.",
        ),
        Kind::ThrustTare => (
            "thrust-tare",
            vec![Param::new(
                "k",
                "-",
                0.0,
                (0.0, 0.15),
                0.02,
                "blockage area (CdS) over disc area; thrust - k q_slip pi R^2 (physical bounds: 0-0.15: a drag area is not negative)",
            )],
            &[Loads],
            "The motor, its mount and the stand sit in the slipstream: they take back a drag force \
             proportional to the slipstream's dynamic pressure (1/2 rho (V + dv)^2), so the stand reads \
             less thrust than the propeller makes, about k T when static.",
        ),
        Kind::TorqueTare => (
            "torque-tare",
            vec![
                Param::new(
                    "q0",
                    "N m",
                    0.0,
                    (0.0, 0.2),
                    1e-3,
                    "constant torque (bearing friction: never below zero)",
                ),
                Param::new(
                    "q1",
                    "N m s/rad",
                    0.0,
                    (0.0, 1e-4),
                    1e-6,
                    "torque per rad/s (windage, viscous friction: never below zero)",
                ),
            ],
            &[Loads],
            "The torque cell also feels the motor's bearing friction and windage: Q0 + Q1 omega on top \
             of the propeller's torque. Largest relative error at low RPM, thrust unaffected.",
        ),
    };
    Builtin {
        kind,
        id,
        params,
        hooks,
        explanation,
    }
}

const KINDS: [Kind; 15] = [
    Kind::TipLoss,
    Kind::HubLoss,
    Kind::ReScaling,
    Kind::DragScale,
    Kind::ReLift,
    Kind::Compressibility,
    Kind::StallDelay,
    Kind::PostStall,
    Kind::ElasticTwist,
    Kind::PitchOffset,
    Kind::ChordScale,
    Kind::Density,
    Kind::RpmScale,
    Kind::ThrustTare,
    Kind::TorqueTare,
];

/// Every built-in effect, in the documented order.
pub fn all() -> &'static [Arc<dyn Effect>] {
    static ALL: OnceLock<Vec<Arc<dyn Effect>>> = OnceLock::new();
    ALL.get_or_init(|| KINDS.iter().map(|&k| Arc::new(make(k)) as Arc<dyn Effect>).collect())
}

/// The ids of the built-in effects.
pub fn ids() -> Vec<&'static str> {
    KINDS.iter().map(|&k| make(k).id).collect()
}

/// A built-in effect by id.
pub fn get(id: &str) -> Option<Arc<dyn Effect>> {
    all().iter().find(|e| e.id() == id).cloned()
}

/// Viterna-Corrigan post-stall lift and drag (and d cl/d alpha) at `alpha` beyond the positive
/// stall of a QPROP section, for flat-plate drag `cd_max`; `None` below stall or for sections
/// without a stall angle.
fn viterna(q: &QpropAirfoil, alpha: f64, msq: f64, cd_max: f64) -> Option<(f64, f64, f64)> {
    let k = &q.coeffs;
    let pg = 1.0 / (1.0 - msq).sqrt();
    let a_s = (k.cl_max / pg - k.cl0) / k.cl_a;
    if !(a_s > 0.02 && a_s < 1.2) || alpha <= a_s {
        return None;
    }
    let a = alpha.min(PI / 2.0);
    let cl_s = k.cl_max;
    let cd_s = q.drag(&DragInput {
        alpha: a_s,
        cl: cl_s,
        stalled: false,
        re: k.re_ref,
        mach: msq.sqrt(),
    });
    let (ss, cs) = a_s.sin_cos();
    let b2 = (cd_s - cd_max * ss * ss) / cs;
    let a1 = 0.5 * cd_max;
    let a2 = (cl_s - cd_max * ss * cs) * ss / (cs * cs);
    let (s, c) = a.sin_cos();
    let cl = a1 * (2.0 * a).sin() + a2 * c * c / s;
    let dcl = if alpha < PI / 2.0 {
        2.0 * a1 * (2.0 * a).cos() - a2 * c * (2.0 * s * s + c * c) / (s * s)
    } else {
        0.0
    };
    let cd = cd_max * s * s + b2 * c;
    Some((cl, dcl, cd))
}

impl Effect for Builtin {
    fn id(&self) -> &str {
        self.id
    }

    fn params(&self) -> &[Param] {
        &self.params
    }

    fn hooks(&self) -> &[Hook] {
        self.hooks
    }

    fn explanation(&self) -> &str {
        self.explanation
    }

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        match self.kind {
            Kind::Compressibility => vec![vec![0.45, 1.0], vec![0.3, 1.0], vec![0.7, 1.5]],
            Kind::StallDelay => vec![vec![3.0]],
            Kind::HubLoss => vec![vec![1.0]],
            Kind::TipLoss => vec![vec![0.3]],
            _ => Vec::new(),
        }
    }

    fn measurement(&self, p: &[f64], point: &mut PointState) {
        match self.kind {
            Kind::Density => point.fluid.rho *= p[0],
            Kind::RpmScale => point.omega *= p[0],
            _ => {}
        }
    }

    fn geometry(&self, p: &[f64], point: &PointState, g: &mut StationGeom) {
        match self.kind {
            Kind::PitchOffset => g.beta += p[0].to_radians(),
            Kind::ChordScale => g.chord *= p[0],
            Kind::ElasticTwist => {
                let s = point.rpm() / ELASTIC_REF_RPM;
                g.beta -= (p[0] * s * s * g.x).to_radians();
            }
            _ => {}
        }
    }

    fn inflow(&self, p: &[f64], _point: &PointState, rotor: &Rotor, o: &mut SolverOptions) {
        match self.kind {
            Kind::TipLoss => {
                o.tip_loss = true;
                o.tip_loss_strength = p[0];
            }
            Kind::HubLoss => {
                o.hub_loss_strength = p[0];
                o.hub_radius = rotor.stations.first().map(|s| s.r - 0.5 * s.dr).unwrap_or(0.0);
            }
            _ => {}
        }
    }

    fn lift(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        inner: &dyn SectionAero,
        (alpha, re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        Ok(match self.kind {
            Kind::Compressibility if !base.stalled => {
                // base = cl_inc / sqrt(1 - M^2); the effect makes the exponent pg/2.
                let f = (1.0 - msq).powf(-(p[1] - 1.0) / 2.0);
                let f_msq = f * (p[1] - 1.0) / 2.0 / (1.0 - msq);
                LiftEval {
                    cl: base.cl * f,
                    dcl_dalpha: base.dcl_dalpha * f,
                    dcl_dmsq: base.dcl_dmsq * f + base.cl * f_msq,
                    ..base
                }
            }
            Kind::ReLift => {
                let f = (re.max(1.0) / RE_SCALING_REF).powf(p[0]);
                LiftEval {
                    cl: base.cl * f,
                    dcl_dalpha: base.dcl_dalpha * f,
                    dcl_dmsq: base.dcl_dmsq * f,
                    dcl_dre: base.dcl_dre * f + base.cl * f * p[0] / re.max(1.0),
                    ..base
                }
            }
            Kind::StallDelay => augment_lift(
                base,
                attached_lift(inner, alpha, msq),
                snel_fraction(p[0], ctx.geom.chord, ctx.geom.r),
            ),
            Kind::PostStall if base.stalled => match inner.as_qprop().and_then(|q| viterna(q, alpha, msq, p[0])) {
                Some((cl, dcl, _)) => LiftEval {
                    cl,
                    dcl_dalpha: dcl,
                    dcl_dmsq: 0.0,
                    ..base
                },
                None => base,
            },
            _ => base,
        })
    }

    fn drag(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        inner: &dyn SectionAero,
        d: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        Ok(match self.kind {
            Kind::ReScaling => {
                let re_ref = inner.as_qprop().map_or(RE_SCALING_REF, |q| q.coeffs.re_ref);
                cd * (d.re.max(1.0) / re_ref).powf(p[0])
            }
            Kind::DragScale => cd * p[0],
            Kind::Compressibility => {
                let rise = |mc: f64| if d.mach > mc { 10.0 * (d.mach - mc).powi(3) } else { 0.0 };
                let base_mcrit = inner.as_qprop().map_or(MCRIT0, |q| q.mcrit);
                cd - rise(base_mcrit) + rise(p[0])
            }
            Kind::PostStall if d.stalled => {
                let msq = d.mach * d.mach;
                match inner.as_qprop().and_then(|q| viterna(q, d.alpha, msq.min(0.9), p[0])) {
                    Some((_, _, cd_v)) => {
                        // The Reynolds-scaled profile drag stays; the stall term is Viterna's.
                        let k = inner.as_qprop().map(|q| q.coeffs);
                        let stall = k.map_or(0.0, |k| 2.0 * (d.alpha - (k.clcd0 - k.cl0) / k.cl_a).sin().powi(2));
                        (cd - stall).max(0.0).max(cd_v)
                    }
                    None => cd,
                }
            }
            _ => cd,
        })
    }

    fn loads(&self, p: &[f64], point: &PointState, result: &PointResult, l: &mut Loads) -> Result<(), EffectError> {
        match self.kind {
            Kind::ThrustTare => {
                let radius = 0.5 * point.diameter;
                let area = PI * radius * radius;
                let vs = point.v + result.dv;
                l.thrust -= p[0] * 0.5 * point.fluid.rho * vs * vs * area;
            }
            Kind::TorqueTare => l.torque += p[0] + p[1] * point.omega,
            _ => {}
        }
        Ok(())
    }
}
