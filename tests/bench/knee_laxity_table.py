#!/usr/bin/env python3
"""Tables of tests/bench/knee_laxity.sh's runs: laxity (the change of a coordinate under a load,
from the unloaded knee at the same angle) and the ACL cut's effect on the MCL's strain."""
import csv
import functools
import json
import sys
from pathlib import Path

out = Path(sys.argv[1])


def rows(run, name):
    path = out / run / name
    if not path.exists():
        return None
    with open(path) as f:
        return list(csv.DictReader(f))


def pose(run, angle):
    table = rows(run, "kinematics.csv")
    if table is None:
        return None
    return next((r for r in table if float(r["angle_deg"]) == angle), None)


def ligament(run, name, angle):
    table = rows(run, "flexion.csv")
    if table is None:
        return None
    return next((r for r in table if r["ligament"] == name and float(r["angle_deg"]) == angle),
                None)


@functools.lru_cache(maxsize=None)
def summary_ligaments(run):
    path = out / run / "summary.json"
    return json.loads(path.read_text())["results"]["ligaments"] if path.exists() else None


def net_force(run, name, angle):
    """The ligament's whole pull on the femur: footprint and contact (flexion.csv's
    femur_net_force_n), from summary.json's vectors (runs before that column have them too)."""
    ligaments = summary_ligaments(run)
    if ligaments is None or name not in ligaments:
        return None
    for a in ligaments[name]["angles"]:
        if a["angle_deg"] == angle:
            f = [a["femur_force_n"][k] + a["contact"].get("femur", {}).get("force_n", [0, 0, 0])[k]
                 for k in range(3)]
            return sum(x * x for x in f) ** 0.5
    return None


def change(run, base, column, angle):
    a, b = pose(run, angle), pose(base, angle)
    if a is None or b is None:
        return "failed"
    return f"{float(a[column]) - float(b[column]):+.1f}"


TESTS = [  # run, load, coordinate, published at 30 degrees
    ("anterior", "100 N anterior", "anterior_mm",
     "6.0 +- 2.5 mm (90 N, 12 cadaver knees, KSSTA 2020;28:1159); 5.8 mm (Komzak 2013)"),
    ("posterior", "100 N posterior", "anterior_mm", ""),
    ("valgus", "10 N m valgus", "varus_deg",
     "valgus 2.3 +- 0.9 deg (15 N m, extension, living; Heesterbeek 2008)"),
    ("varus", "10 N m varus", "varus_deg",
     "varus 2.8 +- 1.3 deg (15 N m, extension, living; Heesterbeek 2008)"),
    ("internal", "5 N m internal", "internal_rotation_deg", "12.1 deg (Komzak 2013)"),
    ("external", "5 N m external", "internal_rotation_deg", "-10.1 deg (Komzak 2013)"),
]

print("| test | load | change at 0 deg | change at 30 deg | published at 30 deg |")
print("| --- | --- | --- | --- | --- |")
for run, load, column, published in TESTS:
    print(f"| {run} | {load} | {column} {change(run, 'intact', column, 0)} | "
          f"{change(run, 'intact', column, 30)} | {published} |")

print()
print("N: each ligament's whole pull on the femur, footprint and contact (femur_net_force_n).")
print()
print("| run | angle | anterior_mm | varus_deg | internal_deg | MCL mean fiber strain % | "
      "MCL regional peak % | MCL N | ACL N | LCL N | PCL N |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for run in ["intact", "anterior", "valgus", "acl-cut", "acl-cut-anterior", "acl-cut-valgus"]:
    for angle in (0.0, 30.0):
        p = pose(run, angle)
        if p is None:
            print(f"| {run} | {angle:g} | failed |" + " |" * 9)
            continue
        mcl = ligament(run, "MCL", angle)
        forces = []
        for name in ("MCL", "ACL", "LCL", "PCL"):
            f = net_force(run, name, angle)
            forces.append(f"{f:.1f}" if f is not None else "cut")
        print(f"| {run} | {angle:g} | {float(p['anterior_mm']):.2f} | {float(p['varus_deg']):.2f} "
              f"| {float(p['internal_rotation_deg']):.2f} | "
              f"{100 * float(mcl['mean_fiber_strain']):.2f} | "
              f"{100 * float(mcl['max_regional_fiber_strain']):.2f} | " + " | ".join(forces) + " |")

print()
print("The ACL cut's effect on the MCL's mean fiber strain, percentage points (Lujan et al. 2007: "
      "+1.8 under 100 N anterior, +0.1 under 10 N m valgus):")
for load in ("anterior", "valgus"):
    for angle in (0.0, 30.0):
        a, b = ligament(f"acl-cut-{load}", "MCL", angle), ligament(load, "MCL", angle)
        if a and b:
            delta = 100 * (float(a["mean_fiber_strain"]) - float(b["mean_fiber_strain"]))
            print(f"- {load}, {angle:g} deg: {delta:+.2f}")
