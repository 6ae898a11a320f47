#!/usr/bin/env bash
# glint view in a real window: Xvfb for the display, xdotool for the keys
# and the mouse. It checks that
#  - P prints the camera as JSON, and a left drag orbits it;
#  - Space writes SCENE-0001.png, byte for byte what glint render writes for
#    the printed camera pasted into the scene, and never overwrites a file;
#  - an idle window (refined to its spp) uses no CPU, and what the screen
#    shows (captured by tests/x11_capture.c, the display off) is glint
#    render's image;
#  - a scene file that stops parsing leaves the window running and names
#    FILE:LINE on stderr; fixed, it is reloaded;
#  - depth, backend, maths, scale, display and help keys and a resize keep it
#    running, and a screenshot after the resize has the window's new size;
#  - Esc quits with status 0.
# SKIPPED (exit 77) without Xvfb or xdotool.
#   tests/view.sh GLINT X11_CAPTURE
set -u
glint=$1
capture=$2
for tool in Xvfb xdotool; do
  if ! command -v $tool >/dev/null 2>&1; then
    echo "view: SKIPPED ($tool is missing; scripts/install-deps.sh installs it)"
    exit 77
  fi
done
work=$(mktemp -d)
xvfb=
viewer=
cleanup() {
  [ -n "$viewer" ] && kill "$viewer" 2>/dev/null
  [ -n "$xvfb" ] && kill "$xvfb" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "view: FAILED: $*"
  echo "--- stdout"; cat "$work/out.txt" 2>/dev/null
  echo "--- stderr"; cat "$work/err.txt" 2>/dev/null
  exit 1
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

# A display of our own: the first free number from 90.
display=90
while [ -e /tmp/.X$display-lock ] || [ -e /tmp/.X11-unix/X$display ]; do
  display=$((display + 1))
done
# -noreset: an X server resets when its last client leaves, and refuses
# connections while it does; xdotool's probe below is such a client, and the
# viewer started just after it would find no display.
Xvfb :$display -screen 0 640x480x24 -nolisten tcp -noreset >/dev/null 2>&1 &
xvfb=$!
export DISPLAY=:$display
wait_for 10 xdotool getdisplaygeometry >/dev/null 2>&1 || fail "Xvfb did not start"

cd "$work"
# Under AddressSanitizer (make test-asan), leaks are not checked here: SDL
# loads the X11 and D-Bus libraries with dlopen, and what they keep is
# reported from unloaded, unnamed modules. The headless test checks glint's
# own code for leaks with SDL's dummy driver.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
scene() { # $1: the camera line; $2: the sphere's radius
  cat <<EOF
{
  $1,
  "image": {"width": 160, "height": 120},
  "background": [0.2, 0.3, 0.6],
  "lights": [{"position": [-4, 8, 6], "color": [1, 1, 1]}],
  "materials": {"red": {"color": [0.9, 0.2, 0.2], "kd": 0.8, "ks": 0.3, "h": 20},
                "glass": {"color": [1, 1, 1], "kd": 0.1, "kt": 0.8, "ior": 1.5}},
  "objects": [
    {"type": "sphere", "center": [0, 1, 0], "radius": $2, "material": "glass"},
    {"type": "sphere", "center": [1.5, 0.5, -1], "radius": 0.5, "material": "red"},
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "red"}
  ]
}
EOF
}
home='"camera": {"from": [0, 2, 6], "at": [0, 1, 0], "up": [0, 1, 0], "fov": 60}'
scene "$home" 1 > scene.json
"$glint" view scene.json -s 2 -t 1 >out.txt 2>err.txt &
viewer=$!
# The window whose title starts with $1, within 10 s.
find_window() {
  window=
  for _ in $(seq 200); do
    window=$(xdotool search --name "$1" 2>/dev/null | head -1)
    [ -n "$window" ] && return 0
    sleep 0.05
  done
  return 1
}
find_window "glint view: scene" || fail "no window"
xdotool windowfocus --sync "$window" 2>/dev/null || true
lines() { grep -c "$1" out.txt 2>/dev/null; }
has_lines() { [ "$(lines "$1")" -ge "$2" ]; }

# P: the camera as JSON, the scene's own to begin with.
xdotool key p
wait_for 20 has_lines '"camera"' 1 || fail "P printed nothing"
[ "$(head -1 out.txt)" = "$home" ] || fail "P printed '$(head -1 out.txt)'"

# A left drag orbits: the eye moves, the point looked at stays.
xdotool mousemove --window "$window" 60 60 mousedown 1
for _ in 1 2 3 4 5; do
  xdotool mousemove_relative 6 2
  sleep 0.05
done
xdotool mouseup 1
sleep 0.3
xdotool key p
wait_for 20 has_lines '"camera"' 2 || fail "P printed nothing after the drag"
moved=$(sed -n 2p out.txt)
[ "$moved" != "$home" ] || fail "the drag did not move the camera"
case "$moved" in
*'"at": [0, 1, 0]'*) ;;
*) fail "orbiting moved the point looked at: $moved" ;;
esac

