#!/usr/bin/env python3
"""Generate squeal's bundled disc and pad meshes (10-node tetrahedra) with Gmsh.

For each refinement level (coarse, medium, fine) and each part of a brake this writes
``meshes/<part>_<level>.msh`` (Gmsh MSH 4.1 ASCII, physical groups named) and
``meshes/<part>_<level>.inp`` (Abaqus input: *NODE, *ELEMENT TYPE=C3D10, *NSET, materials and
sections). The geometry, the sets and the materials are described in ``meshes/README.md``.

Two brakes (``--brake``): the one-pad brake (the default) is ``disc`` and ``pad``; the two-pad
brake is ``two_pad/disc`` (the same disc with the outboard footprint imprinted on its bottom
face too) and ``two_pad/outboard`` (a second pad on the disc's bottom face), and reuses the
one-pad brake's ``pad`` as its inboard pad (not written again).

Usage (from the repository root)::

    python3 tools/mesh/brake_meshes.py                  # the bundled one-pad levels into meshes/
    python3 tools/mesh/brake_meshes.py --levels coarse  # one level
    python3 tools/mesh/brake_meshes.py --brake two-pad  # meshes/two_pad/{disc,outboard}_<level>
    python3 tools/mesh/brake_meshes.py --brake ventilated --levels coarse
                                  # meshes/ventilated/{disc,inboard,outboard}_coarse (separately
                                  # meshed parts: ventilated_meshes.py)
    python3 tools/mesh/brake_meshes.py --levels huge --parts disc --out-dir /tmp/squeal-huge
                                                        # ~1M-dof disc of the scaling study
    python3 tools/mesh/check_meshes.py                  # verify what was written (both brakes)

The output is deterministic: Gmsh runs on one thread with its serial Delaunay mesher, and
nothing time- or host-dependent is written.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass

import gmsh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import abaqus_inp  # noqa: E402
import brake_geometry as geo  # noqa: E402

# The committed meshes were made with this Gmsh (tools/mesh/requirements.txt pins it); another
# version meshes validly but not byte for byte the same.
GMSH_VERSION = "4.15.2"


@dataclass(frozen=True)
class Level:
    """Target element sizes (m) of one refinement level."""

    name: str
    disc_size: float  # disc away from the pad footprint
    contact_size: float  # disc top face under the pad (the footprint)
    pad_size: float  # whole pad (lining and backplate)
    transition: float  # distance over which the disc size grows from contact to disc size
    two_layers: bool  # split the disc annulus and the lining at mid-thickness
    netgen: bool  # also run Gmsh's Netgen optimizer (lifts the worst tets of the finer levels)


LEVELS = {
    # one element through the disc and the lining (the node budget of ~5k allows no more)
    "coarse": Level(
        "coarse",
        disc_size=0.025,
        contact_size=0.013,
        pad_size=0.013,
        transition=0.02,
        two_layers=False,
        netgen=False,
    ),
    "medium": Level(
        "medium",
        disc_size=0.015,
        contact_size=0.008,
        pad_size=0.008,
        transition=0.02,
        two_layers=True,
        netgen=True,
    ),
    "fine": Level(
        "fine",
        disc_size=0.0072,
        contact_size=0.004,
        pad_size=0.004,
        transition=0.02,
        two_layers=True,
        netgen=True,
    ),
    # The scaling study's disc of about a million dofs (about 7x the fine disc's nodes); not
    # bundled: write it outside the repository, e.g.
    # python3 tools/mesh/brake_meshes.py --levels huge --parts disc --out-dir /tmp/squeal-huge
    "huge": Level(
        "huge",
        disc_size=0.0031,
        contact_size=0.0017,
        pad_size=0.0017,
        transition=0.02,
        two_layers=True,
        netgen=True,
    ),
}

# Levels written by default (the bundled meshes).
BUNDLED = ["coarse", "medium", "fine"]


def set_common_options(level: Level, max_size: float) -> None:
    """Mesher options shared by both parts: second order, curved boundary, serial Delaunay."""
    opt = gmsh.option.setNumber
    opt("General.Terminal", 0)
    opt("General.NumThreads", 1)
    opt("Mesh.Algorithm", 6)  # 2-D: Frontal-Delaunay
    opt("Mesh.Algorithm3D", 1)  # 3-D: Delaunay (serial, deterministic)
    opt("Mesh.ElementOrder", 2)
    opt("Mesh.SecondOrderLinear", 0)  # midside nodes on the CAD surfaces (curved boundary)
    opt("Mesh.HighOrderOptimize", 0)
    opt("Mesh.Optimize", 1)
    opt("Mesh.OptimizeNetgen", 1 if level.netgen else 0)
    opt("Mesh.MeshSizeFromPoints", 0)
    opt("Mesh.MeshSizeFromCurvature", 0)
    opt("Mesh.MeshSizeExtendFromBoundary", 0)
    opt("Mesh.MeshSizeMax", max_size)
    opt("Mesh.MeshSizeMin", 0.0)
    opt("Mesh.MshFileVersion", 4.1)
    opt("Mesh.Binary", 0)
    opt("Mesh.SaveAll", 0)
    opt("Geometry.OCCParallel", 0)


def patch_sector_faces(pad: geo.PadGeometry) -> list[int]:
    """The 3 x 3 contact patches of a pad's footprint as OCC faces on its friction face's plane,
    numbered as geo.patch_index."""
    occ = gmsh.model.occ
    z = pad.face_z
    radii = geo.patch_radii(pad)
    angles = geo.patch_angles()
    centre = occ.addPoint(0.0, 0.0, z)
    pts = [[occ.addPoint(r * math.cos(a), r * math.sin(a), z) for a in angles] for r in radii]
    arcs = [
        [occ.addCircleArc(pts[i][j], centre, pts[i][j + 1]) for j in range(3)] for i in range(4)
    ]
    rays = [[occ.addLine(pts[i][j], pts[i + 1][j]) for j in range(4)] for i in range(3)]
    faces = []
    for i in range(3):
        for j in range(3):
            loop = occ.addCurveLoop([arcs[i][j], rays[i][j + 1], -arcs[i + 1][j], -rays[i][j]])
            faces.append(occ.addPlaneSurface([loop]))
    occ.remove([(0, centre)])
    return faces


def tube(r_in: float, r_out: float, z0: float, z1: float) -> list[tuple[int, int]]:
    """A full annular cylinder r_in..r_out, z0..z1 about the z axis."""
    occ = gmsh.model.occ
    outer = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r_out)
    inner = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r_in)
    out, _ = occ.cut([(3, outer)], [(3, inner)])
    return out


def sector(
    r_in: float,
    r_out: float,
    z0: float,
    z1: float,
    angles: tuple[float, float] = (geo.PAD_ANGLE_MIN, geo.PAD_ANGLE_MAX),
) -> list[tuple[int, int]]:
    """An annular sector r_in..r_out, z0..z1 between two angles (the bundled pads': 65..115 deg)."""
    occ = gmsh.model.occ
    span = angles[1] - angles[0]
    outer = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r_out, angle=span)
    inner = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, r_in, angle=span)
    out, _ = occ.cut([(3, outer)], [(3, inner)])
    occ.rotate(out, 0, 0, 0, 0, 0, 1, angles[0])
    return out


