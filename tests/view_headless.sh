#!/usr/bin/env bash
# glint view without a display (SDL's dummy video driver), driven by
# --script, against hand-computed cameras (docs: glint view --help):
#  - a left drag of 100 pixels orbits 30 degrees about up, keeping the
#    point looked at; the wheel dollies to 0.9 of the distance, a right drag
#    of 50 pixels to exp(0.5) of it; a Shift+left drag of half the width pans
#    by half the visible width; holding W flies eye and target together
#    along the view; R goes back to the scene's camera;
#  - the window, refined to 2 samples with the display off, is byte for byte
#    glint render -s 2 (the accumulation reaches the same image), and the
#    screenshot is what glint render writes;
#  - a key's effect is on the very next frame (depth 3 one frame later);
#  - an idle window renders no frames;
#  - a scene file that stops parsing keeps the last scene and names
#    FILE:LINE; fixed, it is reloaded; a resize renders at the new size.
#   tests/view_headless.sh GLINT
set -u
glint=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
unset DISPLAY WAYLAND_DISPLAY
export SDL_VIDEODRIVER=dummy
fail() {
  echo "view_headless: FAILED: $*"
  echo "--- stdout"; cat out.txt
  echo "--- stderr"; cat err.txt
  exit 1
}

scene() { # $1: the sphere's radius
  cat <<EOF
{
  "camera": {"from": [0, 2, 6], "at": [0, 1, 0], "up": [0, 1, 0], "fov": 60},
  "image": {"width": 160, "height": 120},
  "background": [0.2, 0.3, 0.6],
  "lights": [{"position": [-4, 8, 6], "color": [1, 1, 1]}],
  "materials": {"red": {"color": [0.9, 0.2, 0.2], "kd": 0.8, "ks": 0.3, "h": 20},
                "glass": {"color": [1, 1, 1], "kd": 0.1, "kt": 0.8, "ior": 1.5}},
  "objects": [
    {"type": "sphere", "center": [0, 1, 0], "radius": $1, "material": "glass"},
    {"type": "sphere", "center": [1.5, 0.5, -1], "radius": 0.5, "material": "red"},
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "red"}
  ]
}
EOF
}
scene 1 > scene.json
scene 1 > good.json
scene 0.6 > changed.json
printf '{\n  "camera": {"from": [0, 2, 6]\n  oops\n}\n' > broken.json

cat > input.txt <<'EOF'
# the cameras
print camera
drag left 100 0
wait
print camera
key r
wheel 1
wait
print camera
key r
drag right 0 50
wait
print camera
key r
drag shift-left 80 0
wait
print camera
key r
hold w 0.3
wait
print camera
key r
wait
# the window and a screenshot, refined to 2 samples
key h
sleep 0.2
capture shown.ppm
key space
wait
# idle: no frames
print state
sleep 1
print state
# a key shows on the next frame
key 3
print state
key 5
wait
# reloading
copy broken.json scene.json
sleep 1
print state
copy changed.json scene.json
sleep 1
wait
print camera
resize 200 150
wait
print state
quit
EOF
"$glint" view scene.json -s 2 -t 2 --script input.txt >out.txt 2>err.txt ||
  fail "exit status $?"

# The Nth camera printed (P or print camera), as its numbers.
camera() {
  grep '^"camera"' out.txt | sed -n "${1}p" | sed 's/"[a-z]*": //g' |
    tr -c '0-9.e+-' ' '
}
# Compares the numbers of a printed camera with the expected ones, to 1e-4.
expect_camera() { # $1: which; $2: from x y z at x y z
  local got
  got=$(camera "$1")
  awk -v got="$got" -v want="$2" -v which="$1" 'BEGIN {
    n = split(got, g, " "); split(want, w, " ")
    for (i = 1; i <= 6; i++) {
      d = g[i] - w[i]; if (d < 0) d = -d
      if (d > 1e-4) { print "camera " which ": " got " is not " want; exit 1 }
    }
  }' || fail "camera $1"
}
expect_camera 1 "0 2 6 0 1 0"
expect_camera 2 "-3 2 5.196152 0 1 0"            # orbit: 30 degrees about y
expect_camera 3 "0 1.9 5.4 0 1 0"                # wheel: 0.9 of the distance
expect_camera 4 "0 2.648721 9.892308 0 1 0"      # right drag: exp(0.5)
expect_camera 5 "-3.511885 2 6 -3.511885 1 0"    # pan: sqrt(37) tan 30 deg
# Flying forward: eye and target together along (0, -1, -6).
fly=$(camera 6)
awk -v c="$fly" 'BEGIN { split(c, v, " ")
  t = (6 - v[3]) / 6
  if (v[1] != 0 || v[4] != 0 || t < 0.05 ||
      (v[2] - (2 - t)) ^ 2 > 1e-8 || (v[5] - (1 - t)) ^ 2 > 1e-8 ||
      (v[6] + 6 * t) ^ 2 > 1e-8) exit 1 }' || fail "flying: $fly"
