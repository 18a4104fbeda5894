#!/usr/bin/env bash
# Command timings of shipped models (not a test): wall seconds of `eomgen derive`, `derive
# --only T`, `linearize`, `generate` and `check`, median and minimum of REPS runs each, runs of
# the commands interleaved round by round so that all see the same machine load; then the first
# `eomgen simulate` (its compile, with an empty build cache), median and minimum of
# MODEL_TIMES_COMPILES runs. The targets for the bicycle are in docs/performance.md.
#
#   bench/model_times.sh [EOMGEN]     EOMGEN defaults to ../build/generator/eomgen (from here)
#
# Environment (all optional):
#   MODEL_TIMES_MODELS     shipped model stems               (default whipple_bicycle)
#   MODEL_TIMES_REPS       runs of each command               (default 7)
#   MODEL_TIMES_COMPILES   first simulate compiles, 0: none   (default 3)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
eomgen="${1:-$here/../build/generator/eomgen}"
[ -x "$eomgen" ] || { echo "model_times: eomgen not found or not executable: $eomgen" >&2; exit 2; }
reps="${MODEL_TIMES_REPS:-7}"
compiles="${MODEL_TIMES_COMPILES:-3}"
read -r -a models <<< "${MODEL_TIMES_MODELS:-whipple_bicycle}"

# the operating point of each model's linearization (the bicycle's at 5 m/s, as in the paper)
declare -A linearize_args=(
  [whipple_bicycle]="--drop-cyclic --at x_dot=5,theta_r_dot=-16.666666666666667,theta_f_dot=-14.285714285714286")

tmp="$(mktemp -d "${TMPDIR:-/tmp}/model_times.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

seconds() {  # wall seconds of one run of "$@", output discarded
  local start=${EPOCHREALTIME}
  "$@" > /dev/null 2>&1 || { echo "model_times: failed: $*" >&2; exit 1; }
  awk -v a="$start" -v b="${EPOCHREALTIME}" 'BEGIN { printf "%.3f\n", b - a }'
}

summary() {  # median (min) of the numbers in file $1
  sort -n "$1" | awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
                                           printf "%.3f (%.3f)", m, v[1] }'
}

echo "eomgen $("$eomgen" --version 2>/dev/null || echo '?'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%F)"
echo
echo "| model | command | seconds, median (min) of $reps |"
echo "|---|---|---|"
for stem in "${models[@]}"; do
  model="$root/models/$stem.eom"
  # shellcheck disable=SC2206  # the arguments are words
  lin=(${linearize_args[$stem]:-})
  declare -A commands=(
    [check]="check $model"
    [derive]="derive $model"
    ["derive --only T"]="derive $model --only T"
    [linearize]="linearize $model ${lin[*]}"
    [generate]="generate $model -o $tmp/model.hpp")
  names=(check derive "derive --only T" linearize generate)
  for ((round = 0; round < reps; ++round)); do
    for name in "${names[@]}"; do
      # shellcheck disable=SC2086  # the command is words
      seconds "$eomgen" ${commands[$name]} >> "$tmp/${name// /_}"
    done
  done
  for name in "${names[@]}"; do
    echo "| $stem | \`$name\` | $(summary "$tmp/${name// /_}") |"
    rm -f "$tmp/${name// /_}"
  done
  for ((k = 0; k < compiles; ++k)); do
    rm -rf "$tmp/cache"
    EOMGEN_CACHE_DIR="$tmp/cache" seconds "$eomgen" simulate "$model" --t-end 0.01 --no-plot -o "$tmp/run.csv" \
      >> "$tmp/compile"
  done
  [ "$compiles" -gt 0 ] && echo "| $stem | first \`simulate\` (compile and a 0.01 s run), of $compiles | $(summary "$tmp/compile") |"
  rm -f "$tmp/compile"
done
