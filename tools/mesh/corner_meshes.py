"""The bundled brake corner (issue 21, item 6): a ventilated disc in 20-node hexahedra with a
ring of 15-node wedges at the bore, an inboard and an outboard pad (lining and backplate, one
mesh) with a shim each (a mesh of its own, to be tied to the backplate), a caliper housing and
a bracket (anchor) in 10-node tetrahedra, written as ONE Abaqus .inp with element and node sets
and the same model as Nastran bulk data (.bdf, by inp_to_bdf_cdb.py).

  python3 tools/mesh/corner_meshes.py [--levels coarse medium fine] [--out meshes/corner]
                                      [--disc tet10]

`--disc tet10` writes the same corner with the disc in 10-node tetrahedra (each cell split as
the other parts' cells, the Kuhn split, nodes on the same map), as corner_LEVEL_tetdisc.inp: the
check that the disc meshed in hex20 and in tet10 converges to the same frequencies (issue 21's
verification; crates/squeal-reduce/examples/disc_elements.rs, docs/verification.md).

Every part is a structured mesh in cylindrical coordinates (r, theta, z) about the z axis: a
grid of cells, some of them kept, each cell a hexahedron (disc), two wedges (the disc's bore
ring, the quadrilateral split on its diagonal in (r, theta) and swept in z) or six tetrahedra
(the Kuhn split about the cell's main diagonal, conforming between neighbouring cells). Nodes
are placed by mapping their (r, theta, z), midside nodes at the midpoints in (r, theta, z), so
edges along theta are arcs. Nothing is random: the same level gives the same file, byte for byte.

Geometry (m, degrees; the disc turns about z):
- disc: bore 70 mm, outer radius 150 mm; outboard cheek z 0..9 mm, channel 9..19 mm with 18
  radial vanes of 10 degrees, inboard cheek 19..28 mm; the bore ring 70..90 mm in wedges.
- pads over theta 60..120, r 95..145: inboard lining z 28..38, backplate 38..44, shim 44..46;
  outboard mirrored below z = 0 (lining 0..-10, backplate -10..-16, shim -16..-18).
- caliper over theta 60..120: the piston jaw z 46..66 (r 95..180), the finger jaw -34..-18,
  the bridge r 160..180 joining them outside the disc.
- bracket: two arms (theta 52..60 and 120..128) whose ears hold the backplates' ends (the
  abutments) at both pads' backplate levels, joined by a bridge r 152..160 outside the disc
  and by a tie bar on the inboard side (z 44..56, r 70..95); mounts on the tie bar's top.

Sets (node sets; each part an element set): DISC; INBOARD_LINING, INBOARD_BACKPLATE,
INBOARD_SHIM and OUTBOARD_*; CALIPER; BRACKET. Disc: DISC_CLAMP (bore), DISC_FACE_INBOARD and
DISC_FACE_OUTBOARD (the friction faces under each pad, one 10-degree cell wider each side).
Pads (P = INBOARD, OUTBOARD): P_FRICTION (the lining's face on the disc), P_BACK (the
backplate's back face, tie master), P_SHIM_FRONT (tie slave), P_SHIM_BACK (the shim's back),
P_PISTON (the shim back within the two 20 mm pistons' footprints, or the caliper fingers'),
P_ABUTMENT (the backplate's two theta ends). Caliper: CALIPER_PISTON (the piston jaw's face on
the inboard shim), CALIPER_FINGERS (the finger jaw's face on the outboard shim), CALIPER_GUIDE
(the bridge's theta ends, on the guide pins). Bracket: BRACKET_ABUTMENT_INBOARD and
BRACKET_ABUTMENT_OUTBOARD (the ears' faces on the backplates' ends), BRACKET_MOUNT (the tie
bar's top over the arms).
"""

from __future__ import annotations

import argparse
import math
import os
from dataclasses import dataclass, field

import inp_to_bdf_cdb

DEG = math.pi / 180.0

