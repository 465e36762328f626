#!/usr/bin/env bash
# The long mutation-fuzzing run (issue 38): every parser a user file reaches gets
# PROPBET_FUZZ_SECONDS of mutations (default 600 s each, one parser after the other), where the
# test suite gives each 200 cases. A panic, a case slower than 10 s or a non-finite output fails
# and leaves its input in the temporary directory; the counts per parser are written to
# benchsuite/results/fuzz_latest.txt. PROPBET_FUZZ_SEED varies the generator (default fixed, so a
# failure replays).
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p benchsuite/results
PROPBET_FUZZ_SECONDS="${PROPBET_FUZZ_SECONDS:-600}" PROPBET_FUZZ_CASES=100000000 \
  cargo test --release --locked -p propbet-pipeline --test fuzz_parsers -- --test-threads 1 --nocapture \
  2>&1 | tee benchsuite/results/fuzz_latest.txt
