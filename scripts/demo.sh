#!/usr/bin/env bash
# Set-up command 1: install what is missing, build the library and the CLI
# (nothing else: the tests, benchmarks and peers are scripts/test.sh's), render
# the built-in default scene to an EXR and a PNG, then one second of the
# built-in animated scene (24 frames, 960x540), and print where they are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh quadra
mkdir -p out
build/bin/quadra render builtin:showcase --frames 5 --out out/showcase.exr --out out/showcase.png
echo "images: $(pwd)/out/showcase.png $(pwd)/out/showcase.exr"
build/bin/quadra render builtin:flyover --width 960 --height 540 --sequence 0:23 \
  --out 'out/flyover_##.png' | grep -v '^quadra wrote '
echo "sequence: $(pwd)/out/flyover_00.png .. flyover_23.png"
