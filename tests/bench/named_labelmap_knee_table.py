#!/usr/bin/env python3
"""Tables of tests/bench/named_labelmap_knee.sh: what each label was taken for; each knee's cost
and estimated error; each knee's path and ligaments per angle (kinematics.csv, flexion.csv).

  named_labelmap_knee_table.py KNEE (LABEL FLEXION BUILD_S SWEEP_S)...
"""
import json
import sys
from pathlib import Path

from knee_flexion_tables import cost_table, path_tables, runs_of

knee = Path(sys.argv[1])
runs = runs_of(sys.argv[2:])

found = json.loads((knee / "summary.json").read_text())["results"]["found_by_name"]
print("| label | names | taken for |")
print("| ---: | --- | --- |")
for label in found["labels"]:
    print(f"| {label['label']} | {', '.join(label['names'])} | {label['taken_for']} |")
print()

cost_table(runs)
path_tables(runs)
