#!/usr/bin/env python3
"""Check the bundled meshes written by brake_meshes.py, independently of the writer.

The .inp is read by the small parser below (not by the code that wrote it) and the .msh by
Gmsh's own reader. Each check compares against something defined without the mesh: the
analytic volume, the sets recomputed from node coordinates and the dimensions in
brake_geometry.py, the edge midpoints. Exit status 0 when everything passes.

The bundled brakes are checked: the one-pad brake (disc, pad), the two-pad brake
(two_pad/disc, the same pad, two_pad/outboard), each file once, and the levels of the
ventilated brake that are there (check_ventilated.py).

Usage (from the repository root)::

    python3 tools/mesh/check_meshes.py [--levels coarse medium fine] [--mesh-dir meshes]
                                       [--brakes one-pad two-pad ventilated]
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from dataclasses import dataclass, field

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import brake_geometry as geo  # noqa: E402

# Abaqus C3D10 edges of the midside nodes 4..9 (0-based vertex pairs).
ABAQUS_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))

# Coordinates are written with 17 significant digits, so a point the generator placed on a
# plane or a circle reads back to within a few ulps of 0.1 m: 1e-12 m is 1e4 ulps of slack.
GEOM_TOL = 1e-12


def curved_radii(part: geo.Part) -> tuple[float, ...]:
    """Radii of the part's cylindrical surfaces and arcs, whose edges may carry curved midside
    nodes: the disc's cylinders or the pad's two, and the patch arcs of every footprint."""
    own = (
        (geo.DISC_R_IN, geo.DISC_R_OUT, geo.HAT_R_OUT, geo.BORE_R)
        if part.is_disc
        else (part.pads[0].r_in, part.pads[0].r_out)
    )
    return own + tuple(r for pad in part.pads for r in geo.patch_radii(pad))


MATERIALS = {
    "GREY_CAST_IRON": (125.0e9, 0.26, 7200.0),
    "FRICTION_LINING": (2.0e9, 0.25, 2500.0),
    "STEEL": (210.0e9, 0.30, 7850.0),
}
SECTIONS = {
    True: {"DISC": "GREY_CAST_IRON"},  # by Part.is_disc
    False: {"LINING": "FRICTION_LINING", "BACKPLATE": "STEEL"},
}


@dataclass
class InpMesh:
    """What the checker reads from an Abaqus .inp."""

    node_ids: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    coords: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    elsets: dict = field(default_factory=dict)  # name -> (ids (n,), connectivity (n, 10) node ids)
    nsets: dict = field(default_factory=dict)  # name -> list of node ids, file order
    materials: dict = field(default_factory=dict)  # name -> (E, nu, rho)
    sections: dict = field(default_factory=dict)  # elset -> material
    heading: str = ""


def _keyword(line: str) -> tuple[str, dict]:
    parts = [p.strip() for p in line[1:].split(",")]
    params = {}
    for p in parts[1:]:
        if "=" in p:
            k, v = p.split("=", 1)
            params[k.strip().upper()] = v.strip()
        elif p:
            params[p.upper()] = ""
    return parts[0].upper(), params


def read_inp(path: str) -> InpMesh:
    """Parse the subset of Abaqus input that brake_meshes.py writes."""
    mesh = InpMesh()
    node_rows, elems, current = [], {}, None
    material, mat_props = None, {}
    with open(path, encoding="ascii") as f:
        lines = f.read().splitlines()
    for line in lines:
        s = line.strip()
        if not s or s.startswith("**"):
            continue
        if s.startswith("*"):
            kw, params = _keyword(s)
            current = (kw, params)
            if kw == "ELEMENT":
                if params.get("TYPE", "").upper() != "C3D10":
                    raise ValueError(f"{path}: unexpected element type {params}")
                elems.setdefault(params["ELSET"], [])
            elif kw == "NSET":
                mesh.nsets.setdefault(params["NSET"], [])
            elif kw == "MATERIAL":
                material = params["NAME"]
                mat_props[material] = {}
            elif kw == "SOLID SECTION":
                mesh.sections[params["ELSET"]] = params["MATERIAL"]
            continue
        if current is None:
            raise ValueError(f"{path}: data before any keyword: {s}")
        kw, params = current
        vals = [v.strip() for v in s.split(",") if v.strip()]
        if kw == "HEADING":
            mesh.heading = mesh.heading or s
        elif kw == "NODE":
            node_rows.append([float(v) for v in vals])
        elif kw == "ELEMENT":
            if len(vals) != 11:
                raise ValueError(f"{path}: C3D10 line with {len(vals)} values: {s}")
            elems[params["ELSET"]].append([int(v) for v in vals])
        elif kw == "NSET":
            mesh.nsets[params["NSET"]].extend(int(v) for v in vals)
        elif kw == "ELASTIC":
            mat_props[material]["elastic"] = [float(v) for v in vals]
        elif kw == "DENSITY":
            mat_props[material]["density"] = float(vals[0])
        else:
            raise ValueError(f"{path}: unexpected data under *{kw}: {s}")
    rows = np.array(node_rows)
    mesh.node_ids = rows[:, 0].astype(np.int64)
    mesh.coords = rows[:, 1:4]
    for name, rows_e in elems.items():
        arr = np.array(rows_e, dtype=np.int64)
        mesh.elsets[name] = (arr[:, 0], arr[:, 1:])
    for name, p in mat_props.items():
        mesh.materials[name] = (p["elastic"][0], p["elastic"][1], p["density"])
    return mesh


# ---------------------------------------------------------------- tet10 geometry (Abaqus order)


def shape_gradients(xi: np.ndarray) -> np.ndarray:
    """dN/dxi of the C3D10 shape functions at reference points xi (q, 3) -> (q, 10, 3)."""
    lam = np.stack([1.0 - xi.sum(axis=1), xi[:, 0], xi[:, 1], xi[:, 2]], axis=1)
    dlam = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    grads = np.zeros((xi.shape[0], 10, 3))
    for i in range(4):
        grads[:, i, :] = (4.0 * lam[:, i] - 1.0)[:, None] * dlam[i]
    for k, (a, b) in enumerate(ABAQUS_EDGES):
        grads[:, 4 + k, :] = 4.0 * (lam[:, a, None] * dlam[b] + lam[:, b, None] * dlam[a])
    return grads


def reference_nodes() -> np.ndarray:
    """Reference coordinates of the 10 C3D10 nodes."""
    v = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    mids = [(v[a] + v[b]) / 2 for a, b in ABAQUS_EDGES]
    return np.vstack([v, mids])


def collapsed_gauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Stroud's conical product rule on the unit tetrahedron from n-point Gauss-Legendre in
    each direction (Duffy map); exact for polynomials of degree 2n - 3 on the tet."""
    g, w = np.polynomial.legendre.leggauss(n)
    g, w = 0.5 * (g + 1.0), 0.5 * w
    pts, wts = [], []
    for a, wa in zip(g, w):
        for b, wb in zip(g, w):
            for c, wc in zip(g, w):
                x = a
                y = b * (1.0 - a)
                z = c * (1.0 - a) * (1.0 - b)
                pts.append((x, y, z))
                wts.append(wa * wb * wc * (1.0 - a) ** 2 * (1.0 - b))
    return np.array(pts), np.array(wts)


