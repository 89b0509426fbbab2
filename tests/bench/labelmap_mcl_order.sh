#!/bin/bash
# Linear against 10-node tets on a ligament from a label map: the female HRA knee's femur, tibia
# and MCL voxelized into a label map at 0.3 x 0.3 x 1 mm (`ligsim labelmap`), built with
# `ligsim build --labels` and nothing else (the MCL's footprints from its name), once at the
# defaults and once with `--order 2`, each flexed by `ligsim flexion` with no config; one run
# after the other. Prints, as Markdown for tests/bench/record.sh, each build's tets and cell
# size, its build and flexion seconds, and its femur force, regional peak, strain energy and
# length change with their error estimates. Not a test: run it by hand (about 6 minutes on 2
# cores).
#
#   tests/bench/labelmap_mcl_order.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

cd "$SRC"
rm -f "$OUT"/*.times
knee=data/hra-knee/VH_F_Knee_L.glb
mcl="data/hra-knee/VH_F_Ligaments_Knee_L.glb#VH_F_left_tibial_collateral_ligament"
run labelmap "$LIGSIM" labelmap --part "$knee#VH_F_femur_L:1:femur" \
  --part "$knee#VH_F_tibia_L:2:tibia" --part "$mcl:3:MCL" --around "$mcl" --margin 40 \
  --spacing 0.3 0.3 1 --out "$OUT/seg.nrrd"
for order in 1 2; do
  flags=()
  [ "$order" = 1 ] || flags=(--order "$order") # order 1: the defaults, no flag
  run "build_$order" "$LIGSIM" build --labels "$OUT/seg.nrrd" "${flags[@]}" \
    --out "$OUT/order_$order" --force --no-images
  run "flexion_$order" "$LIGSIM" flexion --model "$OUT/order_$order" \
    --out "$OUT/flexion_$order" --no-images
done

python3 - "$OUT" <<'EOF'
import csv, json, sys
from pathlib import Path

out = Path(sys.argv[1])
def seconds(name):
    return float((out / f"{name}.times").read_text().split()[0])
print("| build | tets | cell size (mm) | build s | flexion s | femur force at 0 / 30 / 60 / 90 "
      "degrees (N) | over 2 mm at 90 | strain energy at 90 | length change at 90 |")
print("| --- | ---: | ---: | ---: | ---: | --- | --- | ---: | ---: |")
for order, label in (("1", "defaults (linear)"), ("2", "`--order 2` (10-node)")):
    stages = json.loads((out / f"order_{order}" / "MCL" / "summary.json").read_text())["stages"]
    tets = stages["model"]["figures"]["tets"]
    cell = stages["tetmesh"]["figures"]["used"]["cell_size_mm"]
    with open(out / f"flexion_{order}" / "flexion.csv") as f:
        rows = {float(r["angle_deg"]): r for r in csv.DictReader(f)}
    forces = " / ".join(f"{float(rows[a]['femur_force_n']):.1f} +- "
                        f"{float(rows[a]['femur_force_error_n']):.1f}" for a in (0, 30, 60, 90))
    r = rows[90.0]
    print(f"| {label} | {tets:,} | {cell:.2f} | {seconds(f'build_{order}'):.1f} "
          f"| {seconds(f'flexion_{order}'):.1f} | {forces} "
          f"| {100 * float(r['max_regional_fiber_strain']):.1f} +- "
          f"{100 * float(r['max_regional_fiber_strain_error']):.1f} % "
          f"| {float(r['strain_energy_mj']):.1f} mJ | {float(r['length_change_mm']):.2f} mm |")
EOF
