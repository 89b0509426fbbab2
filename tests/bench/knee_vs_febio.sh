#!/bin/bash
# Each ligament of the HRA female knee swept by ligsim and by FEBio 4 on the same problem
# (`ligsim verify febio`: the ligament's own material and in-situ strain, the prescribed passive
# path of data/hra-knee/flexion.toml): contact off at 0-90 degrees for every ligament (the
# material, the fibers, the in-situ strain and the rigid motion on the real job), then the MCL
# with contact on at 0-30 degrees (the two contact laws). Prints each comparison's table as
# Markdown: tests/bench/record.sh writes it as docs/validation/knee-vs-febio.md.
#
#   tests/bench/knee_vs_febio.sh OUT [CELL_MM]     (CELL_MM default 1.2)
#   FEBIO=path/to/febio4 (default ../shared/tools/febio/bin/febio4 beside the checkout),
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1
cell=${2:-1.2}

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
FEBIO=${FEBIO:-$SRC/../shared/tools/febio/bin/febio4}
[ -x "$FEBIO" ] || { echo "knee_vs_febio.sh: no FEBio executable at $FEBIO (set FEBIO)" >&2; exit 2; }

run build "$LIGSIM" build --config "$SRC/data/hra-knee/knee.toml" --out "$OUT/knee" \
  --cell-size "$cell" --facet-size "$cell" --no-images
echo "The female knee of \`data/hra-knee/knee.toml\` built with \`--cell-size $cell --facet-size $cell\`;"
echo "each ligament swept on the prescribed passive path of \`data/hra-knee/flexion.toml\`."
echo "FEBio's energy and fiber stretch are its node positions measured by ligsim's law; the"
echo "whole-run times include ligsim's building of the bones' distance grids."

compare() {
  name=$1
  title=$2
  shift 2
  run "$name" "$LIGSIM" verify febio --config "$SRC/data/hra-knee/flexion.toml" \
    --febio "$FEBIO" --out "$OUT/$name" "$@"
  echo
  echo "## $title"
  echo
  sed -n '/^| angle/,$p' "$OUT/$name/febio_comparison.md"
}

# One step per 10 degrees (FEBio stops on the MCL's 30-degree steps, with negative Jacobians
# after its time step's retries, where ours converges), and per 5 degrees for the LCL (on
# 30-degree steps FEBio stopped between 0 and 30 degrees).
for ligament in MCL ACL PCL; do
  compare "$ligament-off" "$ligament, contact off" --model "$OUT/knee/$ligament" --contact off \
    --angles 0,10,20,30,40,50,60,70,80,90
done
compare LCL-off "LCL, contact off (5-degree steps)" --model "$OUT/knee/LCL" --contact off \
  --angles 0,5,10,15,20,25,30,35,40,45,50,55,60,65,70,75,80,85,90
compare MCL-on "MCL, contact on (ligsim's barrier at d_hat 0.01 mm, FEBio's penalty scaled by 10)" \
  --model "$OUT/knee/MCL" --contact on --angles 0,10,20,30