# (each move above starts from R, the scene's camera)
expect_camera 7 "0 2 6 0 1 0"                    # a reload keeps the camera

"$glint" render good.json -s 2 -t 2 -o rendered.ppm -q || fail "glint render"
cmp -s shown.ppm rendered.ppm || fail "the window is not glint render's image"
"$glint" render good.json -s 2 -t 2 -o rendered.png -q || fail "glint render"
cmp -s scene-0001.png rendered.png || fail "the screenshot is not glint render's"

states=$(grep '^state:' out.txt)
frames() { printf '%s\n' "$states" | sed -n "${1}p" | sed 's/.*frames \([0-9]*\).*/\1/'; }
[ "$(frames 1)" = "$(frames 2)" ] || fail "an idle window rendered frames"
printf '%s\n' "$states" | sed -n 1p | grep -q 'samples 2/2' || fail "not refined"
[ "$(frames 3)" = "$(($(frames 2) + 1))" ] || fail "the key took more than a frame"
printf '%s\n' "$states" | sed -n 3p | grep -q 'depth 3' || fail "depth 3 not shown"
grep -q 'scene.json:3:3: JSON syntax error' err.txt || fail "no FILE:LINE for the broken scene"
printf '%s\n' "$states" | sed -n 4p | grep -q 'depth 5' || fail "state after the broken scene"
grep -q 'reloaded scene.json' err.txt || fail "the changed scene was not reloaded"
printf '%s\n' "$states" | sed -n 5p | grep -q '200x150 at scale 1.000' ||
  fail "the resize did not render at 200x150"
# A script that is not a text file is refused before any window: a folder
# (read as empty before), a FIFO without a writer (blocked for ever), a NUL
# byte (reported as an overlong line), and control bytes shown escaped.
script_refused() { # $1: the script; $2: the message
  timeout 20 "$glint" view scene.json --script "$1" >out.txt 2>err.txt
  local rc=$?
  [ $rc -eq 2 ] || fail "--script $1: exit status $rc, want 2"
  grep -qF -- "$2" err.txt || fail "--script $1: no '$2'"
}
mkdir folder
mkfifo fifo
printf 'wait\nkey a\0b\n' >nul.txt
printf 'key \001\033[31mred\n' >control.txt
script_refused folder "--script folder: not a regular file"
script_refused fifo "--script fifo: not a regular file"
script_refused nul.txt "nul.txt:2: a NUL byte"
script_refused control.txt "control.txt:1: no key is named '\x01\x1b[31mred'"
# A script without quit ends the viewer where no window shows (it ran until
# killed: no one could close it).
: >empty.txt
timeout 20 "$glint" view scene.json --script empty.txt >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "a script without quit, no display: exit status $rc, want 0"
# Numbers: out of range said so (it said "not a number"), hours refused.
printf 'wheel 1e9\n' >bignum.txt
printf 'sleep 100000\n' >longsleep.txt
printf 'drag left x 5\n' >notnum.txt
script_refused bignum.txt "bignum.txt:1: a number outside -1e6..1e6: '1e9'"
script_refused longsleep.txt "longsleep.txt:1: a time past 3600 seconds: '100000'"
script_refused notnum.txt "notnum.txt:1: not a number: 'x'"
printf 'sleep 0x2\n' >hex.txt
script_refused hex.txt "hex.txt:1: not a number: '0x2'"
# Pixels and notches are whole (wheel 0.5 did nothing, resize 1.5 2.7 made
# a 1x2 window); a time out of range says so (it said -1e6..1e6).
printf 'wheel 0.5\n' >halfwheel.txt
printf 'resize 64 2.7\n' >halfsize.txt
printf 'hold w 1e400\n' >inftime.txt
script_refused halfwheel.txt "halfwheel.txt:1: not a whole number: '0.5'"
script_refused halfsize.txt "halfsize.txt:1: not a whole number: '2.7'"
script_refused inftime.txt "inftime.txt:1: a time past 3600 seconds: '1e400'"
# ...and a number too small for a double is 0, as the options read it (it
# was "outside -1e6..1e6").
printf 'sleep 1e-400\nquit\n' >tiny.txt
timeout 20 "$glint" view scene.json --script tiny.txt >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "sleep 1e-400: exit status $rc, want 0: $(cat err.txt)"
# Without a display a script needs no SDL_VIDEODRIVER, as --benchmark
# needs none ("cannot open a window" before)
printf 'wait\nquit\n' >plain.txt
(unset SDL_VIDEODRIVER; timeout 20 "$glint" view scene.json --script plain.txt) \
  >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "a script without a display: exit status $rc: $(cat err.txt)"
