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
# About 50 s in all on a loaded 2-core machine. Writes into OUTDIR:
#   default_history.png     cases/default.yaml: elastic Carter start-up from rest (rollsim run)
#   fig7_carter_plastic.png cases/carter_plast.yaml: the paper's Figure 7, p_x with g and tau_c
#                           for k_rel = 0.98, 0.6, 0, -0.333 (steady)
#   fig8_meierhofer.png     cases/meierhofer.yaml: Figure 8, Table-1 contact at xi = 0.3 % and
#                           1 %, elastic and plastic tractions (steady)
#   fig9_creep_curves.png   cases/creep_curves.yaml: Figure 9, creep curves per tau_c0, one
#                           colour per k_rel, the elastic curve dashed (steady, 820 points)
#   hertz3d_creep.png       cases/hertz3d_creep.yaml: 3D F_x, F_y, M_z against xi at two eta
#                           and two spins (steady, 68 points, 30 x 30 cells)
#   hertz3d_traction.png    the same ellipse with a plastic layer at xi = -0.1 %, eta = 0.05 %,
#                           spin 1e-4 1/mm: |p| with arrows and the Hertz ellipse (steady)
#   hertz3d_regimes.png     its regimes (adhesion, slip, plastic)
#   twin_disc_temperature.png cases/twin_disc_temperature.yaml: a twin-disc rig's traction and
#                           surface temperatures per revolution (rollsim run, 30 revolutions)
#   hot_creep_curve.png     cases/hot_creep_curve.yaml: a creep curve with mu falling with the
#                           contact temperature, and the same without the table (steady)
#   wheel_rail_contact.png  cases/profiles/wheel_rail_profiles.yaml: S1002 placed on UIC60 as
#                           rollsim places it, the contact patch rollsim check finds
#   wheel_rail_sweep.png    cases/profiles/mbench_a22_right.yaml: the Manchester benchmark's A-2.2
#                           right wheel, contact point, angle and forces against the lateral
#                           displacement (rollsim sweep, 21 positions)
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

# 3D: creep curves of the elliptic contact, and one partial-slip point of it mapped over the
# patch with a plastic layer (tau_c0 = 150 N/mm2, below the friction bound mu p0 = 250; k_rel 0.3).
"$RS" sweep "$ROOT/cases/hertz3d_creep.yaml" -o "$DATA/hertz3d_creep.nc" --quiet >/dev/null
"$PY" "$POST" creep3d "$DATA/hertz3d_creep.nc" -o "$OUT/hertz3d_creep.png" \
    --data "$DATA/hertz3d_creep.csv"
"$RS" run "$ROOT/cases/hertz3d_creep.yaml" --set sweep=null --set rolling.creepage=-0.001 \
    --set rolling.lateral_creepage=0.0005 --set rolling.spin=0.0001 \
    --set plasticity.tau_c0=150 --set plasticity.k_rel=0.3 \
    --set "output.fields=[px,pn,slip,regime,ustar,tauc]" \
    --set "title=\"3D ellipse with a plastic layer: xi -0.1 %, eta 0.05 %, spin 1e-4 1/mm\"" \
    -o "$DATA/hertz3d_plastic.nc" --quiet >/dev/null
"$PY" "$POST" map "$DATA/hertz3d_plastic.nc" --field traction \
    -o "$OUT/hertz3d_traction.png" --data "$DATA/hertz3d_traction.csv"
"$PY" "$POST" map "$DATA/hertz3d_plastic.nc" --field regime \
    -o "$OUT/hertz3d_regimes.png" --data "$DATA/hertz3d_regimes.csv"

# A twin-disc rig with surface temperature: the heated track comes around every revolution.
"$RS" run "$ROOT/cases/twin_disc_temperature.yaml" -o "$DATA/twin_disc_temperature.nc" --quiet >/dev/null
"$PY" "$POST" rig "$DATA/twin_disc_temperature.nc" -o "$OUT/twin_disc_temperature.png" \
    --data "$DATA/twin_disc_temperature.csv"

# A hot contact: mu(T) falling with the contact temperature against the same without the table.
"$RS" sweep "$ROOT/cases/hot_creep_curve.yaml" -o "$DATA/hot_creep_curve.nc" --quiet >/dev/null
"$RS" sweep "$ROOT/cases/hot_creep_curve.yaml" --set friction.temperature_table=null \
    --set output.error_estimate=false -o "$DATA/cold_creep_curve.nc" --quiet >/dev/null
"$PY" "$POST" creepcurve "$DATA/hot_creep_curve.nc" "$DATA/cold_creep_curve.nc" \
    --label "mu(T): 0.4 at 20 degC to 0.2 at 400 degC" --label "mu = 0.4 (no table)" \
    --abs --percent --title "Creep curve of a hot contact (V = 60 m/s, Table 1 contact, elastic)" \
    -o "$OUT/hot_creep_curve.png" --data "$DATA/hot_creep_curve.csv"

# Wheel-rail profiles: the wheel placed on the rail and the contact patch rollsim check finds.
"$PY" "$POST" profiles "$ROOT/cases/profiles/wheel_rail_profiles.yaml" --rollsim "$RS" \
    -o "$OUT/wheel_rail_contact.png" --data "$DATA/wheel_rail_contact.csv"

# A path of wheelset positions: the contact moving from the tread to the flange.
"$RS" sweep "$ROOT/cases/profiles/mbench_a22_right.yaml" -o "$DATA/mbench_a22_right.nc" \
    --quiet >/dev/null
"$PY" "$POST" wheelrail "$DATA/mbench_a22_right.nc" -o "$OUT/wheel_rail_sweep.png" \
    --data "$DATA/wheel_rail_sweep.csv"

echo "wrote $OUT/default_history.png $OUT/fig7_carter_plastic.png $OUT/fig8_meierhofer.png $OUT/fig9_creep_curves.png" \
    "$OUT/hertz3d_creep.png $OUT/hertz3d_traction.png $OUT/hertz3d_regimes.png" \
    "$OUT/twin_disc_temperature.png $OUT/hot_creep_curve.png $OUT/wheel_rail_contact.png" \
    "$OUT/wheel_rail_sweep.png"
