#!/usr/bin/env bash
# The native NeuralFoil engine's speed targets, cold (a fresh polar cache), 2 threads, release:
# a 25-station blade's polars (benchsuite/blade25.qprop, NACA 4412, 6000 rpm static, alpha
# -8..16 deg; target 0.5 s), `propbet run` on the default case (props/apcsf_10x4.7; target 5 s)
# and `propbet validate` on the shared props (target 3 min), each with --engine neuralfoil.
# RUNS sets the runs of the first two (5), RUNS_VALIDATE of the third (1: it takes minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -q -p propbet-cli
shared="${SHARED:-../shared}"
pb="target/release/propbet --threads 2"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mkdir -p benchsuite/results
# Each command exits 1 when a stage reports a problem (a station's prop-file law marked UNFIT,
# stations unconverged past windmilling): timed all the same.
hyperfine --ignore-failure --runs "${RUNS:-5}" --export-json "$out/blade.json" \
  "$pb polars --geometry benchsuite/blade25.qprop --airfoil naca4412 --rpm 6000 --alpha -8:16:1 --quiet --no-cache --engine neuralfoil --out-prop $out/fit.qprop"
hyperfine --ignore-failure --runs "${RUNS:-5}" --export-json "$out/run.json" --prepare "rm -rf $out/cache $out/run" \
  "$pb run props/apcsf_10x4.7 --quiet --engine neuralfoil --cache $out/cache -o $out/run"
hyperfine --ignore-failure --runs "${RUNS_VALIDATE:-1}" --export-json "$out/validate.json" --prepare "rm -rf $out/cache $out/val" \
  "$pb validate --uiuc $shared/data/uiuc --pe0 $shared/data/apc/PE0 --airfoils props/airfoils --per3 $shared/data/apc/PER3 --quiet --engine neuralfoil --cache $out/cache -o $out/val"
python3 - "$out" <<'PY' | tee benchsuite/results/native_latest.txt
import json, sys
d = sys.argv[1]
for name, what, target in [("blade", "25-station blade polars", 0.5), ("run", "run, default case", 5.0),
                           ("validate", "validate, shared props", 180.0)]:
    r = json.load(open(f"{d}/{name}.json"))["results"][0]
    print(f"{what}: median {r['median']:.2f} s of {len(r['times'])} (target {target:g} s, {target / r['median']:.2f}x)")
PY
