#!/bin/sh
# The programs of examples/, built on glint.h and libglint.so alone, run and
# do what their comments say.
set -eu
bin=$1 glint=$2 source=$3 dir=$4
rm -rf "$dir"
mkdir -p "$dir"

# orbit: one frame (the scene's own camera) equals `glint render` at the
# same settings, pixel for pixel; several frames of a scene file; a bad
# scene is an error, not a crash.
"$bin/orbit" whitted 1 "$dir/orbit.png"
"$glint" render whitted -s 1 -q -o "$dir/render.png"
psnr=$("$glint" compare "$dir/orbit.png" "$dir/render.png")
case "$psnr" in *" inf "*) ;; *) echo "FAILED: orbit differs: $psnr"; exit 1 ;; esac
"$bin/orbit" "$source/scenes/giza.json" 4 "$dir/giza.png" |
  grep -q "4 frames of 640x480"
if "$bin/orbit" no-such-scene 1 "$dir/x.png" 2>/dev/null; then
  echo "FAILED: orbit accepted an unknown scene"
  exit 1
fi

# build_scene: a 640x400 PNG of its scene.
"$bin/build_scene" "$dir/built.png" >/dev/null
"$glint" compare "$dir/built.png" "$dir/built.png" >/dev/null
"$glint" render whitted -W 640 -H 400 -s 1 -q -o "$dir/size.png"
"$glint" compare "$dir/built.png" "$dir/size.png" >/dev/null ||
  { echo "FAILED: build_scene did not write a 640x400 image"; exit 1; }

# render_file: renders a file; Ctrl-C cancels, exit 130, nothing written.
"$bin/render_file" "$source/scenes/billiard.json" "$dir/billiard.png" 2>/dev/null |
  grep -q "billiard.png: 640x480"
# a slow scene: 400 glass spheres, 2048x2048
awk 'BEGIN {
  printf "{\"image\": {\"width\": 2048, \"height\": 2048},\n"
  printf " \"camera\": {\"from\": [0, 0, 30], \"at\": [0, 0, 0]},\n"
  printf " \"lights\": [{\"position\": [0, 5, 25]}],\n"
  printf " \"materials\": {\"m\": {\"kr\": 0.5, \"kt\": 0.5, \"ior\": 1.3}},\n"
  printf " \"objects\": ["
  for (i = 0; i < 400; i++)
    printf "%s{\"type\": \"sphere\", \"material\": \"m\", \"center\": [%d, %d, %d], \"radius\": 1.2}",
      (i ? ", " : ""), i % 20 - 10, int(i / 20) - 10, -(i % 7)
  printf "]}\n" }' >"$dir/slow.json"
"$bin/render_file" "$dir/slow.json" "$dir/slow.png" 2>"$dir/err.txt" &
pid=$!
sleep 1
kill -INT $pid
status=0
wait $pid || status=$?
[ $status -eq 130 ] || { echo "FAILED: render_file exit $status, want 130"; exit 1; }
grep -q "interrupted; nothing written" "$dir/err.txt"
[ ! -e "$dir/slow.png" ] || { echo "FAILED: a cancelled render wrote a file"; exit 1; }
echo PASSED
