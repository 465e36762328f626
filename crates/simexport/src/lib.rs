//! Exports for flight simulators, and a plain map for everything else: Gazebo's multicopter
//! motor model, PX4's SIH forward thruster, JSBSim's `<propeller>`, and CT, CP and efficiency
//! over (J, RPM) as CSV and JSON.
//!
//! Each is a simplified form of a set of operating points, a prediction's or a measurement's,
//! and says in a header comment what it came from and how well its simplified form reproduces
//! those points: thrust and torque, median and largest relative difference, over the points
//! carrying at least a quarter of the largest thrust coefficient (near zero thrust a relative
//! difference means nothing). Every file is computed before any is written: an export the data
//! cannot support is refused with what is missing.
//!
//! The formats, as their programs read them:
//! - Gazebo (`gz-sim-multicopter-motor-model-system`, and classic's `gazebo_motor_model`):
//!   thrust = `motorConstant` omega^2, drag torque = `momentConstant` thrust.
//! - PX4 SIH (`simulator_sih/aero.hpp`, `Thruster`): CT(J) = SIH_F_CT0 + SIH_F_CT1 J +
//!   SIH_F_CT2 J^2 and the same for CP, each clamped at 0; SIH_F_CT2 and SIH_F_CP2 at most 0,
//!   SIH_F_CT0 and SIH_F_CP0 above 0 (or SIH falls back to its constant-thrust model).
//! - JSBSim (`FGPropeller`): CT = C_THRUST(J) CT_MACH(M), CP = C_POWER(J) CP_MACH(M), M the
//!   helical tip Mach number; tables interpolated linearly and held at their ends.

use std::fmt::Write as _;

use propbet_units::rpm_to_rev_per_s;

use propbet_model::{nothing, out_of_range, unsuited, Result};

/// One operating point in coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Rotation speed [rpm].
    pub rpm: f64,
    /// Advance ratio J = V/(nD).
    pub j: f64,
    /// CT = T/(rho n^2 D^4).
    pub ct: f64,
    /// CP = P/(rho n^3 D^5) (torque follows as CP/(2 pi) rho n^2 D^5).
    pub cp: f64,
}

/// What an export is made from.
#[derive(Debug, Clone)]
pub struct Source {
    /// The operating points.
    pub points: Vec<Point>,
    /// Propeller diameter [m].
    pub diameter: f64,
    /// Number of blades.
    pub blades: f64,
    /// Moment of inertia about the shaft [kg m^2] and how it was found, when known.
    pub ixx: Option<(f64, String)>,
    /// What the points are, in a sentence ("propbet's prediction of ...").
    pub origin: String,
    /// A short name for the files (the propeller's).
    pub name: String,
    /// True for measurements: curves are smoothed before a table is made of them.
    pub measured: bool,
}

/// The exports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Gazebo's motor model: motorConstant and momentConstant, with the SDF plugin element.
    Gazebo,
    /// PX4 SIH's forward thruster: SIH_F_* parameters.
    Px4Sih,
    /// JSBSim's `<propeller>` file.
    Jsbsim,
    /// CT, CP and efficiency over (J, RPM), CSV and JSON.
    Map,
}

impl Target {
    /// Every target, in the order they are written.
    pub const ALL: [Target; 4] = [Target::Gazebo, Target::Px4Sih, Target::Jsbsim, Target::Map];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Target::Gazebo => "gazebo",
            Target::Px4Sih => "px4-sih",
            Target::Jsbsim => "jsbsim",
            Target::Map => "map",
        }
    }
}

/// How well an export reproduces the points it was made from: the QPROP export's measure
/// (thrust and torque, median and largest relative difference).
pub use propbet_qprop::export::Fidelity as Fit;

