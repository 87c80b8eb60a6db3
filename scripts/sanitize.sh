#!/usr/bin/env bash
# The sanitizer runs of the whole test suite (issue 4), one command each:
#   bash scripts/sanitize.sh asan   AddressSanitizer + LeakSanitizer + UBSan, in build-asan/
#   bash scripts/sanitize.sh tsan   ThreadSanitizer, in build-tsan/
# Installs what is missing, builds the engine, the CLI and the tests (no
# benchmarks) at -O1 -g with QUADRA_SANITIZE (cmake/QuadraSanitizers.cmake),
# and runs ctest. Fails on any failed test and on any sanitizer report, also
# one from a CLI subprocess whose exit status a test only expects non-zero.
# Extra arguments go to ctest (e.g. -R Cli).
#   bash scripts/sanitize.sh asan --build-only [TARGET...]
# only configures and builds (the given CMake targets, else all): how
# scripts/fuzz.sh gets its fuzzers from the same build.
set -euo pipefail
mode=${1:-}
case "$mode" in
  asan) sanitize=address,undefined ;;
  tsan) sanitize=thread ;;
  *)
    echo "usage: scripts/sanitize.sh asan|tsan [--build-only [TARGET...] | ctest arguments]" >&2
    exit 2
    ;;
esac
shift
build_only=false
if [ "${1:-}" = --build-only ]; then
  build_only=true
  shift
fi
cd "$(dirname "$0")/.."
root=$(pwd)
bash scripts/install-deps.sh

build=build-$mode
if [ "$mode" = tsan ]; then
  # TSan needs an instrumented oneTBB to see its synchronization (see the
  # script); CMAKE_PREFIX_PATH makes find_package(TBB) take it, here and in
  # the InstallAndFindPackage consumer.
  bash scripts/tsan-tbb.sh "$build/tbb"
  export CMAKE_PREFIX_PATH="$root/$build/tbb/prefix${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
fi
# -O1: instrumented -O3 builds slowly and gains nothing for finding bugs.
# No -Werror here: instrumentation changes what flow-based warnings see
# (GCC's spurious -Wmaybe-uninitialized and friends); the Release build
# (scripts/build.sh) is the one that holds the code to zero warnings.
if [ "$mode" = asan ]; then
  # clang, with the libFuzzer targets (QUADRA_FUZZ): one build serves the
  # ASan+UBSan suite and scripts/fuzz.sh, and clang instruments the big
  # always-inlined kernels in half GCC's time (tile_kernel_avx2.cpp: 259 s
  # of CPU against 542 s, 2026-11-28), so every ISA copy is instrumented.
  compiler=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DQUADRA_FUZZ=ON)
  flags="-O1 -g"
  # A build-asan/ configured with GCC (before 2026-11-28) cannot switch
  # compilers in place.
  if [ -f "$build/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++$' "$build/CMakeCache.txt"; then
    rm -rf "$build"
  fi
else
  # -fno-var-tracking-assignments: GCC's variable tracking over the big
  # always-inlined kernels is most of an instrumented build (ASan,
  # tile_kernel_scalar.cpp: 130 s with it, 30 s without); reports keep full
  # file:line stacks.
  compiler=()
  flags="-O1 -g -fno-var-tracking-assignments"
fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${compiler[@]}" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" \
  -DQUADRA_SANITIZE="$sanitize" -DQUADRA_BUILD_BENCH=OFF -DQUADRA_WERROR=OFF >/dev/null
if $build_only; then
  cmake --build "$build" -j "$(nproc)" ${1:+--target "$@"}
  exit 0
fi
cmake --build "$build" -j "$(nproc)"

# ASan/LSan/TSan reports go to files, and any file fails the run: a test that
# runs the CLI and expects an error exit would otherwise pass on the exit a
# leak report causes (checked by injecting one). UBSan reports still go to
# stderr (GCC 12's ASan+UBSan runtime ignores log_path for them), where they
# fail the test in-process and the CLI tests' one-line stderr checks see them.
logs=$root/$build/sanitizer-logs
rm -rf "$logs"
mkdir -p "$logs"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$logs/ubsan"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
ASAN_OPTIONS+=":check_initialization_order=1:log_path=$logs/asan"
# lsan.supp names only memory oneTBB allocates and frees itself (see the file).
# A matched suppression is not a finding, but the runtime prints its tally to
# the log file at exit, which would fail the run (a CI run did: a file holding
# only "Suppressions used: tbb::detail::r1::observe"); print_suppressions=0
# keeps the tally out, so a file still means a report.
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
# tsan.supp names only a race that lies wholly inside libtbb (see the file).
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:log_path=$logs/tsan"
TSAN_OPTIONS+=":suppressions=$root/scripts/tsan.supp:print_suppressions=0"

status=0
(cd "$build" && ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@") || status=$?

reports=$(find "$logs" -type f | sort)
if [ -n "$reports" ]; then
  for report in $reports; do
    echo "==== $report"
    cat "$report"
  done
  echo "sanitize.sh $mode: sanitizer reports above" >&2
  status=1
fi
[ "$status" -eq 0 ] && echo "sanitize.sh $mode: clean"
exit "$status"
