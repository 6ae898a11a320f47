#!/bin/sh
# Every C source of the tree is as clang-format writes it (.clang-format).
# Formatting differs between clang-format releases, so the check runs with
# Debian 12's, release 14 (scripts/install-deps.sh), and reports SKIPPED
# (77) without it. Generated tables (*.inc) are left as their generators
# write them. Usage: format.sh SOURCE_DIR
root=$1
command -v clang-format >/dev/null 2>&1 || {
  echo "SKIPPED: no clang-format"
  exit 77
}
version=$(clang-format --version | sed -n 's/.*version \([0-9]*\)\..*/\1/p')
if [ "$version" != 14 ]; then
  echo "SKIPPED: clang-format $version, not 14"
  exit 77
fi
files=$(find "$root/include" "$root/src" "$root/cli" "$root/tests" \
  "$root/tools" "$root/examples" "$root/fuzz" -name '*.[ch]' | sort)
if ! clang-format --dry-run --Werror $files; then
  echo "run: clang-format -i on the files above"
  exit 1
fi
echo "$(echo "$files" | wc -l) files formatted"