/// The fit of (model thrust-like, reference, model torque-like, reference) pairs.
fn fit_of(pairs: &[(f64, f64, f64, f64)]) -> Fit {
    let dt: Vec<f64> = pairs.iter().map(|p| ((p.0 - p.1) / p.1).abs()).collect();
    let dq: Vec<f64> = pairs.iter().map(|p| ((p.2 - p.3) / p.3).abs()).collect();
    Fit::of(&dt, &dq)
}

/// One export, ready to write.
#[derive(Debug, Clone)]
pub struct Exported {
    /// Which.
    pub target: Target,
    /// (file name, contents).
    pub files: Vec<(String, String)>,
    /// How well it reproduces the points.
    pub fit: Fit,
    /// Its values in one line, for the terminal.
    pub values: String,
}

/// The fraction of the largest thrust coefficient below which a point is not scored.
const COUNTED: f64 = 0.25;
/// Points at most this J are static.
const STATIC_J: f64 = 1e-3;
/// The speed of sound JSBSim's Mach tables are placed with (ISA sea level) [m/s].
const SOUND: f64 = 340.294;

/// Makes one export.
pub fn export(target: Target, src: &Source) -> Result<Exported> {
    match target {
        Target::Gazebo => gazebo(src, None),
        Target::Px4Sih => px4_sih(src),
        Target::Jsbsim => jsbsim(src),
        Target::Map => map(src),
    }
}

fn check(src: &Source) -> Result<()> {
    if !(src.diameter.is_finite() && src.diameter > 0.0) {
        out_of_range!("the propeller's diameter {} m is not a length", src.diameter);
    }
    if src.points.is_empty() {
        nothing!("no operating points to export");
    }
    if let Some(p) = src
        .points
        .iter()
        .find(|p| !(p.rpm > 0.0 && p.j.is_finite() && p.ct.is_finite() && p.cp.is_finite()))
    {
        out_of_range!(
            "an operating point without finite values (rpm {}, J {}, CT {}, CP {})",
            p.rpm,
            p.j,
            p.ct,
            p.cp
        );
    }
    Ok(())
}

/// The points that count in a fit error: CT at least a quarter of the largest.
fn counted(points: &[Point]) -> Vec<Point> {
    let ct_max = points.iter().map(|p| p.ct).fold(0.0, f64::max);
    points
        .iter()
        .copied()
        .filter(|p| ct_max > 0.0 && p.ct >= COUNTED * ct_max && p.cp > 0.0)
        .collect()
}

/// The comment lines every export starts with. What comes from the user (file names in the
/// origin) is made printable: a newline in a path must not start a live line of the file.
fn header(src: &Source, what: &str, fit: &Fit, prefix: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{prefix}{what}, written by propbet {}.", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "{prefix}From: {}", propbet_units::printable(&src.origin));
    let _ = writeln!(
        s,
        "{prefix}Diameter {:.4} m, {} blades. This file against those points: {}.",
        src.diameter,
        src.blades,
        fit.against()
    );
    s
}

