#!/bin/sh
# Installs the build into a fresh prefix and uses it as a C developer would:
# examples/orbit.c compiled through pkg-config (shared, then static) and
# through a two-line CMake project with find_package(glint 0.5), each run.
set -eu
build=$1 source=$2
work=$(mktemp -d /tmp/glint-install-XXXXXX)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
libdir=$(dirname "$(find "$prefix" -name libglint.a)")
for f in include/glint.h bin/glint share/man/man1/glint.1 \
         share/man/man5/glint-scene.5; do
  [ -e "$prefix/$f" ] || { echo "FAILED: $f was not installed"; exit 1; }
done
for f in libglint.so libglint.so.0 libglint.so.0.5.0 pkgconfig/glint.pc \
         cmake/glint/glintConfig.cmake cmake/glint/glintConfigVersion.cmake; do
  [ -e "$libdir/$f" ] || { echo "FAILED: $f was not installed"; exit 1; }
done
[ "$(readlink "$libdir/libglint.so.0")" = libglint.so.0.5.0 ] ||
  { echo "FAILED: libglint.so.0 does not point at libglint.so.0.5.0"; exit 1; }
echo "installed: $(cd "$prefix" && find . -type f -o -type l | sort | tr '\n' ' ')"

export PKG_CONFIG_PATH=$libdir/pkgconfig
# shared, through pkg-config
cc -o "$work/orbit-pc" "$source/examples/orbit.c" \
  $(pkg-config --cflags --libs glint) -lm
LD_LIBRARY_PATH=$libdir "$work/orbit-pc" whitted 2 "$work/pc.png"
# static, through pkg-config --static
cc -o "$work/orbit-static" "$source/examples/orbit.c" \
  $(pkg-config --cflags glint) "$(pkg-config --variable=libdir glint)/libglint.a" \
  $(pkg-config --static --libs glint | sed 's/-lglint//') -lm
if ldd "$work/orbit-static" | grep -q libglint; then
  echo "FAILED: the static build links libglint.so"
  exit 1
fi
"$work/orbit-static" whitted 2 "$work/static.png"
# CMake: find_package(glint 0.5 REQUIRED), glint::glint
mkdir "$work/project"
cp "$source/examples/orbit.c" "$work/project/"
cat > "$work/project/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.20)
project(uses_glint C)
find_package(glint 0.5 REQUIRED)
add_executable(orbit orbit.c)
target_link_libraries(orbit PRIVATE glint::glint m)
add_executable(orbit_static orbit.c)
target_link_libraries(orbit_static PRIVATE glint::glint_static m)
CMAKE
cmake -S "$work/project" -B "$work/project/build" \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/project/build" >/dev/null
"$work/project/build/orbit" whitted 2 "$work/cmake.png"
"$work/project/build/orbit_static" whitted 2 "$work/cmake-static.png"
for f in static.png cmake.png cmake-static.png; do
  cmp -s "$work/pc.png" "$work/$f" ||
    { echo "FAILED: $f differs from pc.png"; exit 1; }
done
# 0.x: a package of 0.5 does not satisfy a request for 0.6.
sed -i 's/glint 0.5 REQUIRED/glint 0.6 REQUIRED/' "$work/project/CMakeLists.txt"
if cmake -S "$work/project" -B "$work/project/build6" \
     -DCMAKE_PREFIX_PATH="$prefix" >/dev/null 2>&1; then
  echo "FAILED: find_package(glint 0.6) accepted 0.5"
  exit 1
fi
echo "PASSED: pkg-config (shared and static) and find_package builds run"
