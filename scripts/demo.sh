#!/usr/bin/env bash
# Set-up command 1: install what is missing, build, render the built-in
# default scene to an EXR and a PNG, and print where they are and the frame time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
build/bin/quadra render builtin:showcase --frames 5 --out out/showcase.exr --out out/showcase.png
echo "images: $(pwd)/out/showcase.exr $(pwd)/out/showcase.png"
