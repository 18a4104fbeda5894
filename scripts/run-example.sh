#!/usr/bin/env bash
# The main job: check a shipped model, derive and print its equations of motion, generate
# its optimized C++ header, and run the computed-torque controller built on that header.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${EOMGEN_BUILD_DIR:-$root/build}"
model="${1:-$root/models/double_pendulum.eom}"
"$root/scripts/build.sh" --target eomgen computed_torque >/dev/null
eomgen="$build/generator/eomgen"

echo "== eomgen check $(basename "$model")"
"$eomgen" check "$model"
echo
echo "== eomgen derive $(basename "$model")"
"$eomgen" derive "$model"
echo
header="$build/$(basename "$model" .eom).hpp"
echo "== eomgen generate $(basename "$model") -o $header --stats"
"$eomgen" generate "$model" -o "$header" --stats
echo
echo "== computed-torque tracking on the generated double pendulum (examples/computed_torque)"
"$build/examples/computed_torque/computed_torque"
