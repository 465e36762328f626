//! Writers of the formats this crate reads: the generic CSV, UIUC `J CT CP eta` files and an
//! RCbenchmark step log, for synthetic measurements (`propbet synth`) and tests. Each writes
//! what [`crate::read`] reads back.

use std::fmt::Write as _;

/// One measured point to write.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Point {
    /// Rotation rate [rad/s] (as logged).
    pub omega: f64,
    /// Airspeed [m/s].
    pub v: f64,
    /// Advance ratio with the logged rotation rate.
    pub j: f64,
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
}

/// One sample of a thrust-stand log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogSample {
    /// Time [s].
    pub time: f64,
    /// ESC pulse width [µs].
    pub esc: u32,
    /// Rotation rate [rad/s].
    pub omega: f64,
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
}

/// Generic CSV, self-describing header (`rpm,airspeed_m_s,thrust_N,torque_Nm,air_temp_C,
/// pressure_Pa`); `air` is the logged temperature [K] and pressure [Pa].
pub fn generic(points: &[Point], air: (f64, f64)) -> String {
    let mut s = String::from("rpm,airspeed_m_s,thrust_N,torque_Nm,air_temp_C,pressure_Pa\n");
    for p in points {
        let _ = writeln!(
            s,
            "{:.1},{:.4},{:.6},{:.7},{:.2},{:.0}",
            propbet_units::omega_to_rpm(p.omega),
            p.v,
            p.thrust,
            p.torque,
            air.0 - 273.15,
            air.1
        );
    }
    s
}

/// UIUC files: one `J CT CP eta` sweep per rotation rate in `omegas`, named
/// `{stem}_{rpm}.txt` (the reader takes the RPM from the name); coefficients with density
/// `rho` [kg/m^3] and diameter `d` [m].
pub fn uiuc(points: &[Point], omegas: &[f64], rho: f64, d: f64, stem: &str) -> Vec<(String, String)> {
    let mut files = Vec::new();
    for &omega in omegas {
        let n = propbet_units::omega_to_rev_per_s(omega);
        let scale = propbet_units::Scales::new(rho, n, d);
        let mut s = String::from("J       CT       CP       eta\n");
        for p in points.iter().filter(|p| p.omega == omega) {
            let ct = p.thrust / scale.thrust;
            let cp = p.torque * 2.0 * std::f64::consts::PI * n / scale.power;
            let eta = if cp > 0.0 { p.j * ct / cp } else { 0.0 };
            let _ = writeln!(s, "{:.3}   {:.5}   {:.5}   {:.3}", p.j, ct, cp, eta);
        }
        files.push((format!("{stem}_{:.0}.txt", propbet_units::omega_to_rpm(omega)), s));
    }
    files
}

/// An RCbenchmark log of the samples (11.1 V, 75 % motor efficiency, both speed columns).
pub fn rcbenchmark(samples: &[LogSample]) -> String {
    let mut s = String::from(
        "Time (s),ESC signal (µs),Torque (N·m),Thrust (N),Voltage (V),Current (A),Motor Electrical Speed (RPM),\
         Motor Optical Speed (RPM),Electrical Power (W),Mechanical Power (W),Motor Efficiency (%),\
         Propeller Mech. Efficiency (N/W),Overall Efficiency (N/W),App message,\n",
    );
    for x in samples {
        let (t, esc, q, th) = (x.time, x.esc, x.torque, x.thrust);
        let rpm = propbet_units::omega_to_rpm(x.omega);
        let mech = q * x.omega;
        let elec = mech / 0.75;
        let _ = writeln!(
            s,
            "{t:.2},{esc},{q:.5},{th:.4},11.10,{:.3},{rpm:.0},{rpm:.0},{elec:.3},{mech:.3},75.00,{:.4},{:.4},,",
            elec / 11.1,
            if mech > 0.0 { th / mech } else { 0.0 },
            if elec > 0.0 { th / elec } else { 0.0 },
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{read, Loads, ReadOptions, Speed};

    fn pts() -> Vec<Point> {
        let w = propbet_units::rpm_to_omega(5000.0);
        (0..4)
            .map(|k| Point {
                omega: w,
                v: 2.0 * k as f64,
                j: 0.1 * k as f64,
                thrust: 4.0 - k as f64,
                torque: 0.1,
            })
            .collect()
    }

    #[test]
    fn written_files_read_back() {
        let g = read(&generic(&pts(), (288.15, 101325.0)), &ReadOptions::default()).unwrap();
        assert_eq!(g.points.len(), 4);
        let files = uiuc(&pts(), &[propbet_units::rpm_to_omega(5000.0)], 1.225, 0.25, "x");
        assert_eq!(files[0].0, "x_5000.txt");
        let u = read(
            &files[0].1,
            &ReadOptions {
                name: Some(files[0].0.clone()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(u.points.len(), 4);
        assert!(matches!(u.points[1].loads, Loads::Coefficients { .. }));
        assert!(matches!(u.points[1].speed, Speed::AdvanceRatio(_)));
        let w = propbet_units::rpm_to_omega(6000.0);
        let samples: Vec<LogSample> = (0..8)
            .map(|k| LogSample {
                time: 0.5 * k as f64,
                esc: 1500,
                omega: w,
                thrust: 5.0,
                torque: 0.1,
            })
            .collect();
        let r = read(&rcbenchmark(&samples), &ReadOptions::default()).unwrap();
        assert_eq!(r.points.len(), 1);
        assert!((r.points[0].omega.mean / w - 1.0).abs() < 1e-3);
    }
}
