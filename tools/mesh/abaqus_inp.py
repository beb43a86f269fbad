"""Write the current Gmsh model's second-order tetrahedral mesh as an Abaqus input file.

Node and element ids are Gmsh's tags, so the .inp and the .msh of a part number everything alike.
Physical volumes become *ELEMENT, TYPE=C3D10, ELSET=<name> blocks with a material and a
*SOLID SECTION; physical points and surfaces become *NSET blocks of 16 ids a line.
"""

from __future__ import annotations

from dataclasses import dataclass

import gmsh

GMSH_TET10 = 11  # Gmsh element type: 10-node second-order tetrahedron

# Gmsh type 11 puts midside node 8 on edge (2,3) and 9 on edge (1,3); Abaqus C3D10 puts 8 on
# (1,3) and 9 on (2,3) (0-based). Vertices and midside nodes 4..7 agree.
GMSH_TO_ABAQUS_TET10 = (0, 1, 2, 3, 4, 5, 6, 7, 9, 8)

IDS_PER_LINE = 16


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic material (SI units)."""

    name: str
    young: float  # Pa
    poisson: float
    density: float  # kg/m^3


GREY_CAST_IRON = Material("GREY_CAST_IRON", 125.0e9, 0.26, 7200.0)
FRICTION_LINING = Material("FRICTION_LINING", 2.0e9, 0.25, 2500.0)
STEEL = Material("STEEL", 210.0e9, 0.30, 7850.0)

# Element set (physical volume name) -> material
SECTION_MATERIAL = {
    "DISC": GREY_CAST_IRON,
    "LINING": FRICTION_LINING,
    "BACKPLATE": STEEL,
}


def _fmt(x: float) -> str:
    """A real as Gmsh writes it in MSH 4.1 (printf %.16g), so that both files of a part read
    back to the same doubles."""
    return f"{float(x):.16g}"


def _physical_groups(dim: int) -> list[tuple[str, int]]:
    """(name, tag) of the physical groups of one dimension, in tag order."""
    groups = sorted(gmsh.model.getPhysicalGroups(dim), key=lambda dt: dt[1])
    return [(gmsh.model.getPhysicalName(d, t), t) for d, t in groups]


def _node_set(dim: int, tag: int) -> list[int]:
    """Node ids of a physical group: point groups in entity order, surface groups sorted."""
    if dim == 0:
        ids = []
        for ent in sorted(gmsh.model.getEntitiesForPhysicalGroup(dim, tag)):
            node_tags, _, _ = gmsh.model.mesh.getNodes(0, int(ent))
            ids.extend(int(n) for n in node_tags)
        return ids
    node_tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(dim, tag)
    return sorted(set(int(n) for n in node_tags))


def _volume_elements(tag: int) -> list[tuple[int, list[int]]]:
    """(element id, Abaqus-ordered node ids) of the tet10 of a physical volume, by id."""
    out = []
    for ent in sorted(gmsh.model.getEntitiesForPhysicalGroup(3, tag)):
        types, elem_tags, elem_nodes = gmsh.model.mesh.getElements(3, int(ent))
        for etype, etags, enodes in zip(types, elem_tags, elem_nodes):
            if etype != GMSH_TET10:
                raise RuntimeError(f"unexpected element type {etype} in volume {ent}")
            for k, eid in enumerate(etags):
                gnodes = enodes[10 * k : 10 * k + 10]
                out.append((int(eid), [int(gnodes[i]) for i in GMSH_TO_ABAQUS_TET10]))
    out.sort()
    return out


def _write_ids(lines: list[str], ids: list[int]) -> None:
    for start in range(0, len(ids), IDS_PER_LINE):
        lines.append(", ".join(str(i) for i in ids[start : start + IDS_PER_LINE]))


def write_inp(path: str, part: str, level: str, gmsh_version: str) -> dict:
    """Write the current model's mesh to path; return node, element and set counts."""
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    nodes = sorted((int(t), coords[3 * k : 3 * k + 3]) for k, t in enumerate(node_tags))

    lines = [
        "*HEADING",
        f"squeal bundled brake mesh: {part}, level {level} (C3D10, units m kg s N Pa)",
        f"** Written by tools/mesh/brake_meshes.py from a Gmsh {gmsh_version} mesh.",
        f"** Node and element ids are those of meshes/{part}_{level}.msh. Geometry, sets and",
        "** material sources: meshes/README.md.",
        "*NODE",
    ]
    for tag, xyz in nodes:
        lines.append(f"{tag}, {_fmt(xyz[0])}, {_fmt(xyz[1])}, {_fmt(xyz[2])}")

    counts = {"nodes": len(nodes), "elements": 0, "elsets": {}, "nsets": {}}
    volume_groups = _physical_groups(3)
    for name, tag in volume_groups:
        elems = _volume_elements(tag)
        counts["elements"] += len(elems)
        counts["elsets"][name] = len(elems)
        lines.append(f"*ELEMENT, TYPE=C3D10, ELSET={name}")
        for eid, enodes in elems:
            lines.append(f"{eid}, " + ", ".join(str(n) for n in enodes))

    for dim in (2, 0):
        for name, tag in _physical_groups(dim):
            ids = _node_set(dim, tag)
            counts["nsets"][name] = len(ids)
            lines.append(f"*NSET, NSET={name}")
            _write_ids(lines, ids)

    for name, _ in volume_groups:
        mat = SECTION_MATERIAL[name]
        lines.append(f"*MATERIAL, NAME={mat.name}")
        lines.append("*ELASTIC")
        # the material constants have few digits: %g writes them as an engineer would (2e+09)
        lines.append(f"{mat.young:g}, {mat.poisson:g}")
        lines.append("*DENSITY")
        lines.append(f"{mat.density:g}")
        lines.append(f"*SOLID SECTION, ELSET={name}, MATERIAL={mat.name}")

    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines))
        f.write("\n")
    return counts
