#!/usr/bin/env bash
# Benchmark of issue 6: `propbet diagnose` with 14 candidate effects (the 13 built-in and the
# user-defined `windage` of docs/user_effects.toml), 5-fold and
# leave-one-RPM-out cross-validation, on 1,000 measured points (cam6x3, 20 RPMs x 50 J, made
# by `propbet synth` with a hidden pitch offset and 1 % noise), ladder limited to one step.
# Target (issue 6): <= 10 s on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
mkdir -p benchsuite/results
target/release/propbet synth --prop props/cam6x3/cam6x3.qprop --effect pitch-offset:deg=1.5 \
  --rpm 4000:17000/20 --j 0:0.5/50 --seed 1 --out "$out/big.csv"
test "$(wc -l < "$out/big.csv")" -eq 1001
effects="tip-loss,hub-loss,re-scaling,compressibility,stall-delay,post-stall,elastic-twist,pitch-offset,chord-scale,density,rpm-scale,thrust-tare,torque-tare,windage"
hyperfine --warmup 1 --runs "${RUNS:-10}" --export-json "$out/h.json" \
  "target/release/propbet --threads 2 diagnose --prop props/cam6x3/cam6x3.qprop --measured $out/big.csv --user-effects docs/user_effects.toml --effects $effects --folds 5 --max-steps 1 --out $out/d"
python3 - "$out/h.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["results"][0]
med = r["median"]
print(f"median {med:.2f} s for 14 effects x 1000 points, 5-fold; target 10 s, ratio {10/med:.1f}x under")
PY
cp "$out/h.json" benchsuite/results/diagnose_latest.json
