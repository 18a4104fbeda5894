#!/usr/bin/env bash
# Every shipped model's animation, as a user makes it, in headless Chromium: `eomgen simulate
# --animate` for each run of tests/support/shipped_runs.txt (2 s), then check_page.sh on the
# page at t = 1.5 s (ready, no error, no request, no console message, the mechanism drawn) and,
# given CHECK_VIEW, check_view on its view (every point of the run inside the default view, the
# grid and the axes).
#
#   tests/browser/shipped_pages.sh EOMGEN CACHE_DIR OUT_DIR [CHECK_VIEW]
set -euo pipefail
[ $# -eq 3 ] || [ $# -eq 4 ] || { echo "usage: shipped_pages.sh EOMGEN CACHE_DIR OUT_DIR [CHECK_VIEW]" >&2; exit 2; }
eomgen="$1" cache="$2" out="$3"
view=()
if [ $# -eq 4 ]; then view=(--check-view "$4"); fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
mkdir -p "$out"
failed=()
while read -r model init; do
  case "$model" in ''|'#'*) continue ;; esac
  page="$out/$model.html"
  if ! "$eomgen" simulate "$root/models/$model.eom" --t-end 2 --init "$init" --no-plot -o "$out/$model.csv" \
       --animate "$page" --cache-dir "$cache" > "$out/$model.log" 2>&1; then
    echo "FAIL: $model: eomgen simulate failed:" >&2
    cat "$out/$model.log" >&2
    failed+=("$model")
    continue
  fi
  grep '^animation:' "$out/$model.log"
  "$here/check_page.sh" --load-only "${view[@]+"${view[@]}"}" "$page" 1.5 || failed+=("$model")
done < "$root/tests/support/shipped_runs.txt"
if [ ${#failed[@]} -gt 0 ]; then
  echo "FAIL: the pages of ${failed[*]}" >&2
  exit 1
fi
echo "ok: every shipped model animates"
