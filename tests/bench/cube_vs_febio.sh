#!/bin/bash
# Whole-process wall time and peak memory of the paper's cube, case par_t020_pen, side by side:
# FEBio 4 (2 threads, the input tests/bench/febio_cube.py writes) against
# `ligsim verify cube --cases par_t020_pen` (its two solves, matched and paper energy), and an
# earlier ligsim binary when BEFORE is given. ROUNDS rounds, each running every program once in
# turn (interleaved, so all see the same machine load); medians of wall time and peak resident
# memory (/usr/bin/time), the ratios to FEBio, and the load average before and after. Not a
# test: run it by hand (about half a minute per round; `nice` it on a shared machine).
#
#   tests/bench/cube_vs_febio.sh OUT [ROUNDS]       (default 3 rounds)
#   FEBIO=path/to/febio4 (default ../shared/tools/febio/bin/febio4 beside the checkout),
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim), BEFORE=path/to/an/older/ligsim.
set -euo pipefail
OUT=$1
ROUNDS=${2:-3}
# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
FEBIO=${FEBIO:-$SRC/../shared/tools/febio/bin/febio4}
BEFORE=${BEFORE:-}
if [ ! -x "$FEBIO" ]; then
  echo "cube_vs_febio.sh: no FEBio executable at $FEBIO (set FEBIO)" >&2
  exit 2
fi
"$SRC/tests/bench/febio_cube.py" par_t020_pen "$OUT/cube.feb"

rm -f "$OUT"/*.times
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for _ in $(seq "$ROUNDS"); do
  (cd "$OUT" && run febio env OMP_NUM_THREADS=2 "$FEBIO" -i cube.feb -silent)
  grep -q "N O R M A L" "$OUT/cube.log" ||
    { echo "cube_vs_febio.sh: FEBio did not terminate normally, see $OUT/cube.log" >&2; exit 1; }
  (cd "$SRC" && run ligsim "$LIGSIM" verify cube --cases par_t020_pen --out "$OUT/ligsim")
  if [ -n "$BEFORE" ]; then
    (cd "$SRC" && run before "$BEFORE" verify cube --cases par_t020_pen --out "$OUT/before")
  fi
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

febio_wall=$(cut -d' ' -f1 "$OUT/febio.times" | median)
febio_mib=$(cut -d' ' -f2 "$OUT/febio.times" | median | awk '{print $1 / 1024}')
printf "| program | wall s (median of %d) | peak MiB | FEBio's wall / this |\n" "$ROUNDS"
printf "| --- | ---: | ---: | ---: |\n"
printf "| FEBio 4 | %.2f | %.0f | 1 |\n" "$febio_wall" "$febio_mib"
for name in ligsim before; do
  [ -f "$OUT/$name.times" ] || continue
  wall=$(cut -d' ' -f1 "$OUT/$name.times" | median)
  mib=$(cut -d' ' -f2 "$OUT/$name.times" | median | awk '{print $1 / 1024}')
  printf "| %s | %.2f | %.0f | %.1f |\n" "$name" "$wall" "$mib" "$(echo "$febio_wall / $wall" | bc -l)"
done
