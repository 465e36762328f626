#!/usr/bin/env bash
# Benchmark of issue 2: the 20,000-point sweep V = 0..20 m/s (200 points) x RPM = 2000..20000
# (100 points) of cam6x3, as a whole `propbet predict` process beside the real QPROP 1.22 running
# the same sweep (`qprop cam6x3 s400-6v-dd 0,20/200 2000,20000/100`, built from Drela's source
# into a temporary folder), both timed in one hyperfine run. Target: propbet at least 10x faster.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v hyperfine >/dev/null 2>&1 || { apt-get install -y -qq hyperfine >/dev/null; }
command -v gfortran >/dev/null 2>&1 || { apt-get install -y -qq gfortran >/dev/null; }
shared=${SHARED:-../shared}
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
src="$shared/reference/qprop/src"
(cd "$src" && gfortran -O2 -fdefault-real-8 -std=legacy -o "$out/qprop" \
  qprop.f bnsolv.f cdfun.f gvcalc.f io.f motor.f spline.f tqcalc.f tpdes.f qcget.f)
runs="$shared/reference/qprop/runs"
mkdir -p benchsuite/results
hyperfine --warmup 3 --runs "${RUNS:-30}" --export-json "$out/h.json" \
  -n propbet "target/release/propbet predict --prop props/cam6x3/cam6x3.qprop --v 0:20/200 --rpm 2000:20000/100 --out $out/sweep.csv" \
  -n qprop "cd $runs && $out/qprop cam6x3 s400-6v-dd 0,20/200 2000,20000/100 > $out/qprop.out"
test "$(wc -l < "$out/sweep.csv")" -eq 20001
test "$(grep -v '^#' "$out/qprop.out" | grep -c '[0-9]')" -eq 20000
python3 - "$out/h.json" <<'PY'
import json, sys
r = {x["command"]: x["median"] for x in json.load(open(sys.argv[1]))["results"]}
p, q = r["propbet"], r["qprop"]
print(f"propbet median {p*1000:.1f} ms, QPROP 1.22 median {q*1000:.1f} ms (same run): {q/p:.1f}x (target 10x)")
PY
cp "$out/h.json" benchsuite/results/predict_sweep_latest.json
