#!/usr/bin/env bash
# The workbench's time per change (issue 79): `propbet serve` on the default case on 2 threads,
# a slider moved N times (each change one POST /api/evaluate: compare, the curves and the band),
# the round trip's median beside `propbet run` of the same case (benchsuite/serve.py).
# Target: a median of at most 20 ms per change. Usage: benchsuite/serve.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked -q -p propbet-cli
mkdir -p benchsuite/results
python3 benchsuite/serve.py "${1:-50}" | tee benchsuite/results/serve_latest.txt