/// Gazebo's motor model at the static points (all, or those in an RPM range).
pub fn gazebo(src: &Source, rpm_range: Option<(f64, f64)>) -> Result<Exported> {
    check(src)?;
    let statics: Vec<Point> = src
        .points
        .iter()
        .copied()
        .filter(|p| p.j.abs() <= STATIC_J && p.ct > 0.0 && p.cp > 0.0)
        .filter(|p| rpm_range.is_none_or(|(lo, hi)| p.rpm >= lo && p.rpm <= hi))
        .collect();
    if statics.is_empty() {
        let lowest = src.points.iter().map(|p| p.j).fold(f64::INFINITY, f64::min);
        let range = rpm_range.map_or(String::new(), |(lo, hi)| format!(" between {lo} and {hi} rpm"));
        unsuited!(
            "Gazebo's motor model is a static (hover) model: it needs points at zero airspeed{range}, \
             and these data have none with positive thrust (lowest J {lowest:.3}); give static points \
             (`--v 0` or `--j 0` in the sweep, or a static thrust-stand log)"
        );
    }
    let d = src.diameter;
    // thrust = kf omega^2 with kf = CT rho D^4 / (2 pi)^2; torque = km thrust with
    // km = CQ D / CT = CP D / (2 pi CT). Least squares in relative terms, at the density of
    // standard air, which the motor model assumes throughout.
    let rho = propbet_bemt::Fluid::QPROP_DEFAULT.rho;
    let tau = std::f64::consts::TAU;
    let kf_of = |p: &Point| p.ct * rho * d.powi(4) / (tau * tau);
    let km_of = |p: &Point| p.cp * d / (tau * p.ct);
    // Minimising sum ((k - k_i)/k_i)^2 gives k = sum(1/k_i) / sum(1/k_i^2).
    let rel_lsq = |ks: &[f64]| ks.iter().map(|k| 1.0 / k).sum::<f64>() / ks.iter().map(|k| 1.0 / (k * k)).sum::<f64>();
    let kfs: Vec<f64> = statics.iter().map(kf_of).collect();
    let kf = rel_lsq(&kfs);
    // Torque is km kf omega^2 in the plugin: km fitted to the torque with that kf.
    let kms: Vec<f64> = statics.iter().map(|p| km_of(p) * kf_of(p) / kf).collect();
    let km = rel_lsq(&kms);
    let pairs: Vec<(f64, f64, f64, f64)> = statics
        .iter()
        .map(|p| {
            let w2 = (tau * rpm_to_rev_per_s(p.rpm)).powi(2);
            let (t, q) = (kf_of(p) * w2, km_of(p) * kf_of(p) * w2);
            (kf * w2, t, km * kf * w2, q)
        })
        .collect();
    let fit = fit_of(&pairs);
    let rpm_lo = statics.iter().map(|p| p.rpm).fold(f64::INFINITY, f64::min);
    let rpm_hi = statics.iter().map(|p| p.rpm).fold(0.0, f64::max);
    let omega_max = tau * rpm_to_rev_per_s(rpm_hi);
    let mut c = header(src, "Gazebo multicopter motor model for this propeller", &fit, "  ");
    let _ = writeln!(
        c,
        "  Fitted at {} static points, {:.0} to {:.0} rpm, standard air (1.225 kg/m^3):\n  \
         thrust = motorConstant omega^2 [N], drag torque = momentConstant thrust [N m].\n  \
         maxRotVelocity is the largest RPM of the data, not the motor's limit: set the motor's.\n  \
         jointName, linkName, turningDirection and motorNumber are your model's: edit them.\n  \
         For Gazebo classic the same elements go in a gazebo_motor_model plugin (libgazebo_motor_model.so).",
        statics.len(),
        rpm_lo,
        rpm_hi
    );
    let mut s = format!("<?xml version=\"1.0\"?>\n<!--\n{}-->\n", xml_comment(&c));
    let _ = writeln!(
        s,
        "<plugin filename=\"gz-sim-multicopter-motor-model-system\" name=\"gz::sim::systems::MulticopterMotorModel\">\n  \
         <jointName>rotor_0_joint</jointName>\n  <linkName>rotor_0</linkName>\n  \
         <turningDirection>ccw</turningDirection>\n  <timeConstantUp>0.0125</timeConstantUp>\n  \
         <timeConstantDown>0.025</timeConstantDown>\n  <maxRotVelocity>{omega_max:.1}</maxRotVelocity>\n  \
         <motorConstant>{kf:.6e}</motorConstant>\n  <momentConstant>{km:.6e}</momentConstant>\n  \
         <commandSubTopic>command/motor_speed</commandSubTopic>\n  <motorNumber>0</motorNumber>\n  \
         <rotorDragCoefficient>0</rotorDragCoefficient>\n  <rollingMomentCoefficient>0</rollingMomentCoefficient>\n  \
         <rotorVelocitySlowdownSim>10</rotorVelocitySlowdownSim>\n  <motorType>velocity</motorType>\n</plugin>"
    );
    Ok(Exported {
        target: Target::Gazebo,
        files: vec![("gazebo_motor_model.sdf".into(), s)],
        fit,
        values: format!("motorConstant {kf:.4e} N s^2, momentConstant {km:.4e} m, maxRotVelocity {omega_max:.0} rad/s"),
    })
}

