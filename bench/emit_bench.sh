#!/usr/bin/env bash
# Emitted-code benchmark (not a test): operation counts and nanoseconds per evaluation of M and F
# for the planar chain (n = 2..32) and the 3D universal-joint chain (n = 1..8), for the optimized
# header (shared temporaries) and the unoptimized one (eomgen generate --no-cse), in one run.
#
#   bench/emit_bench.sh [EOMGEN]      EOMGEN defaults to ../build/generator/eomgen (from here)
#   cmake --build BUILD --target emit_bench
#
# Steps: (1) generate both headers for each chain and n with --stats into a temporary directory;
# (2) compile bench/emit_timing.cpp.in once per header, with the same flags for both variants,
# skipping an unoptimized header whose mass_matrix_and_forcing has more than
# EMIT_BENCH_MAX_UNOPT_OPS operations ("too large": it would take minutes and gigabytes to
# compile, and it is not even generated); (3) run every timing program REPS times, interleaved
# round by round so both variants see the same machine load, and print markdown tables of
# medians plus machine information.
#
# Environment (all optional):
#   EMIT_BENCH_OPT            optimization flag for every variant        (default -O2)
#   EMIT_BENCH_MAX_UNOPT_OPS  largest unoptimized op count to compile    (default 300000)
#   EMIT_BENCH_REPS           timed runs per header, median reported     (default 7)
#   EMIT_BENCH_MIN_SECONDS    duration of one timed run                  (default 0.1)
#   EMIT_BENCH_JOBS           parallel compilations                      (default nproc)
#   EMIT_BENCH_QUICK=1        small n only (planar 2 4, 3D 1 2), as a smoke test of the script
#   CXX                       compiler                                   (default g++)
#   EIGEN_INCLUDE             Eigen include directory                    (default /usr/include/eigen3)
set -euo pipefail

start_time=${EPOCHREALTIME}
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
eomgen="${1:-$here/../build/generator/eomgen}"
if [ ! -x "$eomgen" ]; then
  echo "emit_bench: eomgen not found or not executable: $eomgen (pass its path as the first argument)" >&2
  exit 2
fi
eomgen="$(cd "$(dirname "$eomgen")" && pwd)/$(basename "$eomgen")"

opt_level="${EMIT_BENCH_OPT:--O2}"
max_unopt="${EMIT_BENCH_MAX_UNOPT_OPS:-300000}"
reps="${EMIT_BENCH_REPS:-7}"
min_seconds="${EMIT_BENCH_MIN_SECONDS:-0.1}"
njobs="${EMIT_BENCH_JOBS:-$(nproc)}"
cxx="${CXX:-g++}"
eigen_include="${EIGEN_INCLUDE:-/usr/include/eigen3}"
timing_src="$here/emit_timing.cpp.in"
cxxflags=(-std=c++17 "$opt_level" "-I$eigen_include")

for f in "$timing_src" "$root/models/planar_chain.eom" "$root/models/universal_chain.eom" \
         "$eigen_include/Eigen/Core"; do
  [ -f "$f" ] || { echo "emit_bench: missing $f" >&2; exit 2; }
done
command -v "$cxx" > /dev/null || { echo "emit_bench: compiler not found: $cxx" >&2; exit 2; }

chains=(planar_chain universal_chain)
declare -A chain_ns=([planar_chain]="2 4 8 12 16 24 32" [universal_chain]="1 2 4 6 8")
if [ "${EMIT_BENCH_QUICK:-0}" = 1 ]; then
  chain_ns=([planar_chain]="2 4" [universal_chain]="1 2")
fi
declare -A chain_title=(
  [planar_chain]="Planar chain (models/planar_chain.eom, n rods, dof = n)"
  [universal_chain]="3D chain with universal joints (models/universal_chain.eom, n rods, dof = 2n)")

