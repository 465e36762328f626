#!/usr/bin/env bash
# The book's validation table (docs/validation-table.md): `propbet validate` on every UIUC prop
# of the shared data, its validation.md copied into the book. About 25 minutes on 2 cores with a
# cold polar cache, a few minutes warm.
#   scripts/validation-page.sh [SHARED_DIR]     (default: ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
shared=${1:-../shared}
cargo build --release --locked -p propbet-cli
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
target/release/propbet validate --uiuc "$shared/data/uiuc" --pe0 "$shared/data/apc/PE0" \
  --airfoils props/airfoils --per3 "$shared/data/apc/PER3" -o "$out/validation" --quiet || true
test -s "$out/validation/validation.md"
# The table names the output folder as the documented command does (`-o validation`).
sed "s#$out/validation/#validation/#g" "$out/validation/validation.md" > docs/validation-table.md
# What to expect of a prop of each family before any measurement, shipped with propbet.
cp "$out/validation/families.csv" crates/compare/data/validation_families.csv
echo "validation-page: docs/validation-table.md from $(grep -c '^| ' docs/validation-table.md) table rows"
