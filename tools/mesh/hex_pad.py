#!/usr/bin/env python3
"""Write the bundled one-pad brake's pad as 20-node hexahedra (Abaqus C3D20) on a polar grid.

The pad of meshes/README.md: an annular sector r = 85 .. 135 mm over 65 .. 115 deg, friction
lining z = 20 .. 30 mm (ELSET LINING) and steel backplate z = 30 .. 35 mm (ELSET BACKPLATE),
with the sets the scene's defaults read: CONTACT_FACE (the friction face z = 20 mm), PISTON
(the four piston points r = 90, 130 mm at 77.5 and 102.5 deg on z = 35 mm, in the README's
order) and ABUTMENT (the backplate's end faces at 65 and 115 deg). Every element is a C3D20
of the grid (r, theta, z), nodes at the corners and edge midpoints of the cells (serendipity:
no face or cell centres); the arcs are interpolated quadratically through their midside nodes.

Levels (``--cells NR,NT,NL``: elements across the radius, around the sector, through the
lining; the backplate has one layer): NR must be a multiple of 5 and NT of 2 so that the piston
points are nodes. The hex20-pad convergence study of docs/reduction.md used 5,4,1; 10,8,2;
20,16,4 (``--level`` coarse, medium, fine).

Usage (from the repository root)::

    python3 tools/mesh/hex_pad.py --level coarse --out /tmp/hexpad/pad_hex_coarse.inp

Deterministic: no time or host enters the file.
"""

from __future__ import annotations

import argparse
import math

LEVELS = {"coarse": (5, 4, 1), "medium": (10, 8, 2), "fine": (20, 16, 4)}
R = (0.085, 0.135)
THETA_DEG = (65.0, 115.0)
Z = (0.020, 0.030, 0.035)
PISTONS = [(0.090, 77.5), (0.090, 102.5), (0.130, 77.5), (0.130, 102.5)]
MATERIALS = {"FRICTION_LINING": (2.0e9, 0.25, 2500.0), "STEEL": (210.0e9, 0.30, 7850.0)}
SECTIONS = [("LINING", "FRICTION_LINING"), ("BACKPLATE", "STEEL")]

# Abaqus C3D20: corners 1-4 at zeta = -1 counter-clockwise seen from +zeta, 5-8 above, then
# the midsides of edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8. With
# (xi, eta, zeta) along (r, theta, z), e_r x e_theta = e_z: positive Jacobians.
HEX_CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def build(nr: int, nt: int, nl: int):
    """Nodes {doubled grid index: (id, xyz)}, elements [(id, nodes, elset)] and node sets."""
    if nr % 5 or nt % 2 or nl < 1:
        raise SystemExit("--cells: NR a multiple of 5, NT even, NL >= 1 (piston points as nodes)")
    nz = nl + 1
    zs = [Z[0] + (Z[1] - Z[0]) * k / (2 * nl) for k in range(2 * nl)] + [
        Z[1] + (Z[2] - Z[1]) * k / 2 for k in range(3)
    ]

    def xyz(p):
        r = R[0] + (R[1] - R[0]) * p[0] / (2 * nr)
        t = math.radians(THETA_DEG[0] + (THETA_DEG[1] - THETA_DEG[0]) * p[1] / (2 * nt))
        return (r * math.cos(t), r * math.sin(t), zs[p[2]])

    nodes = {}
    for k in range(2 * nz + 1):
        for j in range(2 * nt + 1):
            for i in range(2 * nr + 1):
                if (i % 2) + (j % 2) + (k % 2) >= 2:
                    continue  # a face or cell centre: no node of a serendipity element
                nodes[(i, j, k)] = (len(nodes) + 1, xyz((i, j, k)))
    elements = []
    for k in range(nz):
        for j in range(nt):
            for i in range(nr):
                cs = [(2 * (i + a), 2 * (j + b), 2 * (k + c)) for a, b, c in HEX_CORNERS]
                mids = [tuple((x + y) // 2 for x, y in zip(cs[a], cs[b])) for a, b in HEX_EDGES]
                ids = [nodes[p][0] for p in cs + mids]
                elements.append((len(elements) + 1, ids, "LINING" if k < nl else "BACKPLATE"))
    top = 2 * nz
    sets = {
        "CONTACT_FACE": sorted(n for p, (n, _) in nodes.items() if p[2] == 0),
        "PISTON": [
            nodes[(round((r - R[0]) / (R[1] - R[0]) * 2 * nr),
                   round((t - THETA_DEG[0]) / (THETA_DEG[1] - THETA_DEG[0]) * 2 * nt), top)][0]
            for r, t in PISTONS
        ],
        "ABUTMENT": sorted(
            n for p, (n, _) in nodes.items() if p[1] in (0, 2 * nt) and p[2] >= 2 * nl
        ),
    }
    return nodes, elements, sets


def write(path: str, nodes, elements, sets, label: str) -> None:
    lines = [
        "*HEADING",
        f"squeal one-pad brake's pad in C3D20, {label} (units m kg s N Pa)",
        "** Written by tools/mesh/hex_pad.py: geometry and sets in its docstring.",
        "*NODE",
    ]
    for n, x in sorted(nodes.values()):
        lines.append(f"{n}, {x[0]!r}, {x[1]!r}, {x[2]!r}")
    for elset, _ in SECTIONS:
        lines.append(f"*ELEMENT, TYPE=C3D20, ELSET={elset}")
        for eid, ns, es in elements:
            if es != elset:
                continue
            vals = [str(eid)] + [str(v) for v in ns]
            lines.append(", ".join(vals[:16]) + ",")
            lines.append(", ".join(vals[16:]))
    for name, ids in sets.items():
        lines.append(f"*NSET, NSET={name}")
        for k in range(0, len(ids), 16):
            lines.append(", ".join(str(i) for i in ids[k : k + 16]))
    for mat, (e, nu, rho) in MATERIALS.items():
        lines += [f"*MATERIAL, NAME={mat}", "*ELASTIC", f"{e:g}, {nu:g}", "*DENSITY", f"{rho:g}"]
    for elset, mat in SECTIONS:
        lines.append(f"*SOLID SECTION, ELSET={elset}, MATERIAL={mat}")
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", choices=sorted(LEVELS), default="coarse")
    ap.add_argument("--cells", help="NR,NT,NL instead of a level")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    cells = tuple(int(c) for c in a.cells.split(",")) if a.cells else LEVELS[a.level]
    nodes, elements, sets = build(*cells)
    write(a.out, nodes, elements, sets, f"cells {cells[0]} x {cells[1]} x {cells[2]}")
    print(f"{a.out}: {len(nodes)} nodes, {len(elements)} C3D20, cells {cells}, "
          f"{len(sets['CONTACT_FACE'])} friction-face nodes")


if __name__ == "__main__":
    main()
