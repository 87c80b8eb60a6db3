#!/usr/bin/env bash
# Start-up cost of quadra (docs/performance.md "Start-up"): for each binary,
# the shared libraries it loads (ldd), the wall time of `quadra --version`
# (start-up and exit with no work: the floor of every command), and the wall
# time of drawing a tiny frame, process start to PNG written, split into
# what `--stats` accounts for (scene load, warm-up frame, timed frame, PNG
# write) and the rest (dynamic loading, static initializers, exit). Binaries
# take turns, so a busy machine slows each alike; figures are medians over
# the runs, in ms, each run's wall time including the shell's fork and exec.
#   scripts/startup.sh [--runs N] [--scene builtin:NAME] [BINARY...]
#                                  default: 21 runs, builtin:checker-plane, build/bin/quadra
set -euo pipefail
cd "$(dirname "$0")/.."
runs=21
scene=builtin:checker-plane
binaries=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    *) binaries+=("$1"); shift ;;
  esac
done
((${#binaries[@]})) || binaries=(build/bin/quadra)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One run: wall ms of --version, of the render, then the ms of the render
# that --stats accounts for.
run_once() {
  local start end stats version
  start=$EPOCHREALTIME
  "$1" --version >/dev/null
  end=$EPOCHREALTIME
  version=$(awk -v s="$start" -v e="$end" 'BEGIN { printf "%.3f", (e - s) * 1000 }')
  start=$EPOCHREALTIME
  stats=$("$1" render "$scene" --width 64 --height 64 --out "$work/x.png" --stats)
  end=$EPOCHREALTIME
  awk -v s="$start" -v e="$end" -v version="$version" '
    /^quadra frame_ms/ { for (i = 2; i <= NF; ++i) if ($i ~ /^median=/) frame = substr($i, 8) }
    /^quadra stages_ms/ {
      for (i = 2; i <= NF; ++i) {
        split($i, kv, "=")
        if (kv[1] == "load" || kv[1] == "first_frame" || kv[1] == "write") inside += kv[2]
      }
    }
    END { printf "%s %.3f %.3f\n", version, (e - s) * 1000, inside + frame }' <<<"$stats"
}

median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

for b in "${binaries[@]}"; do run_once "$b" >/dev/null; done  # page cache warm
for ((r = 0; r < runs; ++r)); do
  for i in "${!binaries[@]}"; do run_once "${binaries[$i]}" >>"$work/$i"; done
done
printf '%-40s %9s %10s %9s %9s %9s\n' binary libraries version_ms wall_ms stats_ms rest_ms
for i in "${!binaries[@]}"; do
  version=$(cut -d' ' -f1 "$work/$i" | median)
  wall=$(cut -d' ' -f2 "$work/$i" | median)
  stats=$(cut -d' ' -f3 "$work/$i" | median)
  rest=$(awk '{ print $2 - $3 }' "$work/$i" | median)
  printf '%-40s %9d %10s %9s %9s %9s\n' "${binaries[$i]}" "$(ldd "${binaries[$i]}" | wc -l)" \
    "$version" "$wall" "$stats" "$rest"
done
echo "quadra render $scene --width 64 --height 64 --out x.png --stats; $runs runs each, medians"
