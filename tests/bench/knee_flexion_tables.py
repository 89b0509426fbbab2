#!/usr/bin/env python3
"""Tables of a knee's free flexion from its output (kinematics.csv, flexion.csv), shared by the
benchmark scripts: each run's cost and estimated error, then each run's path and ligaments per
angle, as Markdown.

  knee_flexion_tables.py (LABEL FLEXION BUILD_S SWEEP_S)...
"""
import csv
import sys
from pathlib import Path


def table(flexion, name):
    with open(flexion / name) as f:
        return list(csv.DictReader(f))


def cost_table(runs):
    """Each run's build and sweep seconds and each ligament's largest estimated error."""
    print("Each ligament's largest estimated error of its femoral footprint's force, as a share of "
          "that force, over the angles (the companion's +-, docs/flexion.md#the-error-estimate):")
    print()
    print("| knee | build s | sweep s (with the estimate) | MCL | LCL | ACL | PCL |")
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


def path_tables(runs):
    """Each run's path, articular contact and ligaments per angle."""
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
            ("deepest node in a bone, its own footprint aside (mm)",
             lambda r, a: f"{max(value(n, a, 'max_penetration_mm') for n in ligaments):.2f}"),
        ]
        print(f"{label.capitalize()}:")
        print()
        print("| angle (deg) | " + " | ".join(f"{a:g}" for a in angles) + " |")
        print("| --- |" + " ---: |" * len(angles))
        for text, cell in lines:
            print(f"| {text} | " + " | ".join(cell(r, a) for r, a in zip(path, angles)) + " |")
        print()


def runs_of(arguments):
    """(LABEL FLEXION BUILD_S SWEEP_S)... as a list of runs."""
    return [(arguments[i], Path(arguments[i + 1]), arguments[i + 2], arguments[i + 3])
            for i in range(0, len(arguments), 4)]


if __name__ == "__main__":
    runs = runs_of(sys.argv[1:])
    cost_table(runs)
    path_tables(runs)
