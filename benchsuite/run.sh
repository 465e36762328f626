#!/usr/bin/env bash
# Benchmark of issue 7: `propbet run` on the default case (props/apcsf_10x4.7: STL scan, XFOIL
# polars of 20 stations on the Re rungs covering the measured range, sweeps, comparison with 8 UIUC files, diagnosis, report)
# on 2 threads. Cold: a fresh polar cache each run. Warm: the same cache filled.
# Targets (issues 7 and 16): cold <= 60 s, warm <= 10 s on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
mkdir -p benchsuite/results
hyperfine --runs "${RUNS:-3}" --export-json "$out/cold.json" \
  --prepare "rm -rf $out/cold_cache" \
  "target/release/propbet --threads 2 run --quiet --cache $out/cold_cache -o $out/cold"
target/release/propbet --threads 2 run --quiet --cache "$out/warm_cache" -o "$out/fill" >/dev/null 2>&1
hyperfine --warmup 1 --runs "${RUNS_WARM:-5}" --export-json "$out/warm.json" \
  "target/release/propbet --threads 2 run --quiet --cache $out/warm_cache -o $out/warm"
python3 - "$out/cold.json" "$out/warm.json" <<'PY'
import json, sys
cold = json.load(open(sys.argv[1]))["results"][0]["median"]
warm = json.load(open(sys.argv[2]))["results"][0]["median"]
print(f"cold median {cold:.1f} s (target 60 s, {60/cold:.1f}x under), warm median {warm:.1f} s (target 10 s, {10/warm:.1f}x under)")
PY
cp "$out/cold.json" benchsuite/results/run_cold_latest.json
cp "$out/warm.json" benchsuite/results/run_warm_latest.json