def gauss4() -> np.ndarray:
    """The usual 4-point (degree 2) tet rule used to integrate C3D10 stiffness."""
    a, b = 0.5854101966249685, 0.1381966011250105
    return np.array([[b, b, b], [a, b, b], [b, a, b], [b, b, a]])


def jacobians(x: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """det J of every element (e, 10, 3) at every reference point (q, 3) -> (e, q)."""
    grads = shape_gradients(xi)
    jac = np.einsum("enc,qnd->eqcd", x, grads)
    return np.linalg.det(jac)


# ---------------------------------------------------------------- checks


class Report:
    """Counts passed checks and collects the failed ones (printed as they happen if verbose)."""

    def __init__(self, verbose: bool = True) -> None:
        self.failures: list[str] = []
        self.notes: list[str] = []
        self.passed = 0
        self.verbose = verbose

    def note(self, what: str) -> None:
        self.notes.append(what)
        if self.verbose:
            print(f"NOTE {what}", flush=True)

    def check(self, ok: bool, what: str) -> None:
        if ok:
            self.passed += 1
        else:
            self.failures.append(what)
            if self.verbose:
                print(f"FAIL {what}", flush=True)


def element_coords(mesh: InpMesh, conn: np.ndarray) -> np.ndarray:
    index = np.full(int(mesh.node_ids.max()) + 1, -1, dtype=np.int64)
    index[mesh.node_ids] = np.arange(mesh.node_ids.size)
    return mesh.coords[index[conn]]


def check_midside(
    rep: Report, tag: str, part: geo.Part | None, x: np.ndarray, circles=None
) -> dict:
    """Every midside node sits at its edge's midpoint, unless the edge lies on one of the part's
    cylinders or arcs, where it sits on that circle within the arc's sagitta of the midpoint.
    The cylinders are the part's (about the z axis), or circles: (cx, cy, r) with axes along z."""
    if circles is None:
        circles = [(0.0, 0.0, r) for r in curved_radii(part)]
    n_straight = n_curved = 0
    bad = 0
    for k, (a, b) in enumerate(ABAQUS_EDGES):
        xa, xb, xm = x[:, a], x[:, b], x[:, 4 + k]
        chord = np.linalg.norm(xb - xa, axis=1)
        off = np.linalg.norm(xm - 0.5 * (xa + xb), axis=1)
        straight = off <= GEOM_TOL
        curved = np.zeros_like(straight)
        for cx, cy, r in circles:
            radius = np.hypot(x[..., 0] - cx, x[..., 1] - cy)
            on = (
                (np.abs(radius[:, a] - r) < GEOM_TOL)
                & (np.abs(radius[:, b] - r) < GEOM_TOL)
                & (np.abs(radius[:, 4 + k] - r) < GEOM_TOL)
            )
            # the midpoint of an arc of chord c on radius r lies r - sqrt(r^2 - c^2/4) from the
            # chord's midpoint; an edge running obliquely on a cylinder deviates less
            sagitta = r - np.sqrt(np.maximum(r * r - 0.25 * chord**2, 0.0))
            curved |= on & (off <= sagitta + GEOM_TOL)
        n_straight += int(straight.sum())
        n_curved += int((curved & ~straight).sum())
        bad += int((~straight & ~curved).sum())
    rep.check(
        bad == 0, f"{tag}: {bad} midside nodes neither at their edge midpoint nor on their arc"
    )
    return {"straight_edges": n_straight, "curved_edges": n_curved}


def check_jacobians(rep: Report, tag: str, x: np.ndarray) -> dict:
    det_nodes = jacobians(x, reference_nodes())
    det_g4 = jacobians(x, gauss4())
    qp, _ = collapsed_gauss(3)
    det_q = jacobians(x, qp)
    worst = min(det_nodes.min(), det_g4.min(), det_q.min())
    rep.check(worst > 0.0, f"{tag}: non-positive Jacobian {worst:.3e}")
    # scaled Jacobian: min over points / max over points, per element
    all_det = np.concatenate([det_nodes, det_g4, det_q], axis=1)
    ratio = all_det.min(axis=1) / all_det.max(axis=1)
    return {"min_det_ratio": float(ratio.min())}


def mesh_volume(x: np.ndarray) -> float:
    """Exact volume of the quadratic tets: det J is cubic, the rule is exact to degree 3."""
    qp, qw = collapsed_gauss(3)
    return float((jacobians(x, qp) @ qw).sum())


def node_table(mesh: InpMesh) -> dict:
    return {int(i): mesh.coords[k] for k, i in enumerate(mesh.node_ids)}


def polar(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.hypot(c[:, 0], c[:, 1]), np.arctan2(c[:, 1], c[:, 0])


def ids_where(mesh: InpMesh, mask: np.ndarray) -> set:
    return set(int(i) for i in mesh.node_ids[mask])


def in_patch(r, a, k: int, pad: geo.PadGeometry = geo.INBOARD) -> np.ndarray:
    """Nodes inside or on the boundary of patch k (1-based) of a pad's footprint, from the grid
    in brake_geometry."""
    radii, angles = geo.patch_radii(pad), geo.patch_angles()
    i, j = divmod(k - 1, 3)
    eps = 1e-9
    return (
        (r >= radii[i] - eps)
        & (r <= radii[i + 1] + eps)
        & (a >= angles[j] - eps)
        & (a <= angles[j + 1] + eps)
    )


def check_contact_sets(
    rep: Report,
    tag: str,
    mesh: InpMesh,
    pad: geo.PadGeometry,
    suffix: str = "",
    footprint_only: bool = False,
) -> np.ndarray:
    """CONTACT_FACE, CONTACT_PATCH_k and CONTACT (each name followed by suffix) of a pad's
    footprint against sets recomputed from coordinates: the nodes on the pad's friction-face
    plane, only those inside its footprint if footprint_only (a disc face is wider)."""
    c = mesh.coords
    r, a = polar(c)
    face_set, contact_set = f"CONTACT_FACE{suffix}", f"CONTACT{suffix}"
    on_face = np.abs(c[:, 2] - pad.face_z) < GEOM_TOL
    if footprint_only:
        on_face &= (
            (r >= pad.r_in - 1e-9)
            & (r <= pad.r_out + 1e-9)
            & (a >= geo.PAD_ANGLE_MIN - 1e-9)
            & (a <= geo.PAD_ANGLE_MAX + 1e-9)
        )
    face = ids_where(mesh, on_face)
    got_face = set(mesh.nsets.get(face_set, []))
    where = "inside the footprint" if footprint_only else "on the friction face"
    rep.check(
        len(got_face) > 0 and got_face <= face,
        f"{tag}: {len(got_face - face)} {face_set} nodes not at z = {pad.face_z} {where}",
    )
    rep.check(
        len(face) > 0 and got_face == face,
        f"{tag}: {face_set} differs from the nodes on the footprint",
    )
    for k in range(1, 10):
        expect = ids_where(mesh, on_face & in_patch(r, a, k, pad))
        name = f"CONTACT_PATCH{suffix}_{k}"
        got = set(mesh.nsets.get(name, []))
        rep.check(
            len(expect) > 3 and got == expect,
            f"{tag}: {name} differs from the nodes in patch {k}",
        )
    contact = mesh.nsets.get(contact_set, [])
    rep.check(len(contact) == 9, f"{tag}: {contact_set} has {len(contact)} nodes, not 9")
    # patch order is also id order, so a reader that sorts the set keeps the pairing
    rep.check(
        contact == sorted(contact), f"{tag}: {contact_set} ids not ascending in patch order"
    )
    table = node_table(mesh)
    xyz = np.array([table[i] for i in contact]) if contact else np.zeros((0, 3))
    expect_xyz = np.array(geo.contact_points(pad))
    if len(contact) == 9:
        err = np.abs(xyz - expect_xyz).max()
        rep.check(
            err <= GEOM_TOL, f"{tag}: {contact_set} nodes {err:.2e} m from the patch centres"
        )
        for k, nid in enumerate(contact):
            rep.check(
                nid in set(mesh.nsets.get(f"CONTACT_PATCH{suffix}_{k + 1}", [])),
                f"{tag}: {contact_set} node {k + 1} not in CONTACT_PATCH{suffix}_{k + 1}",
            )
    return xyz


def check_disc(rep: Report, tag: str, mesh: InpMesh, x: dict) -> dict:
    c = mesh.coords
    r, _ = polar(c)
    clamp = ids_where(mesh, np.abs(c[:, 2] - geo.FLANGE_Z_BOTTOM) < GEOM_TOL)
    rep.check(
        len(clamp) > 0 and set(mesh.nsets.get("CLAMP", [])) == clamp,
        f"{tag}: CLAMP differs from the nodes at z = {geo.FLANGE_Z_BOTTOM}",
    )
    rep.check(
        bool(
            r[list(np.flatnonzero(np.abs(c[:, 2] - geo.FLANGE_Z_BOTTOM) < GEOM_TOL))].min()
            >= geo.BORE_R - GEOM_TOL
        ),
        f"{tag}: CLAMP node inside the bore",
    )
    vol = mesh_volume(x["DISC"])
    return {
        "volume": {"DISC": (vol, geo.disc_volume())},
        "layers": {
            "disc": layers_ok(x["DISC"], geo.DISC_Z_BOTTOM, geo.DISC_Z_TOP, r_min=geo.HAT_R_OUT)
        },
    }


def between(z: np.ndarray, z0: float, z1: float, tol: float = 0.0) -> np.ndarray:
    """z0..z1 in either order, widened by tol (strictly inside for tol = 0)."""
    lo, hi = min(z0, z1), max(z0, z1)
    if tol == 0.0:
        return (z > lo) & (z < hi)
    return (z >= lo - tol) & (z <= hi + tol)


def check_pad(rep: Report, tag: str, mesh: InpMesh, x: dict, pad: geo.PadGeometry) -> dict:
    c = mesh.coords
    table = node_table(mesh)
    name = pad.load_set
    load = mesh.nsets.get(name, [])
    rep.check(len(load) == 4, f"{tag}: {name} has {len(load)} nodes, not 4")
    rep.check(load == sorted(load), f"{tag}: {name} ids not ascending in point order")
    if len(load) == 4:
        xyz = np.array([table[i] for i in load])
        rep.check(
            bool((xyz[:, 2] == pad.back_z).all()),
            f"{tag}: {name} nodes not at z = {pad.back_z} (the back face)",
        )
        err = np.abs(xyz - np.array(geo.load_points(pad))).max()
        rep.check(err <= GEOM_TOL, f"{tag}: {name} nodes {err:.2e} m from the load points")
    on_end = np.zeros(len(c), dtype=bool)
    for ang in (geo.PAD_ANGLE_MIN, geo.PAD_ANGLE_MAX):
        on_end |= np.abs(c[:, 0] * math.sin(ang) - c[:, 1] * math.cos(ang)) < GEOM_TOL
    abut = ids_where(mesh, on_end & between(c[:, 2], pad.lining_back_z, pad.back_z, GEOM_TOL))
    rep.check(
        len(abut) > 0 and set(mesh.nsets.get("ABUTMENT", [])) == abut,
        f"{tag}: ABUTMENT differs from the backplate end-face nodes",
    )
    # conforming lining/backplate interface: the same node ids on z = lining_back_z from both sides
    iface = {}
    for elset in ("LINING", "BACKPLATE"):
        ids = np.unique(mesh.elsets[elset][1])
        zz = np.array([table[int(i)][2] for i in ids])
        iface[elset] = set(int(i) for i in ids[np.abs(zz - pad.lining_back_z) < GEOM_TOL])
    rep.check(
        len(iface["LINING"]) > 0 and iface["LINING"] == iface["BACKPLATE"],
        f"{tag}: lining/backplate interface not conforming",
    )
    z_lin = x["LINING"][:, :4, 2].mean(axis=1)
    z_bp = x["BACKPLATE"][:, :4, 2].mean(axis=1)
    rep.check(
        bool(between(z_lin, pad.face_z, pad.lining_back_z).all()),
        f"{tag}: LINING element outside the lining",
    )
    rep.check(
        bool(between(z_bp, pad.lining_back_z, pad.back_z).all()),
        f"{tag}: BACKPLATE element outside the backplate",
    )
    vols = {
        "LINING": (mesh_volume(x["LINING"]), geo.lining_volume(pad)),
        "BACKPLATE": (mesh_volume(x["BACKPLATE"]), geo.backplate_volume(pad)),
    }
    z0, z1 = sorted((pad.face_z, pad.lining_back_z))
    return {"volume": vols, "layers": {"lining": layers_ok(x["LINING"], z0, z1)}}


def layers_ok(x: np.ndarray, z0: float, z1: float, r_min: float = 0.0) -> bool:
    """At least two elements through z0..z1: no element has a vertex on both faces (only
    counting elements entirely at radius >= r_min)."""
    zv = x[:, :4, 2]
    rv = np.hypot(x[:, :4, 0], x[:, :4, 1])
    region = (rv >= r_min - GEOM_TOL).all(axis=1)
    both = (np.abs(zv - z0) < GEOM_TOL).any(axis=1) & (np.abs(zv - z1) < GEOM_TOL).any(axis=1)
    return not bool((both & region).any())


def check_materials(rep: Report, tag: str, part: geo.Part, mesh: InpMesh) -> None:
    sections = SECTIONS[part.is_disc]
    rep.check(set(mesh.elsets) == set(sections), f"{tag}: element sets {sorted(mesh.elsets)}")
    for elset, mat in sections.items():
        rep.check(
            mesh.sections.get(elset) == mat,
            f"{tag}: section of {elset} is {mesh.sections.get(elset)}",
        )
        rep.check(
            mesh.materials.get(mat) == MATERIALS[mat],
            f"{tag}: material {mat} = {mesh.materials.get(mat)}",
        )


def check_msh_agrees(rep: Report, tag: str, msh_path: str, mesh: InpMesh) -> None:
    """Gmsh's reader on the .msh gives the .inp's nodes, tets (8 <-> 9 swapped) and node sets.
    A missing .msh is noted (not a failure): a large level may be shipped as .inp only."""
    import gmsh

    if not os.path.exists(msh_path):
        rep.note(f"{tag}: no {os.path.basename(msh_path)}, its checks skipped")
        return

    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        with open(msh_path, encoding="ascii") as f:
            f.readline()
            version = f.readline().split()
        rep.check(version[:2] == ["4.1", "0"], f"{tag}: .msh is not MSH 4.1 ASCII: {version}")
        gmsh.open(msh_path)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        coords = coords.reshape(-1, 3)
        order = np.argsort(tags)
        rep.check(
            np.array_equal(tags[order].astype(np.int64), mesh.node_ids),
            f"{tag}: .msh and .inp node ids differ",
        )
        rep.check(
            np.array_equal(coords[order], mesh.coords), f"{tag}: .msh and .inp coordinates differ"
        )
        for dim, ptag in gmsh.model.getPhysicalGroups():
            name = gmsh.model.getPhysicalName(dim, ptag)
            if dim == 3:
                etags, enodes = [], []
                for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
                    t, n = gmsh.model.mesh.getElementsByType(11, int(ent))
                    etags.append(t)
                    enodes.append(n.reshape(-1, 10))
                et = np.concatenate(etags).astype(np.int64)
                en = np.concatenate(enodes).astype(np.int64)[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
                o = np.argsort(et)
                ids, conn = mesh.elsets.get(name, (np.zeros(0), np.zeros((0, 10))))
                rep.check(
                    np.array_equal(et[o], ids) and np.array_equal(en[o], conn),
                    f"{tag}: .msh volume {name} differs from ELSET {name}",
                )
            else:
                n, _ = gmsh.model.mesh.getNodesForPhysicalGroup(dim, ptag)
                got = set(int(i) for i in n)
                rep.check(
                    got == set(mesh.nsets.get(name, [])),
                    f"{tag}: .msh group {name} differs from NSET {name}",
                )
        names = {gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()}
        rep.check(
            names == set(mesh.nsets) | set(mesh.elsets), f"{tag}: .msh groups {sorted(names)}"
        )
    finally:
        gmsh.finalize()


# Volume tolerance: the quadratic midside nodes put each boundary edge on its circle at three
# points, and the parabola strays from the circle by O(r t^4) over an arc of angle t: the
# coarsest arcs (40 degrees on the 33 mm bore) make a relative volume error of about 1e-5.
# A dimension 0.1 mm off (5e-3 of the 20 mm disc thickness) or a lost element is far above 5e-5.
VOLUME_RTOL = 5e-5


def check_part(
    rep: Report, mesh_dir: str, part: str, level: str, brake: str = "one-pad"
) -> dict:
    """All checks of one part's .inp, and its agreement with the .msh beside it."""
    tag = f"{geo.BRAKES[brake][part].stem}_{level}"
    mesh = read_inp(os.path.join(mesh_dir, tag + ".inp"))
    info = check_inp(rep, tag, part, mesh, brake)
    check_msh_agrees(rep, tag, os.path.join(mesh_dir, tag + ".msh"), mesh)
    return info


def check_inp(rep: Report, tag: str, part_name: str, mesh: InpMesh, brake: str = "one-pad") -> dict:
    """All checks of one part's mesh as read from its .inp; returns counts and measures."""
    part = geo.BRAKES[brake][part_name]
    x = {name: element_coords(mesh, conn) for name, (_, conn) in mesh.elsets.items()}
    info = {
        "nodes": int(mesh.node_ids.size),
        "elements": sum(v[0].size for v in mesh.elsets.values()),
    }
    rep.check(
        mesh.heading.startswith("squeal bundled brake mesh"), f"{tag}: heading {mesh.heading!r}"
    )
    rep.check(len(np.unique(mesh.node_ids)) == mesh.node_ids.size, f"{tag}: duplicate node ids")
    used = np.unique(np.concatenate([conn.ravel() for _, conn in mesh.elsets.values()]))
    rep.check(
        np.array_equal(used, np.sort(mesh.node_ids)),
        f"{tag}: nodes not used by any element, or undefined",
    )
    for name, xe in x.items():
        info.update(
            {f"{name}_{k}": v for k, v in check_midside(rep, f"{tag} {name}", part, xe).items()}
        )
        info.update(
            {f"{name}_{k}": v for k, v in check_jacobians(rep, f"{tag} {name}", xe).items()}
        )
    check_materials(rep, tag, part, mesh)
    # a disc names each footprint's sets with the pad's suffix; a pad's own sets have none
    contact_xyz = {
        pad.name: check_contact_sets(
            rep,
            tag,
            mesh,
            pad,
            suffix=pad.disc_suffix if part.is_disc else "",
            footprint_only=part.is_disc,
        )
        for pad in part.pads
    }
    if part.is_disc:
        more = check_disc(rep, tag, mesh, x)
    else:
        more = check_pad(rep, tag, mesh, x, part.pads[0])
    for name, (got, exact) in more["volume"].items():
        rel = abs(got - exact) / exact
        rep.check(
            rel < VOLUME_RTOL,
            f"{tag}: {name} volume {got:.9e} vs analytic {exact:.9e} (rel {rel:.1e})",
        )
        info[f"{name}_volume_rel_err"] = rel
    info["layers"] = more["layers"]
    info["nsets"] = {k: len(v) for k, v in mesh.nsets.items()}
    info["elsets"] = {k: int(v[0].size) for k, v in mesh.elsets.items()}
    info["contact_xyz"] = contact_xyz
    return info


def main(argv: list[str] | None = None) -> int:
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description="Check the bundled brake meshes.")
    ap.add_argument("--levels", nargs="+", default=["coarse", "medium", "fine"])
    brakes = list(geo.BRAKES) + ["ventilated"]
    ap.add_argument("--brakes", nargs="+", choices=brakes, default=brakes)
    ap.add_argument(
        "--mesh-dir", default=os.path.normpath(os.path.join(here, "..", "..", "meshes"))
    )
    ap.add_argument(
        "--require-layers",
        nargs="*",
        default=["medium", "fine"],
        help="levels that must have two elements through the disc and the lining",
    )
    args = ap.parse_args(argv)
    rep = Report()
    checked: dict[tuple[str, str], dict] = {}  # (stem, level) -> info: each file once
    totals = []
    for brake in args.brakes:
        print(f"\n{brake} brake\n")
        if brake == "ventilated":
            import check_ventilated as cv

            print(cv.TABLE_HEADER)
            for level in args.levels:
                if cv.check_level(rep, args.mesh_dir, level) is not None:
                    totals.append(f"ventilated {level}: checked")
            continue
        print(table_header(brake))
        for level in args.levels:
            infos = {}
            for name, part in geo.BRAKES[brake].items():
                key = (part.stem, level)
                if key not in checked:
                    info = check_part(rep, args.mesh_dir, name, level, brake)
                    for what, ok in info["layers"].items():
                        if level in args.require_layers:
                            rep.check(
                                ok,
                                f"{part.stem}_{level}: fewer than two elements through the {what}",
                            )
                    print(table_row(f"{part.stem}_{level}", info), flush=True)
                    checked[key] = info
                infos[name] = checked[key]
            check_pairs(rep, brake, level, infos)
            counts = " + ".join(str(infos[name]["nodes"]) for name in geo.BRAKES[brake])
            total = sum(infos[name]["nodes"] for name in geo.BRAKES[brake])
            totals.append(f"{brake} {level}: {counts} = {total} nodes")
    print()
    for line in totals:
        print(line)
    print(f"{rep.passed} passed, {len(rep.failures)} failed, {len(rep.notes)} notes")
    return 0 if not rep.failures else 1


def check_pairs(rep: Report, brake: str, level: str, infos: dict) -> None:
    """Each pad's contact nodes and the disc's under it are the same points, bit for bit."""
    parts = geo.BRAKES[brake]
    disc = next(name for name, part in parts.items() if part.is_disc)
    for pad in parts[disc].pads:
        (pad_part,) = [n for n, p in parts.items() if not p.is_disc and p.pads == (pad,)]
        on_disc = infos[disc]["contact_xyz"][pad.name]
        on_pad = infos[pad_part]["contact_xyz"][pad.name]
        same = on_disc.shape == on_pad.shape == (9, 3) and np.array_equal(on_disc, on_pad)
        gap = np.abs(on_disc - on_pad).max() if on_disc.shape == on_pad.shape else math.inf
        rep.check(
            same,
            f"{brake} {level}: {pad.name} pad's and disc's contact nodes differ "
            f"(up to {gap:.2e} m)",
        )


def table_header(brake: str) -> str:
    """The Markdown table header of table_row; a two-pad disc's cells are inboard / outboard."""
    if brake == "one-pad":
        contact, load = "CONTACT | CONTACT_FACE | CONTACT_PATCH_k", "PISTON"
    else:
        contact = "CONTACT (in / out) | CONTACT_FACE (in / out) | CONTACT_PATCH_k (in / out)"
        load = "PISTON / FINGERS"
    head = (
        f"| file | nodes | C3D10 | CLAMP / ABUTMENT | {contact} | {load} | curved edges"
        " | min detJ ratio | volume rel. err | 2 layers |"
    )
    return head + "\n" + "|---" * 12 + "|"


def table_row(name: str, info: dict) -> str:
    """One Markdown table row of counts and measures for meshes/README.md."""
    n = info["nsets"]
    elems = " + ".join(f"{v} {k}" for k, v in info["elsets"].items())
    # the footprints by their set-name suffix: a pad's own sets and a one-pad disc's have none
    suffixes = [s for s in ("", "_OUTBOARD") if f"CONTACT{s}" in n]

    def per_footprint(fmt) -> str:
        return " / ".join(fmt(s) for s in suffixes)

    def patch_range(s: str) -> str:
        patches = [n[f"CONTACT_PATCH{s}_{k}"] for k in range(1, 10)]
        return f"{min(patches)}..{max(patches)}"

    curved = sum(v for k, v in info.items() if k.endswith("curved_edges"))
    ratio = min(v for k, v in info.items() if k.endswith("min_det_ratio"))
    vol = max(v for k, v in info.items() if k.endswith("volume_rel_err"))
    layers = ", ".join(f"{k} {'yes' if ok else 'no'}" for k, ok in info["layers"].items())
    cells = [
        name,
        str(info["nodes"]),
        elems,
        str(n.get("CLAMP", n.get("ABUTMENT"))),
        per_footprint(lambda s: str(n[f"CONTACT{s}"])),
        per_footprint(lambda s: str(n[f"CONTACT_FACE{s}"])),
        per_footprint(patch_range),
        str(n.get("PISTON", n.get("FINGERS", "-"))),
        str(curved),
        f"{ratio:.3f}",
        f"{vol:.1e}",
        layers,
    ]
    return "| " + " | ".join(cells) + " |"


if __name__ == "__main__":
    sys.exit(main())
