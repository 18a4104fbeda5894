#!/usr/bin/env bash
# Installs everything eomgen needs on Debian 12 with apt-get; does nothing when all is present.
#
#   scripts/install-deps.sh [--fuzz]
#
# --fuzz adds what the parser fuzzer needs (scripts/fuzz.sh): clang 14 and its runtime libraries
# (libFuzzer, the sanitizers) and llvm-symbolizer for the reports' stack traces. The README's
# two commands do not ask for them.
set -euo pipefail

packages=(
  g++ cmake make ninja-build ccache pkg-config
  libginac-dev libcln-dev ginac-tools
  libeigen3-dev libfmt-dev libgtest-dev libgmock-dev
  libcli11-dev nlohmann-json3-dev
  libtinyxml2-dev  # the XML parser of `eomgen import` (URDF)
  libmujoco-dev    # MuJoCo, the oracle of the robots' dynamics in the tests (tests/robots/)
  texlive-latex-base
  gnuplot-nox
  python3       # writes the models of the scaling benchmark (bench/scaling.sh), which the docs test runs
  # the Python modules of models (`eomgen python`, docs/python.md): pybind11 and Python's headers;
  # NumPy for their arrays; pytest, SciPy and Matplotlib for their tests and example; SymPy for
  # their benchmark (bench/python/)
  python3-dev python3-pybind11 python3-numpy python3-pytest python3-scipy python3-matplotlib python3-sympy
  libjs-three   # three.js (r111), embedded into eomgen for `simulate --animate` pages
  chromium      # the browser test of those pages (tests/browser/, headless)
)
for arg in "$@"; do
  case "$arg" in
    --fuzz) packages+=(clang-14 libclang-rt-14-dev llvm-14) ;;
    *) echo "usage: scripts/install-deps.sh [--fuzz]" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "installing: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
