#!/usr/bin/env bash
# The libFuzzer targets (issue 16; tests/fuzz), one command each:
#   bash scripts/fuzz.sh --list             the target names, one a line
#   bash scripts/fuzz.sh TARGET SECONDS     run one for SECONDS; non-zero on a finding
# Installs what is missing, builds the target in the ASan+UBSan build
# (build-asan/: clang, every object instrumented for libFuzzer's coverage;
# scripts/sanitize.sh), and runs it on a working corpus in
# build-asan/corpus/TARGET seeded from tests/fuzz/corpus/TARGET (the
# repository's seeds are never written). A finding (crash, sanitizer report,
# leak, an input slower than 10 s, over 2 GB of memory) is saved as
# build-asan/findings/TARGET/crash-* (or leak-, timeout-, oom-); keep it as a
# regression test (docs/testing.md, "Fuzzing").
# Extra arguments go to libFuzzer (e.g. -jobs=2, -runs=N).
set -euo pipefail
targets=(gltf_json glb image environment lookups_csv render)
cd "$(dirname "$0")/.."
root=$(pwd)

if [ "${1:-}" = --list ]; then
  printf '%s\n' "${targets[@]}"
  exit 0
fi
target=${1:-}
seconds=${2:-}
if [ -z "$target" ] || ! [[ "$seconds" =~ ^[0-9]+$ ]] ||
  ! printf '%s\n' "${targets[@]}" | grep -qx -- "$target"; then
  echo "usage: scripts/fuzz.sh --list | TARGET SECONDS [libFuzzer options]" >&2
  echo "targets: ${targets[*]}" >&2
  exit 2
fi
shift 2

bash scripts/sanitize.sh asan --build-only "fuzz_$target"
build=build-asan

corpus=$root/$build/corpus/$target
findings=$root/$build/findings/$target
mkdir -p "$corpus" "$findings"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The new inputs go to the first folder (the working corpus); the seeds are
# only read. -timeout: one input slower than 10 s is a finding (a hang);
# -rss_limit_mb: so is more than 2 GB (an allocation the input's sizes drove).
echo "fuzz.sh: $target for $seconds s (findings: $findings)"
exec "$root/$build/bin/fuzz_$target" "$corpus" "$root/tests/fuzz/corpus/$target" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$findings/" "$@"
