"""The ventilated two-pad brake's meshes (10-node tetrahedra, Gmsh): `brake_meshes.py --brake
ventilated` writes meshes/ventilated/{disc,inboard,outboard}_<level>.{inp,msh}.

Each part is meshed on its own (non-matching meshes at the contact): the disc's friction faces
are whole annuli meshed without any trace of the pads, and the disc's CONTACT_FACE sets are
chosen after meshing as the friction-face triangles that reach the pad's footprint (their
corners farther from their centroid than the centroid is from the footprint), so their outline
is ragged and covers the footprint. Geometry and sets: meshes/README.md, "Ventilated brake".
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass

import gmsh

import abaqus_inp
import brake_meshes as bm
import ventilated_geometry as vg

GMSH_TRIANGLE6 = 9


@dataclass(frozen=True)
class VentLevel:
    """Target element sizes (m) of one refinement level."""

    name: str
    disc_size: float  # the whole disc (cheeks, vanes, hat, flange)
    pad_size: float  # the whole pad (lining and backplate)
    netgen: bool  # also run Gmsh's Netgen optimizer


LEVELS = {
    # coarse: small enough that `squeal stability` with nodal contact takes about a minute
    # (meshes/README.md); each level about halves the sizes of the one before (fine: 6.5 mm, at
    # which the bore has no inverted curved element; Netgen off: its optimizer inverted or
    # flattened curved elements on the bolt holes and bore)
    "coarse": VentLevel("coarse", disc_size=0.024, pad_size=0.030, netgen=False),
    "medium": VentLevel("medium", disc_size=0.012, pad_size=0.015, netgen=False),
    "fine": VentLevel("fine", disc_size=0.0065, pad_size=0.0075, netgen=False),
    # xfine: the pads only (3.75 mm, four elements through the 15 mm pad), a fourth level of
    # the pads' refinement on a coarser disc (docs/reduction.md, "A fourth pad level"); a disc
    # at half the fine size would need about 100 GB to reduce
    "xfine": VentLevel("xfine", disc_size=0.0, pad_size=0.00375, netgen=False),
}
PAD_ONLY_LEVELS = ("xfine",)
PARTS = ("disc", "inboard", "outboard")


def _level_options(level: VentLevel, size: float) -> None:
    bm.set_common_options(
        bm.Level(level.name, size, size, size, 0.0, False, level.netgen), max_size=size
    )
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)


def _vanes() -> list[tuple[int, int]]:
    """The vanes: the channel between the cheeks cut to straight radial strips."""
    occ = gmsh.model.occ
    height = vg.Z_CHANNEL_TOP - vg.Z_CHANNEL_BOTTOM
    long = vg.R_OUT + 0.01
    boxes = []
    for angle in vg.vane_angles():
        box = occ.addBox(0.0, -0.5 * vg.VANE_WIDTH, vg.Z_CHANNEL_BOTTOM, long, vg.VANE_WIDTH, height)
        occ.rotate([(3, box)], 0, 0, 0, 0, 0, 1, angle)
        boxes.append((3, box))
    channel = bm.tube(vg.R_IN, vg.R_OUT, vg.Z_CHANNEL_BOTTOM, vg.Z_CHANNEL_TOP)
    out, _ = occ.intersect(channel, boxes)
    return out


def _flange() -> list[tuple[int, int]]:
    occ = gmsh.model.occ
    ring = bm.tube(vg.BORE_R, vg.HAT_R_OUT, vg.FLANGE_Z_BOTTOM, vg.FLANGE_Z_TOP)
    height = vg.FLANGE_Z_TOP - vg.FLANGE_Z_BOTTOM
    holes = [
        (3, occ.addCylinder(x, y, vg.FLANGE_Z_BOTTOM, 0, 0, height, vg.BOLT_R))
        for x, y in vg.bolt_centres()
    ]
    out, _ = occ.cut(ring, holes)
    return out


def _bolt_hole_faces(dim_tags: list[tuple[int, int]]) -> list[int]:
    """The cylindrical faces whose centre of mass lies on the bolt circle."""
    out = []
    for dim, tag in dim_tags:
        if dim != 2 or gmsh.model.getType(dim, tag) != "Cylinder":
            continue
        x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag)
        if any(math.hypot(x - cx, y - cy) < 1e-6 for cx, cy in vg.bolt_centres()):
            out.append(tag)
    return sorted(out)


def build_disc(level: VentLevel) -> None:
    """Disc: cheeks, vanes, hat wall and flange fragmented into one conforming mesh.

    Sets: DISC (elements); CLAMP (the bolt holes' faces); CONTACT_FACE and
    CONTACT_FACE_OUTBOARD are added after meshing (friction_face_groups)."""
    occ = gmsh.model.occ
    gmsh.model.add(f"ventilated_disc_{level.name}")
    _level_options(level, level.disc_size)
    pieces = (
        bm.tube(vg.R_IN, vg.R_OUT, vg.Z_BOTTOM, vg.Z_CHANNEL_BOTTOM)
        + bm.tube(vg.R_IN, vg.R_OUT, vg.Z_CHANNEL_TOP, vg.Z_TOP)
        + _vanes()
        + bm.tube(vg.R_IN, vg.HAT_R_OUT, vg.FLANGE_Z_TOP, vg.Z_BOTTOM)
        + _flange()
    )
    out, _ = occ.fragment(pieces, [])
    volumes = sorted(t for d, t in out if d == 3)
    bm.check_cad_volume(volumes, vg.disc_volume(), "ventilated disc")
    occ.synchronize()
    boundary = gmsh.model.getBoundary([(3, v) for v in volumes], oriented=False)
    bm.physical(3, volumes, "DISC")
    bm.physical(2, _bolt_hole_faces(boundary), "CLAMP")


def _friction_face(pad: vg.VentPad) -> int:
    """The disc's planar face at the pad's friction-face height spanning the cheek (r_in..r_out)."""
    found = []
    for dim, tag in gmsh.model.getEntities(2):
        b = gmsh.model.getBoundingBox(dim, tag)
        flat = abs(b[2] - pad.face_z) < 1e-6 and abs(b[5] - pad.face_z) < 1e-6
        if flat and b[3] > vg.R_OUT - 1e-6:
            found.append(tag)
    if len(found) != 1:
        raise RuntimeError(f"expected one friction face at z = {pad.face_z}, found {found}")
    return found[0]


def friction_face_groups() -> None:
    """After meshing: for each pad, the disc's friction-face triangles that reach its
    footprint, as a discrete surface and the physical group pad.disc_face_set."""
    next_tag = int(gmsh.model.mesh.getMaxElementTag()) + 1
    for pad in vg.PADS:
        face = _friction_face(pad)
        tags, nodes = gmsh.model.mesh.getElementsByType(GMSH_TRIANGLE6, face)
        nodes = nodes.reshape(-1, 6)
        keep = []
        for row in nodes:
            corners = [gmsh.model.mesh.getNode(int(n))[0] for n in row[:3]]
            cx = sum(c[0] for c in corners) / 3.0
            cy = sum(c[1] for c in corners) / 3.0
            reach = max(math.hypot(c[0] - cx, c[1] - cy) for c in corners)
            if vg.distance_to_footprint(pad, cx, cy) < reach:
                keep.append([int(n) for n in row])
        entity = gmsh.model.addDiscreteEntity(2)
        gmsh.model.mesh.addElementsByType(
            entity,
            GMSH_TRIANGLE6,
            list(range(next_tag, next_tag + len(keep))),
            [n for row in keep for n in row],
        )
        next_tag += len(keep)
        bm.physical(2, [entity], pad.disc_face_set)


def build_pad(level: VentLevel, pad: vg.VentPad) -> None:
    """Pad: lining and backplate sectors fragmented together (conforming interface).

    Sets: LINING, BACKPLATE (elements); CONTACT_FACE (friction face), ABUTMENT (the backplate's
    two end faces) and the load points (pad.load_set)."""
    occ = gmsh.model.occ
    gmsh.model.add(f"ventilated_{pad.name}_{level.name}")
    _level_options(level, level.pad_size)
    angles = (pad.angle_min, pad.angle_max)
    lo, hi = sorted((pad.face_z, pad.lining_back_z))
    lining = bm.sector(pad.r_in, pad.r_out, lo, hi, angles)
    lo, hi = sorted((pad.lining_back_z, pad.back_z))
    backplate = bm.sector(pad.r_in, pad.r_out, lo, hi, angles)
    out, out_map = occ.fragment(lining + backplate, [])
    lining_vols = sorted(t for d, t in out_map[0] if d == 3)
    backplate_vols = sorted(t for d, t in out_map[1] if d == 3)
    bm.check_cad_volume(lining_vols, vg.lining_volume(pad), "lining")
    bm.check_cad_volume(backplate_vols, vg.backplate_volume(pad), "backplate")
    load_pts = bm.add_points(vg.load_points(pad))
    occ.synchronize()

    lining_boundary = gmsh.model.getBoundary([(3, v) for v in lining_vols], oriented=False)
    friction = bm.faces_at(
        lining_boundary,
        lambda b: abs(b[2] - pad.face_z) < 1e-6 and abs(b[5] - pad.face_z) < 1e-6,
    )
    back_boundary = gmsh.model.getBoundary([(3, v) for v in backplate_vols], oriented=False)
    back_face = bm.faces_at(
        back_boundary,
        lambda b: abs(b[2] - pad.back_z) < 1e-6 and abs(b[5] - pad.back_z) < 1e-6,
    )
    if len(friction) != 1 or len(back_face) != 1:
        raise RuntimeError(f"expected one friction and one back face: {friction}, {back_face}")
    gmsh.model.mesh.embed(0, load_pts, 2, back_face[0])
    abutment = bm.sector_end_faces(back_boundary, angles)
    if len(abutment) != 2:
        raise RuntimeError(f"expected two backplate end faces, found {abutment}")
    bm.physical(3, lining_vols, "LINING")
    bm.physical(3, backplate_vols, "BACKPLATE")
    bm.physical(2, friction, "CONTACT_FACE")
    bm.physical(2, abutment, "ABUTMENT")
    bm.physical(0, load_pts, pad.load_set)


def stem(part: str) -> str:
    return vg.DISC_STEM if part == "disc" else {p.name: p.stem for p in vg.PADS}[part]


def generate(levels: list[str], parts: list[str], out_dir: str) -> dict[str, float]:
    """Write ventilated/<part>_<level>.msh and .inp under out_dir; return seconds per level."""
    os.makedirs(out_dir, exist_ok=True)
    gmsh.initialize(["ventilated_meshes"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    seconds = {}
    if "disc" in parts and any(name in PAD_ONLY_LEVELS for name in levels):
        raise ValueError("the xfine level meshes the ventilated pads only (--parts inboard outboard)")
    try:
        for name in levels:
            level = LEVELS[name]
            seconds[name] = 0.0
            for part in parts:
                start = time.perf_counter()
                gmsh.clear()
                if part == "disc":
                    build_disc(level)
                    after = friction_face_groups
                else:
                    build_pad(level, {p.name: p for p in vg.PADS}[part])
                    after = None
                counts = bm.mesh_and_write(stem(part), level, out_dir, after)
                secs = time.perf_counter() - start
                seconds[name] += secs
                print(
                    f"{stem(part)}_{name}: {counts['nodes']} nodes, {counts['elements']} C3D10, "
                    f"worst tet shape (gamma) {counts['min_gamma']:.3f}, {secs:.1f} s",
                    flush=True,
                )
            print(f"level {name}: {seconds[name]:.1f} s", flush=True)
    finally:
        gmsh.finalize()
    return seconds
