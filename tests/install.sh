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
# glint view's window, beside glint, when the build has it (SDL2); the
# installed glint finds it there.
if [ -x "$build/glint-view" ]; then
  [ -x "$prefix/bin/glint-view" ] ||
    { echo "FAILED: glint-view was not installed"; exit 1; }
  "$prefix/bin/glint" view --help | grep -q "Controls:" ||
    { echo "FAILED: the installed glint view does not run"; exit 1; }
fi
# glint-mpi and its manual page, when the build has MPI.
if [ -x "$build/glint-mpi" ]; then
  [ -x "$prefix/bin/glint-mpi" ] ||
    { echo "FAILED: glint-mpi was not installed"; exit 1; }
  [ -e "$prefix/share/man/man1/glint-mpi.1" ] ||
    { echo "FAILED: glint-mpi.1 was not installed"; exit 1; }
fi
[ "$(readlink "$libdir/libglint.so.0")" = libglint.so.0.5.0 ] ||
  { echo "FAILED: libglint.so.0 does not point at libglint.so.0.5.0"; exit 1; }
echo "installed: $(cd "$prefix" && find . -type f -o -type l | sort | tr '\n' ' ')"

export PKG_CONFIG_PATH=$libdir/pkgconfig
# Runs the three examples built as $1-NAME; their outputs go to $1-*.png.
run_examples() {
  LD_LIBRARY_PATH=$libdir "$1-orbit" whitted 2 "$1.png" >/dev/null
  LD_LIBRARY_PATH=$libdir "$1-build_scene" "$1-built.png" >/dev/null
  LD_LIBRARY_PATH=$libdir "$1-render_file" "$source/scenes/phong.json" \
    "$1-phong.png" >/dev/null 2>&1
}
examples="orbit build_scene render_file"
# shared, through pkg-config
for ex in $examples; do
  cc -o "$work/pc-$ex" "$source/examples/$ex.c" \
    $(pkg-config --cflags --libs glint) -lm
done
run_examples "$work/pc"
# static, through pkg-config --static
for ex in $examples; do
  cc -o "$work/static-$ex" "$source/examples/$ex.c" \
    $(pkg-config --cflags glint) "$(pkg-config --variable=libdir glint)/libglint.a" \
    $(pkg-config --static --libs glint | sed 's/-lglint//') -lm
done
if ldd "$work/static-orbit" | grep -q libglint; then
  echo "FAILED: the static build links libglint.so"
  exit 1
fi
run_examples "$work/static"
# CMake: find_package(glint 0.5 REQUIRED), glint::glint and glint_static
mkdir "$work/project"
cp "$source"/examples/*.c "$work/project/"
cat > "$work/project/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.20)
project(uses_glint C)
find_package(glint 0.5 REQUIRED)
foreach(ex orbit build_scene render_file)
  add_executable(cmake-${ex} ${ex}.c)
  target_link_libraries(cmake-${ex} PRIVATE glint::glint m)
  add_executable(cmakestatic-${ex} ${ex}.c)
  target_link_libraries(cmakestatic-${ex} PRIVATE glint::glint_static m)
endforeach()
CMAKE
cmake -S "$work/project" -B "$work/project/build" \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/project/build" >/dev/null
run_examples "$work/project/build/cmake"
run_examples "$work/project/build/cmakestatic"
for f in static.png project/build/cmake.png project/build/cmakestatic.png \
         static-built.png project/build/cmake-built.png \
         static-phong.png project/build/cmakestatic-phong.png; do
  case $f in
    *built.png) ref=pc-built.png ;;
    *phong.png) ref=pc-phong.png ;;
    *) ref=pc.png ;;
  esac
  cmp -s "$work/$ref" "$work/$f" ||
    { echo "FAILED: $f differs from $ref"; exit 1; }
done
# 0.x: a package of 0.5 does not satisfy a request for 0.6.
sed -i 's/glint 0.5 REQUIRED/glint 0.6 REQUIRED/' "$work/project/CMakeLists.txt"
if cmake -S "$work/project" -B "$work/project/build6" \
     -DCMAKE_PREFIX_PATH="$prefix" >/dev/null 2>&1; then
  echo "FAILED: find_package(glint 0.6) accepted 0.5"
  exit 1
fi
echo "PASSED: examples built through pkg-config (shared, static) and find_package (glint::glint, glint::glint_static) run alike"