/// Least squares a + b x + c x^2 through (x, y) with weights w, c held at most 0 (PX4's
/// parameter bound): the quadratic when its c is not positive, else the line.
fn quadratic_le0(xs: &[f64], ys: &[f64], ws: &[f64]) -> Option<[f64; 3]> {
    let q = poly_lsq(xs, ys, ws, 2)?;
    if q[2] <= 0.0 {
        return Some([q[0], q[1], q[2]]);
    }
    let l = poly_lsq(xs, ys, ws, 1)?;
    Some([l[0], l[1], 0.0])
}

/// Weighted least squares of a polynomial of degree `deg` through (x, y): its coefficients,
/// constant first.
fn poly_lsq(xs: &[f64], ys: &[f64], ws: &[f64], deg: usize) -> Option<Vec<f64>> {
    let a = nalgebra::DMatrix::from_fn(xs.len(), deg + 1, |i, k| ws[i] * xs[i].powi(k as i32));
    let b = nalgebra::DVector::from_iterator(ys.len(), ys.iter().zip(ws).map(|(y, w)| y * w));
    let x = a.svd(true, true).solve(&b, 1e-14).ok()?;
    Some(x.iter().copied().collect())
}

fn distinct_j(points: &[Point]) -> usize {
    let mut js: Vec<f64> = points.iter().map(|p| (p.j * 1e3).round()).collect();
    js.sort_by(f64::total_cmp);
    js.dedup();
    js.len()
}

/// PX4 SIH's forward thruster: CT(J) and CP(J) quadratics over every RPM.
pub fn px4_sih(src: &Source) -> Result<Exported> {
    check(src)?;
    let pts = counted(&src.points);
    if distinct_j(&pts) < 3 {
        unsuited!(
            "PX4 SIH's CT(J) and CP(J) need points at 3 or more advance ratios with thrust; {}: \
             {}",
            if distinct_j(&src.points) <= 1 {
                "these data have only static points (J = 0)".to_string()
            } else {
                format!("these data have {} with thrust", distinct_j(&pts))
            },
            sweep_advice(src)
        );
    }
    let xs: Vec<f64> = pts.iter().map(|p| p.j).collect();
    let ct: Vec<f64> = pts.iter().map(|p| p.ct).collect();
    let cp: Vec<f64> = pts.iter().map(|p| p.cp).collect();
    // Relative least squares: each point weighs 1/value.
    let w_ct: Vec<f64> = ct.iter().map(|v| 1.0 / v).collect();
    let w_cp: Vec<f64> = cp.iter().map(|v| 1.0 / v).collect();
    let (Some(a), Some(b)) = (quadratic_le0(&xs, &ct, &w_ct), quadratic_le0(&xs, &cp, &w_cp)) else {
        unsuited!("the CT(J) and CP(J) least squares have no solution for these points");
    };
    if a[0] <= 0.0 || b[0] <= 0.0 {
        unsuited!(
            "the fitted static coefficients are not positive (SIH_F_CT0 {:.4}, SIH_F_CP0 {:.4}): SIH would fall back \
             to its constant-thrust model",
            a[0],
            b[0]
        );
    }
    let poly = |c: &[f64; 3], j: f64| (c[0] + c[1] * j + c[2] * j * j).max(0.0);
    let pairs: Vec<(f64, f64, f64, f64)> = pts.iter().map(|p| (poly(&a, p.j), p.ct, poly(&b, p.j), p.cp)).collect();
    let fit = fit_of(&pairs);
    let rpm_max = src.points.iter().map(|p| p.rpm).fold(0.0, f64::max);
    let dia_inch = src.diameter / 0.0254;
    let mut s = header(
        src,
        "PX4 SIH forward-thruster parameters for this propeller",
        &fit,
        "# ",
    );
    let _ = writeln!(
        s,
        "# CT(J) = SIH_F_CT0 + SIH_F_CT1 J + SIH_F_CT2 J^2, CP(J) likewise (PX4's simulator_sih), least squares\n\
         # in relative terms over J {:.3} to {:.3} at every RPM of the data (SIH has no RPM dependence).\n\
         # SIH_F_RPM_MAX is the largest RPM of the data, not the motor's limit: set the motor's.\n\
         # Lines for an airframe file (or `param set` in the PX4 shell).",
        xs.iter().copied().fold(f64::INFINITY, f64::min),
        xs.iter().copied().fold(0.0, f64::max)
    );
    let params = [
        ("SIH_F_DIA_INCH", dia_inch),
        ("SIH_F_RPM_MAX", rpm_max.round()),
        ("SIH_F_CT0", a[0]),
        ("SIH_F_CT1", a[1]),
        ("SIH_F_CT2", a[2]),
        ("SIH_F_CP0", b[0]),
        ("SIH_F_CP1", b[1]),
        ("SIH_F_CP2", b[2]),
    ];
    for (k, v) in params {
        let _ = writeln!(s, "param set-default {k} {}", short(v));
    }
    Ok(Exported {
        target: Target::Px4Sih,
        files: vec![("px4_sih.params".into(), s)],
        fit,
        values: format!(
            "CT(J) = {} {:+.5} J {:+.5} J^2, CP(J) = {} {:+.5} J {:+.5} J^2",
            short(a[0]),
            a[1],
            a[2],
            short(b[0]),
            b[1],
            b[2]
        ),
    })
}

