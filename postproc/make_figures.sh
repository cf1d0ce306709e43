#!/bin/sh
# Regenerate the README figures from fresh rollsim runs: each figure of the paper is one
# `rollsim sweep` and one plot command (the lines below are those commands).
#
#   postproc/make_figures.sh [ROLLSIM [OUTDIR [DATADIR]]]
#     ROLLSIM  the rollsim binary (default: build/rollsim)
#     OUTDIR   where the PNGs go (default: docs/figures)
#     DATADIR  keep the netCDF files and the plotted series (CSV, --data) there
#              (default: a temporary directory, removed)
#
# Builds nothing: configure and build first (cmake -S . -B build && cmake --build build).
# About 5 s in all. Writes into OUTDIR:
#   default_history.png     cases/default.yaml: elastic Carter start-up from rest (rollsim run)
#   fig7_carter_plastic.png cases/carter_plast.yaml: the paper's Figure 7, p_x with g and tau_c
#                           for k_rel = 0.98, 0.6, 0, -0.333 (steady)
#   fig8_meierhofer.png     cases/meierhofer.yaml: Figure 8, Table-1 contact at xi = 0.3 % and
#                           1 %, elastic and plastic tractions (steady)
#   fig9_creep_curves.png   cases/creep_curves.yaml: Figure 9, creep curves per tau_c0, one
#                           colour per k_rel, the elastic curve dashed (steady, 820 points)
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
RS=${1:-$ROOT/build/rollsim}
OUT=${2:-$ROOT/docs/figures}
PY=/usr/bin/python3                       # Debian's python3-netcdf4 / -matplotlib
POST="$ROOT/postproc/rollsim_post.py"

if [ ! -x "$RS" ]; then
    echo "make_figures.sh: $RS: no rollsim binary (build first, or pass its path)" >&2
    exit 2
fi
mkdir -p "$OUT"
if [ $# -ge 3 ]; then
    DATA=$3
    mkdir -p "$DATA"
else
    DATA=$(mktemp -d)
    trap 'rm -rf "$DATA"' EXIT INT TERM
fi

# The default case: elastic Carter 2D, rolled 40 mm from rest to steady state.
"$RS" run "$ROOT/cases/default.yaml" -o "$DATA/default.nc" --quiet >/dev/null
"$PY" "$POST" history "$DATA/default.nc" -o "$OUT/default_history.png"

# Figure 7: Carter's case with local plasticity, one panel per k_rel.
"$RS" sweep "$ROOT/cases/carter_plast.yaml" -o "$DATA/fig7.nc" --quiet >/dev/null
"$PY" "$POST" traction "$DATA/fig7.nc" -o "$OUT/fig7_carter_plastic.png" --data "$DATA/fig7.csv"

# Figure 8: the Meierhofer case, elastic (tau_c0 = 1e9, never reached) and plastic overlaid.
"$RS" sweep "$ROOT/cases/meierhofer.yaml" -o "$DATA/fig8.nc" --quiet >/dev/null
"$PY" "$POST" traction "$DATA/fig8.nc" --overlay plasticity.tau_c0 \
    -o "$OUT/fig8_meierhofer.png" --data "$DATA/fig8.csv"

# Figure 9: creep curves, one panel per tau_c0, creepage in %.
"$RS" sweep "$ROOT/cases/creep_curves.yaml" -o "$DATA/fig9.nc" --quiet >/dev/null
"$PY" "$POST" creepcurve "$DATA/fig9.nc" --panel plasticity.tau_c0 --abs --percent \
    --title "Creep curves with local plasticity (Table 1 contact, R = 11.75 mm, 100 cells)" \
    -o "$OUT/fig9_creep_curves.png" --data "$DATA/fig9.csv"

echo "wrote $OUT/default_history.png $OUT/fig7_carter_plastic.png $OUT/fig8_meierhofer.png $OUT/fig9_creep_curves.png"
