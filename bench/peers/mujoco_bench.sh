#!/usr/bin/env bash
# Peer benchmark against MuJoCo (Debian 12: apt-get install libmujoco-dev, MuJoCo 2.2.2).
#
#   bench/peers/mujoco_bench.sh [EOMGEN]      (default: build/generator/eomgen)
#
# For each chain and n: generates our header (eomgen generate --define n=N), writes the same
# chain as MJCF (mujoco_chains.py), compiles mujoco_bench.cpp against both with
# g++ -std=c++17 -O2, runs it, and finally prints markdown tables (ratios are ours / MuJoCo).
# Environment:
#   WORK=/tmp/mujoco-bench        scratch directory (copies eomgen there and works there)
#   PLANAR_NS="1 2 4 8 16 32"     planar chain sizes (n rods, n dof)
#   UNIVERSAL_NS="1 2 4 8"        universal chain sizes (n bodies, 2n dof)
#   ROUNDS=21                     interleaved timing rounds (medians are reported)
#   JOBS=2                        parallel compilations (runs are always sequential)
#   CXX=g++ CXXFLAGS="-O2"
#   MASS_MATRIX_MAX_N=64          above it, M and F are neither compiled nor timed (a closed-form
#                                 M and F of 280,000 operations, planar n = 64 before the
#                                 recursions, took GCC over 20 GB at -O2; from the recursions they
#                                 are 26,000 and compile in under a minute and 1 GB); forward
#                                 dynamics, mj_forward and the simulations are, and qdd is still
#                                 checked against qacc
# The planar n=32 program takes about 20 s to compile at -O2, n = 64 about 2 minutes.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
eomgen_src="${1:-$repo/build/generator/eomgen}"
WORK="${WORK:-/tmp/mujoco-bench}"
PLANAR_NS="${PLANAR_NS-1 2 4 8 16 32}"
UNIVERSAL_NS="${UNIVERSAL_NS-1 2 4 8}"
ROUNDS="${ROUNDS:-21}"
JOBS="${JOBS:-2}"
CXX="${CXX:-g++}"
CXXFLAGS="${CXXFLAGS:--O2}"
MASS_MATRIX_MAX_N="${MASS_MATRIX_MAX_N:-64}"

[[ -x "$eomgen_src" ]] || { echo "no eomgen at $eomgen_src" >&2; exit 1; }
[[ -f /usr/include/mujoco/mujoco.h ]] || { echo "MuJoCo headers missing: apt-get install libmujoco-dev" >&2; exit 1; }
mkdir -p "$WORK"
cp "$eomgen_src" "$WORK/eomgen"
eomgen="$WORK/eomgen"
cd "$WORK"

cases=()
for n in $PLANAR_NS; do cases+=("planar $n"); done
for n in $UNIVERSAL_NS; do cases+=("universal $n"); done

build_one() {  # chain n
  local chain=$1 n=$2 stem=${1}_chain_$2
  "$eomgen" generate "$repo/models/${chain}_chain.eom" --define "n=$n" -o "$stem.hpp"
  python3 "$here/mujoco_chains.py" "$chain" "$n" -o "$stem.xml"
  local t0=$SECONDS without=()
  if (( n > MASS_MATRIX_MAX_N )); then without=(-DEOM_WITHOUT_MASS_MATRIX); fi
  $CXX -std=c++17 $CXXFLAGS "${without[@]}" -DEOM_HEADER="\"$stem.hpp\"" -DEOM_NS=${chain}_chain \
    -I"$WORK" -I"$repo/runtime/include" -I/usr/include/eigen3 \
    "$here/mujoco_bench.cpp" -lmujoco -o "bench_$stem"
  echo "compiled bench_$stem in $((SECONDS - t0)) s" >&2
  echo "$((SECONDS - t0))" > "compile_$stem.txt"
}

echo "compiling ${#cases[@]} programs ($JOBS at a time) ..." >&2
running=0
for c in "${cases[@]}"; do
  build_one $c &
  running=$((running + 1))
  if (( running >= JOBS )); then wait -n; running=$((running - 1)); fi
done
wait
for c in "${cases[@]}"; do
  set -- $c
  [[ -x "bench_${1}_chain_$2" ]] || { echo "build of ${1} n=$2 failed" >&2; exit 1; }
done

for c in "${cases[@]}"; do
  set -- $c
  stem=${1}_chain_$2
  echo "=== $1 n=$2" >&2
  "./bench_$stem" "$stem.xml" "$ROUNDS" | tee "result_$stem.txt" | grep -v '^RESULT' >&2
done

