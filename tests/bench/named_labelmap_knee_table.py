#!/usr/bin/env python3
"""Tables of tests/bench/named_labelmap_knee.sh: what each label was taken for; each knee's cost
and estimated error; each knee's path and ligaments per angle (kinematics.csv, flexion.csv).

  named_labelmap_knee_table.py KNEE (LABEL FLEXION BUILD_S SWEEP_S)...
"""
import csv
import json
import sys
from pathlib import Path

knee = Path(sys.argv[1])
runs = [(sys.argv[i], Path(sys.argv[i + 1]), sys.argv[i + 2], sys.argv[i + 3])
        for i in range(2, len(sys.argv), 4)]


def table(flexion, name):
    with open(flexion / name) as f:
        return list(csv.DictReader(f))


found = json.loads((knee / "summary.json").read_text())["results"]["found_by_name"]
print("| label | names | taken for |")
print("| ---: | --- | --- |")
for label in found["labels"]:
    print(f"| {label['label']} | {', '.join(label['names'])} | {label['taken_for']} |")
print()

print("Each ligament's largest estimated error of its femoral footprint's force, as a share of "
      "that force, over the angles (the companion's +-, docs/flexion.md#the-error-estimate):")
print()
print("| elements | build s | sweep s (with the estimate) | MCL | LCL | ACL | PCL |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for label, flexion, build_s, sweep_s in runs:
    rows = table(flexion, "flexion.csv")
    shares = []
    for name in ["MCL", "LCL", "ACL", "PCL"]:
        share = max(float(r["femur_force_error_n"]) / float(r["femur_force_n"])
                    for r in rows if r["ligament"] == name)
        shares.append(f"{share:.0%}")
    print(f"| {label} | {build_s} | {float(sweep_s):.0f} | " + " | ".join(shares) + " |")
print()

for label, flexion, _, _ in runs:
    path = table(flexion, "kinematics.csv")
    rows = table(flexion, "flexion.csv")
    ligaments = list(dict.fromkeys(r["ligament"] for r in rows))
    angles = [float(r["angle_deg"]) for r in path]
    names = " / ".join(ligaments)

    def value(name, angle, column):
        row = next(r for r in rows if r["ligament"] == name and float(r["angle_deg"]) == angle)
        return float(row[column])

    def each(angle, text):
        return " / ".join(text(name, angle) for name in ligaments)

    lines = [
        ("converged", lambda r, a: r["converged"]),
        ("internal rotation (deg)", lambda r, a: f"{float(r['internal_rotation_deg']):.1f}"),
        ("varus (deg)", lambda r, a: f"{float(r['varus_deg']):.1f}"),
        ("medial / lateral contact (N)",
         lambda r, a: f"{float(r['medial_contact_force_n']):.0f} / "
                      f"{float(r['lateral_contact_force_n']):.0f}"),
        ("medial / lateral contact centre, anterior (mm)",
         lambda r, a: f"{float(r['medial_contact_anterior_mm']):.1f} / "
                      f"{float(r['lateral_contact_anterior_mm']):.1f}"),
        ("residual force on the femur (N)", lambda r, a: r["residual_force_n"]),
        (f"pull on the femur (N), {names}",
         lambda r, a: each(a, lambda n, a: f"{value(n, a, 'femur_net_force_n'):.0f}")),
        (f"femoral footprint's force +- estimate (N), {names}",
         lambda r, a: each(a, lambda n, a: f"{value(n, a, 'femur_force_n'):.0f} +- "
                                           f"{value(n, a, 'femur_force_error_n'):.0f}")),
        (f"regional peak (%), {names}",
         lambda r, a: each(a, lambda n, a: f"{100 * value(n, a, 'max_regional_fiber_strain'):.1f}")),
        (f"one element's peak (%), {names}",
         lambda r, a: each(a, lambda n, a: f"{100 * value(n, a, 'max_fiber_strain'):.1f}")),
        (f"length change (mm), {names}",
         lambda r, a: each(a, lambda n, a: f"{value(n, a, 'length_change_mm'):.2f}")),
        ("deepest free node in a bone (mm)",
         lambda r, a: f"{max(value(n, a, 'max_penetration_mm') for n in ligaments):.2f}"),
    ]
    print(f"{label.capitalize()}:")
    print()
    print("| angle (deg) | " + " | ".join(f"{a:g}" for a in angles) + " |")
    print("| --- |" + " ---: |" * len(angles))
    for text, cell in lines:
        print(f"| {text} | " + " | ".join(cell(r, a) for r, a in zip(path, angles)) + " |")
    print()