def add_points(coords: list[tuple[float, float, float]]) -> list[int]:
    occ = gmsh.model.occ
    return [occ.addPoint(x, y, z) for (x, y, z) in coords]


def faces_at(dim_tags: list[tuple[int, int]], predicate) -> list[int]:
    """Tags of the surfaces among dim_tags whose bounding box satisfies predicate."""
    out = []
    for dim, tag in dim_tags:
        if dim == 2 and predicate(gmsh.model.getBoundingBox(dim, tag)):
            out.append(tag)
    return sorted(out)


def physical(dim: int, tags: list[int], name: str) -> None:
    if not tags:
        raise RuntimeError(f"physical group {name} would be empty")
    gmsh.model.addPhysicalGroup(dim, tags, name=name)


def check_cad_volume(volumes: list[int], exact: float, what: str) -> None:
    """The OCC solids' volume equals the analytic one (guards the CAD construction)."""
    got = sum(gmsh.model.occ.getMass(3, v) for v in volumes)
    # OCC integrates the exact B-rep (planes, cylinders) by Gauss rules: ~1e-12 relative
    if abs(got - exact) > 1e-9 * exact:
        raise RuntimeError(f"{what}: CAD volume {got!r} differs from the analytic {exact!r}")


def contact_size_field(patches: list[int], level: Level) -> None:
    """Mesh size: contact_size on the footprints' patches, growing to disc_size away from them
    (over level.transition from the nearest patch)."""
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "SurfacesList", patches)
    field.setNumber(dist, "Sampling", 40)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", level.contact_size)
    field.setNumber(thr, "SizeMax", level.disc_size)
    field.setNumber(thr, "DistMin", 0.0)
    field.setNumber(thr, "DistMax", level.transition)
    field.setAsBackgroundMesh(thr)


