"""propbet from Python against the command line on the same 20,000-point sweep (cam6x3, 100 RPM
x 200 J), side by side in one run, alternating: `prop.predict(...)` to a DataFrame in a running
interpreter, and `propbet predict ... -o sweep.csv` as a process (its start included, as a user
runs it). Prints the medians and their ratio (target: Python within 1.3 times the command line).
Run by benchsuite/python.sh."""

import statistics
import subprocess
import sys
import tempfile
import time

import propbet

RUNS = int(sys.argv[1]) if len(sys.argv) > 1 else 10
CAM = "props/cam6x3/cam6x3.qprop"
prop = propbet.Prop.from_qprop(CAM)
out = tempfile.mkdtemp()
cli = ["target/release/propbet", "predict", "--prop", CAM, "--rpm", "2000:9000/100", "--j", "0:0.6/200", "-o", f"{out}/cli.csv"]


def timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


for _ in range(2):  # warm-up
    subprocess.run(cli, check=True)
    prop.predict(rpm="2000:9000/100", j="0:0.6/200")
c, p = [], []
for _ in range(RUNS):
    c.append(timed(lambda: subprocess.run(cli, check=True)))
    p.append(timed(lambda: prop.predict(rpm="2000:9000/100", j="0:0.6/200")))
rows = len(prop.predict(rpm="2000:9000/100", j="0:0.6/200"))
mc, mp = statistics.median(c), statistics.median(p)
print(
    f"{rows}-point sweep, median of {RUNS}: command line {mc * 1000:.1f} ms, Python prop.predict {mp * 1000:.1f} ms:"
    f" ratio {mp / mc:.2f} (target <= 1.3)"
)
