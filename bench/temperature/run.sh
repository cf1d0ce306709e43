#!/usr/bin/env bash
# CONTACT's example ertz_temperature against rollsim (bench/RESULTS.md, issue 43).
#   bench/temperature/run.sh BUILD/rollsim [OUT_DIR]
# With CONTACT_ANCHOR set (a CONTACT build with run_case.sh) the example is run there and its
# maximum temperatures are read from its output; else the published reference values are used.
# CONTACT's input examples/ertz_temperature.inp is taken from CONTACT_SOURCE (a checkout of
# CONTACT's repository) when set.
set -eu
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rollsim="$(readlink -f "$1")"
out="${2:-$(mktemp -d)}"
mkdir -p "$out"
ref=()
if [ -n "${CONTACT_ANCHOR:-}" ] && [ -n "${CONTACT_SOURCE:-}" ]; then
  git -C "$CONTACT_SOURCE" show HEAD:examples/ertz_temperature.inp > "$out/ertz_temperature.inp"
  "$CONTACT_ANCHOR/run_case.sh" "$out/ertz_temperature.inp"
  ref=("$out/ertz_temperature.out")
fi
/usr/bin/python3 "$here/compare.py" "$rollsim" "$out" "${ref[@]}"
