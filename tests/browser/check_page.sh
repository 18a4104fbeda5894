#!/usr/bin/env bash
# Opens an animation page (docs/animation.md) in headless Chromium and checks it, failing with
# the reason:
#
#   tests/browser/check_page.sh [--layers LIST] [--follow CHOICE] [--check-view CHECKER] [--load-only]
#                               [--min-drawn N] [--expect-error TEXT]... PAGE.html T1 [T2 ...]
#
# At each time T (the page's #t=T hook: paused at T s): the page says it is ready, with no
# error (uncaught exceptions, rejections, console.error and console.warn, blocked requests),
# it asked for no resource, Chromium logged no console message, and the 3D view has more than
# N (--min-drawn, default 2000) pixels that are not background. Then, unless --load-only, a
# 1280x800 screenshot at each time: each is a PNG of at least 10 KB and no two are the same.
# Name resolution is disabled (--host-resolver-rules), so a page that asked the network would
# fail. --layers LIST (trails,frames,forces) shows those layers, and only those. --follow CHOICE
# makes the camera's choice (mechanism, body:NAME) as a user does. --check-view CHECKER then
# runs CHECKER (check_view) on the page and the view it reported at every time: the camera
# frames the run (or follows), the grid and the axes are drawn. --expect-error TEXT (repeated:
# in order) expects the page to record exactly those errors, and no other (a damaged scene the
# page must survive): its title is then "error: " and the first; the other checks are the same.
# $KEEP_SCREENSHOTS=DIR keeps the screenshots there; $CHROMIUM names the browser.
set -euo pipefail

layers=""
follow=""
view_checker=""
load_only=0
min_drawn=2000
expected_errors=()
while [ $# -gt 0 ]; do
  case "$1" in
    --layers) layers="$2"; shift 2 ;;
    --follow) follow="$2"; shift 2 ;;
    --check-view) view_checker="$2"; shift 2 ;;
    --load-only) load_only=1; shift ;;
    --min-drawn) min_drawn="$2"; shift 2 ;;
    --expect-error)
      # (as JSON and HTML write it unchanged: no quote, backslash, &, < or >)
      case "$2" in *['"\\&<>']*) echo "check_page.sh: --expect-error cannot hold \", \\, &, < or >: $2" >&2; exit 2 ;; esac
      expected_errors+=("$2"); shift 2 ;;
    *) break ;;
  esac
