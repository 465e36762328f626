#!/usr/bin/env bash
# Benchmark of issue 3: polars for a 25-station blade (benchsuite/blade25.qprop, the UIUC APC
# Slow Flyer 10x4.7 geometry resampled to 25 stations; NACA 4412 at every station), one operating
# point (6000 rpm static: the two rungs of the Re ladder around each station's Re, issue 16),
# alpha -8..16 deg step 1, with the real XFOIL on all cores.
# Cold: no cache (every polar from XFOIL). Cached: the same command again from a filled cache.
# Targets (issue 3): cold <= 7 s on 2 cores, cached <= 50 ms.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
mkdir -p benchsuite/results
cmd="target/release/propbet polars --geometry benchsuite/blade25.qprop --airfoil naca4412 --rpm 6000 --alpha -8:16:1 --quiet --out-prop $out/fit.qprop"
hyperfine --runs "${RUNS:-5}" --export-json "$out/cold.json" "$cmd --no-cache"
$cmd --cache "$out/cache" 2>/dev/null || true
hyperfine --warmup 2 --runs "${RUNS_CACHED:-30}" --export-json "$out/cached.json" "$cmd --cache $out/cache"
python3 - "$out/cold.json" "$out/cached.json" <<'PY'
import json, sys
cold = json.load(open(sys.argv[1]))["results"][0]["median"]
cached = json.load(open(sys.argv[2]))["results"][0]["median"]
print(f"cold median {cold:.2f} s (target 7 s, {7/cold:.2f}x), cached median {cached*1000:.1f} ms (target 50 ms, {0.05/cached:.1f}x)")
PY
cp "$out/cold.json" benchsuite/results/polars_blade_cold_latest.json
cp "$out/cached.json" benchsuite/results/polars_blade_cached_latest.json