/// Six significant digits, no exponent for the sizes these files hold.
fn short(v: f64) -> String {
    let s = format!("{v:.6}");
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.6e}")
    } else {
        s
    }
}

/// One RPM's curve: (J, CT, CP) sorted by J.
#[derive(Debug, Clone)]
struct Curve {
    rpm: f64,
    rows: Vec<[f64; 3]>,
}

/// Polynomial least squares of degree `deg` evaluated at `at`.
fn smooth(xs: &[f64], ys: &[f64], deg: usize, at: &[f64]) -> Option<Vec<f64>> {
    let c = poly_lsq(xs, ys, &vec![1.0; xs.len()], deg)?;
    Some(
        at.iter()
            .map(|x| c.iter().rev().fold(0.0, |acc, ck| acc * x + ck))
            .collect(),
    )
}

/// The smoothing applied to measured curves, as the files state it.
pub const SMOOTHING: &str = "each RPM's measured CT(J) and CP(J) smoothed by a least-squares polynomial of degree 3 \
(fewer with fewer than 5 advance ratios), evaluated every 0.025 in J over the measured range";

/// The data as curves of constant RPM (within 3 %) with 3 or more advance ratios; measured
/// curves smoothed ([`SMOOTHING`]).
fn curves(src: &Source) -> Vec<Curve> {
    let mut pts = src.points.clone();
    pts.sort_by(|a, b| a.rpm.total_cmp(&b.rpm));
    // Measurements within 3 % of RPM are one curve (a stand's steps drift); a prediction's
    // points are each at their own RPM, and each RPM is its own curve, labelled with it.
    let within = if src.measured { 1.03 } else { 1.0 };
    let mut groups: Vec<Vec<Point>> = Vec::new();
    for p in pts {
        match groups.last_mut() {
            Some(g) if p.rpm <= g[0].rpm * within => g.push(p),
            _ => groups.push(vec![p]),
        }
    }
    groups
        .into_iter()
        .filter(|g| distinct_j(g) >= 3)
        .filter_map(|mut g| {
            g.sort_by(|a, b| a.j.total_cmp(&b.j));
            let mut rpms: Vec<f64> = g.iter().map(|p| p.rpm).collect();
            rpms.sort_by(f64::total_cmp);
            let rpm = rpms[rpms.len() / 2];
            let rows: Vec<[f64; 3]> = if src.measured {
                let xs: Vec<f64> = g.iter().map(|p| p.j).collect();
                let deg = (distinct_j(&g) - 2).min(3);
                let (lo, hi) = (xs[0], xs[xs.len() - 1]);
                let steps = ((hi - lo) / 0.025).floor() as usize;
                let mut at: Vec<f64> = (0..=steps).map(|k| lo + 0.025 * k as f64).collect();
                if hi - at[at.len() - 1] > 1e-6 {
                    at.push(hi);
                }
                let ct = smooth(&xs, &g.iter().map(|p| p.ct).collect::<Vec<_>>(), deg, &at)?;
                let cp = smooth(&xs, &g.iter().map(|p| p.cp).collect::<Vec<_>>(), deg, &at)?;
                at.iter()
                    .zip(ct.iter().zip(&cp))
                    .map(|(j, (t, p))| [*j, *t, *p])
                    .collect()
            } else {
                let mut rows: Vec<[f64; 3]> = g.iter().map(|p| [p.j, p.ct, p.cp]).collect();
                rows.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-9);
                rows
            };
            Some(Curve { rpm, rows })
        })
        .collect()
}

