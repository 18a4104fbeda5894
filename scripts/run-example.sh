#!/usr/bin/env bash
# The main job: check a shipped model, derive and print its equations of motion, generate its
# optimized C++ header, simulate it (CSV, plot and an animated 3D view in one HTML page), and run
# the computed-torque controller built on the generated double pendulum.
#
#   scripts/run-example.sh [MODEL [SIMULATE OPTIONS...]]
# e.g. scripts/run-example.sh models/heavy_top.eom --t-end 5 --init theta=0.3,phi_dot=60
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
model="${1:-$root/models/double_pendulum.eom}"
shift $(( $# > 0 ? 1 : 0 ))
if [ $# -eq 0 ]; then
  if [ "$(basename "$model")" = double_pendulum.eom ]; then
    set -- --t-end 10 --init theta1=1.8,theta2=-0.6
  else
    set -- --t-end 5
  fi
fi
"$root/scripts/build.sh" --target eomgen computed_torque >/dev/null
eomgen="$build/generator/eomgen"
name="$(basename "$model" .eom)"
out="$build/example-output"
mkdir -p "$out"

echo "== eomgen check $(basename "$model")"
"$eomgen" check "$model"
echo
echo "== eomgen derive $(basename "$model")"
"$eomgen" derive "$model"
echo
header="$out/$name.hpp"
echo "== eomgen generate $(basename "$model") -o $header --stats"
"$eomgen" generate "$model" -o "$header" --stats
echo
echo "== eomgen simulate $(basename "$model") $*"
"$eomgen" simulate "$model" "$@" -o "$out/$name.csv" --plot "$out/$name.svg" --animate "$out/$name.html"
echo "open $out/$name.html in a browser to watch the motion (it works offline, from disk)"
echo
echo "== computed-torque tracking on the generated double pendulum (examples/computed_torque)"
"$build/examples/computed_torque/computed_torque"
