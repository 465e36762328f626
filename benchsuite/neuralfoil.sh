#!/usr/bin/env bash
# Time per NeuralFoil point: propbet's engine (crates/neuralfoil, release build) beside the
# `neuralfoil` package itself (the anchor; .venv from scripts/setup.sh), same machine, same run:
# NACA 4412 at Re 1e5, Ncrit 9, xlarge network, a 25-angle polar (batched: per point of the
# polar) and one point (single), medians of 200 runs each; and the section's Kulfan fit.
# Target (the NeuralFoil issue): at least 10 times faster than the package.
set -euo pipefail
cd "$(dirname "$0")/.."
foil=props/airfoils/naca4412.dat
cargo build --release --locked -q -p propbet-neuralfoil --example bench
ours=$(target/release/examples/bench "$foil")
theirs=$(.venv/bin/python - "$foil" <<'PY'
import json, sys, time
import aerosandbox as asb
import numpy as np
import neuralfoil as nf

af = asb.Airfoil(coordinates=sys.argv[1])
alphas = np.arange(-8.0, 16.1, 1.0)

def med(f, runs=200):
    t = []
    for _ in range(runs):
        s = time.perf_counter(); f(); t.append(time.perf_counter() - s)
    return sorted(t)[len(t) // 2]

fit = med(lambda: af.normalize().to_kulfan_airfoil(n_weights_per_side=8))
k = af.normalize().to_kulfan_airfoil(n_weights_per_side=8).kulfan_parameters
batch = med(lambda: nf.get_aero_from_kulfan_parameters(k, alpha=alphas, Re=1e5, n_crit=9.0)) / len(alphas)
single = med(lambda: nf.get_aero_from_kulfan_parameters(k, alpha=0.0, Re=1e5, n_crit=9.0))
print(json.dumps({"fit_s": fit, "point_batched_s": batch, "point_single_s": single}))
PY
)
mkdir -p benchsuite/results
python3 - "$ours" "$theirs" <<'PY' | tee benchsuite/results/neuralfoil_latest.txt
import json, sys
o, t = json.loads(sys.argv[1]), json.loads(sys.argv[2])
for k, what in [("point_batched_s", "per point, 25-angle polar"), ("point_single_s", "one point"), ("fit_s", "Kulfan fit")]:
    print(f"{what}: propbet {o[k]*1e6:.1f} us, neuralfoil package {t[k]*1e6:.1f} us, {t[k]/o[k]:.1f}x (target 10x)")
PY
