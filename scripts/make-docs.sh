#!/usr/bin/env bash
# Regenerates the pictures in docs/ from the current build:
#   scripts/make-docs.sh           the scene pictures and the highlight crops
#   scripts/make-docs.sh --bench   also the benchmark CSV and plots (minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
glint=build/glint
[ -x "$glint" ] || { echo "make-docs: build first (make build)" >&2; exit 1; }

"$glint" render whitted -b scalar-double -q -o docs/whitted.png
for s in giza billiard phong; do
  "$glint" render "$s" -b scalar-double -W 320 -H 240 -q -o "docs/$s.png"
done

# Thesis figure 5.7: the Whitted highlight under each pow/exp variant, and
# without the Newton step after rcp, from the 4-wide SSE beams.
region=256,144,128,96
for m in minimax taylor fast exact; do
  "$glint" render whitted -b sse --math "$m" --region "$region" -q \
    -o "docs/highlight-$m.png"
done
"$glint" render whitted -b sse --no-newton --region "$region" -q \
  -o docs/highlight-no-newton.png

# The README's Tachyon comparison pictures (when Tachyon is installed).
if command -v tachyon >/dev/null 2>&1; then
  mkdir -p docs/tachyon
  for s in rings-s4 gears-s4; do
    "$glint" render "../shared/scenes/spd/$s.nff" -W 256 -H 256 -s 1 -q \
      -o "docs/tachyon/$s-glint.png"
    tachyon "../shared/scenes/spd/$s.nff" -res 256 256 -raydepth 5 \
      -shade_phong -format PNG -o "docs/tachyon/$s-tachyon.png" >/dev/null
  done
fi

if [ "${1:-}" = "--bench" ]; then
  "$glint" bench --depths 1-15 --runs 3 --csv docs/bench.csv --plot docs/plots \
    | tee docs/bench.txt
fi