done
if [ $# -lt 2 ]; then
  echo "usage: check_page.sh [--layers LIST] [--follow CHOICE] [--check-view CHECKER] [--load-only] [--min-drawn N]" \
       "[--expect-error TEXT]... PAGE.html T1 [T2 ...]" >&2
  exit 2
fi
page="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
shift
[ -f "$page" ] || { echo "FAIL: $page does not exist" >&2; exit 1; }
chromium="${CHROMIUM:-chromium}"
command -v "$chromium" > /dev/null || { echo "FAIL: $chromium not found: scripts/install-deps.sh installs it" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# WebGL without a GPU: SwiftShader through ANGLE; a profile of its own per run, no sandbox
# (containers and CI runners lack the namespaces it needs), no network, no first-run dialogs
flags=(--headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
       --host-resolver-rules="MAP * ~NOTFOUND" --no-first-run --no-default-browser-check
       --disable-extensions --disable-background-networking --disable-component-update
       --disable-sync --hide-scrollbars --window-size=1280,800
       --enable-logging=stderr --v=0 --virtual-time-budget=3000)

fail() {
  echo "FAIL: $page at t=$1: $2" >&2
  exit 1
}

url() {
  local hash="t=$1"
  if [ -n "$layers" ]; then hash="$hash&layers=$layers"; fi
  if [ -n "$follow" ]; then hash="$hash&follow=$follow"; fi
  echo "file://$page#$hash"
}

# run chromium with a fresh profile; its log goes to $work/log
run() {
  rm -rf "$work/profile"
  "$chromium" "${flags[@]}" --user-data-dir="$work/profile" "$@" 2> "$work/log"
}

# the title and the status's errors the page must show: none, or exactly the expected ones
expected_title="ready "
expected_list="[]"
if [ ${#expected_errors[@]} -gt 0 ]; then
  expected_title="error: ${expected_errors[0]}"
  expected_list=$(printf '"%s",' "${expected_errors[@]}")
  expected_list="[${expected_list%,}]"
fi

start=$(date +%s%N)
statuses=()
for t in "$@"; do
  run --dump-dom "$(url "$t")" > "$work/dom.html" || fail "$t" "chromium exited with $?: $(tail -5 "$work/log")"
  title=$(sed -n 's:.*<title>\(.*\)</title>.*:\1:p' "$work/dom.html" | head -1)
  status=$(sed -n 's:.*<pre id="status"[^>]*>\(.*\)</pre>.*:\1:p' "$work/dom.html" | head -1)
  if [ ${#expected_errors[@]} -eq 0 ]; then
    case "$title" in
      "ready "*) ;;
      *) fail "$t" "the page is not ready: title \"$title\", status $status" ;;
    esac
  else
    [ "$title" = "$expected_title" ] || fail "$t" "the title is \"$title\", not \"$expected_title\": status $status"
  fi
  case "$status" in
    *'"ready":true'*) ;;
    *) fail "$t" "status says not ready: $status" ;;
  esac
  case "$status" in
    *"\"errors\":$expected_list"*) ;;
    *) fail "$t" "errors (expected $expected_list): $status" ;;
  esac
  case "$status" in
    *'"requests":0'*) ;;
    *) fail "$t" "the page requested resources: $status" ;;
  esac
  drawn=$(echo "$status" | sed -n 's/.*"drawn":\([0-9]*\).*/\1/p')
  [ -n "$drawn" ] && [ "$drawn" -gt "$min_drawn" ] || fail "$t" "only ${drawn:-no} pixels drawn (need > $min_drawn): $status"
  if grep -q ':CONSOLE' "$work/log"; then
    fail "$t" "console messages: $(grep ':CONSOLE' "$work/log" | head -5)"
  fi
  echo "ok: t=$t: $title, $drawn pixels drawn"
  printf '%s\n' "$status" > "$work/status-${#statuses[@]}.json"
  statuses+=("$work/status-${#statuses[@]}.json")
done

if [ -n "$view_checker" ]; then
  follow_option=()
  if [ -n "$follow" ]; then follow_option=(--follow "$follow"); fi
  "$view_checker" "${follow_option[@]+"${follow_option[@]}"}" "$page" "${statuses[@]}" || fail "$*" "the view is not as docs/animation.md says (above)"
fi

if [ "$load_only" -eq 0 ]; then
  shots=()
  for t in "$@"; do
    shot="$work/shot-$t.png"
    run --screenshot="$shot" "$(url "$t")" > /dev/null || fail "$t" "chromium --screenshot exited with $?: $(tail -5 "$work/log")"
    [ -f "$shot" ] || fail "$t" "no screenshot written: $(tail -5 "$work/log")"
    size=$(stat -c %s "$shot")
    [ "$size" -ge 10000 ] || fail "$t" "the screenshot is only $size bytes"
    [ "$(head -c 8 "$shot" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$t" "the screenshot is no PNG"
    for previous in "${shots[@]+"${shots[@]}"}"; do
      if cmp -s "$previous" "$shot"; then fail "$t" "the screenshot is the same as at another time ($previous)"; fi
    done
    shots+=("$shot")
    if [ -n "${KEEP_SCREENSHOTS:-}" ]; then mkdir -p "$KEEP_SCREENSHOTS"; cp "$shot" "$KEEP_SCREENSHOTS/"; fi
    echo "ok: t=$t: screenshot of $size bytes"
  done
fi
echo "ok: $page in $(( ($(date +%s%N) - start) / 1000000 )) ms"
