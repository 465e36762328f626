#!/usr/bin/env bash
# Benchmark of issue 2: the 20,000-point sweep V = 0..20 m/s (200 points) x RPM = 2000..20000
# (100 points) of cam6x3, as a whole `propbet predict` process, timed with hyperfine.
# Reference: QPROP 1.22 takes 0.36 s for the same sweep on this machine class (issue 2).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
mkdir -p benchsuite/results
hyperfine --warmup 3 --runs "${RUNS:-30}" --export-json "$out/h.json" \
  "target/release/propbet predict --prop props/cam6x3/cam6x3.qprop --v 0:20/200 --rpm 2000:20000/100 --out $out/sweep.csv"
test "$(wc -l < "$out/sweep.csv")" -eq 20001
python3 - "$out/h.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["results"][0]
med = r["median"]
print(f"median {med*1000:.1f} ms, QPROP 1.22 reference 360 ms, ratio {0.36/med:.1f}x")
PY
cp "$out/h.json" benchsuite/results/predict_sweep_latest.json
