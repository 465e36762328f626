#!/usr/bin/env python3
"""Writes the two Tyto Robotics samples of this folder (run from it; deterministic).

Column names as public readers of real Flight Stand and Tyto database exports use them; values
and column order made up (a 10-inch propeller at 1.46e-7 N/rpm^2 and 2.5e-9 N m/rpm^2)."""
import math

MU, DOT = "\u03bc", "\u22c5"  # Flight Stand's micro sign and torque dot


def load(rpm):
    return 1.46e-7 * rpm * rpm, 2.5e-9 * rpm * rpm


def flight_stand():
    names = ["Time (s)"]
    for k in (1, 2):
        p = f"Powertrain {k} - "
        names += [p + f"ESC throttle ({MU}s)", p + "voltage (V)", p + "current (A)",
                  p + "rotation speed (rpm)", p + "force Fz (thrust) (kgf)",
                  p + f"torque MZ (torque) (N{DOT}m)", p + "electrical power (W)",
                  p + "mechanical power (W)", p + "motor & ESC efficiency (%)",
                  p + "propeller efficiency (gf/W)", p + "powertrain efficiency (gf/W)"]
    rows = [",".join(names)]
    t = 0.0
    for step, throttle in enumerate(range(1100, 1900, 100)):
        rpm = [1500.0 * (step + 1), 1400.0 * (step + 1)]
        for i in range(60):
            t += 0.02
            cells = [f"{t:.2f}"]
            for k in (0, 1):
                wobble = 1 + 0.002 * math.sin(7 * i + k)
                r = rpm[k] * wobble
                thrust, torque = load(r)
                # The stand's axes: thrust logged negative, torque positive; loads on every
                # fourth row, the rest empty (each sensor at its own rate).
                has_load = (i + k) % 4 == 0
                cells += [str(throttle), "16.2", f"{0.5 + 1e-3 * r:.3f}", f"{r:.1f}",
                          f"{-thrust / 9.80665:.5f}" if has_load else "",
                          f"{torque:.5f}" if has_load else "", "", "", "", "", ""]
            rows.append(",".join(cells))
    return "\n".join(rows) + "\n"


def database():
    names = ["Time (s)", "Throttle (\u00b5s)", "Rotation speed (rpm)", "Thrust (kgf)",
             f"Torque (N{DOT}m)", "Voltage (V)", "Current (A)", "Electrical power (W)",
             "Mechanical power (W)", "Motor & ESC efficiency (%)", "Propeller efficiency (gf/W)"]
    rows = [",".join(names)]
    for step in range(10):
        rpm = 2000.0 + 800.0 * step
        thrust, torque = load(rpm)
        mech = torque * rpm * math.pi / 30
        rows.append(",".join([f"{4.0 * step:.1f}", str(1150 + 70 * step), f"{rpm:.0f}",
                              f"{thrust / 9.80665:.5f}", f"{torque:.5f}", "16.0",
                              f"{mech / 16 / 0.8:.3f}", f"{mech / 0.8:.2f}", f"{mech:.2f}",
                              "80", f"{thrust / 9.80665e-3 / max(mech, 1e-9):.3f}"]))
    return "\n".join(rows) + "\n"


with open("flight_stand_two_powertrains.csv", "w", encoding="utf-8", newline="") as f:
    f.write(flight_stand())
with open("tyto_database.csv", "w", encoding="utf-8", newline="") as f:
    f.write(database())
