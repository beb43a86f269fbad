"""Checks of the ventilated two-pad brake's meshes (meshes/ventilated), independent of the writer.

Called by check_meshes.py (``--brakes ventilated``, part of the default) and by the unit tests.
Each check compares against something defined without the mesh: the closed-form volumes of
ventilated_geometry.py, sets recomputed from node coordinates, the edge midpoints and circles.
The pairing check is what nodal contact needs of separately meshed parts: every node of a pad's
friction face lies on the disc's face under it (distance along the normal at most PAIR_TOL),
inside one of that face's triangles, and the two meshes do not match there.
"""

from __future__ import annotations

import math
import os
from types import SimpleNamespace

import numpy as np

import check_meshes as cm
import ventilated_geometry as vg

PARTS = ("disc", "inboard", "outboard")
# Every pad face node's distance to the disc face's plane (both are written on the same plane,
# z = 0 or 0.023 m, to %.16g): round-off of 0.1 m coordinates.
PAIR_TOL = 1e-12
# The quadratic midside nodes follow the circles at three points per edge; the coarsest arcs are
# the bolt holes' (r = 7 mm in about 4 to 6 edges): measured relative volume error 2e-5 on the
# coarse disc (see meshes/README.md); a missing vane (1.7e-3 of the volume) is far above.
VOLUME_RTOL = 1e-4


def pad_of(part: str) -> vg.VentPad:
    return {p.name: p for p in vg.PADS}[part]


def stem(part: str) -> str:
    return vg.DISC_STEM if part == "disc" else pad_of(part).stem


def disc_circles() -> list[tuple[float, float, float]]:
    axis = [(0.0, 0.0, r) for r in (vg.R_IN, vg.R_OUT, vg.HAT_R_OUT, vg.BORE_R)]
    return axis + [(x, y, vg.BOLT_R) for x, y in vg.bolt_centres()]


def face_triangles(mesh: cm.InpMesh, name: str, z: float) -> np.ndarray:
    """The corner coordinates (t, 3, 3) of the tets' faces whose 6 nodes all lie in node set
    name on the plane z: the triangles a reader makes of a face set."""
    members = np.zeros(int(mesh.node_ids.max()) + 1, dtype=bool)
    members[mesh.nsets.get(name, [])] = True
    index = np.full(members.size, -1, dtype=np.int64)
    index[mesh.node_ids] = np.arange(mesh.node_ids.size)
    faces = ((0, 1, 2, 4, 5, 6), (0, 1, 3, 4, 8, 7), (1, 2, 3, 5, 9, 8), (0, 2, 3, 6, 9, 7))
    tris = []
    for _, conn in mesh.elsets.values():
        for f in faces:
            nodes = conn[:, f]
            ok = members[nodes].all(axis=1)
            corners = mesh.coords[index[nodes[ok][:, :3]]]
            flat = (np.abs(corners[:, :, 2] - z) < cm.GEOM_TOL).all(axis=1)
            tris.append(corners[flat])
    return np.concatenate(tris) if tris else np.zeros((0, 3, 3))


