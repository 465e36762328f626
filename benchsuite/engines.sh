#!/usr/bin/env bash
# NeuralFoil against XFOIL on the sections of the shipped cases: each blade's polars made by
# both engines (`propbet polars`, the same command but for --engine), compared where both have
# a point (benchsuite/engines.py): CL difference and CD ratio, over every common point and over
# the angles each station works at. Blades: the default case's scan with E63 at every station
# (its run's polars stage), the same scan's own sections (--station-airfoils), the PhotoFoil
# 8x4.5 with NACA 6508 (the section its study fitted), the 25-station benchmark blade with
# NACA 4412. XFOIL's polars come from the cache when it holds them.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked -q -p propbet-cli
pb=target/release/propbet
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
case=props/apcsf_10x4.7
$pb scan $case/apcsf_10x4.7.stl -o "$t/scan" --units mm --stations 0.2:0.96/20 >/dev/null 2>&1
sweep=(--rpm=2300,4000,5000,6000,6600 --j=0:0.7:0.025)
blades=(
  "APC 10x4.7 SF scan, E63|--geometry $t/scan/prop.qprop --airfoil props/airfoils/e63.dat ${sweep[*]}"
  "APC 10x4.7 SF scan, its own sections|--geometry $t/scan/prop.qprop --station-airfoils $t/scan/airfoils ${sweep[*]}"
  "PhotoFoil 8x4.5, NACA 6508|--geometry props/photofoil_8x4.5/QProp_8x4_5.txt --airfoil naca6508 --rpm=4000,6000,8000 --j=0:0.6:0.025"
  "25-station blade, NACA 4412|--geometry benchsuite/blade25.qprop --airfoil naca4412 --rpm 6000 --j=0:0.7:0.05"
)
mkdir -p benchsuite/results
{
  echo "| blade | points | CL difference, median / p90 | CD difference, median / p90 (median signed) | points at the working angles | CL difference there | CD difference there |"
  echo "|---|---|---|---|---|---|---|"
  for b in "${blades[@]}"; do
    name=${b%%|*}
    args=${b#*|}
    for e in xfoil neuralfoil; do
      # shellcheck disable=SC2086
      $pb polars $args --engine $e --quiet --out-prop "$t/$e.qprop" --out-polars "$t/$e.json" >/dev/null 2>&1 || true
    done
    python3 benchsuite/engines.py "$name" "$t/xfoil.json" "$t/neuralfoil.json"
  done
} | tee benchsuite/results/engines_latest.md
