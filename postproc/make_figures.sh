#!/bin/sh
# Regenerate the README figures in docs/figures/ from fresh rollsim runs.
#
#   postproc/make_figures.sh [ROLLSIM]      ROLLSIM: the rollsim binary (default: build/rollsim)
#
# Builds nothing: configure and build first (cmake -S . -B build && cmake --build build).
# Runs two cases (a few seconds) into a temporary directory and writes
#   docs/figures/default_history.png          cases/default.yaml: elastic Carter start-up
#   docs/figures/carter_plastic_traction.png  the same case with local plasticity, last record
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
RS=${1:-$ROOT/build/rollsim}
PY=/usr/bin/python3                       # Debian's python3-netcdf4 / -matplotlib
POST="$ROOT/postproc/rollsim_post.py"
OUT="$ROOT/docs/figures"

if [ ! -x "$RS" ]; then
    echo "make_figures.sh: $RS: no rollsim binary (build first, or pass its path)" >&2
    exit 2
fi
mkdir -p "$OUT"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT INT TERM

# 1. The default case: elastic Carter 2D, rolled 40 mm from rest to steady state.
"$RS" run "$ROOT/cases/default.yaml" -o "$TMP/default.nc" --quiet
"$PY" "$POST" history "$TMP/default.nc" -o "$OUT/default_history.png"

# 2. Carter 2D with local plasticity (tau_c0 = 35 N/mm2, hardening k_rel = 0.6, mu = 0.5,
#    xi = -4e-4), rolled 40 mm from rest: the last record is the steady state. (rollsim's steady
#    mode does not converge with plasticity yet, so the transient gets there.)
"$RS" run "$ROOT/cases/default.yaml" -o "$TMP/plastic.nc" --quiet \
    --set 'title="Carter 2D with local plasticity: tau_c0 = 35 N/mm2, k_rel = 0.6, mu = 0.5, xi = -4e-4"' \
    --set plasticity.tau_c0=35 --set plasticity.k_rel=0.6 \
    --set friction.mu=0.5 --set rolling.creepage=-4e-4 \
    --set 'output.fields=[px,pn,slip,upl,ustar,tauc,regime]'
"$PY" "$POST" traction "$TMP/plastic.nc" -o "$OUT/carter_plastic_traction.png"

echo "wrote $OUT/default_history.png $OUT/carter_plastic_traction.png"