def build_disc(level: Level, part: geo.Part) -> None:
    """Disc: braking annulus, hat wall and hub flange, each pad's footprint in 9 patches.

    The sets of a footprint are named CONTACT_FACE, CONTACT_PATCH_k and CONTACT followed by the
    pad's disc_suffix (CONTACT_PATCH_OUTBOARD_k for the outboard pad)."""
    occ = gmsh.model.occ
    gmsh.model.add(part.stem.replace("/", "_") + f"_{level.name}")
    set_common_options(level, level.disc_size)
    # The annulus as two half-thickness layers sharing a conforming mid-plane face: no tet can
    # reach from one braking face to the other, so there are >= 2 elements through the thickness.
    if level.two_layers:
        annulus = tube(geo.DISC_R_IN, geo.DISC_R_OUT, geo.DISC_Z_BOTTOM, geo.DISC_Z_MID)
        annulus += tube(geo.DISC_R_IN, geo.DISC_R_OUT, geo.DISC_Z_MID, geo.DISC_Z_TOP)
    else:
        annulus = tube(geo.DISC_R_IN, geo.DISC_R_OUT, geo.DISC_Z_BOTTOM, geo.DISC_Z_TOP)
    parts = (
        annulus
        + tube(geo.DISC_R_IN, geo.HAT_R_OUT, geo.FLANGE_Z_TOP, geo.DISC_Z_BOTTOM)
        + tube(geo.BORE_R, geo.HAT_R_OUT, geo.FLANGE_Z_BOTTOM, geo.FLANGE_Z_TOP)
    )
    patches_in = [f for pad in part.pads for f in patch_sector_faces(pad)]
    out, out_map = occ.fragment(parts, [(2, f) for f in patches_in])
    patch_tags = [
        [_single_child(out_map[len(parts) + 9 * n + k], 2) for k in range(9)]
        for n in range(len(part.pads))
    ]
    volumes = sorted(t for d, t in out if d == 3)
    check_cad_volume(volumes, geo.disc_volume(), "disc")
    contact_pts = [add_points(geo.contact_points(pad)) for pad in part.pads]
    occ.synchronize()

    for pts, tags in zip(contact_pts, patch_tags):
        for k, p in enumerate(pts):
            gmsh.model.mesh.embed(0, [p], 2, tags[k])
    boundary = gmsh.model.getBoundary([(3, v) for v in volumes], oriented=False)
    clamp = faces_at(
        boundary,
        lambda b: abs(b[2] - geo.FLANGE_Z_BOTTOM) < 1e-6 and abs(b[5] - geo.FLANGE_Z_BOTTOM) < 1e-6,
    )

    physical(3, volumes, "DISC")
    physical(2, clamp, "CLAMP")
    for pad, pts, tags in zip(part.pads, contact_pts, patch_tags):
        physical(2, tags, f"CONTACT_FACE{pad.disc_suffix}")
        for k, tag in enumerate(tags):
            physical(2, [tag], f"CONTACT_PATCH{pad.disc_suffix}_{k + 1}")
        physical(0, pts, f"CONTACT{pad.disc_suffix}")
    contact_size_field([t for tags in patch_tags for t in tags], level)


def pad_layer(pad: geo.PadGeometry, z0: float, z1: float) -> list[tuple[int, int]]:
    """The pad's sector between two of its heights, in either order."""
    return sector(pad.r_in, pad.r_out, min(z0, z1), max(z0, z1))


