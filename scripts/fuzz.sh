#!/usr/bin/env bash
# Fuzzes glint's readers with libFuzzer (clang), everything built with
# AddressSanitizer and UBSan.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#
# runs each TARGET for SECONDS (default 30) with FUZZ_JOBS parallel jobs
# (default 1). Targets: nff json obj ply ply_gz pack png bmp ppm cli (default:
# all); fuzz/fuzz_load.c, fuzz/fuzz_image.c and fuzz/fuzz_cli.c say what each
# does. A crash, leak, sanitizer report or slow input (over 1 s) stops its
# target, keeps the input in build-sanitize/findings/TARGET/ and fails the run; reproduce it with
# build-sanitize/fuzz_TARGET FILE. Corpora grow in build-sanitize/corpus/TARGET,
# seeded from fuzz/corpus/ (and scenes/ for JSON).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(nff json obj ply ply_gz pack png bmp ppm cli)
jobs=${FUZZ_JOBS:-1}
build=${FUZZ_BUILD:-build-sanitize} # make test-asan's build, shared

if ! command -v clang >/dev/null 2>&1; then
  echo "fuzz: clang is missing (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
mkdir -p "$build"
build=$(cd "$build" && pwd) # the fuzzers run in their own directories
CC=clang cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DGLINT_FUZZ=ON \
  >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" \
  --target $(printf 'fuzz_%s ' "${targets[@]}") >"$build/build.log" 2>&1 ||
  { tail -40 "$build/build.log"; exit 1; }

status=0
for t in "${targets[@]}"; do
  corpus=$build/corpus/$t findings=$build/findings/$t
  # libFuzzer's workers write fuzz-N.log into the working directory: give
  # each target its own, so that two runs in one checkout never share one.
  workdir=$build/work/$t
  mkdir -p "$corpus" "$findings" "$workdir"
  rm -f "$workdir"/fuzz-*.log
  cp -n fuzz/corpus/"$t"/* "$corpus"/ 2>/dev/null || true
  [ "$t" = json ] && cp -n scenes/*.json "$corpus"/
  log=$build/fuzz_$t.log
  # The parsers print their messages and --help: keep them out of the log
  # (sanitizer reports still reach it).
  quiet=0
  [ "$t" = cli ] && quiet=3
  if (cd "$workdir" && "$build/fuzz_$t" -max_total_time="$seconds" \
      -timeout=1 -close_fd_mask=$quiet \
      -rss_limit_mb=2048 -max_len=65536 -jobs="$jobs" -workers="$jobs" \
      -print_final_stats=1 -artifact_prefix="$findings/" \
      "$corpus") >"$log" 2>&1; then
    runs=$(cat "$log" "$workdir"/fuzz-*.log 2>/dev/null |
           awk '/stat::number_of_executed_units/ {s += $2} END {print s + 0}')
    echo "fuzz_$t: ${seconds}s x $jobs, $runs inputs, $(ls "$corpus" | wc -l) in the corpus, no findings"
  else
    echo "fuzz_$t: FINDING (see $log, $workdir/fuzz-*.log and $findings/):"
    cat "$log" "$workdir"/fuzz-*.log 2>/dev/null |
      grep -E "ERROR|SUMMARY|runtime error|Test unit written" | head -5
    status=1
  fi
done
exit $status
