#!/usr/bin/env bash
# Runs the test suite (unit, property, QPROP reference and end-to-end tests).
#   scripts/test.sh          everything, the slow tests included (real XFOIL, whole cases,
#                            headless Chromium): what CI runs
#   scripts/test.sh --fast   without the slow tests (they are marked #[ignore = "slow: ..."]
#                            and listed as ignored)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--fast" ]; then
  cargo test --workspace --locked --release
else
  cargo test --workspace --locked --release --no-fail-fast -- --include-ignored
fi
