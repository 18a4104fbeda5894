#!/usr/bin/env bash
# The peer comparison of issue 7 in one command: eomgen against SymPy's physics.mechanics
# (derivation time, operation counts and evaluation time of M and F, forward dynamics) and
# against MuJoCo (M and bias forces, forward dynamics, 10 s of RK4), then the shipped robots
# (models/robots/*.urdf) against MuJoCo reading the same URDF (issue 29: M and bias forces,
# forward dynamics, generation time), measured in one run on this machine, printed as markdown
# tables with ratios. Not a test; it takes 20-30 minutes.
#
#   bench/compare_peers.sh [EOMGEN]      EOMGEN defaults to build/generator/eomgen
#
# Environment (optional):
#   PEERS_QUICK=1        small chains only (planar 1 2, universal 1) and two robots (ur5, panda),
#                        a smoke run of the scripts
#   PEERS_CAP=120        seconds allowed to each SymPy derivation ("> cap" when hit)
#   PEERS_WORK=DIR       keep every generated header, program and raw result in DIR
# Installs libmujoco-dev and libtinyxml2-dev (which prepares the robots' URDF text for MuJoCo)
# with apt-get when they are missing (Debian 12: MuJoCo 2.2.2). SymPy is
# the one of the machine's python3 (Debian: python3-sympy, installed when missing too).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
eomgen="${1:-$root/build/generator/eomgen}"
[ -x "$eomgen" ] || { echo "compare_peers: eomgen not found at $eomgen (build it: scripts/build.sh)" >&2; exit 2; }
eomgen="$(cd "$(dirname "$eomgen")" && pwd)/$(basename "$eomgen")"

missing=()
[ -f /usr/include/mujoco/mujoco.h ] || missing+=(libmujoco-dev)
[ -f /usr/include/tinyxml2.h ] || missing+=(libtinyxml2-dev)
python3 -c "import sympy" 2> /dev/null || missing+=(python3-sympy)
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

work="${PEERS_WORK:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d "${TMPDIR:-/tmp}/compare_peers.XXXXXX")"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work/sympy" "$work/mujoco" "$work/robots"

planar="1,2,4,8,16,32,64" universal="1,2,4,8" robots="ur5 iiwa14 two_arm_torso panda"
if [ "${PEERS_QUICK:-0}" = 1 ]; then planar="1,2" universal="1" robots="ur5 panda"; fi

echo "# eomgen against its peers"
echo
echo "- machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "- $(g++ --version | head -1); Eigen $(grep -m3 -E 'define EIGEN_(WORLD|MAJOR|MINOR)_VERSION' /usr/include/eigen3/Eigen/src/Core/util/Macros.h | awk '{printf "%s%s", sep, $3; sep="."}')"
echo "- SymPy $(python3 -c 'import sympy; print(sympy.__version__)') on $(python3 --version); MuJoCo $(dpkg-query -W -f='${Version}' libmujoco-dev)"
echo "- $("$eomgen" --version 2>/dev/null | head -1) at $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')"
echo "- started $(date -u '+%Y-%m-%d %H:%M UTC')"
echo

echo "## SymPy physics.mechanics (KanesMethod and LagrangesMethod)"
echo
python3 "$here/peers/sympy_chains.py" bench --eomgen "$eomgen" --cap "${PEERS_CAP:-120}" \
  --planar "$planar" --universal "$universal" --rounds 11 --min-seconds 0.1 --work-dir "$work/sympy"
echo
echo "## MuJoCo"
echo
WORK="$work/mujoco" PLANAR_NS="${planar//,/ }" UNIVERSAL_NS="${universal//,/ }" \
  "$here/peers/mujoco_bench.sh" "$eomgen"
echo
echo "## MuJoCo: the shipped robots"
echo
WORK="$work/robots" ROBOTS="$robots" "$here/peers/mujoco_robots.sh" "$eomgen"
echo
echo "finished $(date -u '+%Y-%m-%d %H:%M UTC')"
