#!/bin/sh
# Every option that `glint --help` and each command's --help (render, view,
# bench, compare) list appears in glint(1), and every
# built-in scene and backend too: the manual page keeps up with the program.
# With glint-mpi and its page ($4, $5), glint-mpi --help's options appear in
# glint-mpi(1).
set -eu
glint=$1 man1=$2 man5=$3 mpi=${4:-} mpi_man=${5:-}
page=$(sed 's/\\-/-/g; s/\\f[BIRP]//g' "$man1")
missing=0
for cmd in "" render view bench compare; do
  help=$("$glint" $cmd --help)
  for opt in $(printf '%s\n' "$help" | grep -o -- '--[a-z][a-z0-9-]*' | sort -u) \
             $(printf '%s\n' "$help" | grep -o -- '^ *-[A-Za-z],' | tr -d ' ,' | sort -u); do
    if ! printf '%s\n' "$page" | grep -q -- "$opt"; then
      echo "glint.1 lacks ${cmd:-glint} $opt"
      missing=1
    fi
  done
done
for word in GLINT_ISA whitted giza billiard phong scalar-float scalar-double \
            sse avx2 avx512 stream-sse stream-avx2 stream-avx512 130; do
  printf '%s\n' "$page" | grep -q -- "$word" ||
    { echo "glint.1 lacks $word"; missing=1; }
done
# glint-scene(5) names every JSON section and NFF entity.
scene=$(sed 's/\\-/-/g; s/\\f[BIRP]//g' "$man5")
for word in camera image background ambient lights materials objects sphere \
            plane triangle cone mesh checker-planar checker-solid absorb \
            hither angle; do
  printf '%s\n' "$scene" | grep -q -- "$word" ||
    { echo "glint-scene.5 lacks $word"; missing=1; }
done
if [ -n "$mpi" ]; then
  mpi_page=$(sed 's/\\-/-/g; s/\\f[BIRP]//g' "$mpi_man")
  for opt in $("$mpi" --help | grep -o -- '--[a-z][a-z0-9-]*' | sort -u); do
    printf '%s\n' "$mpi_page" | grep -q -- "$opt" ||
      { echo "glint-mpi.1 lacks $opt"; missing=1; }
  done
fi
# All are well-formed for man(1) when groff is here to check.
if command -v groff >/dev/null 2>&1; then
  for f in "$man1" "$man5" ${mpi_man:+"$mpi_man"}; do
    warnings=$(groff -man -Tutf8 -ww -z "$f" 2>&1 || true)
    [ -z "$warnings" ] || { echo "$f: $warnings"; missing=1; }
  done
fi
[ $missing -eq 0 ] && echo "PASSED: the manual pages cover every option"
exit $missing
