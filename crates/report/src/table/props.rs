//! `props.csv` of `propbet compare-props`: the propellers ranked by grams per watt at hover,
//! with full throttle's thrust and current and their ranges over each prediction's band.

use propbet_pipeline::stages::SideProp;

use super::columns::{table, Table};
use super::{csv_rows, Num};

/// A row of props.csv.
#[derive(serde::Serialize)]
struct Row {
    rank: usize,
    prop: String,
    diameter_m: Num,
    hover_thrust_n: Num,
    hover_g_per_w: Num,
    hover_g_per_w_lo: Num,
    hover_g_per_w_hi: Num,
    hover_throttle: Num,
    hover_battery_amps: Num,
    hover_motor_amps: Num,
    hover_rpm: Num,
    hover_endurance_min: Num,
    full_thrust_n: Num,
    full_thrust_lo_n: Num,
    full_thrust_hi_n: Num,
    full_battery_amps: Num,
    full_battery_amps_lo: Num,
    full_battery_amps_hi: Num,
    full_rpm: Num,
    no_hover: String,
}

fn row(k: usize, p: &SideProp, hover: f64) -> Row {
    let h = p.hover.as_ref().ok();
    let f = p.full.first().and_then(|(_, r)| r.as_ref().ok());
    let band = p.full_band.first().copied().flatten();
    use propbet_units::{omega_to_rpm, seconds_to_minutes};
    Row {
        rank: k + 1,
        prop: p.name.clone(),
        diameter_m: p.diameter.into(),
        hover_thrust_n: hover.into(),
        hover_g_per_w: p.hover_g_per_w().into(),
        hover_g_per_w_lo: p.hover_band.map(|b| b.0).into(),
        hover_g_per_w_hi: p.hover_band.map(|b| b.1).into(),
        hover_throttle: h.map(|x| x.2.throttle).into(),
        hover_battery_amps: h.map(|x| x.2.battery_amps).into(),
        hover_motor_amps: h.map(|x| x.0.amps).into(),
        hover_rpm: h.map(|x| omega_to_rpm(x.0.omega)).into(),
        hover_endurance_min: h.and_then(|x| x.2.endurance).map(seconds_to_minutes).into(),
        full_thrust_n: f.map(|x| x.0.loads.thrust).into(),
        full_thrust_lo_n: band.map(|b| b.thrust.0).into(),
        full_thrust_hi_n: band.map(|b| b.thrust.1).into(),
        full_battery_amps: f.map(|x| x.2.battery_amps).into(),
        full_battery_amps_lo: band.map(|b| b.battery_amps.0).into(),
        full_battery_amps_hi: band.map(|b| b.battery_amps.1).into(),
        full_rpm: f.map(|x| omega_to_rpm(x.0.omega)).into(),
        no_hover: p.hover.as_ref().err().cloned().unwrap_or_default(),
    }
}

/// The ranked table as CSV (`hover`: the thrust of one propeller at hover [N]).
pub fn csv(props: &[SideProp], hover: f64) -> Result<Vec<u8>, csv::Error> {
    csv_rows(props.iter().enumerate().map(|(k, p)| row(k, p, hover)), true)
}

/// The ranked table's columns.
pub fn columns(props: &[SideProp], hover: f64) -> Result<Table, super::columns::Error> {
    table(props.iter().enumerate().map(|(k, p)| row(k, p, hover)))
}
