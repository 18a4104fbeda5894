#!/usr/bin/env bash
# Fuzzes the model parser (tests/fuzz/model_fuzzer.cpp: parse_model on arbitrary text) with
# libFuzzer under ASan + UBSan for SECONDS seconds, on WORKERS processes (default 1).
#
#   scripts/fuzz.sh SECONDS [WORKERS]
#
# Installs clang 14 and libFuzzer when missing (scripts/install-deps.sh --fuzz), configures and
# builds the fuzzer alone with clang into build-fuzz/ (or $EOMGEN_FUZZ_BUILD_DIR) through ccache
# (scripts/build.sh), then fuzzes. The seeds are read where they are, so they never go stale:
# every model of models/ and the short models of tests/fuzz/seeds/ (one per statement kind). The
# inputs that grow the coverage are kept in build-fuzz/fuzz-corpus/ (git-ignored) and seed the
# next run.
#
# Prints executions per second, coverage (cov: edges, ft: features) and the corpus size, and
# exits 1 on any finding: a crash, an exception other than a located SourceError, undefined
# behaviour, a leak, an input that takes more than 10 s (a hang) or more than 2 GB. Each finding's
# input is written to $EOMGEN_FUZZ_FINDINGS (default build-fuzz/fuzz-findings/) and its path
# printed, with the command that replays it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage() { echo "usage: scripts/fuzz.sh SECONDS [WORKERS]" >&2; exit 2; }
[ $# -ge 1 ] && [ $# -le 2 ] || usage
seconds="$1"
workers="${2:-1}"
[[ "$seconds" =~ ^[1-9][0-9]*$ ]] && [[ "$workers" =~ ^[1-9][0-9]*$ ]] || usage

build="${EOMGEN_FUZZ_BUILD_DIR:-$root/build-fuzz}"
corpus="$build/fuzz-corpus"
findings="${EOMGEN_FUZZ_FINDINGS:-$build/fuzz-findings}"
logs="$build/fuzz-logs"

"$root/scripts/install-deps.sh" --fuzz
# clang for the first configuration of the folder (CXX is read only then); Debug keeps Eigen's
# and the standard library's assertions, -O1 is libFuzzer's recommended speed, -g1 gives the
# reports' stack traces their lines
CXX=clang++-14 EOMGEN_BUILD_DIR="$build" \
EOMGEN_CMAKE_ARGS="-DEOMGEN_FUZZ=ON -DEOMGEN_WERROR=ON -DEOMGEN_BUILD_TESTS=OFF -DEOMGEN_BUILD_BENCH=OFF -DEOMGEN_BUILD_EXAMPLES=OFF -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS=-O1 -DCMAKE_CXX_FLAGS_DEBUG=-g1" \
  "$root/scripts/build.sh" --target eomgen_model_fuzzer
fuzzer="$build/tests/fuzz/eomgen_model_fuzzer"

# this run's findings in a folder of their own, so that an earlier run's do not count
run_findings="$findings/$(date +%Y%m%d-%H%M%S)"
mkdir -p "$corpus" "$run_findings"
rm -rf "$logs" && mkdir -p "$logs"
export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
# ASan's own bookkeeping, not the parser, is what grows over a long run: the allocation stack of
# every live and quarantined block (a fuzzer makes a great many distinct ones) and the quarantine
# of freed memory took a worker past 1 GB in ten minutes and toward -rss_limit_mb in thirty.
# Without allocation stacks and with a smaller quarantine it stays small; a crash's own stack
# trace is unaffected, and replaying a finding (below, default options) shows the allocation's.
export ASAN_OPTIONS="detect_leaks=1:malloc_context_size=0:quarantine_size_mb=64:${ASAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

echo "== fuzzing the model parser for $seconds s on $workers worker(s); logs in $logs/"
# -jobs: one process per worker, each for the whole time, all sharing the corpus folder; each
# job's output goes to fuzz-N.log in the current folder
status=0
(cd "$logs" && "$fuzzer" -jobs="$workers" -workers="$workers" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
  -dict="$root/tests/fuzz/model.dict" -use_value_profile=1 -print_funcs=0 -print_final_stats=1 \
  -artifact_prefix="$run_findings/" \
  "$corpus" "$root/models" "$root/tests/fuzz/seeds" > "$logs/libfuzzer.log" 2>&1) || status=$?

exec_per_s=0
for log in "$logs"/fuzz-*.log; do
  [ -f "$log" ] || continue
  # the last status line (DONE when the job ran to its end) and the job's mean speed
  last="$(grep -aE '^#[0-9]+' "$log" | grep -a 'cov:' | tail -1 || true)"
  speed="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  echo "$(basename "$log" .log): ${last:-no status line} ${speed:+(mean $speed exec/s)}"
  exec_per_s=$((exec_per_s + ${speed:-0}))
done
echo "== $exec_per_s executions/s in all; corpus: $(find "$corpus" -type f | wc -l) inputs in $corpus"

found=()
while IFS= read -r -d '' f; do found+=("$f"); done \
  < <(find "$run_findings" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) -print0)
if [ ${#found[@]} -gt 0 ] || [ "$status" -ne 0 ]; then
  for log in "$logs"/fuzz-*.log; do
    [ -f "$log" ] || continue
    # the report: from the sanitizer's or the target's first line to the saved input, with the
    # top 20 frames of its stack (a stack overflow has thousands) and its summary
    awk '/^==[0-9]+==ERROR|^==eomgen fuzz finding|^==[0-9]+== ERROR: libFuzzer|runtime error:|^ALARM: working on the last Unit/ { on = 1; n = 0 }
         on && (++n <= 24 || /^SUMMARY|Test unit written to/) { print }
         /Test unit written to/ { on = 0 }' "$log"
  done
  echo "== FAILED: libFuzzer exited with $status; ${#found[@]} finding(s) (replay with LSAN_OPTIONS=$LSAN_OPTIONS):"
  for f in "${found[@]}"; do
    echo "   $f"
    echo "     replay:   LSAN_OPTIONS=\$LSAN_OPTIONS $fuzzer $f"
    echo "     minimize: $fuzzer -minimize_crash=1 -max_total_time=60 -exact_artifact_path=$f.min $f"
  done
  exit 1
fi
rmdir "$run_findings" 2>/dev/null || true
echo "== no findings"
