#!/bin/bash
# The live window against the quasi-static sweep: each model is built, swept quasi-statically to
# 90 degrees (`ligsim flexion --angles 0,90`), and dragged there in `ligsim view` by a script
# (0 -> 90 degrees in 2 s, a 1 s hold: 300 frames of 10 ms), every frame recorded. The models
# are those of the ViewCli tests (the shipped VHF MCL, the HRA female MCL as linear tets of
# 1.5 mm, the four-ligament HRA knee built for live use) and the HRA female MCL as linear tets
# of 0.6 mm, too slow for the test suite; one run after the other. Prints, as Markdown for
# tests/bench/record.sh, each ligament's femur force and peak fiber strain over 2 mm in the
# last frame and in the sweep at 90 degrees, and the frames computed per second. Then what the
# live knee's mesh costs: the shipped knee (data/hra-knee/knee.toml as it is) and the live one
# swept 0-120 degrees, each ligament's whole pull on the femur and regional peak side by side.
# The sweeps leave out the error estimate's companion solve: no table prints it.
# Not a test: run it by hand (about 25 minutes on 2 cores). Needs xvfb-run unless $DISPLAY is
# set.
#
#   tests/bench/view_vs_sweep.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

cd "$SRC"
rm -f "$OUT"/*.times
printf "time_s,angle_deg\n0,0\n2,90\n3,90\n" >"$OUT/drag.csv"
screen=()
[ -n "${DISPLAY:-}" ] || screen=(xvfb-run -a -s "-screen 0 1280x1024x24")

# name | build flags | flexion config | window size (none: not viewed) | sweep angles
models=(
  "vhf-mcl|--config data/vhf-right-knee/mcl.toml|data/vhf-right-knee/flexion.toml|320|0,90"
  "hra-mcl-1.5|--config data/hra-knee/mcl-female.toml --cell-size 1.5 --facet-size 1.5 --order 1|data/hra-knee/flexion.toml|320|0,90"
  "hra-mcl-0.6|--config data/hra-knee/mcl-female.toml --cell-size 0.6 --facet-size 0.6 --order 1|data/hra-knee/flexion.toml|640|0,90"
  "knee-live|--config data/hra-knee/knee.toml --cell-size 2.5 --facet-size 2.5 --facet-distance 0.3|data/hra-knee/flexion.toml|320|0,30,60,90,120"
  "knee-shipped|--config data/hra-knee/knee.toml|data/hra-knee/flexion.toml||0,30,60,90,120"
)
: >"$OUT/models.txt.new"
for entry in "${models[@]}"; do
  IFS='|' read -r name flags config size angles <<<"$entry"
  # shellcheck disable=SC2086 # the build flags are words
  run "build_$name" "$LIGSIM" build $flags --no-images --force --out "$OUT/$name"
  run "sweep_$name" "$LIGSIM" flexion --config "$config" --model "$OUT/$name" --angles "$angles" \
    --no-images --no-error-estimate --out "$OUT/sweep_$name"
  [ -n "$size" ] || continue
  rm -rf "$OUT/view_$name"
  run "view_$name" "${screen[@]}" "$LIGSIM" view --config "$config" --model "$OUT/$name" \
    --script "$OUT/drag.csv" --record "$OUT/view_$name" --size "$size"
  echo "$name|$flags|$size" >>"$OUT/models.txt.new"
done
mv "$OUT/models.txt.new" "$OUT/models.txt"

python3 - "$OUT" <<'EOF'
import csv, json, re, sys
from pathlib import Path

out = Path(sys.argv[1])
print("| model (build flags) | tets | ligament | femur force, last frame / sweep (N) "
      "| over 2 mm, last frame / sweep (%) | frames computed per s (window) |")
print("| --- | ---: | --- | --- | --- | ---: |")
for line in (out / "models.txt").read_text().splitlines():
    name, flags, size = line.split("|")
    stages = json.loads((out / name / "summary.json").read_text())["stages"]
    tets = sum(s["figures"]["tets"] for key, s in stages.items()
               if key.split("/")[-1] == "model" and "companion" not in key.split("/"))
    sweep = json.loads((out / f"sweep_{name}" / "summary.json").read_text())["results"]
    with open(out / f"view_{name}" / "frames.csv") as f:
        last = list(csv.DictReader(f))[-1]
    computed = re.search(r"([0-9.]+) computed",
                         (out / f"view_{name}.out").read_text()).group(1)
    first = True
    for ligament, figures in sweep["ligaments"].items():
        [at_90] = [a for a in figures["angles"] if a["angle_deg"] == 90.0]
        model = f"{name} (`{flags}`)" if first else ""
        print(f"| {model} | {f'{tets:,}' if first else ''} | {ligament} "
              f"| {float(last[ligament + '_femur_force_n']):.1f} / "
              f"{at_90['femur_force_magnitude_n']:.1f} "
              f"| {float(last[ligament + '_regional_peak_pct']):.2f} / "
              f"{100 * at_90['max_regional_fiber_strain']:.2f} "
              f"| {f'{computed} ({size} px wide)' if first else ''} |")
        first = False

def sweep_rows(name):
    with open(out / f"sweep_{name}" / "flexion.csv") as f:
        return {(r["ligament"], float(r["angle_deg"])): r for r in csv.DictReader(f)}


shipped, live = sweep_rows("knee-shipped"), sweep_rows("knee-live")
angles = sorted({angle for _, angle in shipped})


def per_ligament_and_angle(caption, cell):
    """A table of cell(shipped row, live row) per ligament and angle."""
    print()
    print(caption)
    print()
    print("| ligament | " + " | ".join(f"{a:g} deg" for a in angles) + " |")
    print("| --- |" + " --- |" * len(angles))
    for ligament in dict.fromkeys(name for name, _ in shipped):
        cells = [cell(shipped[(ligament, a)], live[(ligament, a)]) for a in angles]
        print(f"| {ligament} | " + " | ".join(cells) + " |")


per_ligament_and_angle(
    "What the live knee's mesh costs: each ligament's whole pull on the femur "
    "(`femur_net_force_n`, N) and its peak over 2 mm regions (%), shipped / live, both swept "
    "quasi-statically on `data/hra-knee/flexion.toml`'s path:",
    lambda a, b: (f"{float(a['femur_net_force_n']):.1f} / {float(b['femur_net_force_n']):.1f} N, "
                  f"{100 * float(a['max_regional_fiber_strain']):.1f} / "
                  f"{100 * float(b['max_regional_fiber_strain']):.1f} %"))
per_ligament_and_angle(
    "The overlay shows each femoral footprint's force (`femur_force_n`), not the whole pull: "
    "footprint / whole pull (N), shipped; live:",
    lambda a, b: (f"{float(a['femur_force_n']):.1f} / {float(a['femur_net_force_n']):.1f}; "
                  f"{float(b['femur_force_n']):.1f} / {float(b['femur_net_force_n']):.1f}"))
EOF
