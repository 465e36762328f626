#!/usr/bin/env bash
# propbet from Python against the command line on the same 20,000-point sweep
# (benchsuite/python.py: side by side in one run, alternating). Target: `prop.predict` within
# 1.3 times the command line's median. Usage: benchsuite/python.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked -q -p propbet-cli
scripts/python-package.sh > /dev/null
.venv/bin/python benchsuite/python.py "${1:-10}" | tee benchsuite/results/python_latest.txt
