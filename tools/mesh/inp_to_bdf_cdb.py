"""Write a squeal .inp mesh (as tools/mesh/abaqus_inp.py writes them) as Nastran bulk data
(.bdf) and as an Ansys .cdb, for the readers' tests: the same nodes, elements, sets and
materials in three formats.

    python3 tools/mesh/inp_to_bdf_cdb.py meshes/pad_coarse.inp OUT_STEM

writes OUT_STEM.bdf and OUT_STEM.cdb. Reals are written with Python's repr (the shortest text
that reads back to the same double), so the three files read to the same bits:

- .bdf: free field (comma separated; a fixed 8 or 16 character field cannot hold 17 digits),
  names in HyperMesh comments ($HMNAME PROP/MAT, $HMSET), one PSOLID per element set, MAT1
  with E and NU (G left blank), SET1 per node set, CTETRA/CHEXA/CPENTA in Nastran's grid order.
- .cdb: the blocked layout of CDWRITE with its format lines, but reals 24 characters wide
  with 17 significant digits ((3i9,6e24.16e3)) instead of CDWRITE's 14; SOLID187 for C3D10,
  SOLID186 for C3D20 and its prism form for C3D15; CMBLOCK per set; MPDATA EX, PRXY, DENS.

Only the .inp subset squeal's generator writes is read: *NODE, *ELEMENT (C3D10, C3D20,
C3D20R, C3D15) with ELSET=, *NSET, *MATERIAL with *ELASTIC (isotropic) and *DENSITY,
*SOLID SECTION. Anything else stops the script.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field

# Abaqus (= squeal) order -> Nastran order: nastran[k] = abaqus[ABAQUS_FROM_NASTRAN[k]].
# CHEXA lists the vertical edges (Abaqus 16-19) before the top face's (Abaqus 12-15);
# CPENTA likewise (Abaqus 12-14 vertical, 9-11 top).
NASTRAN_FROM_ABAQUS = {
    "C3D10": list(range(10)),
    "C3D20": list(range(12)) + [16, 17, 18, 19, 12, 13, 14, 15],
    "C3D15": list(range(9)) + [12, 13, 14, 9, 10, 11],
}
NASTRAN_CARD = {"C3D10": "CTETRA", "C3D20": "CHEXA", "C3D15": "CPENTA"}


def solid186_prism(n: list[int]) -> list[int]:
    """The 20 SOLID186 nodes of a C3D15 (Abaqus order): I J K K M N O O, Q R K T, U V O X,
    Y Z A A (Ansys Element Reference, SOLID186 prism form)."""
    i, j, k, m, nn, o = n[0:6]
    q, r, t, u, v, x, y, z, a = n[6:15]
    return [i, j, k, k, m, nn, o, o, q, r, k, t, u, v, o, x, y, z, a, a]


@dataclass
class Mesh:
    nodes: list[tuple[int, tuple[float, float, float]]] = field(default_factory=list)
    # (id, abaqus type, nodes in Abaqus order, element set)
    elements: list[tuple[int, str, list[int], str]] = field(default_factory=list)
    node_sets: dict[str, list[int]] = field(default_factory=dict)
    materials: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    sections: list[tuple[str, str]] = field(default_factory=list)


def _params(line: str) -> tuple[str, dict[str, str]]:
    parts = [p.strip() for p in line[1:].split(",")]
    key = parts[0].upper().replace(" ", "")
    params = {}
    for p in parts[1:]:
        if p:
            k, _, v = p.partition("=")
            params[k.strip().upper()] = v.strip()
    return key, params


def read_inp(path: str) -> Mesh:
    mesh = Mesh()
    key, params, material = "", {}, ""
    pending: list[int] = []
    with open(path, encoding="utf-8") as f:
        lines = [ln.strip() for ln in f]
    for line in lines:
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            key, params = _params(line)
            if key == "MATERIAL":
                material = params["NAME"]
                mesh.materials[material] = (0.0, 0.0, 0.0)
            elif key == "SOLIDSECTION":
                mesh.sections.append((params["ELSET"], params["MATERIAL"]))
            elif key == "NSET":
                mesh.node_sets.setdefault(params["NSET"], [])
            elif key not in ("HEADING", "NODE", "ELEMENT", "ELASTIC", "DENSITY"):
                raise SystemExit(f"{path}: *{key} is not in the subset this script reads")
            continue
        values = [v.strip() for v in line.rstrip(",").split(",")]
        if key == "NODE":
            mesh.nodes.append((int(values[0]), tuple(float(v) for v in values[1:4])))
        elif key == "ELEMENT":
            pending += [int(v) for v in values]
            ty = "C3D20" if params["TYPE"].upper() == "C3D20R" else params["TYPE"].upper()
            if not line.endswith(","):
                mesh.elements.append((pending[0], ty, pending[1:], params["ELSET"]))
                pending = []
        elif key == "NSET":
            mesh.node_sets[params["NSET"]] += [int(v) for v in values if v]
        elif key == "ELASTIC":
            e, nu = float(values[0]), float(values[1])
            mesh.materials[material] = (e, nu, mesh.materials[material][2])
        elif key == "DENSITY":
            e, nu, _ = mesh.materials[material]
            mesh.materials[material] = (e, nu, float(values[0]))
    return mesh


def _free_card(name: str, values: list[str]) -> list[str]:
    """A free-field card: 8 data fields on the first line, 8 on each continuation."""
    out = []
    for k in range(0, max(len(values), 1), 8):
        head = name if k == 0 else "+"
        out.append(",".join([head] + values[k : k + 8]))
    return out


def write_bdf(mesh: Mesh, path: str, source: str) -> None:
    sets = sorted({s for _, _, _, s in mesh.elements})
    material_of = dict(mesh.sections)
    mat_ids = {name: k for k, name in enumerate(sorted(mesh.materials), 1)}
    pid = {name: k for k, name in enumerate(sets, 1)}
    lines = [f"$ Written by tools/mesh/inp_to_bdf_cdb.py from {source}", "SOL 103", "CEND", "BEGIN BULK"]
    for name, mid in mat_ids.items():
        e, nu, rho = mesh.materials[name]
        lines.append(f'$HMNAME MAT {mid} "{name}"')
        lines.append(f"MAT1,{mid},{e!r},,{nu!r},{rho!r}")
    for name, p in pid.items():
        lines.append(f'$HMNAME PROP {p} "{name}"')
        lines.append(f"PSOLID,{p},{mat_ids[material_of[name]]}")
    for nid, x in mesh.nodes:
        lines.append(f"GRID,{nid},,{x[0]!r},{x[1]!r},{x[2]!r}")
    for eid, ty, n, s in mesh.elements:
        grids = [str(n[k]) for k in NASTRAN_FROM_ABAQUS[ty]]
        lines += _free_card(NASTRAN_CARD[ty], [str(eid), str(pid[s])] + grids)
    for k, (name, ids) in enumerate(mesh.node_sets.items(), 1):
        lines.append(f'$HMSET {k} 1 "{name}"')
        lines += _free_card("SET1", [str(k)] + [str(i) for i in ids])
    lines.append("ENDDATA")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def _e(x: float) -> str:
    """A real in 24 characters with 17 significant digits (e24.16e3)."""
    mantissa, exponent = f"{x:.16E}".split("E")
    return f"{mantissa}E{int(exponent):+04d}".rjust(24)


def _ints(values: list[int], width: int, per_line: int) -> list[str]:
    return ["".join(f"{v:{width}d}" for v in values[k : k + per_line]) for k in range(0, len(values), per_line)]


def write_cdb(mesh: Mesh, path: str, source: str) -> None:
    sets = sorted({s for _, _, _, s in mesh.elements})
    material_of = dict(mesh.sections)
    mat_ids = {name: k for k, name in enumerate(sorted(mesh.materials), 1)}
    lines = [
        f"/COM, Written by tools/mesh/inp_to_bdf_cdb.py from {source}",
        "/PREP7",
        "/NOPR",
        "ET,       1,187",
        "ET,       2,186",
        "KEYOPT,2,2,1",
        f"NBLOCK,6,SOLID,{len(mesh.nodes):10d},{len(mesh.nodes):10d}",
        "(3i9,6e24.16e3)",
    ]
    for nid, x in mesh.nodes:
        lines.append(f"{nid:9d}{0:9d}{0:9d}" + "".join(_e(v) for v in x))
    lines += ["N,R5.3,LOC,       -1,", f"EBLOCK,19,SOLID,{len(mesh.elements):10d},{len(mesh.elements):10d}", "(19i9)"]
    for eid, ty, n, s in mesh.elements:
        mat = mat_ids[material_of[s]]
        nodes = solid186_prism(n) if ty == "C3D15" else n
        et = 1 if ty == "C3D10" else 2
        record = [mat, et, 1, 1, 0, 0, 0, 0, len(nodes), 0, eid] + nodes
        lines += _ints(record, 9, 19)
    lines.append(f"{-1:9d}")
    by_set: dict[str, list[int]] = {s: [] for s in sets}
    for eid, _, _, s in mesh.elements:
        by_set[s].append(eid)
    for name, ids in list(by_set.items()):
        lines += [f"CMBLOCK,{name},ELEM,{len(ids):8d}", "(8i10)"] + _ints(ids, 10, 8)
    for name, ids in mesh.node_sets.items():
        lines += [f"CMBLOCK,{name},NODE,{len(ids):8d}", "(8i10)"] + _ints(ids, 10, 8)
    for name, mid in mat_ids.items():
        e, nu, rho = mesh.materials[name]
        lines.append("MPTEMP,R5.0, 1, 1,  0.00000000    ,")
        for lab, v in (("EX", e), ("PRXY", nu), ("DENS", rho)):
            lines.append(f"MPDATA,R5.0, 1,{lab:<4},{mid:8d}, 1, {v!r},")
    lines.append("/GOPR")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def main(argv: list[str]) -> None:
    if len(argv) != 3:
        raise SystemExit(__doc__)
    mesh = read_inp(argv[1])
    source = argv[1].replace("\\", "/").split("/")[-1]
    write_bdf(mesh, argv[2] + ".bdf", source)
    write_cdb(mesh, argv[2] + ".cdb", source)


if __name__ == "__main__":
    main(sys.argv)
