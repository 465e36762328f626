#!/usr/bin/env bash
# Runs the whole test suite (unit, property, QPROP reference and end-to-end tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --locked --release
