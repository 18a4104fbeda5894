#!/usr/bin/env bash
# Peer benchmark of the shipped robots (models/robots/*.urdf) against MuJoCo 2.2.2 reading the
# same URDF (Debian 12: apt-get install libmujoco-dev libtinyxml2-dev).
#
#   bench/peers/mujoco_robots.sh [EOMGEN]      (default: build/generator/eomgen)
#
# Times `eomgen generate ROBOT.urdf` (wall time, runs interleaved over the robots), compiles
# mujoco_robots.cpp against each header with g++ -std=c++17 -O2, runs it (cross-check, then ns
# per call in interleaved rounds) and prints markdown tables; ratios are ours / MuJoCo, and the
# targets of issue 29 are forward dynamics and M + F at most 0.1 of MuJoCo's, generation at
# most 0.5 s per robot. The Panda (a mimic constraint) is timed for M and F only, and for the
# controller functions: inverse dynamics against mj_inverse (target at most 0.1) and the tool's
# position Jacobian against mj_kinematics + mj_comPos + mj_jac (target at most 0.3), the tool
# being the leaf link tool_of names below (its output_jacobian_<tool>_position).
# Environment:
#   WORK=/tmp/mujoco-robots        scratch directory (copies eomgen there and works there)
#   ROBOTS="ur5 iiwa14 two_arm_torso panda"
#   ROUNDS=21                      interleaved timing rounds (medians and minima are reported)
#   GENERATE_RUNS=5                runs of eomgen generate per robot
#   JOBS=2                         parallel compilations (runs are always sequential)
#   CXX=g++ CXXFLAGS="-O2"
# Each program takes about 20 s to compile at -O2 (two at a time, on the 2-core machine of docs/performance.md).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
eomgen_src="${1:-$repo/build/generator/eomgen}"
WORK="${WORK:-/tmp/mujoco-robots}"
ROBOTS="${ROBOTS-ur5 iiwa14 two_arm_torso panda}"
ROUNDS="${ROUNDS:-21}"
GENERATE_RUNS="${GENERATE_RUNS:-5}"
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
echo "load average at the start of the robots: $(load)" >&2
echo "$(load)" > load_start.txt

# generation: wall time of each run, the robots interleaved run by run
for r in $ROBOTS; do : > "generate_$r.txt"; done
for ((run = 1; run <= GENERATE_RUNS; ++run)); do
  for r in $ROBOTS; do
    t0=$(date +%s%N)
    "$eomgen" generate "$repo/models/robots/$r.urdf" -o "$r.hpp"
    t1=$(date +%s%N)
    echo "$(((t1 - t0) / 1000))" >> "generate_$r.txt"  # microseconds
  done
done

tool_of() {  # robot: the leaf link whose position Jacobian is timed
  case $1 in
    ur5) echo tool0 ;;
    iiwa14) echo iiwa_link_ee ;;
    two_arm_torso) echo left_ee ;;
    panda) echo panda_hand_tcp ;;
    *)  # another robot: the first position output of its header
      grep -o -m1 'output_jacobian_[A-Za-z0-9_]*_position(' "$1.hpp" | sed 's/^output_jacobian_//; s/_position($//' ;;
  esac
}

build_one() {  # robot
  local r=$1 t0=$SECONDS
  $CXX -std=c++17 $CXXFLAGS -DEOM_HEADER="\"$r.hpp\"" -DEOM_NS="$r" -DEOM_TOOL="$(tool_of "$r")" \
    -I"$WORK" -I"$repo/runtime/include" -I"$repo/tests" -I/usr/include/eigen3 \
    "$here/mujoco_robots.cpp" -lmujoco -ltinyxml2 -o "bench_$r"
  echo "compiled bench_$r in $((SECONDS - t0)) s" >&2
  echo "$((SECONDS - t0))" > "compile_$r.txt"
}

echo "compiling $(wc -w <<< "$ROBOTS") programs ($JOBS at a time) ..." >&2
running=0
for r in $ROBOTS; do
  build_one "$r" &
  running=$((running + 1))
  if (( running >= JOBS )); then wait -n; running=$((running - 1)); fi
done
wait
for r in $ROBOTS; do
  [[ -x "bench_$r" ]] || { echo "build of $r failed" >&2; exit 1; }
done

echo "$(load)" > load_runs.txt
for r in $ROBOTS; do
  echo "=== $r" >&2
  "./bench_$r" "$repo/models/robots/$r.urdf" "$ROUNDS" | tee "result_$r.txt" | grep -v '^RESULT' >&2
done
echo "$(load)" > load_end.txt

python3 - "$WORK" "$ROUNDS" "$GENERATE_RUNS" $ROBOTS <<'EOF'
import statistics, sys
work, rounds, generate_runs, robots = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
rows = []
for robot in robots:
    r = {}
    for line in open(f"{work}/result_{robot}.txt"):
        if line.startswith("RESULT "):
            _, k, v = line.split()
            r[k] = float(v)
        elif line.startswith("tool: "):
            r["tool"] = line.split()[1]
    seconds = [int(x) / 1e6 for x in open(f"{work}/generate_{robot}.txt").read().split()]
    r["gen"], r["genmin"] = statistics.median(seconds), min(seconds)
    r["compile"] = float(open(f"{work}/compile_{robot}.txt").read())
    r["lines"] = sum(1 for _ in open(f"{work}/{robot}.hpp"))
    rows.append((robot, r))
load = {k: open(f"{work}/load_{k}.txt").read().strip() for k in ("start", "runs", "end")}

