#!/bin/bash
# What the interactive mode's Newton iterations buy (docs/flexion.md): the HRA female MCL as
# linear tets of 0.6 mm (data/hra-knee/mcl-female.toml with --order 1) swept 0-120 degrees
# quasi-statically and interactively with up to 12 solves a frame (the default) and with 4; the
# 6,141-tet VHF MCL (data/vhf-right-knee/mcl.toml, the view-fps mesh) swept interactively with
# one solve a frame (the paper's scheme) and with up to 12. One run after the other. Prints, as
# Markdown for tests/bench/record.sh, the femur force per angle, the frames that met their
# equation, the implicit Euler steps in all, the frames per second and the sweeps' wall seconds. Not a test: run it by hand
# (about 15 minutes on 2 cores).
#
#   tests/bench/interactive_iterations.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

cd "$SRC"
rm -f "$OUT"/*.times
angles=0,30,60,90,120
run build_hra "$LIGSIM" build --config data/hra-knee/mcl-female.toml --cell-size 0.6 \
  --facet-size 0.6 --order 1 --no-images --force --out "$OUT/hra"
run build_vhf "$LIGSIM" build --config data/vhf-right-knee/mcl.toml --cell-size 1.1 \
  --facet-size 0.95 --facet-distance 0.08 --no-images --force --out "$OUT/vhf"

hra=(flexion --model "$OUT/hra" --config data/hra-knee/flexion.toml --angles "$angles"
  --no-images --no-error-estimate)
vhf=(flexion --model "$OUT/vhf" --config data/vhf-right-knee/flexion.toml --no-images
  --no-error-estimate --mode interactive)
run hra_static "$LIGSIM" "${hra[@]}" --out "$OUT/hra_static"
run hra_12 "$LIGSIM" "${hra[@]}" --mode interactive --out "$OUT/hra_12"
run hra_4 "$LIGSIM" "${hra[@]}" --mode interactive --set interactive.max_iterations=4 \
  --out "$OUT/hra_4"
# The first sweep of a model also builds the bones' contact grids into its folder (contact/,
# reused after: 11 s against 3 here); warm up once so both runs compared find them built.
run vhf_warm_up "$LIGSIM" "${vhf[@]}" --out "$OUT/vhf_warm_up"
run vhf_1 "$LIGSIM" "${vhf[@]}" --set interactive.max_iterations=1 --out "$OUT/vhf_1"
run vhf_12 "$LIGSIM" "${vhf[@]}" --out "$OUT/vhf_12"

python3 - "$OUT" <<'EOF'
import csv, json, sys
from pathlib import Path

out = Path(sys.argv[1])


def rows(run):
    with open(out / run / "flexion.csv") as f:
        return list(csv.DictReader(f))


def wall_s(run):
    return float((out / f"{run}.times").read_text().split()[0])


def tets(model):
    return json.loads((out / model / "summary.json").read_text())["stages"]["model"]["figures"]["tets"]


def fps(run):
    results = json.loads((out / run / "summary.json").read_text())["results"]
    return f"{results['frames_per_second']:.3g}" if "frames_per_second" in results else ""


runs = [("hra", "hra_static", "quasi-static"),
        ("hra", "hra_12", "interactive, up to 12 solves a frame (default)"),
        ("hra", "hra_4", "interactive, up to 4 solves a frame"),
        ("vhf", "vhf_1", "interactive, 1 solve a frame (the paper's scheme)"),
        ("vhf", "vhf_12", "interactive, up to 12 solves a frame (default)")]
print("Femur force (footprint, N) at each angle swept; converged: the rows whose frame met its "
      "equation (quasi-static: whose pose converged); steps: the implicit Euler steps of the "
      "whole sweep, a frame done again in halves counting each half (flexion.csv's "
      "`newton_iterations` in this mode).")
print()
print("| MCL (tets) | sweep | femur force per angle (N) | converged | steps | frames per s "
      "| wall s |")
print("| --- | --- | --- | ---: | ---: | ---: | ---: |")
for model, run, label in runs:
    r = rows(run)
    forces = " / ".join(f"{float(x['femur_force_n']):.1f} at {float(x['angle_deg']):g}" for x in r)
    converged = sum(int(x["converged"]) for x in r)
    name = "HRA female, linear 0.6 mm" if model == "hra" else "VHF, 1.1 mm"
    steps = f"{sum(int(x['newton_iterations']) for x in r):,}" if fps(run) else ""
    print(f"| {name} ({tets(model):,}) | {label} | {forces} | {converged} of {len(r)} "
          f"| {steps} | {fps(run)} | {wall_s(run):.0f} |")
EOF
