#!/bin/bash
# Does the flexion's error estimate hold the model's real discretisation error? The female HRA
# MCL as data/hra-knee/mcl-female.toml builds it (1.2 mm cells) swept 0-120 degrees by
# data/hra-knee/flexion.toml with its error estimate, against the same config at 0.9 mm cells
# swept without one; contact on, one run after the other. Prints, as Markdown for
# tests/bench/record.sh, per angle the two femur forces, their difference, the estimate and
# the ratio of the two, and the same for the peak strain over 2 mm regions. Not a test: run it
# by hand (about 15 minutes on 2 cores).
#
#   tests/bench/mcl_error_estimate.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

cd "$SRC"
rm -f "$OUT"/*.times
run build_model "$LIGSIM" build --config data/hra-knee/mcl-female.toml --out "$OUT/model" \
  --force --no-images
run sweep_model "$LIGSIM" flexion --model "$OUT/model" --out "$OUT/sweep_model" \
  --config data/hra-knee/flexion.toml --no-images
run build_fine "$LIGSIM" build --config data/hra-knee/mcl-female.toml --cell-size 0.9 \
  --out "$OUT/fine" --force --no-images
run sweep_fine "$LIGSIM" flexion --model "$OUT/fine" --out "$OUT/sweep_fine" \
  --config data/hra-knee/flexion.toml --no-images --no-error-estimate

python3 - "$OUT" <<'EOF'
import csv, json, sys
from pathlib import Path

out = Path(sys.argv[1])
def rows(name):
    with open(out / name / "flexion.csv") as f:
        return {float(r["angle_deg"]): r for r in csv.DictReader(f)}
def tets(name):
    return json.loads((out / name / "summary.json").read_text())["stages"]["model"]["figures"]["tets"]
model, fine = rows("sweep_model"), rows("sweep_fine")
ratio = json.loads((out / "model" / "summary.json").read_text())["results"]["companion"]["size_ratio"]
print(f"The model: 1.2 mm cells, {tets('model'):,} tets, its companion's elements "
      f"{ratio:.2f} times as large; the reference: 0.9 mm cells, {tets('fine'):,} tets. "
      "Contact on.")
print()
print("| angle (deg) | 1.2 mm cells (N) | 0.9 mm cells (N) | difference (N) | estimate (N) "
      "| estimate / difference | regional peak 1.2 / 0.9 mm (%) | its estimate (%) |")
print("| ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: |")
for a in sorted(model):
    m, f = model[a], fine[a]
    force, reference = float(m["femur_force_n"]), float(f["femur_force_n"])
    difference, estimate = abs(force - reference), float(m["femur_force_error_n"])
    held = f"{estimate / difference:.2g}" if difference > 0 else "-"
    print(f"| {a:g} | {force:.2f} | {reference:.2f} | {difference:.2f} | {estimate:.2f} | {held} "
          f"| {100 * float(m['max_regional_fiber_strain']):.2f} / "
          f"{100 * float(f['max_regional_fiber_strain']):.2f} "
          f"| {100 * float(m['max_regional_fiber_strain_error']):.2f} |")
EOF