def build_pad(level: Level, part: geo.Part) -> None:
    """Pad: lining and backplate sectors fragmented together, friction face split into 9 patches.

    Sets: LINING, BACKPLATE (elements); CONTACT_FACE, CONTACT_PATCH_k, CONTACT, ABUTMENT and the
    load points (pad.load_set)."""
    occ = gmsh.model.occ
    (pad,) = part.pads
    gmsh.model.add(part.stem.replace("/", "_") + f"_{level.name}")
    set_common_options(level, level.pad_size)
    # The lining as two half-thickness layers (see build_disc): >= 2 elements through it.
    if level.two_layers:
        lining = pad_layer(pad, pad.face_z, pad.lining_mid_z)
        lining += pad_layer(pad, pad.lining_mid_z, pad.lining_back_z)
    else:
        lining = pad_layer(pad, pad.face_z, pad.lining_back_z)
    backplate = pad_layer(pad, pad.lining_back_z, pad.back_z)
    patches_in = patch_sector_faces(pad)
    solids = lining + backplate
    out, out_map = occ.fragment(solids, [(2, f) for f in patches_in])
    lining_vols = sorted(t for k in range(len(lining)) for d, t in out_map[k] if d == 3)
    backplate_vols = sorted(
        t for k in range(len(lining), len(solids)) for d, t in out_map[k] if d == 3
    )
    patch_tags = [_single_child(out_map[len(solids) + k], 2) for k in range(9)]
    check_cad_volume(lining_vols, geo.lining_volume(pad), "lining")
    check_cad_volume(backplate_vols, geo.backplate_volume(pad), "backplate")
    contact_pts = add_points(geo.contact_points(pad))
    load_pts = add_points(geo.load_points(pad))
    occ.synchronize()

    for k, p in enumerate(contact_pts):
        gmsh.model.mesh.embed(0, [p], 2, patch_tags[k])
    back_boundary = gmsh.model.getBoundary([(3, v) for v in backplate_vols], oriented=False)
    back_face = faces_at(
        back_boundary,
        lambda b: abs(b[2] - pad.back_z) < 1e-6 and abs(b[5] - pad.back_z) < 1e-6,
    )
    if len(back_face) != 1:
        raise RuntimeError(f"expected one backplate back face, found {back_face}")
    gmsh.model.mesh.embed(0, load_pts, 2, back_face[0])
    abutment = sector_end_faces(back_boundary)
    if len(abutment) != 2:
        raise RuntimeError(f"expected two backplate end faces, found {abutment}")

    physical(3, lining_vols, "LINING")
    physical(3, backplate_vols, "BACKPLATE")
    physical(2, patch_tags, "CONTACT_FACE")
    for k, tag in enumerate(patch_tags):
        physical(2, [tag], f"CONTACT_PATCH_{k + 1}")
    physical(2, abutment, "ABUTMENT")
    physical(0, contact_pts, "CONTACT")
    physical(0, load_pts, pad.load_set)


def sector_end_faces(
    dim_tags: list[tuple[int, int]],
    angles: tuple[float, float] = (geo.PAD_ANGLE_MIN, geo.PAD_ANGLE_MAX),
) -> list[int]:
    """Planar faces among dim_tags lying in one of the two radial planes at the sector's ends."""
    out = []
    for dim, tag in dim_tags:
        if dim != 2 or gmsh.model.getType(dim, tag) != "Plane":
            continue
        x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag)
        for angle in angles:
            # the centroid lies on the radial line at this angle, on the pad's side of the axis
            along = x * math.cos(angle) + y * math.sin(angle)
            across = -x * math.sin(angle) + y * math.cos(angle)
            if abs(across) < 1e-9 and along > 0.0:
                out.append(tag)
    return sorted(out)


def _single_child(children: list[tuple[int, int]], dim: int) -> int:
    tags = [t for d, t in children if d == dim]
    if len(tags) != 1:
        raise RuntimeError(f"expected one child of dimension {dim}, found {children}")
    return tags[0]


def mesh_and_write(stem: str, level: Level, out_dir: str, after_mesh=None) -> dict:
    """Mesh the current model (second order), call after_mesh() if given (groups made from the
    mesh), renumber, write .msh and .inp; return counts."""
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    if after_mesh is not None:
        after_mesh()
    gmsh.model.mesh.renumberNodes()
    gmsh.model.mesh.renumberElements()
    base = os.path.join(out_dir, f"{stem}_{level.name}")
    os.makedirs(os.path.dirname(base), exist_ok=True)
    gmsh.write(base + ".msh")
    counts = abaqus_inp.write_inp(base + ".inp", stem, level.name, gmsh.__version__)
    tets, _ = gmsh.model.mesh.getElementsByType(abaqus_inp.GMSH_TET10)
    gamma = gmsh.model.mesh.getElementQualities(tets, "gamma")
    counts["min_gamma"] = float(min(gamma))
    return counts


