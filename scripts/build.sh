#!/usr/bin/env bash
# Installs dependencies when needed, configures and builds into build/ (or $EOMGEN_BUILD_DIR).
# Extra arguments go to the build step (e.g. --target NAME). $EOMGEN_CMAKE_ARGS are passed to
# the configuration: the first one, and again on an existing build when it is set (so that CI's
# -DEOMGEN_WERROR=ON holds in a build folder configured without it).
#
# Builds with Ninja and through ccache: a second build of the same sources, in this clone or
# another one anywhere on the machine, takes its objects from the cache (~/.cache/ccache, or
# $CCACHE_DIR). Paths below the repository root are hashed relative to it, so clones in
# different folders share entries.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
"$root/scripts/install-deps.sh"
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache ${EOMGEN_CMAKE_ARGS:-}
elif [ -n "${EOMGEN_CMAKE_ARGS:-}" ]; then
  cmake "$build" ${EOMGEN_CMAKE_ARGS}
fi
cmake --build "$build" -j"$(nproc)" "$@"
