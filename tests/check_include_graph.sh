#!/usr/bin/env bash
# IncludesPointDownThePipeline: every quoted include in the engine points to
# its own folder or to one earlier in the pipeline order below (the order of
# docs/architecture.md), so no stage reaches into a later one; the engine never
# includes the lab, tools, tests or benchmarks; the lab never includes tools,
# tests or benchmarks. A folder under engine/ missing from the order fails too,
# so a new stage must be placed before it compiles into the product.
#   check_include_graph.sh ROOT        check the tree at ROOT
#   check_include_graph.sh --self-test check that a planted back edge is caught
set -euo pipefail

order=(core simd window texture io scene shading vertex clip setup bin tile api)

rank_of() {
  local i
  for i in "${!order[@]}"; do
    [[ ${order[$i]} == "$1" ]] && { echo "$i"; return; }
  done
  echo -1
}

check() {
  local root=$1 failures=0 file folder target from to line
  cd "$root"
  for folder in engine/*/; do
    folder=$(basename "$folder")
    if [[ $(rank_of "$folder") -lt 0 ]]; then
      echo "engine/$folder: not in the pipeline order (${order[*]})"
      failures=$((failures + 1))
    fi
  done
  while IFS= read -r line; do
    file=${line%%:*}
    target=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"${line#*:}")
    case "$file" in
      engine/* | simd/*)
        folder=${file#engine/}
        folder=${folder%%/*}
        [[ $file == simd/* ]] && folder=simd
        to=${target%%/*}
        [[ $target == */* ]] || continue  # a file beside it (generated kernels)
        # The public headers (include/quadra) include nothing of the engine,
        # so any folder may include them (the facade in api/ does).
        [[ $to == quadra ]] && continue
        if [[ $to == lab || $to == tools || $to == tests || $to == bench ]]; then
          echo "$file includes $target: the engine must not depend on $to/"
          failures=$((failures + 1))
          continue
        fi
        from=$(rank_of "$folder")
        if [[ $(rank_of "$to") -lt 0 ]]; then
          echo "$file includes $target: $to/ is not a pipeline folder"
          failures=$((failures + 1))
        elif [[ $(rank_of "$to") -gt $from ]]; then
          echo "$file includes $target: $to/ comes after $folder/ in the pipeline (${order[*]})"
          failures=$((failures + 1))
        fi
        ;;
      lab/*)
        to=${target%%/*}
        if [[ $to == tools || $to == tests || $to == bench ]]; then
          echo "$file includes $target: the lab must not depend on $to/"
          failures=$((failures + 1))
        fi
        ;;
    esac
  done < <(grep -rHE '^#include "' engine simd lab 2>/dev/null || true)
  if ((failures)); then
    echo "$failures include(s) against the pipeline order"
    return 1
  fi
  echo "every include points down the pipeline (${order[*]})"
}

if [[ ${1:-} == --self-test ]]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/engine/setup" "$work/engine/tile" "$work/lab/texture"
  echo '#include "setup/triangle_record.h"' >"$work/engine/tile/tile_stage.h"
  if ! (check "$work" >/dev/null); then
    echo "self-test: a forward include was flagged"
    exit 1
  fi
  echo '#include "tile/tile_buffers.h"' >"$work/engine/setup/triangle_setup.h"
  if (check "$work" >/dev/null); then
    echo "self-test: a back edge (setup -> tile) was not caught"
    exit 1
  fi
  rm "$work/engine/setup/triangle_setup.h"
  echo '#include "lab/texture/ground_truth.h"' >"$work/engine/setup/triangle_setup.h"
  if (check "$work" >/dev/null); then
    echo "self-test: an engine include of the lab was not caught"
    exit 1
  fi
  rm "$work/engine/setup/triangle_setup.h"
  mkdir -p "$work/engine/extra"
  if (check "$work" >/dev/null); then
    echo "self-test: an unplaced engine folder was not caught"
    exit 1
  fi
  echo "self-test: back edges, engine-to-lab includes and unplaced folders are caught"
  exit 0
fi
check "$1"
