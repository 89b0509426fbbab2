#!/usr/bin/env python3
"""Writes a FEBio 4 input (.feb) of one case of the paper's cube (data/febio-cube), the set-up its
README gives: 16^3 x 5 linear tets, bottom face fixed, the case's force on every top node ramped
over 10 load steps, trans iso Mooney-Rivlin (uncoupled; volumetric U = k/2 (ln J)^2), BFGS with
line search, skyline, dtol 1e-6, etol 1e-8, rtol 1e-8. Only penalty cases with FEBio's default
volumetric law (names ending in _pen) are written. The .log holds the final node displacements.

    tests/bench/febio_cube.py CASE OUT.feb [REFERENCE_DIR]   (default data/febio-cube)
"""
import json
import os
import sys


def read_mesh(path):
    nodes, elements, sets = [], [], {}
    section = None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if words[0] in ("NODES", "ELEMENTS", "BOTTOM_NODES", "TOP_NODES"):
                section = words[0]
                continue
            if section == "NODES":
                nodes.append((int(words[0]), words[1], words[2], words[3]))
            elif section == "ELEMENTS":
                elements.append((int(words[0]), [int(w) for w in words[1:5]]))
            else:
                sets.setdefault(section, []).extend(int(w) for w in words)
    return nodes, elements, sets


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    name, out = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    reference = sys.argv[3] if len(sys.argv) == 4 else os.path.join(here, "../../data/febio-cube")
    with open(os.path.join(reference, "cases.json")) as f:
        cases = json.load(f)["cases"]
    chosen = [c for c in cases if c["name"] == name]
    if not chosen:
        sys.exit(f"febio_cube.py: no case '{name}' in {reference}/cases.json")
    case = chosen[0]
    material = case["material"]
    if case["incompressibility"] != "penalty" or material["volumetric"] != "lnj":
        sys.exit(f"febio_cube.py: '{name}' is not a penalty case with U = k/2 (ln J)^2")
    nodes, elements, sets = read_mesh(os.path.join(reference, "mesh.txt"))
    fiber = ",".join(str(v) for v in case["fiber"])
    force = ",".join(str(v) for v in case["force_per_top_node_n"])

    lines = [
        '<?xml version="1.0" encoding="ISO-8859-1"?>',
        f"<!-- The paper's cube, case {name}, written by tests/bench/febio_cube.py. -->",
        '<febio_spec version="4.0">',
        '  <Module type="solid"/>',
        "  <Control>",
        "    <analysis>STATIC</analysis>",
        "    <time_steps>10</time_steps>",
        "    <step_size>0.1</step_size>",
        "    <plot_level>PLOT_NEVER</plot_level>",
        '    <solver type="solid">',
        "      <symmetric_stiffness>symmetric</symmetric_stiffness>",
        "      <dtol>1e-06</dtol>",
        "      <etol>1e-08</etol>",
        "      <rtol>1e-08</rtol>",
        "      <lstol>0.9</lstol>",
        '      <qn_method type="BFGS"/>',
        "    </solver>",
        "  </Control>",
        "  <Material>",
        '    <material id="1" name="cube" type="trans iso Mooney-Rivlin">',
        "      <density>1</density>",
        f"      <k>{material['k_mpa']}</k>",
        f"      <c1>{material['c1_mpa']}</c1>",
        f"      <c2>{material['c2_mpa']}</c2>",
        f"      <c3>{material['c3_mpa']}</c3>",
        f"      <c4>{material['c4']}</c4>",
        f"      <c5>{material['c5_mpa']}</c5>",
        f"      <lam_max>{material['lam_star']}</lam_max>",
        f'      <fiber type="vector">{fiber}</fiber>',
        "    </material>",
        "  </Material>",
        "  <Mesh>",
        '    <Nodes name="cube">',
    ]
    lines += [f'      <node id="{i}">{x},{y},{z}</node>' for i, x, y, z in nodes]
    lines += ["    </Nodes>", '    <Elements type="tet4" name="cube">']
    lines += [f'      <elem id="{i}">{",".join(map(str, n))}</elem>' for i, n in elements]
    lines += ["    </Elements>"]
    for set_name, key in (("bottom", "BOTTOM_NODES"), ("top", "TOP_NODES")):
        lines.append(f'    <NodeSet name="{set_name}">{",".join(map(str, sets[key]))}</NodeSet>')
    lines += [
        "  </Mesh>",
        "  <MeshDomains>",
        '    <SolidDomain name="cube" mat="cube"/>',
        "  </MeshDomains>",
        "  <Boundary>",
        '    <bc name="bottom" node_set="bottom" type="zero displacement">',
        "      <x_dof>1</x_dof>",
        "      <y_dof>1</y_dof>",
        "      <z_dof>1</z_dof>",
        "    </bc>",
        "  </Boundary>",
        "  <Loads>",
        '    <nodal_load name="top" node_set="top" type="nodal_force">',
        "      <relative>0</relative>",
        f'      <value lc="1">{force}</value>',
        "    </nodal_load>",
        "  </Loads>",
        "  <LoadData>",
        '    <load_controller id="1" type="loadcurve">',
        "      <interpolate>LINEAR</interpolate>",
        "      <points>",
        "        <pt>0,0</pt>",
        "        <pt>1,1</pt>",
        "      </points>",
        "    </load_controller>",
        "  </LoadData>",
        "  <Output>",
        "    <logfile>",
        '      <node_data data="ux;uy;uz" delim=" "/>',
        "    </logfile>",
        "  </Output>",
        "</febio_spec>",
    ]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
