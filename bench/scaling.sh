#!/usr/bin/env bash
# Scaling benchmark (not a test): how the wall time of `eomgen check`, `eomgen derive` and
# `eomgen generate` grows with the size of a model. For each family of models and each size N
# it runs the three commands REPS times, round by round (check, derive, generate, then again),
# so that all three see the same machine load, and prints one markdown table per family: the
# median and the minimum of the runs of each command, and the growth exponent of each command,
# the log-log slope of the minima against N, between the two largest sizes measured and by
# least squares over all of them (1: linear, 2: quadratic, ...). Each time is of the whole
# process, start-up included, so the smallest models measure mostly the fixed cost (a few ms).
#
# The families (bench/scaling/models.py writes the generated ones into a temporary directory,
# which the script removes, as it does every generated header):
#   chained        N chained derived parameters, each using the one before it twice   10 .. 1000
#   nested_points  N points, each from the previous one's position inside sin and cos  5 .. 40
#   nested_sin     a point at l*sin(sin(...sin(q)...))*a.1, N sines deep              10 .. 200
#   cosine_sum     a potential of N cosine terms, one expression                       10 .. 1000
#   parameter_sum  a derived parameter summing N parameters                            10 .. 10000
#   planar_chain   models/planar_chain.eom --define n=N (N coordinates)                5 .. 200
#   universal_chain models/universal_chain.eom --define n=N (2N coordinates)           2 .. 100
#
#   bench/scaling.sh [EOMGEN]      EOMGEN defaults to build/generator/eomgen
#
# Environment (all optional):
#   SCALING_REPS=3           runs of each command at each size; the table gives median and min
#   SCALING_QUICK=1          a smoke run: the two smallest sizes of each family, one run each
#   SCALING_BUDGET=120       seconds one run may take (timeout(1)); a command that takes longer
#                            is reported as "> budget" at that size, not run again there and
#                            not run at the family's larger sizes ("skipped")
#   SCALING_CAP=200          largest number of coordinates of a chain to run at all
#   SCALING_GENERATE_CAP=100 chains with more coordinates than this time only check and derive
# Any other failure of eomgen (a non-zero status other than the budget's timeout) stops the
# script with status 1, naming the model, its size and the command. A full run took 11 minutes
# on 2 shared cores (docs/performance.md, "Scaling with model size"); the quick run a few seconds.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
eomgen="${1:-$root/build/generator/eomgen}"
[ -x "$eomgen" ] || { echo "scaling: eomgen not found or not executable: $eomgen (build it: scripts/build.sh)" >&2; exit 2; }
command -v timeout > /dev/null || { echo "scaling: timeout(1) not found (coreutils)" >&2; exit 2; }
command -v python3 > /dev/null || { echo "scaling: python3 not found" >&2; exit 2; }

quick="${SCALING_QUICK:-0}"
reps="${SCALING_REPS:-3}"
budget="${SCALING_BUDGET:-120}"
cap="${SCALING_CAP:-200}"
generate_cap="${SCALING_GENERATE_CAP:-100}"
[ "$quick" = 1 ] && reps=1
for v in reps budget cap generate_cap; do
  [[ "${!v}" =~ ^[1-9][0-9]*$ ]] || { echo "scaling: $v must be a positive integer, got '${!v}'" >&2; exit 2; }
done

# family, sizes, and how many coordinates size N has (chains only: the caps apply to those)
families=(chained nested_points nested_sin cosine_sum parameter_sum planar_chain universal_chain)
declare -A sizes=(
  [chained]="10 20 40 100 200 500 1000"
  [nested_points]="5 10 20 40"
  [nested_sin]="10 25 50 95 200"
  [cosine_sum]="10 100 1000"
  [parameter_sum]="10 100 1000 10000"
  [planar_chain]="5 10 20 50 100 200"
  [universal_chain]="2 5 10 25 50 100")