# Space: a screenshot, what glint render writes for that camera.
touch scene-0001.png # taken: the screenshot must not overwrite it
xdotool key space
wait_for 30 test -s scene-0002.png || fail "no screenshot"
[ ! -s scene-0001.png ] || fail "the screenshot overwrote a file"
shot=$(grep '^wrote scene-0002.png' out.txt | sed 's/.*, "camera"/"camera"/')
[ -n "$shot" ] || fail "the screenshot's line is missing"
scene "$shot" 1 > pasted.json
"$glint" render pasted.json -s 2 -o pasted.png -q || fail "glint render failed"
cmp -s pasted.png scene-0002.png || fail "the screenshot differs from glint render"

# Idle: refined to 2 spp, the window waits without using the CPU. The
# refinement may still be running on a loaded machine (under ASan, beside
# other tests): first wait, up to 20 s, for a half second without CPU time.
ticks() { awk '{print $14 + $15}' "/proc/$viewer/stat"; }
previous=$(ticks)
for _ in $(seq 40); do
  sleep 0.5
  now=$(ticks)
  [ "$now" -eq "$previous" ] && break
  previous=$now
done
before=$(ticks)
sleep 3
used=$(($(ticks) - before))
# 1% of a core is 3 ticks (of 10 ms) in 3 s.
[ "$used" -le 3 ] || fail "an idle window used $used clock ticks in 3 s"

# The screen itself, the display turned off: what glint render renders.
xdotool key h
sleep 0.5
"$capture" "$window" captured.ppm || fail "no screen capture"
"$glint" compare captured.ppm pasted.png --min-psnr 1000 >compare.txt 2>&1 ||
  fail "the screen differs from glint render: $(cat compare.txt)"
grep -q 'PSNR inf' compare.txt || fail "the screen is not glint render's image"
xdotool key h

# A broken scene file: the last good scene stays, stderr says FILE:LINE.
sleep 1.1 # a new modification time, whatever the file system's resolution
printf '{\n  "camera": {"from": [0, 2, 6]\n  oops\n}\n' > scene.json
wait_for 20 grep -q "scene.json:3" err.txt || fail "no FILE:LINE for the broken scene"
kill -0 "$viewer" 2>/dev/null || fail "the broken scene ended the viewer"
sleep 1.1
scene "$home" 0.7 > scene.json
wait_for 20 grep -q "reloaded scene.json" err.txt || fail "the fixed scene was not reloaded"

# Keys that change what is rendered, and a resize.
for key in 3 b m bracketleft bracketright h F1 h F1 1 5; do
  xdotool key $key
  sleep 0.1
done
xdotool windowsize "$window" 200 150
sleep 0.5
kill -0 "$viewer" 2>/dev/null || fail "the viewer ended after keys and a resize"
xdotool key space
wait_for 30 test -s scene-0003.png || fail "no screenshot after the resize"
grep -q '^wrote scene-0003.png (200x150' out.txt || fail "the screenshot after the resize is not 200x150"

# Esc quits, with status 0.
xdotool key Escape
for _ in $(seq 400); do
  kill -0 "$viewer" 2>/dev/null || break
  sleep 0.05
done
kill -0 "$viewer" 2>/dev/null && fail "Esc did not quit"
wait "$viewer"
status=$?
viewer=
[ "$status" -eq 0 ] || fail "exit status $status"

# Esc during a pass that takes seconds quits at once (events were read
# between passes only: the window ignored Esc and its close for the whole
# pass). Three glass spheres in each other at depth 22, where the rays
# double at every level: 12 s a pass with one thread.
printf 'v\nfrom 0 0 -3\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.001\n%s\n' \
  'resolution 128 128' >nested.nff
printf 'b 0.2 0.3 0.5\nl 5 5 -5\nf 1 1 1 0 1 10 1 1.5\n%s\n' \
  's 0 0 0 1' >>nested.nff
printf 's 0 0 0 0.6\ns 0 0 0 0.3\n' >>nested.nff
"$glint" view nested.nff -d 22 -t 1 >out.txt 2>err.txt &
viewer=$!
find_window "glint view: nested" || fail "no window for the deep scene"
sleep 1
xdotool key --window "$window" Escape
start=$(date +%s%N)
for _ in $(seq 100); do
  kill -0 "$viewer" 2>/dev/null || break
  sleep 0.05
done
took=$((($(date +%s%N) - start) / 1000000))
kill -0 "$viewer" 2>/dev/null && fail "Esc during a pass: still running after $took ms"
wait "$viewer"
status=$?
viewer=
[ "$status" -eq 0 ] || fail "Esc during a pass: exit status $status"
echo "view: PASSED"
