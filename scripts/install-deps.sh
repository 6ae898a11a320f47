#!/usr/bin/env bash
# Installs the Debian packages glint needs to build and test, if missing.
# Safe to run repeatedly: it does nothing when everything is present.
#   scripts/install-deps.sh          what make render and make test need
#   scripts/install-deps.sh --peers  also the renderers glint bench compares
#                                    against (Tachyon, Embree 3) and assimp
set -euo pipefail

packages=(
  build-essential   # gcc, make
  cmake             # the build
  pkg-config        # finds libpng and friends
  libpng-dev        # PNG output
  libcjson-dev      # glint's JSON scene format
  zlib1g-dev        # .gz meshes
  libcmocka-dev     # the unit-test framework
  libopenexr-dev    # linear film output as .exr (OpenEXRCore)
  gnuplot-nox       # glint bench --plot
  clang             # the fuzz targets (libFuzzer)
  clang-format      # the format test (tests/format.sh)
  libclang-rt-14-dev # libFuzzer and clang's sanitizer runtimes
  libsdl2-dev       # glint view's window
  xvfb              # a display for the window test
  xdotool           # keys and mouse for the window test
  libopenmpi-dev    # glint-mpi (Open MPI)
  openmpi-bin       # mpirun, for glint-mpi and its test
  iproute2          # network namespaces: glint-mpi's test across hosts
)
if [ "${1:-}" = "--peers" ]; then
  packages+=(
    tachyon-bin-nox # glint bench --spd times Tachyon on the same files
    libembree-dev   # glint-embree-bench, for glint bench --meshes
    libassimp-dev   # glint-mesh-load-bench
  )
elif [ $# -gt 0 ]; then
  echo "usage: $0 [--peers]" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "install-deps: missing packages ${missing[*]}; run as root:" >&2
  echo "  apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
# Another install running holds the package manager's lock: wait for it (up
# to 10 minutes) instead of failing.
lock=(-o DPkg::Lock::Timeout=600)
"${sudo[@]}" apt-get "${lock[@]}" update -q
"${sudo[@]}" apt-get "${lock[@]}" install -y -q --no-install-recommends \
  "${missing[@]}"
