#!/usr/bin/env bash
# Two glint binaries, the same renders, interleaved: the median render time
# (glint render's own, without loading or writing) of each case and backend
# over RUNS runs, and old/new. For a closing note's "before and after in one
# run". Usage:
#   scripts/bench-compare.sh OLD_GLINT NEW_GLINT [CASE ...]
# CASE is SCENE@DEPTH[@SPP] (a built-in name or a scene file; SPP default 1).
# Environment: RUNS (3), THREADS (1), BACKENDS (auto,avx512,stream-avx512,
# avx2,stream-avx2,sse,stream-sse,scalar-float), WIDTH/HEIGHT (the scene's).
set -euo pipefail
old=$1 new=$2
shift 2
runs=${RUNS:-3}
threads=${THREADS:-1}
IFS=, read -r -a backends <<<"${BACKENDS:-auto,avx512,stream-avx512,avx2,stream-avx2,sse,stream-sse,scalar-float}"
size=()
[[ -n ${WIDTH:-} ]] && size+=(-W "$WIDTH")
[[ -n ${HEIGHT:-} ]] && size+=(-H "$HEIGHT")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# seconds and backend of one render, as "S BACKEND"
one() {
  local bin=$1 scene=$2 depth=$3 spp=$4 backend=$5
  "$bin" render "$scene" -b "$backend" -d "$depth" -s "$spp" -t "$threads" \
    "${size[@]}" --stats -o "$out/image.ppm" 2>&1 |
    awk '$1 == "render" {s = $2} $1 == "backend" {b = $2; sub(",", "", b)}
         END {print s, b}'
}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

printf '%-22s %-14s %10s %10s %8s  %s\n' case backend "old ms" "new ms" old/new \
  "(auto ran)"
for c in "$@"; do
  IFS=@ read -r scene depth spp <<<"$c"
  spp=${spp:-1}
  for b in "${backends[@]}"; do
    : >"$out/old" ; : >"$out/new"
    ran=
    for ((r = 0; r < runs; r++)); do
      one "$old" "$scene" "$depth" "$spp" "$b" | cut -d' ' -f1 >>"$out/old"
      line=$(one "$new" "$scene" "$depth" "$spp" "$b")
      echo "${line%% *}" >>"$out/new"
      ran=${line#* }
    done
    o=$(median <"$out/old") n=$(median <"$out/new")
    extra=
    [[ $b == auto ]] && extra="($ran)"
    printf '%-22s %-14s %10.1f %10.1f %8.2f  %s\n' "$(basename "$scene")@$depth" "$b" \
      "$(echo "$o*1000" | bc -l)" "$(echo "$n*1000" | bc -l)" \
      "$(echo "$o/$n" | bc -l)" "$extra"
  done
done
