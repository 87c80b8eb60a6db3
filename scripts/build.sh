#!/usr/bin/env bash
# Installs missing packages, then configures and builds quadra (Release,
# warnings are errors) in build/. Arguments: targets to build (default: all of
# them), and -D... settings for CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
targets=() settings=()
for arg in "$@"; do
  case "$arg" in
    -D*) settings+=("$arg") ;;
    *) targets+=(--target "$arg") ;;
  esac
done
# Ninja shows one progress line and keeps both cores busy to the end; a
# build/ made earlier with another generator keeps it.
generator=()
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
echo "quadra: configuring build/"
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DQUADRA_WERROR=ON \
  "${settings[@]}" >/dev/null
echo "quadra: building ${*:-everything} with $(nproc) jobs"
cmake --build build -j "$(nproc)" "${targets[@]}"
