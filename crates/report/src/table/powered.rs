//! The table of `propbet predict --motor`: one row per (driver, airspeed) point with QPROP's
//! electrical columns (propbet's names and SI units), then the battery's and the band's where
//! asked for; as CSV, as JSON records, or as typed columns.

use propbet_bemt::{Fluid, PointResult};
use propbet_compare::band::PointBand;
use propbet_model::Model;
use propbet_motor::{Drive, Powered};
use propbet_pipeline::stages::{PoweredPoint, PoweredTable};
use propbet_settings::spec::TableFormat;
use propbet_units::{omega_to_rpm, seconds_to_minutes};

use super::columns::{table, Table};
use super::{csv_rows, Error, Num};

/// A powered prediction: the table, and what its rows say of the air and the propeller.
pub struct PoweredRun {
    /// The motor, the points (one per driver value and airspeed) and their band.
    pub table: PoweredTable,
    rho: f64,
    air: String,
    tip_radius: f64,
    battery: bool,
}

impl PoweredRun {
    /// The rows of `table`, solved with `model` in `fluid` (and its air's words).
    pub fn new(table: PoweredTable, model: &Model, fluid: &(Fluid, String), battery: bool) -> PoweredRun {
        PoweredRun {
            table,
            rho: fluid.0.rho,
            air: fluid.1.clone(),
            tip_radius: model.rotor.tip_radius,
            battery,
        }
    }

    /// Each row: QPROP's columns, then the battery's (with a battery) and the band's (with
    /// `--band`).
    fn rows(&self) -> impl Iterator<Item = (PoweredRow, Tail)> + '_ {
        self.table.points.iter().enumerate().map(|(i, p)| {
            let tail = Tail {
                battery: self.battery.then(|| battery_columns(p)),
                band: self.table.band.as_ref().map(|b| band_columns(b[i].as_ref())),
            };
            (row(p, self.rho, &self.air, self.tip_radius), tail)
        })
    }

    /// The table's columns.
    pub fn table(&self) -> Result<Table, super::columns::Error> {
        table(self.rows())
    }

    /// The table as CSV.
    pub fn csv(&self) -> Result<Vec<u8>, csv::Error> {
        csv_rows(self.rows(), true)
    }
}

impl PoweredRun {
    /// Each operating point found, in the table's order (a point without one has none).
    pub fn solved(&self) -> Vec<PointResult> {
        self.table
            .points
            .iter()
            .filter_map(|p| p.outcome.as_ref().ok().map(|(_, r)| r.clone()))
            .collect()
    }

    /// The table in `format`.
    pub fn body(&self, format: TableFormat) -> Result<Vec<u8>, Error> {
        Ok(match format {
            TableFormat::Csv => self.csv()?,
            TableFormat::Json => json_records(&self.table()?)?,
        })
    }

    /// The terminal's warnings: the first points without an operating point, and the
    /// stations that did not converge.
    pub fn warnings(&self) -> Vec<String> {
        let points = &self.table.points;
        let unsolved: Vec<(&PoweredPoint, &str)> = points.iter().filter_map(|p| p.problem().map(|w| (p, w))).collect();
        let mut out: Vec<String> = unsolved
            .iter()
            .take(5)
            .map(|(p, why)| format!("warning: V {} m/s: {why}", p.v))
            .collect();
        if unsolved.len() > 5 {
            out.push(format!(
                "warning: {} more points without an operating point",
                unsolved.len() - 5
            ));
        }
        let failed: usize = points
            .iter()
            .filter_map(|p| p.outcome.as_ref().ok())
            .map(|(_, r)| r.not_converged)
            .sum();
        if failed > 0 {
            out.push(format!(
                "{failed} station solutions did not converge (column not_converged)"
            ));
        }
        out
    }
}

/// A row of the powered table: QPROP's columns (propbet's names and SI units) and g/W.
#[derive(serde::Serialize)]
struct PoweredRow {
    v_m_s: Num,
    rpm: Num,
    volts: Num,
    amps: Num,
    thrust_n: Num,
    torque_nm: Num,
    shaft_power_w: Num,
    electrical_power_w: Num,
    eta_motor: Num,
    eta_prop: Num,
    eta_total: Num,
    g_per_w: Num,
    j: Num,
    ct: Num,
    cp: Num,
    adv_qprop: Num,
    ct_qprop: Num,
    cp_qprop: Num,
    dv_m_s: Num,
    cl_avg: Num,
    cd_avg: Num,
    not_converged: Option<usize>,
    flags: String,
    /// Why the point has no operating point (empty where it has one).
    no_solution: String,
    rho_kg_m3: Num,
    air: String,
}