# Materials: name -> (E Pa, nu, rho kg/m^3). Cast iron, lining and steel as the bundled brakes;
# the shim a damped steel-elastomer laminate as one equivalent solid (a representative value,
# not a measurement); the caliper housing nodular iron.
MATERIALS = {
    "GREY_CAST_IRON": (1.25e11, 0.26, 7200.0),
    "FRICTION_LINING": (2e9, 0.25, 2500.0),
    "STEEL": (2.1e11, 0.3, 7850.0),
    "SHIM_LAMINATE": (5e9, 0.3, 6000.0),
    "NODULAR_IRON": (1.69e11, 0.275, 7100.0),
}


@dataclass(frozen=True)
class Level:
    name: str
    refine: int  # each cell of the coarse grid split into refine^3


# "finer" (refine 4) is the scale of issue 21's goal, "about 300k nodes" (docs/benchmarks.md,
# "Where the fine corner's time goes on main"): not bundled, not run by the tests.
LEVELS = {
    "coarse": Level("coarse", 1),
    "medium": Level("medium", 2),
    "fine": Level("fine", 3),
    "finer": Level("finer", 4),
}


def refined(edges: list[float], n: int) -> list[float]:
    """The edges with each interval split into n equal ones."""
    out = []
    for a, b in zip(edges, edges[1:]):
        out += [a + (b - a) * k / n for k in range(n)]
    return out + [edges[-1]]


@dataclass
class Model:
    """Nodes by key, elements by element set, node sets."""

    nodes: dict = field(default_factory=dict)  # key -> (id, (x, y, z), (r, t, z))
    elements: list = field(default_factory=list)  # (id, type, node ids, elset)
    node_sets: dict = field(default_factory=dict)

    def node(self, part: str, key: tuple, rtz: tuple[float, float, float]) -> int:
        k = (part,) + key
        if k not in self.nodes:
            r, t, z = rtz
            self.nodes[k] = (len(self.nodes) + 1, (r * math.cos(t), r * math.sin(t), z), rtz)
        return self.nodes[k][0]