# ...and the range's ends are in it (1e6 was refused as outside -1e6..1e6)
printf 'wheel 1000000\nwheel -1e6\nwait\nquit\n' >ends.txt
timeout 20 "$glint" view scene.json --script ends.txt >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "wheel 1e6: exit status $rc, want 0: $(cat err.txt)"
# A copy that is refused: exit status 2 and its message.
copy_refused() { # $1: the copy command; $2: the message
  printf '%s\nquit\n' "$1" >copy.txt
  timeout 20 "$glint" view scene.json --script copy.txt >out.txt 2>err.txt
  local rc=$?
  [ $rc -eq 2 ] || fail "$1: exit status $rc, want 2"
  grep -qF -- "$2" err.txt || fail "$1: no '$2'"
}
# copy takes regular files only: /dev/zero never ends (it filled the disk).
copy_refused "copy /dev/zero zero.json" \
  "copy.txt:1: cannot copy /dev/zero to zero.json: not a regular file"
[ ! -e zero.json ] || fail "copy /dev/zero made zero.json"
# ...onto a regular file that is not itself (it was emptied), and not onto
# a FIFO (it blocked for ever).
cp good.json same.json
ln -s same.json same-link.json
copy_refused "copy same-link.json same.json" \
  "cannot copy same-link.json to same.json: they are the same file"
cmp -s same.json good.json || fail "copy onto itself emptied the file"
copy_refused "copy same.json fifo" "the destination is not a regular file"
# ...and not from a FIFO (the open waited for a writer for ever).
copy_refused "copy fifo from-fifo.json" \
  "cannot copy fifo to from-fifo.json: not a regular file"
[ ! -e from-fifo.json ] || fail "copy from a FIFO made from-fifo.json"
# ...nor onto the script itself, nor a capture (the script became a PNG).
copy_refused "copy same.json copy.txt" \
  "cannot copy same.json to copy.txt: the destination is this script"
printf 'wait\ncapture self.png\nquit\n' >self.png
cp self.png self-kept.txt
script_refused self.png "self.png:2: capture self.png: that is this script"
cmp -s self.png self-kept.txt || fail "capture replaced the script"
# A link to nothing takes its screenshot's number (it blocked every
# screenshot: "cannot write here").
cp good.json shot.json
ln -s /nonexistent/x shot-0001.png
printf 'wait\nkey space\nquit\n' >shot.txt
timeout 20 "$glint" view shot.json -W 32 -H 24 --script shot.txt \
  >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "screenshot past a dangling link: exit status $rc"
[ -f shot-0002.png ] || fail "no screenshot past a dangling link"
# F twice: back at the window's size (it went on rendering, and capturing,
# at the screen's).
printf 'wait\nkey f\nwait\nkey f\nwait\ncapture back.ppm\nquit\n' >full.txt
timeout 20 "$glint" view shot.json -W 48 -H 36 --script full.txt \
  >out.txt 2>err.txt
