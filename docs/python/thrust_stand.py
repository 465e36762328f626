"""A prediction against a thrust-stand log, drawn with matplotlib.

The PhotoFoil 8x4.5's QPROP file against its RCbenchmark step test (props/photofoil_8x4.5),
at the study's air density. Run from the repository root; writes thrust_stand.png (or the
path given as the first argument).
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import propbet

case = "props/photofoil_8x4.5"
prop = propbet.Prop.from_qprop(f"{case}/QProp_8x4_5.txt")
log = propbet.read_measurements(f"{case}/StepsTestV2_2022-01-18_153833.csv")
print(f"{len(log)} steady points, {len(log.attrs['dropped'])} rows not used")

# The prediction on a static sweep over the logged RPM range, in the logged air.
rpm = np.linspace(log.rpm.min(), log.rpm.max(), 40)
sweep = prop.predict(rpm=rpm, air={"rho": 1.1648})

# The same points compared one by one (each at its own RPM): the error in numbers.
metrics, points = propbet.compare(prop, log.file.iloc[0], rho=1.1648)
print(f"thrust: mean error {100 * (points.thrust_pred / points.thrust_n - 1).mean():+.1f} %")

fig, (ax_t, ax_q) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
ax_t.errorbar(log.rpm, log.thrust_n, yerr=log.thrust_sd, fmt="o", ms=4, label="measured (RCbenchmark)")
ax_t.plot(sweep.rpm, sweep.thrust_n, label="propbet")
ax_t.set(xlabel="rotation speed [rpm]", ylabel="thrust [N]", title="Thrust")
ax_q.errorbar(log.rpm, log.torque_nm, yerr=log.torque_sd, fmt="o", ms=4, label="measured (RCbenchmark)")
ax_q.plot(sweep.rpm, sweep.torque_nm, label="propbet")
ax_q.set(xlabel="rotation speed [rpm]", ylabel="torque [N m]", title="Torque")
for ax in (ax_t, ax_q):
    ax.grid(alpha=0.3)
    ax.legend()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "thrust_stand.png", dpi=120)
