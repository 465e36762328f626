#!/usr/bin/env bash
# Rebuilds this case from ../shared (run from the repository root, after scripts/setup.sh).
# 1. geometry: UIUC's measured r/R, c/R, beta of the APC 10x4.7 Slow Flyer, R = 5 in, written as
#    a QPROP prop file in inches with QPROP's generic coefficients (first inflow estimate only);
# 2. coefficients: XFOIL polars of the E63 section (APC's PE0 file names E63 for this prop) at
#    each station's Re and Mach at 5000 rpm static, fitted per station by `propbet polars`
#    (Ncrit 9, free transition: the settings the shipped files were made with).
set -euo pipefail
here=props/apcsf_10x4.7
geom=$here/apcsf_10x4.7_geom.txt   # copy of ../shared/data/uiuc/apcsf_10x4.7_geom.txt
{
  echo "APC 10x4.7 Slow Flyer (UIUC measured geometry)"
  echo ""
  echo " 2  5.0      ! Nblades  R"
  echo ""
  echo " 0.50  5.8   ! CL0     CL_a"
  echo " -0.3  1.2   ! CLmin   CLmax"
  echo ""
  echo " 0.028  0.050  0.050  0.5   !  CD0    CD2u  CD2l    CLCD0"
  echo " 70000   -0.5        !  REref  REexp"
  echo ""
  echo " 0.0254  0.0254   1.0  !  Rfac   Cfac   Bfac"
  echo " 0.0     0.0      0.0  !  Radd   Cadd   Badd"
  echo ""
  echo "#  r [in]   chord [in]   beta [deg]"
  awk 'NR > 1 && NF == 3 { printf " %7.4f  %7.4f  %6.2f\n", $1 * 5.0, $2 * 5.0, $3 }' "$geom"
} > "$here/apcsf_10x4.7_geometry.qprop"
target/release/propbet polars --geometry "$here/apcsf_10x4.7_geometry.qprop" \
  --airfoil props/airfoils/e63.dat --rpm 5000 --v 0 --ncrit 9 --trip free --quiet \
  --out-prop "$here/apcsf_10x4.7.qprop" --out-polars "$here/apcsf_10x4.7.polars.json"
