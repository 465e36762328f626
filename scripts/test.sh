#!/usr/bin/env bash
# Runs the test suite (unit, property, QPROP reference and end-to-end tests).
#   scripts/test.sh          everything, the slow tests included (real XFOIL, whole cases,
#                            headless Chromium), in the release profile, then the Python
#                            package's tests (its wheel built and installed into .venv, pytest
#                            against the binary just built) and the workbench's browser tests:
#                            what CI runs
#   scripts/test.sh --fast   without the slow tests (they are marked #[ignore = "slow: ..."]
#                            and listed as ignored), in the `fast` profile (optimised, no LTO,
#                            incremental): no XFOIL, no Chromium, no timed assertion, no
#                            Python package
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--fast" ]; then
  # XFOIL and Chromium are out of reach: a fast test that starts either fails.
  shims=$(mktemp -d)
  trap 'rm -rf "$shims"' EXIT
  for b in xfoil chromium chromium-browser google-chrome; do
    printf '#!/bin/sh\necho "%s is not run in the fast tier" >&2\nexit 127\n' "$b" > "$shims/$b"
    chmod +x "$shims/$b"
  done
  PATH="$shims:$PATH" cargo test --workspace --locked --profile fast
else
  cargo test --workspace --locked --release --no-fail-fast -- --include-ignored
  scripts/python-package.sh
  PROPBET_BIN="$PWD/target/release/propbet" .venv/bin/python -m pytest -q -p no:cacheprovider crates/python/tests
  # The workbench in a real browser (Debian's chromium, driven by Playwright).
  PROPBET_BIN="$PWD/target/release/propbet" .venv/bin/python -m pytest -q -p no:cacheprovider tests/browser
fi
