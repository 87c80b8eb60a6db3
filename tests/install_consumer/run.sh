#!/usr/bin/env bash
# InstallAndFindPackage: install the build tree to a temporary prefix; check
# that it holds only what an embedder needs (no lab, no kernels, no tests) and
# that every installed header compiles on its own; then build the consumer
# against it with find_package(quadra) and run it. With --oiio-peer (the
# build made quadra_oiio_peer.so), also check that the installed quadra finds
# the installed module: its `report textures` has OpenImageIO's rows.
set -euo pipefail
build_dir=$1
oiio_peer=${2:-}
source_dir=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
include="$work/prefix/include/quadra"
mapfile -t headers < <(cd "$include" && find . -type f | sed 's#^\./##' | sort)
echo "installed headers (${#headers[@]}): ${headers[*]}"
for h in "${headers[@]}"; do
  case "$h" in
    lab/* | *_impl.h | *_lanes.h | */tile_* | */kernel_*)
      echo "not for embedders, but installed: $h"
      exit 1
      ;;
  esac
  echo "#include \"$h\"" | c++ -std=c++20 -fsyntax-only -I"$include" -x c++ - ||
    { echo "installed header does not compile on its own: $h"; exit 1; }
done
if find "$work/prefix" -name '*lab*' | grep .; then
  echo "the lab library was installed"
  exit 1
fi
cmake -S "$source_dir" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer" "$work/consumer.exr"
if [[ $oiio_peer == --oiio-peer ]]; then
  "$work/prefix/bin/quadra" report textures --size 8 --lookups 36 --threads 2 \
    --out-dir "$work/report" >"$work/report.txt"
  grep -q '^| oiio-trilinear |' "$work/report.txt" || {
    echo "the installed quadra did not measure OpenImageIO:"
    grep '^OpenImageIO' "$work/report.txt"
    exit 1
  }
fi