fn row(p: &PoweredPoint, rho: f64, air: &str, tip_radius: f64) -> PoweredRow {
    let none = Num(None);
    let (solved, r): (Option<&Powered>, Option<&PointResult>) = match &p.outcome {
        Ok((s, r)) => (Some(s), Some(r)),
        Err(_) => (None, None),
    };
    // A point without a solution keeps its driver's value in the driver's own column.
    let (mut rpm, mut volts, mut amps, mut thrust) = (None, None, None, None);
    match p.drive {
        Drive::Omega(w) => rpm = Some(omega_to_rpm(w)),
        Drive::Volts(v) => volts = Some(v),
        Drive::Amps(a) => amps = Some(a),
        Drive::Thrust(t) => thrust = Some(t),
        Drive::Throttle { .. } => {}
    }
    PoweredRow {
        v_m_s: p.v.into(),
        rpm: solved.map(|s| omega_to_rpm(s.omega)).or(rpm).into(),
        volts: solved.map(|s| s.volts).or(volts).into(),
        amps: solved.map(|s| s.amps).or(amps).into(),
        thrust_n: solved.map(|s| s.loads.thrust).or(thrust).into(),
        torque_nm: solved.map(|s| s.loads.torque).into(),
        shaft_power_w: solved.map(Powered::shaft_power).into(),
        electrical_power_w: solved.map(Powered::electrical_power).into(),
        eta_motor: solved.map(Powered::motor_efficiency).into(),
        eta_prop: r.map(|r| r.eta).into(),
        eta_total: solved.zip(r).map(|(s, r)| s.motor_efficiency() * r.eta).into(),
        g_per_w: solved.map(Powered::grams_per_watt).into(),
        j: r.and_then(|r| r.j).into(),
        ct: r.and_then(|r| r.ct).into(),
        cp: r.and_then(|r| r.cp).into(),
        adv_qprop: r.and_then(|r| r.adv_qprop).into(),
        ct_qprop: r.and_then(|r| r.ct_qprop).into(),
        cp_qprop: r.and_then(|r| r.cp_qprop).into(),
        dv_m_s: r.map(|r| r.dv).into(),
        cl_avg: r.map(|r| r.cl_avg).into(),
        cd_avg: r.map(|r| r.cd_avg).into(),
        not_converged: r.map(|r| r.not_converged),
        flags: r
            .map(|r| propbet_bemt::check::implausible(r, rho, tip_radius).join("; "))
            .unwrap_or_default(),
        no_solution: p.problem().unwrap_or_default().to_string(),
        rho_kg_m3: if r.is_some() { rho.into() } else { none },
        air: super::sweep::air_cell(air),
    }
}

/// The columns after QPROP's: the battery's and the band's, each where asked for.
struct Tail {
    battery: Option<BatteryColumns>,
    band: Option<super::sweep::BandColumns>,
}

impl serde::Serialize for Tail {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("Tail", 11)?;
        if let Some(b) = &self.battery {
            st.serialize_field("throttle", &b.throttle)?;
            st.serialize_field("battery_volts", &b.battery_volts)?;
            st.serialize_field("battery_amps", &b.battery_amps)?;
            st.serialize_field("battery_power_w", &b.battery_power_w)?;
            st.serialize_field("endurance_min", &b.endurance_min)?;
        }
        if let Some(b) = &self.band {
            st.serialize_field("ct_lo", &b.ct_lo)?;
            st.serialize_field("ct_hi", &b.ct_hi)?;
            st.serialize_field("cp_lo", &b.cp_lo)?;
            st.serialize_field("cp_hi", &b.cp_hi)?;
            st.serialize_field("eta_lo", &b.eta_lo)?;
            st.serialize_field("eta_hi", &b.eta_hi)?;
        }
        st.end()
    }
}

/// The band's columns of a row: empty where the point has no operating point.
fn band_columns(b: Option<&PointBand>) -> super::sweep::BandColumns {
    super::sweep::BandColumns {
        ct_lo: b.map(|b| b.ct.lo).into(),
        ct_hi: b.map(|b| b.ct.hi).into(),
        cp_lo: b.map(|b| b.cp.lo).into(),
        cp_hi: b.map(|b| b.cp.hi).into(),
        eta_lo: b.map(|b| b.eta.lo).into(),
        eta_hi: b.map(|b| b.eta.hi).into(),
    }
}

/// The battery's columns of a row (with --battery): empty where the battery cannot give the
/// point.
struct BatteryColumns {
    throttle: Num,
    battery_volts: Num,
    battery_amps: Num,
    battery_power_w: Num,
    endurance_min: Num,
}

fn battery_columns(p: &PoweredPoint) -> BatteryColumns {
    let s = p.supply.as_ref().and_then(|s| s.as_ref().ok());
    BatteryColumns {
        throttle: s.map(|s| s.throttle).into(),
        battery_volts: s.map(|s| s.battery_volts).into(),
        battery_amps: s.map(|s| s.battery_amps).into(),
        battery_power_w: s.map(|s| s.battery_power).into(),
        endurance_min: s.and_then(|s| s.endurance).map(seconds_to_minutes).into(),
    }
}

/// A table as a JSON array of records: numbers as numbers, an empty cell as null.
fn json_records(t: &Table) -> serde_json::Result<Vec<u8>> {
    use super::columns::Column;
    use serde_json::Value;
    let rows = t.columns.first().map_or(0, |c| match c {
        Column::Num(v) => v.len(),
        Column::Int(v) => v.len(),
        Column::Bool(v) => v.len(),
        Column::Text(v) => v.len(),
    });
    let records: Vec<Value> = (0..rows)
        .map(|i| {
            let fields = t.names.iter().zip(&t.columns).map(|(name, c)| {
                let v = match c {
                    Column::Num(v) => serde_json::Number::from_f64(v[i]).map_or(Value::Null, Value::Number),
                    Column::Int(v) => v[i].into(),
                    Column::Bool(v) => v[i].into(),
                    Column::Text(v) => v[i].clone().into(),
                };
                (name.clone(), v)
            });
            Value::Object(fields.collect())
        })
        .collect();
    let mut j = serde_json::to_vec_pretty(&records)?;
    j.push(b'\n');
    Ok(j)
}