/// Linear interpolation in a table sorted by x, held at its ends (JSBSim's FGTable).
fn lookup(table: &[(f64, f64)], x: f64) -> f64 {
    let n = table.len();
    if x <= table[0].0 {
        return table[0].1;
    }
    if x >= table[n - 1].0 {
        return table[n - 1].1;
    }
    let k = table.partition_point(|r| r.0 <= x).max(1);
    let (a, b) = (table[k - 1], table[k]);
    a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
}

fn curve_at(c: &Curve, j: f64, col: usize) -> f64 {
    let t: Vec<(f64, f64)> = c.rows.iter().map(|r| (r[0], r[col])).collect();
    lookup(&t, j)
}

fn too_few_curves(src: &Source, what: &str) -> propbet_model::Error {
    let js = distinct_j(&src.points);
    let why = if js <= 1 {
        "these data have only static points (J = 0)".to_string()
    } else {
        "no RPM of these data has 3 or more advance ratios".to_string()
    };
    propbet_model::Error::Unsuited(format!(
        "{what} needs curves over J (3 or more advance ratios at one RPM); {why}: {}",
        sweep_advice(src)
    ))
}

/// What would give the points over J an export needs: a sweep for a prediction, files of a
/// stream for measurements (`--j` does not go with `--measured`).
fn sweep_advice(src: &Source) -> &'static str {
    if src.measured {
        "give measurements in a stream (wind-tunnel files, or a log with airspeed), or export the \
         prediction with --prop and --j 0:0.6:0.05"
    } else {
        "give a J sweep (`--j 0:0.6:0.05`)"
    }
}

/// A name fit for a file: letters, digits, '-', '_' and '.' kept, the rest '_'.
pub fn file_stem(name: &str) -> String {
    // The name before any parenthesis or comma, at most 40 characters, one '_' between words.
    let head = name.split(['(', ',', ';']).next().unwrap_or("");
    let s: String = head
        .chars()
        .take(40)
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let mut s = s.trim_matches(|c| c == '_' || c == '.').to_string();
    while s.contains("__") {
        s = s.replace("__", "_");
    }
    if s.is_empty() {
        "propeller".into()
    } else {
        s
    }
}

/// Text safe inside an XML comment, which may not hold "--".
fn xml_comment(s: &str) -> String {
    let mut s = s.to_string();
    while s.contains("--") {
        s = s.replace("--", "- -");
    }
    s
}

