#!/bin/bash
# The female HRA MCL (data/hra-knee/mcl-female.toml: 10-node tets, 2.4 mm facets, the footprints'
# rims kept) built at each cell size given, then swept 0-120 degrees by data/hra-knee/
# flexion.toml without the error estimate, one run after the other: the tets, the sweep's wall
# time, the femur force per angle and its largest difference to the last (finest) size, the
# regional peak at 90 degrees and the bound footprint areas. Prints Markdown tables for
# tests/bench/record.sh. Not a test: run it by hand (about 15 minutes on 2 cores without contact).
#
#   tests/bench/mcl_cell_ladder.sh OUT [CELL_MM...]      (default 2.4 1.8 1.2 0.9)
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim); CONTACT=off sweeps without contact.
set -euo pipefail
OUT=$1
shift
CELLS=("$@")
[ ${#CELLS[@]} -gt 0 ] || CELLS=(2.4 1.8 1.2 0.9)

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

cd "$SRC"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
for cell in "${CELLS[@]}"; do
  rm -f "$OUT/sweep_$cell.times"
  run "build_$cell" "$LIGSIM" build --config data/hra-knee/mcl-female.toml \
    --cell-size "$cell" --out "$OUT/cell_$cell"
  run "sweep_$cell" "$LIGSIM" flexion --model "$OUT/cell_$cell" --out "$OUT/sweep_$cell" \
    --config data/hra-knee/flexion.toml --contact "$CONTACT" --no-images --no-error-estimate
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo

python3 - "$OUT" "$CONTACT" "${CELLS[@]}" <<'EOF'
import csv, json, sys

out, contact, cells = sys.argv[1], sys.argv[2], sys.argv[3:]
rows = {}
for cell in cells:
    with open(f"{out}/sweep_{cell}/flexion.csv") as f:
        rows[cell] = {float(r["angle_deg"]): r for r in csv.DictReader(f)}
finest = rows[cells[-1]]
angles = sorted(finest)
print(f"Contact {contact}. Differences are to the {cells[-1]} mm cells, the largest over the angles.")
print()
print("| cells (mm) | tets | sweep s | femur force at " + " / ".join(f"{a:g}" for a in angles)
      + " deg (N) | largest difference | regional peak at 90 deg | bound femoral / tibial (mm^2) |")
print("| ---: | ---: | ---: | --- | ---: | ---: | --- |")
for cell in cells:
    with open(f"{out}/cell_{cell}/summary.json") as f:
        stages = json.load(f)["stages"]
    tets = stages["tetmesh"]["figures"]["tets"]
    area = stages["model"]["figures"]["footprint_area_mm2"]
    with open(f"{out}/sweep_{cell}.times") as f:
        wall = float(f.read().split()[0])
    forces = [float(rows[cell][a]["femur_force_n"]) for a in angles]
    worst = max(abs(float(rows[cell][a]["femur_force_n"]) / float(finest[a]["femur_force_n"]) - 1)
                for a in angles)
    peak = 100 * float(rows[cell][90.0]["max_regional_fiber_strain"]) if 90.0 in rows[cell] else float("nan")
    print(f"| {cell} | {tets:,} | {wall:.1f} | " + " / ".join(f"{v:.2f}" for v in forces)
          + f" | {100 * worst:.1f} % | {peak:.2f} % | {area['femur']:.1f} / {area['tibia']:.1f} |")
EOF
