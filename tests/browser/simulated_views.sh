#!/usr/bin/env bash
# The view of real runs, as `eomgen simulate --animate` writes them: the double pendulum of the
# README (10 s; the pivot and both rods) and the Whipple bicycle riding 25 m (5 s). check_page.sh
# with check_view at two times each: by default a fixed camera frames every point of every
# sample, with the grid and the axes; the bicycle followed by choice keeps it in the view.
#
#   tests/browser/simulated_views.sh EOMGEN CHECK_VIEW CACHE_DIR OUT_DIR
set -euo pipefail
[ $# -eq 4 ] || { echo "usage: simulated_views.sh EOMGEN CHECK_VIEW CACHE_DIR OUT_DIR" >&2; exit 2; }
eomgen="$1" check_view="$2" cache="$3" out="$4"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
mkdir -p "$out"

simulate() {  # MODEL T_END INIT
  "$eomgen" simulate "$root/models/$1.eom" --t-end "$2" --init "$3" --no-plot -o "$out/$1.csv" \
    --animate "$out/$1.html" --cache-dir "$cache" > "$out/$1.log" 2>&1 || { cat "$out/$1.log" >&2; exit 1; }
  grep '^animation:' "$out/$1.log"
}

simulate double_pendulum 10 theta1=1.8,theta2=-0.6
"$here/check_page.sh" --load-only --check-view "$check_view" "$out/double_pendulum.html" 2.4 7.5
simulate whipple_bicycle 5 x_dot=5,theta_r_dot=-16.666666666666667,theta_f_dot=-14.285714285714286,phi_dot=0.5
"$here/check_page.sh" --load-only --check-view "$check_view" "$out/whipple_bicycle.html" 0.5 4
"$here/check_page.sh" --load-only --follow mechanism --check-view "$check_view" "$out/whipple_bicycle.html" 0.5 4
echo "ok: the simulated runs are framed whole, and followed by choice"
