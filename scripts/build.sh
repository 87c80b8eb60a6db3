#!/usr/bin/env bash
# Installs missing packages, then configures and builds quadra (Release) in
# build/. Extra arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DQUADRA_WERROR=ON "$@" >/dev/null
cmake --build build -j "$(nproc)"
