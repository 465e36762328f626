#!/usr/bin/env bash
# Benchmark of issue 16: `propbet validate` on the six shared UIUC props (../shared/data), cold
# (a fresh polar cache: every XFOIL polar computed), default model, 2 threads.
# Target (issue 16): cold <= 10 min on 2 cores. One run by default (RUNS=n for more): a cold
# validation is minutes of XFOIL, and its spread is a few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -p propbet-cli
shared="${SHARED:-../shared}"
out=$(mktemp -d)
mkdir -p benchsuite/results
# validate exits 1 when a stage reports a problem (stations unconverged past windmilling):
# timed all the same.
hyperfine --ignore-failure --runs "${RUNS:-1}" --export-json "$out/validate.json" \
  --prepare "rm -rf $out/cache $out/val" \
  "target/release/propbet --threads 2 validate --uiuc $shared/data/uiuc --pe0 $shared/data/apc/PE0 --airfoils props/airfoils --quiet --cache $out/cache -o $out/val"
python3 - "$out/validate.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["results"][0]["median"]
print(f"validate cold median {t:.0f} s (target 600 s, {600/t:.1f}x under)")
PY
cp "$out/validate.json" benchsuite/results/validate_cold_latest.json
