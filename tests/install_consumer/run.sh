#!/usr/bin/env bash
# InstallAndFindPackage: install the build tree to a temporary prefix; check
# that it holds only what an embedder needs (the public headers quadra/*, no
# engine headers, no lab, no tests), that every installed header compiles on
# its own and that quadra.pc works; then build the consumer against it with
# find_package(quadra), render its in-memory quad from C++ and from C, and
# check the pixels and depths equal bit for bit the installed CLI's EXR of the same quad as glTF;
# then build and run the README's examples (examples/) the same way: the C++
# and C triangles must print the same pixel. With --oiio-peer (the
# build made quadra_oiio_peer.so), also check that the installed quadra finds
# the installed module: its `report textures` has OpenImageIO's rows. With
# --python PYTHON DIR (the build made the module, installed into DIR under
# the prefix), run examples/triangle.py against the installed module, with
# --python-preload LIBS (a sanitizer build; colon-separated) preloading the sanitizer runtime
# into the uninstrumented interpreter (tests/CMakeLists.txt says why).
#   run.sh BUILD_DIR [--oiio-peer] [--python PYTHON DIR [--python-preload LIBS]]
set -euo pipefail
build_dir=$1
shift
oiio_peer=
python=
python_dir=
python_preload=
while (($#)); do
  case "$1" in
    '') ;; # an option CMake's generator expression left out
    --oiio-peer) oiio_peer=--oiio-peer ;;
    --python)
      python=$2
      python_dir=$3
      shift 2
      ;;
    --python-preload)
      python_preload=$2
      shift
      ;;
    *)
      echo "run.sh: unknown option $1" >&2
      exit 2
      ;;
  esac
  shift
done
source_dir=$(cd "$(dirname "$0")" && pwd)
# The consumer is built with the build's own compilers: a sanitizer build's
# libquadra.so needs the runtime of the compiler that instrumented it (the
# ASan build is clang's, scripts/sanitize.sh).
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
cc=$(sed -n 's/^CMAKE_C_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
compilers=(-DCMAKE_CXX_COMPILER="${cxx:=c++}" -DCMAKE_C_COMPILER="${cc:=cc}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
include="$work/prefix/include"
mapfile -t headers < <(cd "$include" && find . -type f | sed 's#^\./##' | sort)
echo "installed headers (${#headers[@]}): ${headers[*]}"
for h in "${headers[@]}"; do
  case "$h" in
    quadra/*.hpp | quadra/*.h) ;;
    *)
      echo "not a public header, but installed: $h"
      exit 1
      ;;
  esac
  echo "#include <$h>" | "$cxx" -std=c++20 -fsyntax-only -I"$include" -x c++ - ||
    { echo "installed header does not compile on its own: $h"; exit 1; }
done
if grep -rlE '#include "(api|scene|core|io|texture|window|simd)/' "$include"; then
  echo "an installed header includes the engine's internals"
  exit 1
fi
# A sanitizer build's libquadra.so needs its runtime linked into the program
# (first in the library list); the CMake package says so itself
# (quadra_sanitizer_link_interface), a plain pkg-config link gets it here.
sanitize=$(sed -n 's/^QUADRA_SANITIZE:STRING=//p' "$build_dir/CMakeCache.txt")
sanitize_flags=${sanitize:+-fsanitize=$sanitize}
# A TSan build links the oneTBB built with TSan (scripts/tsan-tbb.sh); the
# installed libquadra.so finds oneTBB by the loader's search, which would
# give it the system's, whose synchronization TSan cannot see (false races in
# oneTBB's inlined partitioner). The programs below get that build's first.
if [[ $sanitize == *thread* ]]; then
  tbb_dir=$(sed -n 's/^TBB_DIR:PATH=//p' "$build_dir/CMakeCache.txt")
  export LD_LIBRARY_PATH="${tbb_dir%/cmake/TBB}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
# pkg-config alone (no CMake): compile and link a version query.
printf '#include <quadra/quadra.hpp>\n#include <cstdio>\nint main() { std::puts(quadra::version()); }\n' >"$work/pc.cpp"
PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --exists quadra ||
  { echo "pkg-config does not find quadra.pc"; exit 1; }
# shellcheck disable=SC2046
"$cxx" -std=c++20 $sanitize_flags "$work/pc.cpp" -o "$work/pc" $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags --libs quadra)
[[ $(LD_LIBRARY_PATH="$work/prefix/lib" "$work/pc") == $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --modversion quadra) ]] ||
  { echo "the pkg-config build reports another version"; exit 1; }
if find "$work/prefix" -name '*lab*' | grep .; then
  echo "the lab library was installed"
  exit 1
fi
cmake -S "$source_dir" -B "$work/build" "${compilers[@]}" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
mkdir "$work/quad"
"$work/build/consumer" gltf "$work/quad"
"$work/prefix/bin/quadra" render "$work/quad/quad.gltf" --shading unlit --width 64 --height 48 --threads 2 \
  --out "$work/reference.exr" >/dev/null
"$work/build/consumer" render "$work/consumer.raw"
"$work/build/read_reference" "$work/reference.exr" "$work/consumer.raw"
"$work/build/consumer_c" "$work/consumer_c.raw"
"$work/build/read_reference" "$work/reference.exr" "$work/consumer_c.raw"
# The README's example (examples/), as a newcomer builds it.
cmake -S "$source_dir/../../examples" -B "$work/examples" "${compilers[@]}" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/examples" >/dev/null
cxx_line=$("$work/examples/triangle")
c_line=$("$work/examples/triangle_c")
echo "$cxx_line"
[[ $c_line == "$cxx_line" ]] || { echo "the C example printed another line: $c_line"; exit 1; }
if [[ -n $python ]]; then
  [[ -d $work/prefix/$python_dir ]] || { echo "the Python module was not installed into $python_dir"; exit 1; }
  # From the prefix only: the installed module finds the installed libquadra.so.
  (
    cd "$work"
    if [[ -n $python_preload ]]; then
      export LD_PRELOAD=$python_preload ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0
    fi
    PYTHONPATH="$work/prefix/$python_dir" "$python" "$source_dir/../../examples/triangle.py"
  )
fi
if [[ $oiio_peer == --oiio-peer ]]; then
  "$work/prefix/bin/quadra" report textures --size 8 --lookups 36 --threads 2 \
    --out-dir "$work/report" >"$work/report.txt"
  grep -q '^| oiio-trilinear |' "$work/report.txt" || {
    echo "the installed quadra did not measure OpenImageIO:"
    grep '^OpenImageIO' "$work/report.txt"
    exit 1
  }
fi
