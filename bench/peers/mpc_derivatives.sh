#!/usr/bin/env bash
# Benchmark of the derivatives for MPC (issue 36) against our own forward dynamics and against
# MuJoCo 2.2.2's mjd_transitionFD (Debian 12: apt-get install libmujoco-dev libtinyxml2-dev).
#
#   bench/peers/mpc_derivatives.sh [EOMGEN]      (default: build/generator/eomgen)
#
# For each case, generates the header with --linearization (a shipped robot, or a chain with
# --define n=N and its MJCF from mujoco_chains.py), compiles mpc_derivatives.cpp against it with
# g++ -std=c++17 -O2, runs the programs one after another and prints a markdown table: ns per
# call (medians over interleaved rounds) and the ratios of issue 36's targets,
#   forward_dynamics_derivatives / forward_dynamics   at most 3
#   eomrt::linearization / forward_dynamics           at most 4
#   eomrt::step_derivatives / mjd_transitionFD        at most 0.1 (both RK4, h = 1 ms; MuJoCo's
#                                                     forward differences, eps 1e-6)
# and eomrt::linearization against the path a header without forward_dynamics_derivatives takes
# (linearization_terms, M's Cholesky factor and three solves),
# with the cross-check of our Phi against MuJoCo's A (centered differences) and the load average.
# Environment:
#   WORK=/tmp/mpc-derivatives   scratch directory
#   ROBOTS="ur5 iiwa14 two_arm_torso"   (the Panda has a mimic constraint: no forward_dynamics_derivatives)
#   PLANAR_NS="2 4 8 16"   UNIVERSAL_NS="2 4 8"   (universal n has 2n coordinates)
#   ROUNDS=21   JOBS=2   CXX=g++   CXXFLAGS="-O2"
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
eomgen_src="${1:-$repo/build/generator/eomgen}"
WORK="${WORK:-/tmp/mpc-derivatives}"
ROBOTS="${ROBOTS-ur5 iiwa14 two_arm_torso}"
PLANAR_NS="${PLANAR_NS-2 4 8 16}"
UNIVERSAL_NS="${UNIVERSAL_NS-2 4 8}"
ROUNDS="${ROUNDS:-21}"
JOBS="${JOBS:-2}"
CXX="${CXX:-g++}"
CXXFLAGS="${CXXFLAGS:--O2}"

[[ -x "$eomgen_src" ]] || { echo "no eomgen at $eomgen_src" >&2; exit 1; }
[[ -f /usr/include/mujoco/mujoco.h ]] || { echo "MuJoCo headers missing: apt-get install libmujoco-dev" >&2; exit 1; }
[[ -f /usr/include/tinyxml2.h ]] || { echo "tinyxml2 headers missing: apt-get install libtinyxml2-dev" >&2; exit 1; }
mkdir -p "$WORK"
cp "$eomgen_src" "$WORK/eomgen"
eomgen="$WORK/eomgen"
cd "$WORK"
load() { cut -d' ' -f1-3 /proc/loadavg; }

cases=()
for r in $ROBOTS; do cases+=("robot $r"); done
for n in $PLANAR_NS; do cases+=("planar $n"); done
for n in $UNIVERSAL_NS; do cases+=("universal $n"); done

build_one() {  # kind name-or-n
  local kind=$1 arg=$2 stem ns model t0=$SECONDS
  if [[ $kind == robot ]]; then
    stem=$arg ns=$arg model="$repo/models/robots/$arg.urdf"
    "$eomgen" generate "$model" --linearization -o "$stem.hpp"
    echo "$model" > "$stem.model"
  else
    stem=${kind}_$arg ns=${kind}_chain
    "$eomgen" generate "$repo/models/${kind}_chain.eom" --define "n=$arg" --linearization -o "$stem.hpp"
    python3 "$here/mujoco_chains.py" "$kind" "$arg" -o "$stem.xml"
    echo "$WORK/$stem.xml" > "$stem.model"
  fi
  $CXX -std=c++17 $CXXFLAGS -DEOM_HEADER="\"$stem.hpp\"" -DEOM_NS="$ns" -I"$WORK" -I"$repo/runtime/include" \
    -I"$repo/tests" -I/usr/include/eigen3 "$here/mpc_derivatives.cpp" -lmujoco -ltinyxml2 -o "mpc_$stem"
  echo "compiled mpc_$stem in $((SECONDS - t0)) s" >&2
}

stem_of() { [[ $1 == robot ]] && echo "$2" || echo "${1}_$2"; }

echo "generating and compiling ${#cases[@]} programs ($JOBS at a time) ..." >&2
running=0
for c in "${cases[@]}"; do
  build_one $c &
  running=$((running + 1))
  if ((running >= JOBS)); then wait -n; running=$((running - 1)); fi
done
wait

load_start=$(load)
for c in "${cases[@]}"; do
  stem=$(stem_of $c)
  echo "running mpc_$stem ..." >&2
  "./mpc_$stem" "$(cat "$stem.model")" "$ROUNDS" > "$stem.out"
done
load_end=$(load)

result() { awk -v k="$2" '$1 == "RESULT" && $2 == k { print $3 }' "$1.out"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
ratio3() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }

echo
echo "MPC derivatives, $(date -u +%Y-%m-%d), $(nproc) cores, load average $load_start at the start of the runs and $load_end at the end; g++ $CXXFLAGS, $ROUNDS interleaved rounds, ns per call median (minimum)."
echo
echo "| model | nq | forward_dynamics | forward_dynamics_derivatives | eomrt::linearization | terms and solves | step_derivatives (RK4) | mjd_transitionFD (RK4) | derivatives / forward | linearization / forward | linearization / terms and solves | step / transitionFD | Phi vs MuJoCo's A |"
echo "|:--|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
for c in "${cases[@]}"; do
  stem=$(stem_of $c)
  f=$(result "$stem" ns_forward) d=$(result "$stem" ns_derivatives) l=$(result "$stem" ns_linearize)
  s=$(result "$stem" ns_step) m=$(result "$stem" ns_transitionFD) o=$(result "$stem" ns_terms)
  echo "| $stem | $(result "$stem" nq) | $f ($(result "$stem" nsmin_forward)) | $d ($(result "$stem" nsmin_derivatives)) | $l ($(result "$stem" nsmin_linearize)) | $o ($(result "$stem" nsmin_terms)) | $s ($(result "$stem" nsmin_step)) | $m ($(result "$stem" nsmin_transitionFD)) | $(ratio "$d" "$f") | $(ratio "$l" "$f") | $(ratio "$l" "$o") | $(ratio3 "$s" "$m") | $(result "$stem" err_phi) |"
done