fn xml_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// CT, CP and efficiency over (J, RPM): the prediction's points as they are, or the
/// measurements smoothed.
pub fn map(src: &Source) -> Result<Exported> {
    check(src)?;
    let cs = curves(src);
    if cs.is_empty() {
        return Err(too_few_curves(src, "A map over (J, RPM)"));
    }
    if cs.len() < 2 {
        unsuited!(
            "a map over (J, RPM) needs curves at 2 or more RPMs; these data have one ({:.0} rpm): \
             give more RPMs (`--rpm 4000,6000`) or more files, or export jsbsim or px4-sih for one RPM",
            cs[0].rpm
        );
    }
    // Its fit: the measured points against the smoothed curves (a prediction's are its own).
    let pts = counted(&src.points);
    let pairs: Vec<(f64, f64, f64, f64)> = pts
        .iter()
        .filter_map(|p| {
            let c = cs.iter().find(|c| (p.rpm - c.rpm).abs() <= 0.03 * c.rpm)?;
            let (lo, hi) = (c.rows[0][0], c.rows[c.rows.len() - 1][0]);
            (p.j >= lo - 1e-9 && p.j <= hi + 1e-9).then(|| (curve_at(c, p.j, 1), p.ct, curve_at(c, p.j, 2), p.cp))
        })
        .collect();
    let fit = fit_of(&pairs);
    let note = if src.measured {
        format!("Smoothing: {SMOOTHING}.")
    } else {
        "The prediction's own points, no fit.".to_string()
    };
    let mut csv = header(src, "CT, CP and efficiency over (J, RPM)", &fit, "# ");
    let _ = writeln!(
        csv,
        "# {note}\n# CT = T/(rho n^2 D^4), CP = P/(rho n^3 D^5), eta = J CT/CP; v at this diameter."
    );
    csv.push_str("rpm,j,v_m_s,ct,cp,eta\n");
    let mut json_curves = Vec::new();
    for c in &cs {
        let mut rows = Vec::new();
        for r in &c.rows {
            let eta = if r[0] > 0.0 && r[1] > 0.0 && r[2] > 0.0 {
                r[0] * r[1] / r[2]
            } else {
                0.0
            };
            let v = r[0] * rpm_to_rev_per_s(c.rpm) * src.diameter;
            let _ = writeln!(
                csv,
                "{:.0},{:.4},{:.4},{:.6},{:.6},{:.4}",
                c.rpm, r[0], v, r[1], r[2], eta
            );
            rows.push(serde_json::json!({"j": r[0], "v_m_s": v, "ct": r[1], "cp": r[2], "eta": eta}));
        }
        json_curves.push(serde_json::json!({"rpm": c.rpm, "points": rows}));
    }
    let doc = serde_json::json!({
        "propeller": src.name,
        "from": src.origin,
        "note": note,
        "diameter_m": src.diameter,
        "blades": src.blades,
        "fit": fit,
        "curves": json_curves,
    });
    let mut json = serde_json::to_string_pretty(&doc).map_err(|e| propbet_model::Error::Unsuited(e.to_string()))?;
    json.push('\n');
    Ok(Exported {
        target: Target::Map,
        files: vec![("map.csv".into(), csv), ("map.json".into(), json)],
        fit,
        values: format!(
            "{} RPMs ({}), {} points",
            cs.len(),
            cs.iter()
                .map(|c| format!("{:.0}", c.rpm))
                .collect::<Vec<_>>()
                .join(", "),
            cs.iter().map(|c| c.rows.len()).sum::<usize>()
        ),
    })
}

mod jsbsim;
mod source;

pub use jsbsim::{blade_ixx, jsbsim, IXX_ASSUMED};
pub use source::{exports, exports_of, predicted_by, source, ExportFrom, ExportSpec, Said};

#[cfg(test)]
mod tests;