def inside_any(tris: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Whether each point's (x, y) lies in one of the triangles (corners, straight edges)."""
    a, b, c = tris[:, 0, :2], tris[:, 1, :2], tris[:, 2, :2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    out = np.zeros(len(pts), dtype=bool)
    for k, p in enumerate(pts[:, :2]):
        l1 = ((p[0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (p[1] - a[:, 1])) / det
        l2 = ((b[:, 0] - a[:, 0]) * (p[1] - a[:, 1]) - (p[0] - a[:, 0]) * (b[:, 1] - a[:, 1])) / det
        eps = 1e-9
        out[k] = bool(((l1 >= -eps) & (l2 >= -eps) & (l1 + l2 <= 1 + eps)).any())
    return out


def check_disc_sets(rep: cm.Report, tag: str, mesh: cm.InpMesh) -> None:
    c = mesh.coords
    near_hole = np.zeros(len(c), dtype=bool)
    for x, y in vg.bolt_centres():
        near_hole |= np.abs(np.hypot(c[:, 0] - x, c[:, 1] - y) - vg.BOLT_R) < cm.GEOM_TOL
    in_flange = cm.between(c[:, 2], vg.FLANGE_Z_BOTTOM, vg.FLANGE_Z_TOP, cm.GEOM_TOL)
    clamp = cm.ids_where(mesh, near_hole & in_flange)
    rep.check(
        len(clamp) > 0 and set(mesh.nsets.get("CLAMP", [])) == clamp,
        f"{tag}: CLAMP differs from the nodes on the five bolt holes",
    )
    r = np.hypot(c[:, 0], c[:, 1])
    for pad in vg.PADS:
        name = pad.disc_face_set
        ids = mesh.nsets.get(name, [])
        on_face = cm.ids_where(mesh, (np.abs(c[:, 2] - pad.face_z) < cm.GEOM_TOL) & (r > 0.5 * vg.R_IN))
        rep.check(
            len(ids) > 0 and set(ids) <= on_face,
            f"{tag}: {name} nodes not on the friction face z = {pad.face_z}",
        )


def check_pad_sets(rep: cm.Report, tag: str, mesh: cm.InpMesh, x: dict, pad: vg.VentPad) -> None:
    c = mesh.coords
    table = cm.node_table(mesh)
    face = cm.ids_where(mesh, np.abs(c[:, 2] - pad.face_z) < cm.GEOM_TOL)
    rep.check(
        len(face) > 0 and set(mesh.nsets.get("CONTACT_FACE", [])) == face,
        f"{tag}: CONTACT_FACE differs from the nodes at z = {pad.face_z}",
    )
    load = mesh.nsets.get(pad.load_set, [])
    rep.check(len(load) == 4, f"{tag}: {pad.load_set} has {len(load)} nodes, not 4")
    if len(load) == 4:
        xyz = np.array([table[i] for i in load])
        err = np.abs(xyz - np.array(vg.load_points(pad))).max()
        rep.check(err <= cm.GEOM_TOL, f"{tag}: {pad.load_set} nodes {err:.2e} m from the points")
    on_end = np.zeros(len(c), dtype=bool)
    for ang in (pad.angle_min, pad.angle_max):
        on_end |= np.abs(c[:, 0] * math.sin(ang) - c[:, 1] * math.cos(ang)) < cm.GEOM_TOL
    abut = cm.ids_where(
        mesh, on_end & cm.between(c[:, 2], pad.lining_back_z, pad.back_z, cm.GEOM_TOL)
    )
    rep.check(
        len(abut) > 0 and set(mesh.nsets.get("ABUTMENT", [])) == abut,
        f"{tag}: ABUTMENT differs from the backplate end-face nodes",
    )
    iface = {}
    for elset in ("LINING", "BACKPLATE"):
        ids = np.unique(mesh.elsets[elset][1])
        zz = np.array([table[int(i)][2] for i in ids])
        iface[elset] = set(int(i) for i in ids[np.abs(zz - pad.lining_back_z) < cm.GEOM_TOL])
    rep.check(
        len(iface["LINING"]) > 0 and iface["LINING"] == iface["BACKPLATE"],
        f"{tag}: lining/backplate interface not conforming",
    )
    z_lin = x["LINING"][:, :4, 2].mean(axis=1)
    rep.check(
        bool(cm.between(z_lin, pad.face_z, pad.lining_back_z).all()),
        f"{tag}: LINING element outside the lining",
    )


def check_part(rep: cm.Report, mesh_dir: str, part: str, level: str) -> dict:
    """All checks of one part's .inp, and its agreement with the .msh beside it."""
    tag = f"{stem(part)}_{level}"
    mesh = cm.read_inp(os.path.join(mesh_dir, tag + ".inp"))
    info = check_inp(rep, tag, part, mesh)
    cm.check_msh_agrees(rep, tag, os.path.join(mesh_dir, tag + ".msh"), mesh)
    info["mesh"] = mesh
    return info


def check_inp(rep: cm.Report, tag: str, part: str, mesh: cm.InpMesh) -> dict:
    is_disc = part == "disc"
    x = {name: cm.element_coords(mesh, conn) for name, (_, conn) in mesh.elsets.items()}
    rep.check(
        mesh.heading.startswith("squeal bundled brake mesh"), f"{tag}: heading {mesh.heading!r}"
    )
    rep.check(len(np.unique(mesh.node_ids)) == mesh.node_ids.size, f"{tag}: duplicate node ids")
    used = np.unique(np.concatenate([conn.ravel() for _, conn in mesh.elsets.values()]))
    rep.check(
        np.array_equal(used, np.sort(mesh.node_ids)),
        f"{tag}: nodes not used by any element, or undefined",
    )
    if is_disc:
        circles = disc_circles()
    else:
        pad = pad_of(part)
        circles = [(0.0, 0.0, pad.r_in), (0.0, 0.0, pad.r_out)]
    info = {"nodes": int(mesh.node_ids.size), "curved": 0, "ratio": 1.0}
    for name, xe in x.items():
        info["curved"] += cm.check_midside(rep, f"{tag} {name}", None, xe, circles)["curved_edges"]
        ratio = cm.check_jacobians(rep, f"{tag} {name}", xe)["min_det_ratio"]
        info["ratio"] = min(info["ratio"], ratio)
    cm.check_materials(rep, tag, SimpleNamespace(is_disc=is_disc), mesh)
    if is_disc:
        check_disc_sets(rep, tag, mesh)
        volumes = {"DISC": (cm.mesh_volume(x["DISC"]), vg.disc_volume())}
    else:
        check_pad_sets(rep, tag, mesh, x, pad)
        volumes = {
            "LINING": (cm.mesh_volume(x["LINING"]), vg.lining_volume(pad)),
            "BACKPLATE": (cm.mesh_volume(x["BACKPLATE"]), vg.backplate_volume(pad)),
        }
    info["volume_rel_err"] = 0.0
    for name, (got, exact) in volumes.items():
        rel = abs(got - exact) / exact
        rep.check(
            rel < VOLUME_RTOL,
            f"{tag}: {name} volume {got:.9e} vs analytic {exact:.9e} (rel {rel:.1e})",
        )
        info["volume_rel_err"] = max(info["volume_rel_err"], rel)
    info["nsets"] = {k: len(v) for k, v in mesh.nsets.items()}
    info["elsets"] = {k: int(v[0].size) for k, v in mesh.elsets.items()}
    return info


def check_pairs(rep: cm.Report, level: str, infos: dict) -> dict:
    """What nodal contact needs of each pad and the disc face under it: every pad face node on
    the disc face's plane (PAIR_TOL) and inside one of its triangles; the disc face reaching
    beyond the footprint (its outline is the disc mesh's, not the pad's); non-matching meshes
    (most pad face nodes are not disc nodes). Returns per pad: face nodes, disc face nodes, pad
    nodes on a disc node."""
    disc = infos["disc"]["mesh"]
    out = {}
    for pad in vg.PADS:
        mesh = infos[pad.name]["mesh"]
        table = cm.node_table(mesh)
        pts = np.array([table[i] for i in mesh.nsets.get("CONTACT_FACE", [])])
        tris = face_triangles(disc, pad.disc_face_set, pad.face_z)
        gap = float(np.abs(pts[:, 2] - pad.face_z).max()) if len(pts) else math.inf
        rep.check(
            gap <= PAIR_TOL,
            f"ventilated {level}: {pad.name} pad face nodes up to {gap:.2e} m off the disc face",
        )
        inside = inside_any(tris, pts) if len(tris) else np.zeros(len(pts), dtype=bool)
        rep.check(
            len(pts) > 0 and bool(inside.all()),
            f"ventilated {level}: {int((~inside).sum())} {pad.name} pad face nodes outside "
            f"the disc's {pad.disc_face_set}",
        )
        dtable = cm.node_table(disc)
        dface = np.array([dtable[i] for i in disc.nsets.get(pad.disc_face_set, [])])
        beyond = np.array([vg.distance_to_footprint(pad, p[0], p[1]) for p in dface])
        rep.check(
            bool((beyond > 1e-6).any()),
            f"ventilated {level}: the disc's {pad.disc_face_set} ends on the pad's outline",
        )
        # a pad node on a disc node: same coordinates to 1e-9 m
        keys = {tuple(np.round(p / 1e-9).astype(np.int64)) for p in dface}
        shared = sum(tuple(np.round(p / 1e-9).astype(np.int64)) in keys for p in pts)
        rep.check(
            shared < 0.5 * len(pts),
            f"ventilated {level}: {shared} of {len(pts)} {pad.name} face nodes on disc nodes",
        )
        out[pad.name] = {"pad_face": len(pts), "disc_face": len(dface), "shared": shared}
    return out


def table_row(name: str, info: dict) -> str:
    n = info["nsets"]
    elems = " + ".join(f"{v} {k}" for k, v in info["elsets"].items())
    cells = [
        name,
        str(info["nodes"]),
        elems,
        str(n.get("CLAMP", n.get("ABUTMENT"))),
        " / ".join(str(n[s]) for s in ("CONTACT_FACE", "CONTACT_FACE_OUTBOARD") if s in n),
        str(n.get("PISTON", n.get("FINGERS", "-"))),
        str(info["curved"]),
        f"{info['ratio']:.3f}",
        f"{info['volume_rel_err']:.1e}",
    ]
    return "| " + " | ".join(cells) + " |"


TABLE_HEADER = (
    "| file | nodes | C3D10 | CLAMP / ABUTMENT | CONTACT_FACE (in / out) | PISTON / FINGERS"
    " | curved edges | min detJ ratio | volume rel. err |\n" + "|---" * 9 + "|"
)


def check_level(rep: cm.Report, mesh_dir: str, level: str) -> dict | None:
    """Check one level's three files, if they are there (only coarse is bundled); print rows."""
    paths = [os.path.join(mesh_dir, f"{stem(p)}_{level}.inp") for p in PARTS]
    if not all(os.path.exists(p) for p in paths):
        rep.note(f"ventilated {level}: not in {mesh_dir} (only coarse is bundled), not checked")
        return None
    infos = {p: check_part(rep, mesh_dir, p, level) for p in PARTS}
    for p in PARTS:
        print(table_row(f"{stem(p)}_{level}", infos[p]), flush=True)
    pairs = check_pairs(rep, level, infos)
    for name, c in pairs.items():
        print(
            f"ventilated {level} {name}: {c['pad_face']} pad face nodes on {c['disc_face']} "
            f"disc face nodes, {c['shared']} on a disc node",
            flush=True,
        )
    return infos
