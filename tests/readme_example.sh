#!/bin/sh
# The README's JSON scene renders as pasted.
set -eu
glint=$1 readme=$2
dir=$(mktemp -d /tmp/glint-readme-XXXXXX)
trap 'rm -rf "$dir"' EXIT
awk '/^```json$/ {on = 1; next} on && /^```$/ {exit} on' "$readme" >"$dir/scene.json"
[ -s "$dir/scene.json" ] || { echo "FAILED: no JSON block in the README"; exit 1; }
"$glint" render "$dir/scene.json" -W 64 -H 48 -q -o "$dir/scene.png"
[ -s "$dir/scene.png" ] && echo "PASSED: the README's scene renders"
