#!/usr/bin/env bash
# Runs the whole test suite: installs dependencies, configures, builds, runs ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh"
# a test that hangs fails by name after 15 minutes (the longest takes about 3) rather than
# holding the run until CI gives up on it; tests with their own TIMEOUT keep it
ctest --test-dir "$build" --output-on-failure --timeout 900 -j"$(nproc)"