declare -A coordinates_per_n=([planar_chain]=1 [universal_chain]=2)
declare -A describe=(
  [chained]="N derived parameters, a{i} = a{i-1}*(1 + sin(a{i-1}/L)) + L; a pendulum of length aN"
  [nested_points]="N points, p{i} = p{i-1} + l*sin(dot(position(p{i-1}), a.2)/l)*a.1 + l*cos(dot(position(p{i-1}), a.1)/l)*a.2; a particle at pN"
  [nested_sin]="a particle at l*sin(sin(...sin(q)...))*a.1, N sines deep (in pieces of at most 95, each a helper point, beyond the language's nesting limit of 100)"
  [cosine_sum]="a pendulum with the potential k*(cos(q) + cos(2*q)/2 + ... + cos(N*q)/N)"
  [parameter_sum]="N parameters and a derived parameter L = k1 + ... + kN; a pendulum of length L"
  [planar_chain]="models/planar_chain.eom --define n=N: N rods, N coordinates"
  [universal_chain]="models/universal_chain.eom --define n=N: N rods on universal joints, 2N coordinates")
commands=(check derive generate)

tmp="$(mktemp -d "${TMPDIR:-/tmp}/scaling.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

now() {  # seconds since the epoch, to the microsecond
  if [ -n "${EPOCHREALTIME:-}" ]; then echo "${EPOCHREALTIME/,/.}"; else date +%s.%N; fi
}

fmt() {  # a time in seconds with 3 to 4 significant digits
  awk -v t="$1" 'BEGIN { if (t >= 100) printf "%.0f", t; else if (t >= 10) printf "%.1f", t;
                         else if (t >= 1) printf "%.2f", t; else if (t >= 0.1) printf "%.3f", t;
                         else printf "%.4f", t }'
}

# run one command once under the budget; sets `result` to its wall seconds, or to "timeout";
# any other failure ends the script. $1: family, $2: N, $3: command, the rest: eomgen's arguments
run_once() {
  local family="$1" n="$2" name="$3" start end status=0
  shift 3
  start="$(now)"
  timeout --kill-after=10 "$budget" "$eomgen" "$@" > /dev/null 2> "$tmp/stderr" || status=$?
  end="$(now)"
  if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
    result=timeout
    return
  fi
  if [ "$status" -ne 0 ]; then
    {
      echo "scaling: 'eomgen $name' failed with status $status on family $family, N = $n"
      echo "scaling: command: $eomgen $*"
      case "$family" in
        planar_chain | universal_chain) ;;
        *) echo "scaling: the model is the output of: python3 bench/scaling/models.py $family $n" ;;
      esac
      echo "scaling: it printed:"
      head -20 "$tmp/stderr"
    } >&2
    exit 1
  fi
  result="$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.6f", b - a }')"
}

