#!/usr/bin/env bash
# Two glint binaries, the same renders, interleaved: the median render time
# of each case and backend over RUNS runs, and old/new. For a closing note's
# "before and after in one run". Each run is one `glint bench` process (an
# untimed warm-up render, then the timed one): its time is the render's
# alone, with no image written. (`glint render --stats` times the render
# while its image writer encodes the tiles on a thread of its own: pinned
# to one CPU, that thread's work lands in the render time, and a binary
# older than the writer would be measured without it.) Usage:
#   scripts/bench-compare.sh OLD_GLINT NEW_GLINT [CASE ...]
# CASE is SCENE@DEPTH[@SPP] (a built-in name or a scene file; SPP default 1).
# Environment: RUNS (3), THREADS (1), BACKENDS (auto,avx512,stream-avx512,
# avx2,stream-avx2,sse,stream-sse,scalar-float), WIDTH/HEIGHT (the scene's),
# CPUS (a list such as "2 4 6 8": each case and backend runs pinned to one
# of these CPUs with taskset, as many at a time as there are CPUs; on a
# machine with nothing else running, give it cores that share nothing).
# The two binaries alternate old-new, new-old, ... so that a drift in the
# machine's speed during a case falls on both alike.
set -euo pipefail
old=$1 new=$2
shift 2
runs=${RUNS:-3}
threads=${THREADS:-1}
IFS=, read -r -a backends <<<"${BACKENDS:-auto,avx512,stream-avx512,avx2,stream-avx2,sse,stream-sse,scalar-float}"
read -r -a cpus <<<"${CPUS:-}"
size=()
[[ -n ${WIDTH:-} ]] && size+=(-W "$WIDTH")
[[ -n ${HEIGHT:-} ]] && size+=(-H "$HEIGHT")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# seconds and backend of one render on CPU $6 (none: anywhere), as "S BACKEND"
one() {
  local bin=$1 scene=$2 depth=$3 spp=$4 backend=$5 cpu=$6 dir=$7
  local pin=()
  [[ -n $cpu ]] && pin=(taskset -c "$cpu")
  rm -f "$dir/run.csv" # a run that fails prints nothing, not the last one's
  "${pin[@]}" "$bin" bench --scenes "$scene" --depths "$depth" \
    --backends "$backend" -s "$spp" -t "$threads" "${size[@]}" --runs 1 \
    --csv "$dir/run.csv" >/dev/null 2>&1
  # scene,depth,backend,width,height,spp,threads,runs,median_s,...
  awk -F, 'NR == 2 {print $9, $3}' "$dir/run.csv"
}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

# One case and backend, RUNS times each binary; writes the table's row.
measure() {
  local c=$1 b=$2 cpu=$3 row=$4 scene depth spp line ran= extra=
  IFS=@ read -r scene depth spp <<<"$c"
  spp=${spp:-1}
  local dir=$out/$row.d
  mkdir -p "$dir"
  : >"$dir/old"
  : >"$dir/new"
  for ((r = 0; r < runs; r++)); do
    if ((r % 2)); then
      line=$(one "$new" "$scene" "$depth" "$spp" "$b" "$cpu" "$dir")
      echo "${line%% *}" >>"$dir/new"
      one "$old" "$scene" "$depth" "$spp" "$b" "$cpu" "$dir" | cut -d' ' -f1 >>"$dir/old"
    else
      one "$old" "$scene" "$depth" "$spp" "$b" "$cpu" "$dir" | cut -d' ' -f1 >>"$dir/old"
      line=$(one "$new" "$scene" "$depth" "$spp" "$b" "$cpu" "$dir")
      echo "${line%% *}" >>"$dir/new"
    fi
    ran=${line#* }
  done
  local o n
  o=$(median <"$dir/old") n=$(median <"$dir/new")
  [[ $b == auto ]] && extra="($ran)"
  awk -v c="$(basename "$scene")@$depth" -v b="$b" -v o="$o" -v n="$n" -v x="$extra" \
    'BEGIN {printf "%-22s %-14s %10.1f %10.1f %8.2f  %s\n", c, b, o * 1000,
            n * 1000, (n > 0 ? o / n : 0), x}' >"$out/$row"
}

printf '%-22s %-14s %10s %10s %8s  %s\n' case backend "old ms" "new ms" old/new \
  "(auto ran)"
rows=0
declare -A busy=() # pid -> CPU
for c in "$@"; do
  for b in "${backends[@]}"; do
    if ((${#cpus[@]} == 0)); then
      measure "$c" "$b" "" "$rows"
    else
      cpu=
      for k in "${cpus[@]}"; do # a free CPU, or wait for one
        [[ " ${busy[*]} " == *" $k "* ]] || { cpu=$k; break; }
      done
      if [[ -z $cpu ]]; then
        wait -n -p done_pid || true
        cpu=${busy[$done_pid]}
        unset "busy[$done_pid]"
      fi
      measure "$c" "$b" "$cpu" "$rows" &
      busy[$!]=$cpu
    fi
    rows=$((rows + 1))
  done
done
wait
for ((r = 0; r < rows; r++)); do
  cat "$out/$r"
done
