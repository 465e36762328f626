#!/usr/bin/env bash
# The guide's pictures of the report and the workbench (docs/guide/img/*.png): the shipped cases
# run and their reports (and `propbet serve`'s page) photographed in headless Chromium. Run it after changing the report:
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
# Run where the README's first command writes (`run_apcsp_10x7` in the working folder), so
# that every path the pictures show is the one a new user sees.
repo=$PWD
(cd "$tmp" && "$repo/target/release/propbet" run "$repo/props/apcsp_10x7" -o run_apcsp_10x7 --quiet >/dev/null 2>&1) || true
(cd "$tmp" && "$repo/target/release/propbet" run "$repo/props/photofoil_8x4.5" -o run_photofoil_8x4.5 --quiet >/dev/null 2>&1) || true
shoot "$tmp/run_apcsp_10x7/report.html" docs/guide/img/report_top.png 900
shoot "$tmp/run_apcsp_10x7/compare/report.html" docs/guide/img/compare_top.png 1300
shoot "$tmp/run_photofoil_8x4.5/diagnose/report.html" docs/guide/img/diagnose_top.png 1300
# The workbench's first screen: `propbet serve` on the default case, the page photographed
# once its first evaluation is drawn.
"$repo/target/release/propbet" serve "$repo/props/apcsp_10x7" --save-to "$tmp" > "$tmp/serve.out" 2>/dev/null &
serve=$!
for _ in $(seq 300); do [ -s "$tmp/serve.out" ] && break; sleep 0.2; done
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1400,900 \
  --user-data-dir="$tmp/profile" --virtual-time-budget=8000 \
  --screenshot="$repo/docs/guide/img/workbench.png" "$(head -1 "$tmp/serve.out")" >/dev/null 2>&1
kill "$serve"
ls -l docs/guide/img