def default_parts(brake: str) -> list[str]:
    """The parts a brake writes: all but those it reuses from another brake."""
    return [name for name, part in geo.BRAKES[brake].items() if not part.reused]


def generate(
    levels: list[str], parts: list[str], out_dir: str, brake: str = "one-pad"
) -> dict[str, float]:
    """Write <stem>_<level>.msh and .inp under out_dir for every level and named part of the
    brake (stems as in geo.BRAKES: two_pad/disc goes to out_dir/two_pad/disc_<level>.*).
    Returns the seconds each level took."""
    if gmsh.__version__ != GMSH_VERSION:
        print(
            f"warning: Gmsh {gmsh.__version__}, not {GMSH_VERSION}: the meshes will differ from "
            "the committed ones",
            file=sys.stderr,
        )
    os.makedirs(out_dir, exist_ok=True)
    gmsh.initialize(["brake_meshes"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    seconds = {}
    try:
        for name in levels:
            level = LEVELS[name]
            seconds[name] = 0.0
            for part_name in parts:
                part = geo.BRAKES[brake][part_name]
                start = time.perf_counter()
                gmsh.clear()
                if part.is_disc:
                    build_disc(level, part)
                else:
                    build_pad(level, part)
                counts = mesh_and_write(part.stem, level, out_dir)
                secs = time.perf_counter() - start
                seconds[name] += secs
                print(
                    f"{part.stem}_{name}: {counts['nodes']} nodes, {counts['elements']} C3D10, "
                    f"worst tet shape (gamma) {counts['min_gamma']:.3f}, {secs:.1f} s",
                    flush=True,
                )
            print(f"level {name}: {seconds[name]:.1f} s", flush=True)
    finally:
        gmsh.finalize()
    return seconds


def main(argv: list[str] | None = None) -> int:
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.normpath(os.path.join(here, "..", "..", "meshes"))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--brake",
        choices=list(geo.BRAKES) + ["ventilated"],
        default="one-pad",
        help="one-pad: disc and pad (default); two-pad: two_pad/disc and two_pad/outboard "
        "(its inboard pad is the one-pad brake's pad); ventilated: ventilated/disc, "
        "ventilated/inboard and ventilated/outboard (meshes/README.md, Ventilated brake)",
    )
    ap.add_argument(
        "--levels",
        nargs="+",
        choices=list(LEVELS) + ["xfine"],
        default=BUNDLED,
        help="xfine: the ventilated pads only (--brake ventilated --parts inboard outboard)",
    )
    ap.add_argument(
        "--parts",
        nargs="+",
        choices=sorted({p for parts in geo.BRAKES.values() for p in parts} | {"inboard"}),
        help="parts of the brake to write (default: all it does not reuse)",
    )
    ap.add_argument("--out-dir", default=default_out)
    args = ap.parse_args(argv)
    if args.brake == "ventilated":
        import ventilated_meshes as vm

        parts = args.parts or list(vm.PARTS)
        if any(p not in vm.PARTS for p in parts) or "huge" in args.levels:
            ap.error(f"the ventilated brake writes the parts {', '.join(vm.PARTS)} (no huge level)")
        if "xfine" in args.levels and "disc" in parts:
            ap.error("the xfine level meshes the ventilated pads only: add --parts inboard outboard")
        vm.generate(args.levels, parts, args.out_dir)
        return 0
    if "xfine" in args.levels:
        ap.error("the xfine level is the ventilated brake's pads only (--brake ventilated)")
    parts = args.parts or default_parts(args.brake)
    own = default_parts(args.brake)
    if any(p not in own for p in parts):
        ap.error(f"the {args.brake} brake writes the parts {', '.join(own)}")
    generate(args.levels, parts, args.out_dir, args.brake)
    return 0


if __name__ == "__main__":
    sys.exit(main())