def f(x): return f"{x:.0f}" if x >= 100 else f"{x:.1f}"
def ratio(r, a, b): return f"{r[a] / r[b]:.2f}" if a in r and b in r else "–"
def ns(r, k): return f(r[k]) if k in r else "–"
def err(r, k): return f"{r[k]:.1e}" if k in r else "–"
def fd(r): return r["nc"] == 0

print(f"\nLoad average (1, 5, 15 min): {load['start']} before generating, {load['runs']} before the timed runs, "
      f"{load['end']} after them.")
print("\n### Cross-check (max-abs error / max-abs value, worst of 8 random states inside the joint ranges, joint torques up to 10 N m)\n")
print("| robot | dof | constraints | M vs mj_fullM | F vs applied + passive - bias | qdd vs qacc |")
print("|---|---:|---:|---:|---:|---:|")
for robot, r in rows:
    print(f"| {robot} | {int(r['nq'])} | {int(r['nc'])} | {err(r, 'err_M')} | {err(r, 'err_F')} | {err(r, 'err_qdd')} |")

for kind, prefix in (("medians", "ns_"), ("minima", "nsmin_")):
    print(f"\n### ns per call ({kind} of {rounds} interleaved rounds); ratio = ours / MuJoCo, target at most 0.10\n")
    print("| robot | dof | ours M+F | MJ M+bias (crb+rne) | ratio M+F | ours FD (eomrt) | ours M,F+Cholesky (eomrt) | MJ FD (crb+rne+passive+factorM+solveM) | mj_forward | ratio FD/mj_forward | ratio FD/MJ FD |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for robot, r in rows:
        g = {k[len(prefix):]: v for k, v in r.items() if k.startswith(prefix)}
        print(f"| {robot} | {int(r['nq'])} | {ns(g, 'ours_MF')} | {ns(g, 'mj_MF')} | {ratio(g, 'ours_MF', 'mj_MF')} | "
              f"{ns(g, 'ours_fd')} | {ns(g, 'ours_fd_chol')} | {ns(g, 'mj_fd')} | {ns(g, 'mj_forward')} | "
              f"{ratio(g, 'ours_fd', 'mj_forward')} | {ratio(g, 'ours_fd', 'mj_fd')} |")

print("\n### Controller functions: cross-check (max-abs error / max-abs value, worst of 8 random states with accelerations up to 5 rad/s^2)\n")
print("| robot | tool | inverse dynamics vs qfrc_inverse | tool position Jacobian vs mj_jac jacp |")
print("|---|---|---:|---:|")
for robot, r in rows:
    print(f"| {robot} | {r.get('tool', '–')} | {err(r, 'err_id')} | {err(r, 'err_jac')} |")
for kind, prefix in (("medians", "ns_"), ("minima", "nsmin_")):
    print(f"\n### Controller functions, ns per call ({kind} of {rounds} interleaved rounds); ratio = ours / MuJoCo, targets at most 0.10 (inverse dynamics) and 0.30 (Jacobian)\n")
    print("| robot | dof | ours inverse_dynamics | mj_inverse | ratio ID | mj_inverseSkip(POS) (position stage done) | ratio ID / skip | ours tool Jacobian | MJ kinematics+comPos+jac | ratio Jacobian |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for robot, r in rows:
        g = {k[len(prefix):]: v for k, v in r.items() if k.startswith(prefix)}
        print(f"| {robot} | {int(r['nq'])} | {ns(g, 'ours_id')} | {ns(g, 'mj_inverse')} | {ratio(g, 'ours_id', 'mj_inverse')} | "
              f"{ns(g, 'mj_inv_vel')} | {ratio(g, 'ours_id', 'mj_inv_vel')} | {ns(g, 'ours_jac')} | {ns(g, 'mj_jac')} | "
              f"{ratio(g, 'ours_jac', 'mj_jac')} |")

print(f"\n### Generation: `eomgen generate ROBOT.urdf` wall time [s], median (min) of {generate_runs} runs, target at most 0.5 s\n")
print("| robot | generate [s] | header lines | bench compile [s] |")
print("|---|---:|---:|---:|")
for robot, r in rows:
    print(f"| {robot} | {r['gen']:.3f} ({r['genmin']:.3f}) | {r['lines']} | {r['compile']:.0f} |")

print("\n### Targets of issue 29 (medians; minima in parentheses)\n")
print("| robot | FD / mj_forward <= 0.1 | M+F / MJ M+bias <= 0.1 | generate <= 0.5 s |")
print("|---|---|---|---|")
def verdict(value, low, target): return f"{'met' if value <= target else 'missed'}: {value:.2f} ({low:.2f})"
for robot, r in rows:
    fdv = verdict(r["ns_ours_fd"] / r["ns_mj_forward"], r["nsmin_ours_fd"] / r["nsmin_mj_forward"], 0.1) if fd(r) else "– (mimic: M+F only)"
    mfv = verdict(r["ns_ours_MF"] / r["ns_mj_MF"], r["nsmin_ours_MF"] / r["nsmin_mj_MF"], 0.1)
    print(f"| {robot} | {fdv} | {mfv} | {verdict(r['gen'], r['genmin'], 0.5)} s |")

print("\n### Targets for the controller functions (medians; minima in parentheses)\n")
print("| robot | inverse_dynamics / mj_inverse <= 0.1 | tool Jacobian / (kinematics + comPos + jac) <= 0.3 |")
print("|---|---|---|")
for robot, r in rows:
    idv = verdict(r["ns_ours_id"] / r["ns_mj_inverse"], r["nsmin_ours_id"] / r["nsmin_mj_inverse"], 0.1)
    jv = verdict(r["ns_ours_jac"] / r["ns_mj_jac"], r["nsmin_ours_jac"] / r["nsmin_mj_jac"], 0.3)
    print(f"| {robot} | {idv} | {jv} |")
EOF
