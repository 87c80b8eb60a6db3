#!/usr/bin/env bash
# Renders the pictures the documentation shows (docs/images/) with the CLI
# that scripts/demo.sh builds, so that each picture is what quadra makes of
# its scene today. Run it after a change to what a frame looks like.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/bin/quadra ] || bash scripts/build.sh quadra
mkdir -p docs/images
build/bin/quadra render builtin:showcase --width 960 --height 540 --samples 4 \
  --out docs/images/showcase.png
