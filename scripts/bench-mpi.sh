#!/usr/bin/env bash
# glint-mpi's scaling table (docs/mpi.md): tiles of one 4K Billiard frame
# (3840x2160, depth 15, 5 spp) and the 48 frames of an animation (1280x720), at 1, 2
# and 4 ranks on both schedules, and 2 ranks with rank 1 slowed 3x.
#   scripts/bench-mpi.sh [BUILD_DIR]     (default: build)
# Efficiency is T1 / (N x TN) over the rendering time (startup, the MPI
# launch with the scene's broadcast and BVH, is shown apart). More ranks
# than this machine has CPUs are flagged "oversubscribed". With a slowed
# rank, the ideal time for the capacity left is T1 / (1 + 1/3).
# Each figure is the median of RUNS runs (default 3). Run it with nothing
# else on the machine. Environment, for larger machines:
#   RANKS="1 2 4 8 16"   the rank counts (default "1 2 4")
#   THREADS=N            threads per rank (default: glint-mpi's own, the
#                        CPUs a rank may use shared among its host's ranks)
#   SCHEDULES=dynamic    the schedules (default "dynamic static")
#   SLOWED=0             skip the run with a slowed rank
set -euo pipefail
build=${1:-build}
RUNS=${RUNS:-3}
RANKS=${RANKS:-1 2 4}
SCHEDULES=${SCHEDULES:-dynamic static}
SLOWED=${SLOWED:-1}
threads=()
[ -n "${THREADS:-}" ] && threads=(-t "$THREADS")
here=$(cd "$(dirname "$0")/.." && pwd)
glint_mpi=$build/glint-mpi
[ -x "$glint_mpi" ] || { echo "bench-mpi: $glint_mpi is missing (build with Open MPI)" >&2; exit 2; }
cpus=$(nproc)
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Runs glint-mpi on $1 ranks (the rest: its arguments) $RUNS times; prints
# the median "STARTUP RENDER" in seconds from its summaries.
measure() {
  local n=$1
  shift
  for _ in $(seq "$RUNS"); do
    "${mpi[@]}" -np "$n" "$glint_mpi" "${threads[@]}" "$@" >"$out/log" 2>&1 ||
      { cat "$out/log" >&2; exit 1; }
    sed -n 's/.*startup \([0-9.]*\) s, rendering\( and writing\)\? \([0-9.]*\) s.*/\1 \3/p' "$out/log" | head -1
    rm -rf "$out/frames"
  done | sort -k2 -n | awk '{ a[NR] = $0 } END { print a[int((NR + 1) / 2)] }'
}

flag() { [ "$1" -gt "$cpus" ] && echo " (oversubscribed)" || true; }

table() { # $1: title; the rest: glint-mpi's arguments
  local title=$1
  shift
  echo "$title"
  echo "| ranks | schedule | startup s | render s | efficiency |"
  echo "|------:|----------|----------:|---------:|-----------:|"
  local t1=
  for schedule in $SCHEDULES; do
    for n in $RANKS; do
      [ "$schedule" = static ] && [ "$n" -eq 1 ] && [ -n "$t1" ] && continue
      read -r startup render < <(measure "$n" "$@" --schedule $schedule)
      [ -z "$t1" ] && t1=$render
      eff=$(awk -v a="$t1" -v b="$render" -v n="$n" 'BEGIN { printf "%.0f%%", 100 * a / (n * b) }')
      echo "| $n$(flag "$n") | $schedule | $startup | $render | $eff |"
    done
  done
  echo
  T1=$t1
}

echo "glint-mpi scaling (medians of $RUNS runs), $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?'), $cpus CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), $(date -u +%F)${THREADS:+, $THREADS thread(s) per rank}"
echo
table "Tiles: billiard 3840x2160, depth 15, 5 spp, 64-pixel tiles" \
  billiard -W 3840 -H 2160 -d 15 -s 5 -o "$out/tiles.png"
if [ "$SLOWED" != 0 ]; then
echo "Rank 1 slowed 3x (GLINT_MPI_TEST_SLOW=1:3), 2 ranks; ideal = T1 / (1 + 1/3)"
echo "| schedule | render s | ideal s | time / ideal |"
echo "|----------|---------:|--------:|-------------:|"
ideal=$(awk -v t="$T1" 'BEGIN { printf "%.3f", t * 0.75 }')
for schedule in dynamic static; do
  read -r _ render < <(GLINT_MPI_TEST_SLOW=1:3 measure 2 billiard -W 3840 -H 2160 \
    -d 15 -s 5 -o "$out/slow.png" --schedule $schedule)
  echo "| $schedule | $render | $ideal | $(awk -v a="$render" -v b="$ideal" 'BEGIN { printf "%.2f", a / b }') |"
done
echo
fi
table "Frames: scenes/billiard-flight.json, frames 1-48, 1280x720, depth 5, 5 spp" \
  "$here/scenes/billiard-flight.json" --frames 1-48 -W 1280 -H 720 -o "$out/frames/f%02d.png"
