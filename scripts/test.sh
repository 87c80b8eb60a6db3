#!/usr/bin/env bash
# Set-up command 2: install what is missing, build (warnings are errors), and
# run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)" --timeout 600
