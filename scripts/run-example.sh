#!/usr/bin/env bash
# The main job: derive and print the equations of motion of a shipped example.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh" --target double_pendulum_equations >/dev/null
"$build/examples/double_pendulum_equations"
