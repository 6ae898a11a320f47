#!/usr/bin/env bash
# glint-mpi under Open MPI's mpirun, ranks oversubscribed on this machine.
# It checks that
#  - the image is byte for byte glint render's for 1 to 4 ranks, tiles of
#    several sizes, both schedules, a region and a .pfm film, and a JSON
#    scene with a mesh (which rank 0 alone reads, and broadcasts);
#  - --frames writes the frames glint render --frames writes, on both
#    schedules;
#  - the default tile side follows the ranks' threads and the image size;
#  - ranks that may use fewer of their host's CPUs than it has, or run more
#    threads than they may use, get a note (none with -q);
#  - a rank slowed 4x (GLINT_MPI_TEST_SLOW) changes nothing in the image
#    and, scheduled dynamically, renders fewer tiles than rank 0;
#  - rank 0 slowed 40x keeps its worker fed (it renders on a thread of its
#    own while its main thread serves);
#  - ranks that would render differently refuse to start, naming them;
#  - a bad argument or a missing scene is one message and exit status 2;
#  - ranks that start but cannot reach each other end the job after
#    --timeout, with no image;
#  - a worker killed mid-animation ends the job within 30 s, naming rank 1
#    and its host, with no partial file; --resume then completes the
#    animation, every frame as glint render writes it;
#  - a worker that hangs (SIGSTOP) ends the job after --timeout, naming it:
#    scheduled statically, with the frames it held missing (no partial
#    file); dynamically, after rank 0 has rendered those too (every frame
#    written).
# SKIPPED (exit 77) without mpirun.
#   tests/mpi.sh GLINT GLINT_MPI SCENES_DIR
set -u
glint=$1
glint_mpi=$2
scenes=$3
if ! command -v mpirun >/dev/null 2>&1; then
  echo "mpi: SKIPPED (mpirun is missing; scripts/install-deps.sh installs openmpi-bin)"
  exit 77
