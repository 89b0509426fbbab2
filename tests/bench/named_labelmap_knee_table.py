#!/usr/bin/env python3
"""Tables of tests/bench/named_labelmap_knee.sh: what each label was taken for, and the free
knee's path and ligaments per angle (kinematics.csv, flexion.csv)."""
import csv
import json
import sys
from pathlib import Path

knee, flexion = Path(sys.argv[1]), Path(sys.argv[2])


def table(name):
    with open(flexion / name) as f:
        return list(csv.DictReader(f))


found = json.loads((knee / "summary.json").read_text())["results"]["found_by_name"]
print("| label | names | taken for |")
print("| ---: | --- | --- |")
for label in found["labels"]:
    print(f"| {label['label']} | {', '.join(label['names'])} | {label['taken_for']} |")
print()

path = table("kinematics.csv")
rows = table("flexion.csv")
ligaments = list(dict.fromkeys(r["ligament"] for r in rows))
angles = [float(r["angle_deg"]) for r in path]


def cell(name, angle, column, form):
    row = next(r for r in rows if r["ligament"] == name and float(r["angle_deg"]) == angle)
    return form.format(float(row[column]))


def per_ligament(column, form, angle):
    return " / ".join(cell(name, angle, column, form) for name in ligaments)


lines = [
    ("converged", lambda r, a: r["converged"]),
    ("internal rotation (deg)", lambda r, a: f"{float(r['internal_rotation_deg']):.1f}"),
    ("varus (deg)", lambda r, a: f"{float(r['varus_deg']):.1f}"),
    ("medial / lateral contact (N)",
     lambda r, a: f"{float(r['medial_contact_force_n']):.0f} / {float(r['lateral_contact_force_n']):.0f}"),
    ("medial / lateral contact centre, anterior (mm)",
     lambda r, a: f"{float(r['medial_contact_anterior_mm']):.1f} / "
                  f"{float(r['lateral_contact_anterior_mm']):.1f}"),
    ("residual force on the femur (N)", lambda r, a: r["residual_force_n"]),
    (f"pull on the femur (N), {' / '.join(ligaments)}",
     lambda r, a: per_ligament("femur_net_force_n", "{:.0f}", a)),
    (f"regional peak (%), {' / '.join(ligaments)}",
     lambda r, a: per_ligament("max_regional_fiber_strain", "{:.1%}", a).replace("%", "")),
    (f"one element's peak (%), {' / '.join(ligaments)}",
     lambda r, a: per_ligament("max_fiber_strain", "{:.1%}", a).replace("%", "")),
    (f"length change (mm), {' / '.join(ligaments)}",
     lambda r, a: per_ligament("length_change_mm", "{:.2f}", a)),
    ("deepest free node in a bone (mm)",
     lambda r, a: f"{max(float(cell(n, a, 'max_penetration_mm', '{}')) for n in ligaments):.2f}"),
]
print("| angle (deg) | " + " | ".join(f"{a:g}" for a in angles) + " |")
print("| --- |" + " ---: |" * len(angles))
for label, value in lines:
    print(f"| {label} | " + " | ".join(value(r, a) for r, a in zip(path, angles)) + " |")
