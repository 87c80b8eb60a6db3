#!/usr/bin/env bash
# CTest CApiLitEqualsTheCli: the C API's pbr frame lit by an environment
# given as a float array equals, bit for bit (colour and depth), the CLI's
# `quadra render --shading pbr --env FILE.exr` of an EXR holding the same
# texels. The texels are builtin:sky's as `quadra env` writes them, read back
# as floats by read_reference, which also judges the frames.
#   lit_equals_cli.sh QUADRA READ_REFERENCE TEST_C_API FILE.glb
set -euo pipefail
quadra=$1 read_reference=$2 test_c_api=$3 glb=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
line=$("$quadra" env builtin:sky --out "$work/env.exr")
width=$(sed -n 's/.* width=\([0-9]*\).*/\1/p' <<<"$line")
height=$(sed -n 's/.* height=\([0-9]*\).*/\1/p' <<<"$line")
[ -n "$width" ] && [ -n "$height" ] || { echo "no size in: $line" >&2; exit 1; }
"$read_reference" --channels "$work/env.exr" "$work/env.raw" R G B
"$quadra" render "$glb" --shading pbr --env "$work/env.exr" --width 64 --height 48 --threads 2 \
  --out "$work/cli.exr" >/dev/null
"$test_c_api" --lit "$glb" "$work/env.raw" "$width" "$height" "$work/c.raw"
"$read_reference" "$work/cli.exr" "$work/c.raw"