fi
work=$(mktemp -d)
job=
stopped= # a rank this test stopped, should mpirun have left it
cleanup() {
  [ -n "$job" ] && kill -9 "$job" 2>/dev/null
  [ -n "$stopped" ] && kill -9 "$stopped" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "mpi: FAILED: $*"
  for f in "$work"/*.out "$work"/*.err; do
    [ -s "$f" ] && { echo "--- $f"; tail -20 "$f"; }
  done
  exit 1
}
cd "$work"
# Open MPI refuses root without these; CI runs as root. LeakSanitizer (make
# test-asan) reports what Open MPI's own libraries keep, so leaks are not
# checked here; glint's code is checked for them by the other tests.
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
export OMPI_MCA_btl_vader_single_copy_mechanism=none # no ptrace in containers
run() { # $1: ranks; the rest: glint-mpi's arguments
  local n=$1
  shift
  timeout 120 "${mpi[@]}" -np "$n" "$glint_mpi" "$@"
}

# The same image: ranks x tile sizes x schedules.
"$glint" render whitted -W 161 -H 119 -s 2 -o ref.png -q || fail "glint render"
for n in 1 2 3 4; do
  for tile in 16 48; do
    for schedule in dynamic static; do
      run $n whitted -W 161 -H 119 -s 2 --tile $tile --schedule $schedule \
        -o "t$n-$tile-$schedule.png" >run.out 2>run.err ||
        fail "$n ranks, $tile-pixel tiles, $schedule: exit status $?"
      cmp -s ref.png "t$n-$tile-$schedule.png" ||
        fail "$n ranks, $tile-pixel tiles, $schedule: not glint render's image"
    done
  done
done
grep -q "^t4-48-static.png: 161x119, .*, 4 ranks, static schedule, 12 tiles of 48 pixels" run.out ||
  fail "the summary: $(head -1 run.out)"

# A region, into a linear film.
"$glint" render billiard -W 200 -H 150 -s 1 --region 20,30,101,77 -o ref.pfm -q
run 3 billiard -W 200 -H 150 -s 1 --region 20,30,101,77 --tile 32 -o r.pfm -q \
  >run.out 2>run.err || fail "region: exit status $?"
cmp -s ref.pfm r.pfm || fail "region: not glint render's film"

# A scene with a mesh, packed by rank 0 and loaded by every rank.
printf 'v -1 0 0\nv 1 0 0\nv 0 1.5 0\nv 0 0.5 1\nf 1 2 3\nf 1 2 4\nf 2 3 4\n' >tetra.obj
cat >mesh.json <<'EOF'
{
  "camera": {"from": [0, 1, 4], "at": [0, 0.5, 0], "up": [0, 1, 0], "fov": 50},
  "image": {"width": 96, "height": 72},
  "lights": [{"position": [3, 5, 4], "color": [1, 1, 1]}],
  "materials": {"m": {"color": [0.8, 0.6, 0.3], "kd": 0.7, "ks": 0.4, "h": 30}},
  "objects": [{"type": "mesh", "file": "tetra.obj", "material": "m"}]
}
EOF
"$glint" render mesh.json -o mesh-ref.png -q || fail "glint render mesh.json"
run 2 mesh.json --tile 16 -o mesh.png -q >run.out 2>run.err || fail "mesh: exit status $?"
cmp -s mesh-ref.png mesh.png || fail "mesh: not glint render's image"

# Frames: both schedules, against glint render --frames.
anim="$scenes/billiard-flight.json"
"$glint" render "$anim" --frames 1-7 -W 96 -H 72 -s 1 -o ref/f%02d.png -q ||
  fail "glint render --frames"
for schedule in dynamic static; do
  run 3 "$anim" --frames 1-7 -W 96 -H 72 -s 1 --schedule $schedule \
    -o "$schedule/f%02d.png" >run.out 2>run.err || fail "frames, $schedule: exit status $?"
  for f in 1 2 3 4 5 6 7; do
    cmp -s "ref/f0$f.png" "$schedule/f0$f.png" ||
      fail "frames, $schedule: frame $f is not glint render's"
  done
done
grep -q "^7 frames written by 3 ranks, static schedule" run.out ||
  fail "the frames' summary: $(grep written run.out)"

# The tile side chosen from the ranks' threads: 64 pixels for one thread,
# more for more, so that each rank's threads have 16 of glint's own tiles
# each in a tile, and smaller again while the image has fewer than 8 tiles
# a rank. The image is glint render's whatever the side.
"$glint" render whitted -W 640 -H 480 -s 1 -o side-ref.png -q || fail "glint render"
for case in "1 16 9 224" "2 4 20 128" "2 1 80 64"; do
  read -r n threads tiles side <<<"$case"
  run "$n" whitted -W 640 -H 480 -s 1 -t "$threads" -o side.png >run.out 2>run.err ||
    fail "$n ranks of $threads threads: exit status $?"
  cmp -s side-ref.png side.png || fail "$n ranks of $threads threads: not glint render's image"
  grep -q "^side.png: 640x480, .*, $tiles tiles of $side pixels" run.out ||
    fail "$n ranks of $threads threads: not $tiles tiles of $side pixels: $(head -1 run.out)"
done

# A note when ranks may use fewer of their host's CPUs than it has (mpirun
# binds 2 ranks or fewer to a core each), or run more threads than they
# may use; none with --bind-to none, and none with -q.
bound=$("${mpi[@]}" -np 1 nproc) all=$(nproc)
run 1 whitted -W 64 -H 48 -o note.png >run.out 2>run.err || fail "note: exit status $?"
if [ "$bound" -lt "$all" ]; then
  grep -q "^glint-mpi: note: the 1 rank on .* may use $bound of its $all CPUs (mpirun binds" run.err ||
    fail "no note of the $bound CPUs of $all the rank may use: $(cat run.err)"
fi
timeout 120 "${mpi[@]}" -np 1 --bind-to none "$glint_mpi" whitted -W 64 -H 48 -o note.png \
  >run.out 2>run.err || fail "note, --bind-to none: exit status $?"
! grep -q "note:" run.err || fail "a note with --bind-to none: $(cat run.err)"
run 1 whitted -W 64 -H 48 -t $((bound + 1)) -o note.png >run.out 2>run.err || fail "note: exit status $?"
grep -q "^glint-mpi: note: rank 0 (.*) runs $((bound + 1)) threads on the $bound CPUs\{0,1\} it may use; they will take turns" run.err ||
  fail "no note of $((bound + 1)) threads on $bound CPUs: $(cat run.err)"
run 1 whitted -W 64 -H 48 -t $((bound + 1)) -q -o note.png >run.out 2>run.err || fail "note, -q: exit status $?"
! grep -q "note:" run.err || fail "a note with -q: $(cat run.err)"

# A slowed rank: the same image, and fewer tiles for it when dynamic.
"$glint" render billiard -W 320 -H 240 -d 15 -o slow-ref.png -q
GLINT_MPI_TEST_SLOW=1:4 run 2 billiard -W 320 -H 240 -d 15 --tile 32 \
  -o slow.png >slow.out 2>run.err || fail "slowed: exit status $?"
cmp -s slow-ref.png slow.png || fail "slowed: not glint render's image"
tiles() { sed -n "s/^  rank $1 .*: \([0-9]*\) tiles, .*/\1/p" slow.out; }
[ "$(tiles 1)" -lt "$(tiles 0)" ] ||
  fail "the slowed rank 1 rendered $(tiles 1) tiles, rank 0 $(tiles 0)"

# Rank 0 slowed 40x: its main thread serves the workers while its own unit
# renders on another thread, so the worker renders 11 of the 12 frames
# while rank 0 renders one. When rank 0 rendered between its turns as the
# master, the worker's two queued frames ran out while rank 0's one took
# the time of 40, and rank 0 rendered 7.
GLINT_MPI_TEST_SLOW=0:40 run 2 "$anim" --frames 1-12 -W 320 -H 240 -s 1 \
  -o busy/f%02d.png >busy.out 2>run.err || fail "rank 0 slowed: exit status $?"
frames0=$(sed -n 's/^  rank 0 .*: \([0-9]*\) frames\{0,1\}, .*/\1/p' busy.out)
[ -n "$frames0" ] && [ "$frames0" -le 2 ] ||
  fail "rank 0, slowed 40x, rendered ${frames0:-?} of 12 frames: the worker waited for it"

# Ranks that would render differently: none starts.
"${mpi[@]}" -np 1 "$glint_mpi" whitted -o x.png : -np 1 "$glint_mpi" whitted \
  -o x.png -b scalar-double >run.out 2>run.err
status=$?
[ "$status" -ne 0 ] || fail "mismatched ranks: exit status 0"
grep -q "the ranks would render differently" run.err ||
  fail "mismatched ranks: no message"
grep -q "rank 1 (.*): glint .*, backend scalar-double" run.err ||
  fail "mismatched ranks: rank 1 not named"
[ ! -e x.png ] || fail "mismatched ranks: an image was written"
# Each rank its own arguments (MPMD): a different depth (a mixed image was
# written), a different --tile (the worker wrote past its tile: heap
# corruption), a worker refusing its own option (the job hung).
for extra in "-d 1" "--tile 32"; do
  # shellcheck disable=SC2086
  "${mpi[@]}" -np 1 "$glint_mpi" whitted -W 64 -H 48 -s 1 --tile 16 -o x.png : \
    -np 1 "$glint_mpi" whitted -W 64 -H 48 -s 1 --tile 16 $extra -o x.png \
    >run.out 2>run.err
  status=$?
  [ "$status" -eq 2 ] || fail "ranks given $extra apart: exit status $status"
  grep -q "the ranks would render differently" run.err ||
    fail "ranks given $extra apart: no message"
  [ ! -e x.png ] || fail "ranks given $extra apart: an image was written"
done
# A worker refusing its own option, or given --help (it left before
# MPI_Init, and the job hung there): named with what it says, no image.
worker_refuses() { # $1: the worker's option; $2: what rank 0 says of it
  timeout 60 "${mpi[@]}" -np 1 "$glint_mpi" whitted -W 64 -H 48 -o x.png : \
    -np 1 "$glint_mpi" whitted "$1" >run.out 2>run.err
  local status=$?
  [ "$status" -eq 2 ] || fail "a worker given $1: exit status $status"
  grep -q "rank 1 (.*): $2" run.err || fail "a worker given $1: not named"
  [ ! -e x.png ] || fail "a worker given $1: an image was written"
}
worker_refuses --bogus "unknown option '--bogus'"
# glint-mpi's own messages say glint-mpi (its argument errors said glint)
grep -q "^glint-mpi: rank 1 (.*): unknown option '--bogus'" run.err ||
  fail "a worker's refusal: not glint-mpi's own message: $(cat run.err)"
worker_refuses --help "its arguments ask for --help"
# A rank whose memory limit (ulimit -v) breaks Open MPI's shared memory:
# MPI_Init succeeds, no message passes, and every rank waited for ever. The
# start-up watchdog ends the job after --timeout, saying why; no image.
unreachable=(sh -c '[ "$OMPI_COMM_WORLD_RANK" = 1 ] && ulimit -v 50000; exec "$0" "$@"')
timeout 60 "${mpi[@]}" -np 2 "${unreachable[@]}" "$glint_mpi" whitted -W 64 -H 48 \
  --timeout 3 -o x.png >run.out 2>run.err
status=$?
[ "$status" -ne 0 ] && [ "$status" -ne 124 ] ||
  fail "a rank that cannot be reached: exit status $status"
# (AddressSanitizer, reserving its shadow memory, cannot start under the
# limit at all)
grep -q "AddressSanitizer" run.err ||
  grep -q "the ranks did not all reach each other within 10 s" run.err ||
  fail "a rank that cannot be reached: not said"
[ ! -e x.png ] || fail "a rank that cannot be reached: an image was written"
# Out of memory is exit status 1 from glint-mpi as from glint (it was 2):
# rank 0's film for a 16384x16384 PFM, under a limit on every rank.
limited=(sh -c 'ulimit -v 1500000; exec "$0" "$@"')
timeout 60 "${mpi[@]}" -np 2 "${limited[@]}" "$glint_mpi" whitted \
  -W 16384 -H 16384 -q -o big.pfm >run.out 2>run.err
status=$?
# (AddressSanitizer, reserving its shadow memory, cannot start under the
# limit, nor can some Open MPI transports: glint-mpi then says nothing)
if grep -q "^glint-mpi:" run.err; then
  [ "$status" -eq 1 ] || fail "a film out of memory: exit status $status"
  grep -q "^glint-mpi: out of memory for a 16384x16384 film" run.err ||
    fail "a film out of memory: not said: $(cat run.err)"
  [ ! -e big.pfm ] || fail "a film out of memory: an image was written"
else
  echo "a film out of memory: SKIPPED (glint-mpi cannot start under ulimit -v here)"
fi
# A scene file named without an extension is rank 0's file, as glint render
# reads it: refused as no scene file, once (ranks called it an unknown
# built-in scene)
cp "$anim" bare
run 2 bare -q -o x.png >run.out 2>run.err
status=$?
[ "$status" -eq 2 ] || fail "a bare-named file: exit status $status"
[ "$(grep -c "bare: not a scene file" run.err)" -eq 1 ] ||
  fail "a bare-named file: not one message"
rm -f bare

# Bad input: one message, status 2.
run 3 nowhere.json -q >run.out 2>run.err
[ $? -ne 0 ] || fail "a missing scene: exit status 0"
[ "$(grep -c 'nowhere.json: No such file or directory' run.err)" -eq 1 ] ||
  fail "a missing scene: not one message"
run 2 whitted --schedule sometimes >run.out 2>run.err
[ $? -ne 0 ] || fail "a bad --schedule: exit status 0"
[ "$(grep -c "schedule: 'sometimes' is not dynamic or static" run.err)" -eq 1 ] ||
  fail "a bad --schedule: not one message"
run 2 whitted --tile 24 >run.out 2>run.err
[ $? -ne 0 ] || fail "a --tile off the renderer's grid: exit status 0"
[ "$(grep -c "^glint-mpi: --tile: 24 is not a multiple of 16" run.err)" -eq 1 ] ||
  fail "a --tile off the renderer's grid: not one message of glint-mpi's"
# (--tile with --frames was taken and ignored)
run 2 whitted --frames 0-1 --tile 64 >run.out 2>run.err
[ $? -ne 0 ] || fail "--tile with --frames: exit status 0"
[ "$(grep -c "tile: with --frames each rank renders whole frames" run.err)" -eq 1 ] ||
  fail "--tile with --frames: not one message"
GLINT_ISA=bogus run 2 whitted -W 8 -H 8 -o isa.png >run.out 2>run.err
[ $? -ne 0 ] || fail "GLINT_ISA=bogus: exit status 0"
[ "$(grep -c "GLINT_ISA='bogus' is not none, sse, avx2 or avx512" run.err)" -eq 1 ] ||
  fail "GLINT_ISA=bogus: not one message"
[ ! -e isa.png ] || fail "GLINT_ISA=bogus: an image was written"

# The pid of rank $1 of the running job (ranks run in this test's folder).
rank_pid() {
  for p in $(pgrep -x glint-mpi); do
    [ "$(readlink "/proc/$p/cwd")" = "$work" ] || continue # another job's
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null |
      grep -qx "OMPI_COMM_WORLD_RANK=$1" && { echo "$p"; return 0; }
  done
  return 1
}
# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local limit=$1
  shift
  for _ in $(seq $((limit * 20))); do
    "$@" && return 0
    sleep 0.05
  done
  return 1
}
written() { [ "$(grep -c '^frame .*, rank' "$1" 2>/dev/null)" -ge "$2" ]; }
only_frames() { # no temporary or partial file beside the frames
  for f in "$1"/* "$1"/.[!.]*; do
    [ -e "$f" ] || continue
    case "$(basename "$f")" in
    f[0-9][0-9].png) ;;
    *) fail "$2: $(basename "$f") was left behind" ;;
    esac
  done
}

# A worker killed mid-animation (every rank slowed, so that rank 0 cannot
# finish the frames alone before mpirun ends the job).
"$glint" render "$anim" --frames 1-60 -W 96 -H 72 -s 1 -o kref/f%02d.png -q
GLINT_MPI_TEST_SLOW=0:200,1:200 run 2 "$anim" --frames 1-60 -W 96 -H 72 -s 1 \
  -o killed/f%02d.png >kill.out 2>kill.err &
job=$!
wait_for 60 written kill.out 1 || fail "killing: no frame was written"
pid=$(rank_pid 1) || fail "killing: rank 1 not found"
start=$(date +%s)
kill -9 "$pid"
wait "$job"
status=$?
job=
[ "$status" -ne 0 ] || fail "killing: exit status 0"
[ $(($(date +%s) - start)) -le 30 ] || fail "killing: the job took over 30 s to end"
grep -q "rank 1 .* on node $(hostname)" kill.err || fail "killing: rank 1 and its host are not named"
only_frames killed "killing"
done_before=$(ls killed | wc -l)
[ "$done_before" -lt 60 ] || fail "killing: every frame was written anyway"
run 2 "$anim" --frames 1-60 -W 96 -H 72 -s 1 -o killed/f%02d.png --resume \
  >resume.out 2>resume.err || fail "--resume: exit status $?"
grep -q "^$((60 - done_before)) frames\? written, $done_before kept (--resume)" resume.out ||
  fail "--resume: $(grep written resume.out)"
for f in kref/*; do
  cmp -s "$f" "killed/$(basename "$f")" || fail "--resume: $(basename "$f") is not glint render's"
done
echo "killed rank 1 after $done_before of 60 frames; --resume wrote the other $((60 - done_before))"

# A worker that hangs (SIGSTOP) holding frames. Static: its frames never
# come, and the job ends after --timeout naming it, with no partial file.
hang() { # $1: schedule, $2: folder, $3: ranks slowed, $4: --timeout,
         # $5: the seconds within which the job must end
  GLINT_MPI_TEST_SLOW=$3 run 2 "$anim" --frames 1-30 -W 96 -H 72 -s 1 \
    --schedule "$1" --timeout "$4" -o "$2/f%02d.png" >hang.out 2>hang.err &
  job=$!
  wait_for 60 written hang.out 1 || fail "hanging ($1): no frame was written"
  pid=$(rank_pid 1) || fail "hanging ($1): rank 1 not found"
  start=$(date +%s)
  stopped=$pid
  kill -STOP "$pid"
  wait "$job"
  status=$?
  job=
  [ "$status" -eq 2 ] || fail "hanging ($1): exit status $status"
  echo "hanging ($1): the job ended $(($(date +%s) - start)) s after the stop"
  [ $(($(date +%s) - start)) -le "$5" ] || fail "hanging ($1): the job took over $5 s to end"
  only_frames "$2" "hanging ($1)"
}
hang static hung 0:20,1:20 2 30
grep -q "rank 1 ($(hostname)) has sent nothing for 2 s while it owes" hang.err ||
  fail "hanging (static): rank 1 is not named"
# Dynamic: rank 0 renders what the silent rank holds, writes every frame,
# and then ends the job naming it, however long that takes after the
# timeout: slowed 120x, rank 0 is still rendering when the 1 s runs out
# (the job was ended there, and every frame not yet written lost). Slowed
# 60x, it ended 5 s after the stop under ctest -j2 and 11 s in the
# sanitized build; slowed twice as much, a machine four times as fast
# still has work left past the timeout, and the time limit is raised to
# match.
hang dynamic hung-dynamic 0:120,1:20 1 60
grep -q "rank 1 ($(hostname)) has sent nothing for 1 s while it owes .*; rank 0 renders them" hang.err ||
  fail "hanging (dynamic): rank 1 is not named when it goes silent: $(cat hang.err)"
grep -q "rank 1 ($(hostname)) went silent for 1 s .*every frame was in" hang.err ||
  fail "hanging (dynamic): rank 1 is not named at the end: $(cat hang.err)"
for f in 01 02 03 04 05 06 07 08 09 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30; do
  cmp -s "kref/f$f.png" "hung-dynamic/f$f.png" || fail "hanging (dynamic): frame $f is not glint render's"
done
echo "mpi: PASSED"
