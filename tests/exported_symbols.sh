#!/bin/sh
# The shared library exports exactly the functions glint.h declares: every
# defined dynamic symbol is declared there, and every declared function is
# exported. Usage: exported_symbols.sh libglint.so include/glint.h
lib=$1
header=$2
syms=$(nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}')
if [ -z "$syms" ]; then
  echo "$lib exports nothing"
  exit 1
fi
status=0
for s in $syms; do
  if ! grep -qw -- "$s" "$header"; then
    echo "exported but not declared in glint.h: $s"
    status=1
  fi
done
for f in $(grep -oE '\bglint_[a-z0-9_]+\(' "$header" | tr -d '(' | sort -u); do
  if ! printf '%s\n' "$syms" | grep -qx -- "$f"; then
    echo "declared in glint.h but not exported: $f"
    status=1
  fi
done
[ $status -eq 0 ] && echo "$(printf '%s\n' "$syms" | wc -l) symbols, all from glint.h"
exit $status