tmp="$(mktemp -d "${TMPDIR:-/tmp}/emit_bench.XXXXXX")"
cleanup() {
  local pids
  pids="$(jobs -pr)"
  if [ -n "$pids" ]; then
    # shellcheck disable=SC2086  # one pid per word
    kill $pids 2> /dev/null || true
    wait 2> /dev/null || true
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

elapsed() {  # seconds since $1 (an EPOCHREALTIME value), one decimal
  awk -v a="$1" -v b="${EPOCHREALTIME}" 'BEGIN { printf "%.1f", b - a }'
}

declare -A nq ops_u ops_o size_o size_u
cells=()

# ---- 1. generate ------------------------------------------------------------------------------
echo "emit_bench: generating headers into $tmp" >&2
t_gen=${EPOCHREALTIME}
for chain in "${chains[@]}"; do
  for n in ${chain_ns[$chain]}; do
    key="${chain}_$n"
    cells+=("$key")
    "$eomgen" generate "$root/models/$chain.eom" -D "n=$n" -o "$tmp/$key.opt.hpp" --stats \
      > "$tmp/$key.stats"
    read -r "ops_u[$key]" "ops_o[$key]" < <(awk '$1 == "mass_matrix_and_forcing" { print $2, $3 }' \
      "$tmp/$key.stats")
    if [ -z "${ops_u[$key]:-}" ] || [ -z "${ops_o[$key]:-}" ]; then
      echo "emit_bench: no mass_matrix_and_forcing row in the --stats output for $key:" >&2
      cat "$tmp/$key.stats" >&2
      exit 1
    fi
    nq[$key]="$(sed -n 's/.*static constexpr int nq = \([0-9]*\);.*/\1/p' "$tmp/$key.opt.hpp" | head -n 1)"
    size_o[$key]="$(wc -c < "$tmp/$key.opt.hpp")"
    if [ "${ops_u[$key]}" -le "$max_unopt" ]; then
      "$eomgen" generate "$root/models/$chain.eom" -D "n=$n" -o "$tmp/$key.unopt.hpp" --no-cse \
        --stats > "$tmp/$key.unopt.stats"
      size_u[$key]="$(wc -c < "$tmp/$key.unopt.hpp")"
    fi
    echo "  $key: nq=${nq[$key]} ops unoptimized=${ops_u[$key]} optimized=${ops_o[$key]}" >&2
  done
done
gen_seconds="$(elapsed "$t_gen")"

# ---- 2. compile (largest headers first, EMIT_BENCH_JOBS at a time) ---------------------------
compile_one() {  # header namespace executable: writes executable.status and executable.seconds
  local t0=${EPOCHREALTIME} status=0
  "$cxx" "${cxxflags[@]}" -x c++ "-DEMIT_HEADER=\"$1\"" "-DEMIT_NAMESPACE=eomgen_models::$2" \
    "$timing_src" -o "$3" > "$3.log" 2>&1 || status=$?
  elapsed "$t0" > "$3.seconds"
  echo "$status" > "$3.status"
}

units=()  # "size header namespace executable", sorted by size below
for key in "${cells[@]}"; do
  chain="${key%_*}"
  units+=("${size_o[$key]} $tmp/$key.opt.hpp $chain $tmp/$key.opt.exe")
  if [ -n "${size_u[$key]:-}" ]; then
    units+=("${size_u[$key]} $tmp/$key.unopt.hpp $chain $tmp/$key.unopt.exe")
  fi
done
echo "emit_bench: compiling ${#units[@]} timing programs ($cxx ${cxxflags[*]}, $njobs at a time)" >&2
t_comp=${EPOCHREALTIME}
running=0
while read -r _ header ns exe; do
  if [ "$running" -ge "$njobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  compile_one "$header" "$ns" "$exe" &
  running=$((running + 1))
done < <(printf '%s\n' "${units[@]}" | sort -k1,1nr)
wait || true
comp_seconds="$(elapsed "$t_comp")"
for unit in "${units[@]}"; do
  read -r _ _ _ exe <<< "$unit"
  if [ "$(cat "$exe.status" 2> /dev/null || echo missing)" != 0 ]; then
    echo "emit_bench: compiling $(basename "$exe" .exe) failed:" >&2
    head -n 40 "$exe.log" >&2 || true
    exit 1
  fi
  echo "  $(basename "$exe" .exe): $(cat "$exe.seconds") s" >&2
done

# ---- 3. time: REPS rounds, each running every program once -----------------------------------
echo "emit_bench: timing, $reps rounds of ~${min_seconds} s per program" >&2
load_before="$(cut -d' ' -f1-3 /proc/loadavg 2> /dev/null || echo '?')"
t_time=${EPOCHREALTIME}
for ((round = 1; round <= reps; ++round)); do
  for key in "${cells[@]}"; do
    for variant in opt unopt; do
      exe="$tmp/$key.$variant.exe"
      [ -x "$exe" ] || continue
      "$exe" "$min_seconds" 1 > "$tmp/run.out"
      if [ "$round" -eq 1 ]; then
        sed -n 's/^check //p' "$tmp/run.out" > "$tmp/$key.$variant.check"
      fi
      grep -v '^check ' "$tmp/run.out" >> "$tmp/$key.$variant.ns"
    done
  done
done
time_seconds="$(elapsed "$t_time")"
load_after="$(cut -d' ' -f1-3 /proc/loadavg 2> /dev/null || echo '?')"

# Both headers must compute the same M and F (the sums over all states agree to rounding).
for key in "${cells[@]}"; do
  [ -f "$tmp/$key.unopt.check" ] || continue
  if ! awk -v a="$(cat "$tmp/$key.opt.check")" -v b="$(cat "$tmp/$key.unopt.check")" 'BEGIN {
         d = a - b; if (d < 0) d = -d; s = (a < 0 ? -a : a); if (s < 1) s = 1
         exit !(d <= 1e-9 * s) }'; then
    echo "emit_bench: $key: optimized and unoptimized headers disagree" \
      "(sum of M and F: $(cat "$tmp/$key.opt.check") vs $(cat "$tmp/$key.unopt.check"))" >&2
    exit 1
  fi
done

# ---- 4. report ---------------------------------------------------------------------------------
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
fmt_ns() { awk -v x="$1" 'BEGIN { if (x >= 100) printf "%.0f", x; else printf "%.1f", x }'; }
fmt_size() {
  awk -v b="$1" 'BEGIN { if (b >= 1048576) printf "%.2f MiB", b / 1048576;
                         else if (b >= 10240) printf "%.0f KiB", b / 1024;
                         else printf "%.1f KiB", b / 1024 }'
}
fmt_ratio() {
  awk -v a="$1" -v b="$2" 'BEGIN { r = a / b; if (r < 1000) printf "%.1fx", r; else printf "%.3gx", r }'
}

