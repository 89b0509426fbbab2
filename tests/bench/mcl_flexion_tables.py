#!/usr/bin/env python3
"""Tables of one ligament's flexion from its build and flexion folders (summary.json,
flexion.csv), for tests/bench/hra_mcls.sh: each model's size and cost, then per model its fiber
strain, pull on the femur and length change per angle with their error estimates, as Markdown.

  mcl_flexion_tables.py (LABEL MODEL_DIR FLEXION_DIR BUILD_TIMES FLEXION_TIMES)...
"""
import csv
import json
import sys
from pathlib import Path


def times(file):
    """Wall seconds and peak MiB of the one run /usr/bin/time recorded in `file`."""
    wall_s, peak_kib = Path(file).read_text().split()[:2]
    return float(wall_s), float(peak_kib) / 1024


def cost_table(runs):
    print("| model | tets, nodes | companion: tets, elements as large | build s (peak MiB) "
          "| sweep s (peak MiB) | angles converged | deepest free node in a bone (mm) |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: |")
    for label, model, flexion, build_times, flexion_times in runs:
        summary = json.loads((Path(model) / "summary.json").read_text())
        stages, companion = summary["stages"], summary["results"]["companion"]
        mesh = stages["model"]["figures"]
        build_s, build_mib = times(build_times)
        sweep_s, sweep_mib = times(flexion_times)
        companion_text = (f"{stages['companion/model']['figures']['tets']:,}, "
                          f"{companion['size_ratio']:.2f} times" if companion["built"]
                          else "not built")
        rows = rows_of(flexion)
        converged = sum(int(r["converged"]) for r in rows)
        deepest = max(float(r["max_penetration_mm"]) for r in rows)
        print(f"| {label} | {mesh['tets']:,}, {mesh['nodes']:,} | {companion_text} "
              f"| {build_s:.0f} ({build_mib:.0f}) | {sweep_s:.0f} ({sweep_mib:.0f}) "
              f"| {converged} of {len(rows)} | {deepest:.2g} |")
    print()


def rows_of(flexion):
    with open(Path(flexion) / "flexion.csv") as f:
        return list(csv.DictReader(f))


def percent(fraction):
    return f"{100 * float(fraction):.1f} %"


def share(fraction):
    """A share of the volume, in percent ("0" for none)."""
    return f"{100 * float(fraction):.2g} %" if float(fraction) else "0"


def angle_table(label, flexion):
    print(f"{label}; +- is the error estimate (the companion's difference, "
          "docs/flexion.md#the-error-estimate):")
    print()
    print("| angle (deg) | mean fiber strain | max fiber strain (one element) "
          "| max over 2 mm regions | volume beyond the failure strain | femur force (N) "
          "| length change |")
    print("| ---: | ---: | ---: | --- | ---: | --- | --- |")
    for r in rows_of(flexion):
        regional = (f"{100 * float(r['max_regional_fiber_strain']):.1f} +- "
                    f"{100 * float(r['max_regional_fiber_strain_error']):.2g} %")
        force = f"{float(r['femur_force_n']):.1f} +- {float(r['femur_force_error_n']):.1f}"
        length = (f"{float(r['length_change_pct']):.1f} % ({float(r['length_change_mm']):.2f} mm)"
                  if float(r["angle_deg"]) != 0 else "0")
        print(f"| {float(r['angle_deg']):g} | {percent(r['mean_fiber_strain'])} "
              f"| {percent(r['max_fiber_strain'])} | {regional} "
              f"| {share(r['volume_beyond_failure_strain'])} | {force} | {length} |")
    print()


def main(args):
    if not args or len(args) % 5:
        sys.exit(__doc__)
    runs = [args[i:i + 5] for i in range(0, len(args), 5)]
    cost_table(runs)
    for label, _, flexion, _, _ in runs:
        angle_table(label, flexion)


if __name__ == "__main__":
    main(sys.argv[1:])
