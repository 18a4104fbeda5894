#!/usr/bin/env bash
# Installs dependencies when needed, configures and builds into build/ (or $EOMGEN_BUILD_DIR).
# Extra arguments go to the build step (e.g. --target NAME).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
"$root/scripts/install-deps.sh"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${EOMGEN_CMAKE_ARGS:-}
fi
cmake --build "$build" -j"$(nproc)" "$@"
