#!/bin/sh
# examples/orbit (built on libglint.so and glint.h alone) must run, and its
# one-frame orbit (the scene's own camera) must equal `glint render` at the
# same settings, pixel for pixel: a renderer's frame is glint_render's image.
set -eu
orbit=$1 glint=$2 dir=$3
mkdir -p "$dir"
"$orbit" whitted 1 "$dir/orbit.png"
"$glint" render whitted -s 1 -q -o "$dir/render.png"
psnr=$("$glint" compare "$dir/orbit.png" "$dir/render.png")
echo "orbit against glint render: $psnr"
case "$psnr" in *" inf "*) ;; *) echo "FAILED: the images differ" >&2; exit 1 ;; esac
# Several frames and a scene file, through the same renderer.
"$orbit" "$(dirname "$0")/../scenes/giza.json" 4 "$dir/giza.png" |
  grep -q "4 frames of 640x480"
# A bad scene is an error, not a crash.
if "$orbit" no-such-scene 1 "$dir/x.png" 2>/dev/null; then
  echo "FAILED: an unknown scene was accepted" >&2
  exit 1
fi
echo PASSED
