#!/usr/bin/env bash
# The guide's pictures of the report (docs/guide/img/*.png): the shipped cases run and their
# reports photographed in headless Chromium. Run it after changing the report:
#   scripts/screenshots.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked -p propbet-cli
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
shoot() { # page, output, height
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1400,"$3" \
    --user-data-dir="$tmp/profile" --screenshot="$2" "file://$1" >/dev/null 2>&1
}
target/release/propbet run props/apcsf_10x4.7 -o "$tmp/apc" --quiet >/dev/null 2>&1 || true
target/release/propbet run props/photofoil_8x4.5 -o "$tmp/pf" --quiet >/dev/null 2>&1 || true
shoot "$tmp/apc/report.html" docs/guide/img/report_top.png 900
shoot "$tmp/apc/compare/report.html" docs/guide/img/compare_top.png 1300
shoot "$tmp/pf/diagnose/report.html" docs/guide/img/diagnose_top.png 1300
ls -l docs/guide/img