summary() {  # "median (min)" of the numbers in file $1
  local median min
  read -r median min < <(sort -g "$1" | awk '{ v[NR] = $1 }
    END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.6f %.6f\n", m, v[1] }')
  echo "$(fmt "$median") ($(fmt "$min"))"
}

minimum() { sort -g "$1" | head -1; }

# growth exponents from the lines "N seconds" of file $1: "last-two / least-squares", or "–" for
# fewer than two sizes; "(N <= K)" when the largest size run ($2) was not measured
exponents() {
  awk -v largest="$2" 'NF == 2 && $2 > 0 { n++; N[n] = $1; x[n] = log($1); y[n] = log($2) }
       END {
         if (n < 2) { printf "–"; exit }
         last = (y[n] - y[n - 1]) / (x[n] - x[n - 1])
         for (i = 1; i <= n; i++) { sx += x[i]; sy += y[i] }
         mx = sx / n; my = sy / n
         for (i = 1; i <= n; i++) { sxy += (x[i] - mx) * (y[i] - my); sxx += (x[i] - mx) ^ 2 }
         printf "%.2f / %.2f", last, sxy / sxx
         if (N[n] != largest) printf " (N <= %s)", N[n]
       }' "$1"
}

start_all="$(now)"
echo "# eomgen scaling with model size"
echo
commit='?'
if commit="$(git -C "$root" rev-parse --short HEAD 2> /dev/null)"; then
  git -C "$root" diff --quiet HEAD 2> /dev/null || commit+=" (with uncommitted changes)"
else
  commit='?'
fi
echo "- $("$eomgen" --version 2> /dev/null | head -1) ($eomgen) at commit $commit"
echo "- machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at the start"
echo "- started $(date -u '+%Y-%m-%d %H:%M UTC'); wall seconds of the whole process, median (min) of $reps run(s), interleaved round by round"
echo "- budget $budget s per run; chains up to $cap coordinates, \`generate\` up to $generate_cap$([ "$quick" = 1 ] && echo '; QUICK: the two smallest sizes of each family')"
echo "- growth exponent: log-log slope of the minima against N, between the two largest sizes measured / least squares over all sizes measured"

for family in "${families[@]}"; do
  read -r -a ns <<< "${sizes[$family]}"
  [ "$quick" = 1 ] && ns=("${ns[@]:0:2}")
  per_n="${coordinates_per_n[$family]:-}"
  echo
  echo "## $family"
  echo
  echo "${describe[$family]}."
  echo
  echo "| family | N | check [s] median (min) | derive [s] median (min) | generate [s] median (min) |"
  echo "|---|---:|---:|---:|---:|"
  declare -A over_budget=()
  for name in "${commands[@]}"; do : > "$tmp/minima_$name"; done
  largest_run="" largest_generate=""  # the largest sizes run, for the exponents' "(N <= K)"
  for n in "${ns[@]}"; do
    label="$n"
    if [ -n "$per_n" ]; then
      coords=$((n * per_n))
      if [ "$coords" -gt "$cap" ]; then
        echo "| $family | $n | not run: $coords coordinates > SCALING_CAP = $cap | | |"
        continue
      fi
      [ "$per_n" -gt 1 ] && label="$n ($coords coordinates)"
      model="$root/models/$family.eom"
      args=("$model" --define "n=$n")
    else
      coords=0
      model="$tmp/${family}_$n.eom"
      python3 "$here/scaling/models.py" "$family" "$n" > "$model"
      args=("$model")
    fi
    largest_run="$n"
    [ "$coords" -le "$generate_cap" ] && largest_generate="$n"
    declare -A cell=()
    active=()
    for name in "${commands[@]}"; do
      : > "$tmp/times_$name"
      if [ -n "${over_budget[$name]:-}" ]; then
        cell[$name]="skipped (> budget at N = ${over_budget[$name]})"
      elif [ "$name" = generate ] && [ "$coords" -gt "$generate_cap" ]; then
        cell[$name]="not run: $coords coordinates > SCALING_GENERATE_CAP = $generate_cap"
      else
        active+=("$name")
      fi
    done
    for ((round = 0; round < reps; ++round)); do
      for name in "${active[@]}"; do
        [ -n "${cell[$name]:-}" ] && continue  # it ran out of budget in an earlier round
        case "$name" in
          generate) extra=(-o "$tmp/generated.hpp") ;;
          *) extra=() ;;
        esac
        run_once "$family" "$n" "$name" "$name" "${args[@]}" "${extra[@]}"
        if [ "$result" = timeout ]; then
          cell[$name]="> $budget (budget)"
          over_budget[$name]="$n"
        else
          echo "$result" >> "$tmp/times_$name"
        fi
      done
    done
    rm -f "$tmp/generated.hpp"
    for name in "${active[@]}"; do
      if [ -z "${cell[$name]:-}" ]; then
        cell[$name]="$(summary "$tmp/times_$name")"
        echo "$n $(minimum "$tmp/times_$name")" >> "$tmp/minima_$name"
      fi
    done
    echo "| $family | $label | ${cell[check]} | ${cell[derive]} | ${cell[generate]} |"
    unset cell
    [ -z "$per_n" ] && rm -f "$model"
  done
  echo "| $family | growth exponent (last two / all) | $(exponents "$tmp/minima_check" "$largest_run") | $(exponents "$tmp/minima_derive" "$largest_run") | $(exponents "$tmp/minima_generate" "$largest_generate") |"
  unset over_budget
done

echo
echo "finished $(date -u '+%Y-%m-%d %H:%M UTC'), $(awk -v a="$start_all" -v b="$(now)" 'BEGIN { printf "%.0f", b - a }') s in all"