class Grid:
    """A structured grid of one part in (r, theta, z): edges along each direction."""

    def __init__(self, model: Model, part: str, r, t_deg, z):
        self.model, self.part = model, part
        self.edges = (list(r), [v * DEG for v in t_deg], list(z))

    def coord(self, doubled: tuple[int, int, int]) -> tuple[float, float, float]:
        """(r, theta, z) of the point at doubled index coordinates (midpoints are odd)."""
        out = []
        for d, h in enumerate(doubled):
            e = self.edges[d]
            out.append(e[h // 2] if h % 2 == 0 else 0.5 * (e[h // 2] + e[h // 2 + 1]))
        return tuple(out)

    def node(self, doubled: tuple[int, int, int]) -> int:
        return self.model.node(self.part, doubled, self.coord(doubled))

    def cells(self, keep):
        """Index triples of the cells kept by keep(centre (r, t_deg, z))."""
        r, t, z = self.edges
        for k in range(len(z) - 1):
            for j in range(len(t) - 1):
                for i in range(len(r) - 1):
                    c = (0.5 * (r[i] + r[i + 1]), 0.5 * (t[j] + t[j + 1]) / DEG, 0.5 * (z[k] + z[k + 1]))
                    if keep(*c):
                        yield i, j, k


def corner(i, j, k, a, b, c):
    return (2 * (i + a), 2 * (j + b), 2 * (k + c))


def mid(p, q):
    return tuple((x + y) // 2 for x, y in zip(p, q))


# Abaqus C3D20: corners 1-4 at zeta = -1 counter-clockwise seen from +zeta, 5-8 above, then
# the midsides of edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8.
HEX_CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
# Abaqus C3D15: bottom triangle 1-3, top 4-6, midsides of 1-2, 2-3, 3-1, 4-5, 5-6, 6-4, 1-4,
# 2-5, 3-6.
WEDGE_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
# Abaqus C3D10: corners 1-4, midsides of 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
# The Kuhn split of the unit cube: one tetrahedron per order of the three directions.
KUHN = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]


def quadratic(grid: Grid, corners: list[tuple], edges) -> list[int]:
    pts = corners + [mid(corners[a], corners[b]) for a, b in edges]
    return [grid.node(p) for p in pts]


def orient(tet: list[tuple]) -> list[tuple]:
    """The tetrahedron's corners ordered for a positive volume in (r, theta, z) (the map to
    (x, y, z) keeps orientation: e_r x e_theta = e_z)."""
    a, b, c, d = tet
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
           + u[2] * (v[0] * w[1] - v[1] * w[0]))
    return [a, c, b, d] if det < 0 else tet


def add_cells(model: Model, grid: Grid, elset: str, keep, kind) -> None:
    """Adds the kept cells of grid as elements of elset: kind(i, j, k) -> 'hex', 'wedge', 'tet'."""
    for i, j, k in grid.cells(keep):
        shape = kind(i, j, k)
        cs = [corner(i, j, k, *p) for p in HEX_CORNERS]
        if shape == "hex":
            model.elements.append((len(model.elements) + 1, "C3D20", quadratic(grid, cs, HEX_EDGES), elset))
        elif shape == "wedge":
            # The (r, theta) quadrilateral split on its diagonal 0-2, both triangles
            # counter-clockwise seen from +z, swept from bottom to top.
            for tri in ((0, 1, 2), (0, 2, 3)):
                w = [cs[a] for a in tri] + [cs[a + 4] for a in tri]
                model.elements.append((len(model.elements) + 1, "C3D15", quadratic(grid, w, WEDGE_EDGES), elset))
        else:
            for order in KUHN:
                p = [0, 0, 0]
                tet = [corner(i, j, k, *p)]
                for d in order:
                    p[d] = 1
                    tet.append(corner(i, j, k, *p))
                model.elements.append((len(model.elements) + 1, "C3D10", quadratic(grid, orient(tet), TET_EDGES), elset))


def height(side: str, h: float) -> float:
    """The z of a pad layer at height h on the inboard side (above the disc's inboard face,
    z = 28 mm) or its mirror on the outboard side (below the outboard face, z = 0)."""
    return h if side == "INBOARD" else 0.028 - h


def level(side: str, z: float) -> float:
    """The inverse of height: the inboard-side height of z on side."""
    return z if side == "INBOARD" else 0.028 - z


def build(level_: Level, disc_elements: str = "hex20") -> tuple[Model, dict]:
    """The corner at level_, its disc in disc_elements ("hex20": hexahedra with a ring of
    wedges at the bore; "tet10": every disc cell split in six tetrahedra)."""
    m = Model()
    n = level_.refine
    sets_by_part: dict = {}

    # The disc.
    disc = Grid(m, "disc", refined([0.07, 0.09, 0.11, 0.13, 0.15], n),
                refined([10.0 * j for j in range(37)], n), refined([0.0, 0.009, 0.019, 0.028], n))

    def in_disc(r, t, z):
        channel = 0.009 < z < 0.019
        return not channel or int(t // 10.0) % 2 == 0

    def disc_kind(i, j, k):
        if disc_elements == "tet10":
            return "tet"
        return "wedge" if disc.edges[0][i] < 0.09 - 1e-12 else "hex"

    add_cells(m, disc, "DISC", in_disc, disc_kind)

    pad_t = refined([60.0 + 10.0 * j for j in range(7)], n)
    pad_r = refined([0.095, 0.12, 0.145], n)
    for side in ("INBOARD", "OUTBOARD"):
        zs = [height(side, v) for v in refined([0.028, 0.038, 0.044], n)]
        body = Grid(m, side.lower(), pad_r, pad_t, sorted(zs))
        add_cells(m, body, f"{side}_LINING", lambda r, t, z, s=side: level(s, z) < 0.038, lambda *_: "tet")
        add_cells(m, body, f"{side}_BACKPLATE", lambda r, t, z, s=side: level(s, z) > 0.038, lambda *_: "tet")
        shim = Grid(m, side.lower() + "_shim", pad_r, pad_t, sorted([height(side, 0.044), height(side, 0.046)]))
        add_cells(m, shim, f"{side}_SHIM", lambda *_: True, lambda *_: "tet")

    cal = Grid(m, "caliper", refined([0.095, 0.12, 0.145, 0.16, 0.18], n), pad_t,
               refined([-0.034, -0.018, 0.005, 0.023, 0.046, 0.066], n))
    add_cells(m, cal, "CALIPER", lambda r, t, z: r > 0.16 or z > 0.046 or z < -0.018, lambda *_: "tet")

    br_t = sorted(set(round(v, 9) for v in refined([52.0, 56.0, 60.0], n) + refined([60.0 + 10.0 * j for j in range(7)], n) + refined([120.0, 124.0, 128.0], n)))
    br = Grid(m, "bracket", refined([0.07, 0.095, 0.12, 0.145, 0.152, 0.16], n), br_t,
              refined([-0.016, -0.010, 0.005, 0.023, 0.038, 0.044, 0.056], n))

    def in_bracket(r, t, z):
        arm = t < 60.0 or t > 120.0
        ear = (-0.016 < z < -0.010 or 0.038 < z < 0.044) and 0.095 < r < 0.152
        bridge = 0.152 < r < 0.16 and z < 0.044
        bar = z > 0.044 and (r < 0.095 or arm)
        return (arm and (ear or bridge)) or bar

    add_cells(m, br, "BRACKET", in_bracket, lambda *_: "tet")

    # Node sets, by the nodes' (r, theta, z) in each part.
    eps = 1e-9

    def nset(name, part, pred):
        ids = sorted(v[0] for k, v in m.nodes.items() if k[0] == part and pred(*v[2]))
        m.node_sets[name] = ids

    def tdeg(t):
        return t / DEG

    nset("DISC_CLAMP", "disc", lambda r, t, z: abs(r - 0.07) < eps)
    nset("DISC_FACE_INBOARD", "disc", lambda r, t, z: abs(z - 0.028) < eps and r > 0.09 - eps and 50 - eps < tdeg(t) < 130 + eps)
    nset("DISC_FACE_OUTBOARD", "disc", lambda r, t, z: abs(z) < eps and r > 0.09 - eps and 50 - eps < tdeg(t) < 130 + eps)
    pistons = [(0.12, 75.0), (0.12, 105.0)]
    for side in ("INBOARD", "OUTBOARD"):
        p = side.lower()

        def at(h, s=side):
            return lambda r, t, z: abs(level(s, z) - h) < eps

        nset(f"{side}_FRICTION", p, at(0.028))
        nset(f"{side}_BACK", p, at(0.044))
        nset(f"{side}_ABUTMENT", p, lambda r, t, z, s=side: (abs(tdeg(t) - 60) < eps or abs(tdeg(t) - 120) < eps) and level(s, z) > 0.038 - eps)
        nset(f"{side}_SHIM_FRONT", p + "_shim", at(0.044))
        nset(f"{side}_SHIM_BACK", p + "_shim", at(0.046))

        def in_piston(r, t, z, s=side):
            on = abs(level(s, z) - 0.046) < eps
            return on and any(math.hypot(r * math.cos(t) - c * math.cos(a * DEG), r * math.sin(t) - c * math.sin(a * DEG)) < 0.02 + eps for c, a in pistons)

        nset(f"{side}_PISTON", p + "_shim", in_piston)
    nset("CALIPER_PISTON", "caliper", lambda r, t, z: abs(z - 0.046) < eps and r < 0.145 + eps)
    nset("CALIPER_FINGERS", "caliper", lambda r, t, z: abs(z + 0.018) < eps and r < 0.145 + eps)
    nset("CALIPER_GUIDE", "caliper", lambda r, t, z: (abs(tdeg(t) - 60) < eps or abs(tdeg(t) - 120) < eps) and r > 0.16 - eps)
    nset("BRACKET_ABUTMENT_INBOARD", "bracket", lambda r, t, z: (abs(tdeg(t) - 60) < eps or abs(tdeg(t) - 120) < eps) and 0.038 - eps < z < 0.044 + eps and 0.095 - eps < r < 0.145 + eps)
    nset("BRACKET_ABUTMENT_OUTBOARD", "bracket", lambda r, t, z: (abs(tdeg(t) - 60) < eps or abs(tdeg(t) - 120) < eps) and -0.016 - eps < z < -0.010 + eps and 0.095 - eps < r < 0.145 + eps)
    nset("BRACKET_MOUNT", "bracket", lambda r, t, z: abs(z - 0.056) < eps and r < 0.095 + eps and (tdeg(t) < 60 + eps or tdeg(t) > 120 - eps))
    return m, sets_by_part


def used_nodes(m: Model) -> list:
    used = {i for _, _, ns, _ in m.elements for i in ns}
    return sorted((v[0], v[1]) for v in m.nodes.values() if v[0] in used)


SECTIONS = [
    ("DISC", "GREY_CAST_IRON"),
    ("INBOARD_LINING", "FRICTION_LINING"),
    ("INBOARD_BACKPLATE", "STEEL"),
    ("INBOARD_SHIM", "SHIM_LAMINATE"),
    ("OUTBOARD_LINING", "FRICTION_LINING"),
    ("OUTBOARD_BACKPLATE", "STEEL"),
    ("OUTBOARD_SHIM", "SHIM_LAMINATE"),
    ("CALIPER", "NODULAR_IRON"),
    ("BRACKET", "GREY_CAST_IRON"),
]


def write_inp(m: Model, path: str, level: str) -> dict:
    nodes = used_nodes(m)
    used = {i for i, _ in nodes}
    lines = [
        "*HEADING",
        f"squeal bundled brake corner, level {level} (C3D20, C3D15, C3D10; units m kg s N Pa)",
        "** Written by tools/mesh/corner_meshes.py: geometry and sets in its docstring.",
        "*NODE",
    ]
    for i, x in nodes:
        lines.append(f"{i}, {x[0]!r}, {x[1]!r}, {x[2]!r}")
    counts = {"nodes": len(nodes), "elements": len(m.elements), "elsets": {}}
    for elset, _ in SECTIONS:
        for ty in ("C3D20", "C3D15", "C3D10"):
            els = [e for e in m.elements if e[3] == elset and e[1] == ty]
            if not els:
                continue
            counts["elsets"][f"{elset} {ty}"] = len(els)
            lines.append(f"*ELEMENT, TYPE={ty}, ELSET={elset}")
            for eid, _, ns, _ in els:
                # 16 values a line at most: the C3D20's last nodes on a continuation line.
                vals = [str(eid)] + [str(v) for v in ns]
                lines.append(", ".join(vals[:16]) + ("," if len(vals) > 16 else ""))
                if len(vals) > 16:
                    lines.append(", ".join(vals[16:]))
    for name, ids in m.node_sets.items():
        ids = [i for i in ids if i in used]
        lines.append(f"*NSET, NSET={name}")
        for k in range(0, len(ids), 16):
            lines.append(", ".join(str(i) for i in ids[k : k + 16]))
    for mat, (e, nu, rho) in MATERIALS.items():
        lines += [f"*MATERIAL, NAME={mat}", "*ELASTIC", f"{e:g}, {nu:g}", "*DENSITY", f"{rho:g}"]
    for elset, mat in SECTIONS:
        lines.append(f"*SOLID SECTION, ELSET={elset}, MATERIAL={mat}")
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    return counts


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--levels", nargs="+", default=["coarse"], choices=sorted(LEVELS))
    ap.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "..", "meshes", "corner"))
    ap.add_argument("--disc", default="hex20", choices=["hex20", "tet10"],
                    help="the disc's elements (tet10: written as corner_LEVEL_tetdisc.inp, .inp only)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for name in args.levels:
        m, _ = build(LEVELS[name], args.disc)
        if args.disc == "tet10":
            counts = write_inp(m, os.path.join(args.out, f"corner_{name}_tetdisc.inp"), name)
            print(name, "tet10 disc", counts)
            continue
        inp = os.path.join(args.out, f"corner_{name}.inp")
        counts = write_inp(m, inp, name)
        mesh = inp_to_bdf_cdb.read_inp(inp)
        inp_to_bdf_cdb.write_bdf(mesh, os.path.join(args.out, f"corner_{name}.bdf"), os.path.basename(inp))
        print(name, counts)


if __name__ == "__main__":
    main()