python3 - "$WORK" "${cases[@]}" <<'EOF'
import sys
work, cases = sys.argv[1], [c.split() for c in sys.argv[2:]]
rows = []
for chain, n in cases:
    stem = f"{chain}_chain_{n}"
    r = {}
    for line in open(f"{work}/result_{stem}.txt"):
        if line.startswith("RESULT "):
            _, k, v = line.split()
            r[k] = float(v)
    r["compile"] = float(open(f"{work}/compile_{stem}.txt").read())
    rows.append((chain, int(n), r))

def f(x): return f"{x:.0f}" if x >= 100 else f"{x:.1f}"
def ratio(a, b): return f"{a / b:.2f}"

print("\n### Cross-check (M, F, qdd: max-abs error / max-abs value; kinematics: max-abs error; worst of 8 random states) and RK4 trajectory agreement (max-abs difference)\n")
print("| chain | n | dof | M vs mj_fullM | F vs -qfrc_bias | qdd vs qacc | xmat vs C_ab (abs) | tip pos (abs) | tip vel (abs) | max\\|dq\\| 1 s | max\\|dqd\\| 1 s | max\\|dq\\| 10 s | max\\|dqd\\| 10 s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for chain, n, r in rows:
    print(f"| {chain} | {n} | {int(r['nq'])} | {r['err_M']:.1e} | {r['err_F']:.1e} | {r['err_qdd']:.1e} | "
          f"{r['err_R']:.1e} | {r['err_tip']:.1e} | {r['err_vtip']:.1e} | "
          f"{r['dq_1s']:.1e} | {r['dqd_1s']:.1e} | {r['dq_10s']:.1e} | {r['dqd_10s']:.1e} |")

print("\n### ns per call (medians of interleaved rounds); ratio = ours / MuJoCo\n")
print("| chain | n | dof | ours M+F | MJ M (crb) | MJ bias (rne) | MJ M+bias | ratio M+F | ours FD (eomrt) | ours FD (LLT only) | MJ FD (crb+rne+factorM+solveM) | mj_forward | ratio FD/MJ FD | ratio FD/mj_forward |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for chain, n, r in rows:
    print(f"| {chain} | {n} | {int(r['nq'])} | {f(r['ns_ours_MF'])} | {f(r['ns_mj_M'])} | {f(r['ns_mj_bias'])} | "
          f"{f(r['ns_mj_MF'])} | {ratio(r['ns_ours_MF'], r['ns_mj_MF'])} | {f(r['ns_ours_fd'])} | "
          f"{f(r['ns_ours_fd_raw'])} | {f(r['ns_mj_fd'])} | {f(r['ns_mj_forward'])} | "
          f"{ratio(r['ns_ours_fd'], r['ns_mj_fd'])} | {ratio(r['ns_ours_fd'], r['ns_mj_forward'])} |")

print("\nMinima over the rounds instead of medians (less sensitive to other work on the machine):\n")
print("| chain | n | dof | ours M+F | MJ M+bias | ratio M+F | ours FD (eomrt) | ours FD (LLT) | MJ FD | mj_forward | ratio FD/MJ FD | ratio FD(LLT)/MJ FD |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for chain, n, r in rows:
    print(f"| {chain} | {n} | {int(r['nq'])} | {f(r['nsmin_ours_MF'])} | {f(r['nsmin_mj_MF'])} | "
          f"{ratio(r['nsmin_ours_MF'], r['nsmin_mj_MF'])} | {f(r['nsmin_ours_fd'])} | {f(r['nsmin_ours_fd_raw'])} | "
          f"{f(r['nsmin_mj_fd'])} | {f(r['nsmin_mj_forward'])} | {ratio(r['nsmin_ours_fd'], r['nsmin_mj_fd'])} | "
          f"{ratio(r['nsmin_ours_fd_raw'], r['nsmin_mj_fd'])} |")

print("\n### 10 s simulation, RK4, dt = 1 ms (10 000 steps, 4 dynamics evaluations each); wall time [s], median (min) of 5 interleaved repetitions\n")
print("| chain | n | dof | ours eomrt::simulate | ours rk_step loop + forward_dynamics_unconstrained | ours rk_step loop + bare LLT | MuJoCo mj_step (RK4) | ratio simulate/MJ | ratio bare loop/MJ | bench compile [s] |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for chain, n, r in rows:
    def w(k): return f"{r['sim_' + k]:.4f} ({r['simmin_' + k]:.4f})"
    print(f"| {chain} | {n} | {int(r['nq'])} | {w('ours')} | {w('loop_fd')} | {w('loop_raw')} | {w('mj')} | "
          f"{ratio(r['sim_ours'], r['sim_mj'])} | {ratio(r['sim_loop_raw'], r['sim_mj'])} | {r['compile']:.0f} |")
EOF