rc=$?
[ $rc -eq 0 ] || fail "fullscreen and back: exit status $rc"
[ "$(head -c 11 back.ppm | tr '\n' ' ')" = "P6 48 36 25" ] ||
  fail "fullscreen and back: not 48x36 again"
# A copy that fails leaves the destination as it was: from a missing file,
# TO was emptied (and a missing TO created empty).
cp good.json kept.json
copy_refused "copy missing.json kept.json" \
  "cannot copy missing.json to kept.json: No such file or directory"
cmp -s kept.json good.json || fail "copy from a missing file changed its destination"
copy_refused "copy missing.json made.json" "cannot copy missing.json to made.json"
[ ! -e made.json ] || fail "copy from a missing file made its destination"
# A copy over a file keeps that file's permissions, as fopen's did.
cp good.json moded.json
chmod 600 moded.json
printf 'copy scene.json moded.json\nquit\n' >copy.txt
timeout 20 "$glint" view scene.json --script copy.txt >out.txt 2>err.txt ||
  fail "copy over a file: $(cat err.txt)"
[ "$(stat -c %a moded.json)" = 600 ] || fail "copy over a file changed its mode"
cmp -s moded.json scene.json || fail "copy over a file: not copied"
ls -a | grep -q '\.tmp$' && fail "a copy left a temporary file: $(ls -a | grep '\.tmp$')"
# A capture through a link to a scene or mesh file would replace it (it
# wrote a PNG over the scene being viewed): refused, the file kept.
cp good.json linked.json
ln -s linked.json linked.png
printf 'wait\ncapture linked.png\nquit\n' >capture.txt
timeout 20 "$glint" view scene.json -s 1 --script capture.txt >out.txt 2>err.txt
rc=$?
[ $rc -eq 2 ] || fail "a capture onto a link to a scene: exit status $rc, want 2"
grep -qF "capture.txt:2: linked.png: a link to " err.txt ||
  fail "a capture onto a link to a scene: no message"
cmp -s linked.json good.json || fail "a capture replaced the scene it links to"
# Ctrl-C during a pass that takes seconds cancels the pass: exit 130 at once
# (it rendered the pass to its end first: 12 s here, 87 s for Whitted at
# 16384x16384). Three glass spheres in each other, where the rays double
# at every level.
printf 'v\nfrom 0 0 -3\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.001\n%s\n' \
  'resolution 128 128' >nested.nff
printf 'b 0.2 0.3 0.5\nl 5 5 -5\nf 1 1 1 0 1 10 1 1.5\n%s\n' \
  's 0 0 0 1' >>nested.nff
printf 's 0 0 0 0.6\ns 0 0 0 0.3\n' >>nested.nff
start=$(date +%s%N)
timeout --preserve-status -s INT 1 "$glint" view nested.nff -d 22 -t 1 \
  --benchmark 3 >out.txt 2>err.txt
rc=$?
took=$((($(date +%s%N) - start) / 1000000))
[ $rc -eq 130 ] || fail "Ctrl-C during a pass: exit status $rc, want 130"
[ $took -lt 5000 ] || fail "Ctrl-C during a pass: stopped after $took ms"
grep -qF "glint: view: interrupted" err.txt || fail "Ctrl-C during a pass: no message"
# A window resized past the memory there is: exit status 1 (out of memory,
# as glint --help says), not 2. (Not under AddressSanitizer, which cannot
# start under a limit on address space.)
if [ -z "${ASAN_OPTIONS:-}" ]; then
  printf 'resize 16384 16384\nwait\nquit\n' >huge.txt
  (ulimit -v 3000000; timeout 60 "$glint" view scene.json -s 1 --script huge.txt) \
    >out.txt 2>err.txt
  rc=$?
  [ $rc -eq 1 ] || fail "a window past memory: exit status $rc, want 1"
  grep -qF "out of memory for a 16384x16384 frame" err.txt ||
    fail "a window past memory: no message"
fi
echo "view_headless: PASSED"