cpu_model="$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2> /dev/null || true)"
[ -n "$cpu_model" ] || cpu_model="$(uname -m)"
eigen_version="$(awk '/#define EIGEN_(WORLD|MAJOR|MINOR)_VERSION/ { v = v (v == "" ? "" : ".") $3 } END { print v }' \
  "$eigen_include/Eigen/src/Core/util/Macros.h" 2> /dev/null || true)"

echo "# Emitted code: optimized vs. unoptimized (--no-cse) headers"
echo
echo "- machine: nproc = $(nproc), CPU: $cpu_model"
echo "- compiler: $("$cxx" --version | head -n 1); flags for every variant: ${cxxflags[*]}" \
  "(no -ffast-math, no -march=native); Eigen ${eigen_version:-?}; $("$eomgen" --version 2> /dev/null | head -n 1)"
echo "- ops: eomgen --stats for mass_matrix_and_forcing (adds + muls + divs + function calls);" \
  "unoptimized = every output as its own tree, without sharing (what --no-cse emits);" \
  "optimized = the emitted straight-line code with shared temporaries"
echo "- ns: nanoseconds per call of Model::mass_matrix_and_forcing<double> over 64 fixed random" \
  "states (every entry of M and F summed into a volatile sink), median of $reps timed runs of" \
  "~${min_seconds} s per header; both variants were measured in the same run, interleaved" \
  "round by round, while the machine had other load (load average $load_before before," \
  "$load_after after timing), so single cells are noisy"
echo "- unoptimized headers above $max_unopt ops are too large to compile in reasonable time:" \
  "they are neither generated nor compiled (\"too large\"); the optimized and unoptimized" \
  "headers that were both compiled computed the same M and F (checked)"
echo "- speedup = ns unoptimized / ns optimized; ratio = ops unoptimized / ops optimized;" \
  "they differ because the compiler's own common-subexpression elimination recovers part of" \
  "the sharing in the unoptimized code and because a sin or cos call costs more than an add"

for chain in "${chains[@]}"; do
  echo
  echo "## ${chain_title[$chain]}"
  echo
  echo "| n | dof | ops unoptimized | ops optimized | ratio | ns unoptimized | ns optimized | speedup | header size optimized |"
  echo "|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
  for n in ${chain_ns[$chain]}; do
    key="${chain}_$n"
    ns_o="$(median "$tmp/$key.opt.ns")"
    if [ -f "$tmp/$key.unopt.ns" ]; then
      ns_u="$(median "$tmp/$key.unopt.ns")"
      ns_u_text="$(fmt_ns "$ns_u")"
      speedup="$(fmt_ratio "$ns_u" "$ns_o")"
    else
      ns_u_text="too large"
      speedup="-"
    fi
    echo "| $n | ${nq[$key]} | ${ops_u[$key]} | ${ops_o[$key]} | $(fmt_ratio "${ops_u[$key]}" "${ops_o[$key]}")" \
      "| $ns_u_text | $(fmt_ns "$ns_o") | $speedup | $(fmt_size "${size_o[$key]}") |"
  done
done

echo
echo "## Build details"
echo
echo "| chain | n | header size unoptimized | compile s unoptimized | compile s optimized |"
echo "|:--|--:|--:|--:|--:|"
for key in "${cells[@]}"; do
  chain="${key%_*}"
  n="${key##*_}"
  if [ -n "${size_u[$key]:-}" ]; then
    su="$(fmt_size "${size_u[$key]}")"
    cu="$(cat "$tmp/$key.unopt.exe.seconds")"
  else
    su="not generated"
    cu="-"
  fi
  echo "| $chain | $n | $su | $cu | $(cat "$tmp/$key.opt.exe.seconds") |"
done
echo
echo "Wall time $(elapsed "$start_time") s: generating $gen_seconds s, compiling $comp_seconds s" \
  "($njobs parallel jobs), timing $time_seconds s."
