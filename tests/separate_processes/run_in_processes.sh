#!/usr/bin/env bash
# Runs a command COUNT times, each in a process of its own and each under a time limit, and fails
# naming the run that failed or hung. GiNaC's hash values, and with them its order of terms,
# come from addresses that change from process to process, so a cost that depends on them shows
# up in some processes only: a test that passes in one process can hang in one of twenty.
#
#   run_in_processes.sh COUNT LIMIT_SECONDS COMMAND [ARGUMENT...]
set -uo pipefail
if [ $# -lt 3 ]; then
  echo "usage: run_in_processes.sh COUNT LIMIT_SECONDS COMMAND [ARGUMENT...]" >&2
  exit 2
fi
count="$1" limit="$2"
shift 2
log="$(mktemp "${TMPDIR:-/tmp}/run_in_processes.XXXXXX")"
trap 'rm -f "$log"' EXIT
slowest=0
for ((run = 1; run <= count; ++run)); do
  start=$(date +%s%N)
  timeout --kill-after=5 "$limit" "$@" > "$log" 2>&1
  status=$?
  elapsed=$(( ($(date +%s%N) - start) / 1000000 ))
  (( elapsed > slowest )) && slowest=$elapsed
  if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
    echo "run $run of $count: no result within $limit s: $*" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  if [ "$status" -ne 0 ]; then
    echo "run $run of $count failed with status $status: $*" >&2
    tail -n 40 "$log" >&2
    exit 1
  fi
done
echo "$count runs in separate processes, each within $limit s (the slowest took $slowest ms): $*"
