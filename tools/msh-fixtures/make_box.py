"""Writes the box fixtures of the .msh reader tests with Gmsh itself.

One small straight-sided tet10 mesh of a box (a brake-pad-like block), written by Gmsh as
MSH 2.2 ASCII, 2.2 binary, 4.1 ASCII and 4.1 binary (little-endian, Gmsh's native order), and
as 4.1 ASCII and binary with parametric node coordinates (Mesh.SaveParametric);
`swap_endian.py` then makes big-endian copies of the binary files:
  python3 tools/msh-fixtures/swap_endian.py box_v41_binary.msh box_v41_binary_be.msh
  python3 tools/msh-fixtures/swap_endian.py box_v22_binary.msh box_v22_binary_be.msh

Physical groups (what the reader turns into sets):
  volume  1 "pad"            -> element set
  volume  2 "pad_again"      -> element set (same volume in a second group: MSH 2.2 writes
                                each tet10 twice, once per group, with different numbers)
  surface 3 "friction_face"  -> node set (top face z = H, with its quadratic triangles)
  point   4 "corner"         -> node set (one node, at the origin)
  curve   7 (no name)        -> node set "PHYSICAL_1_7" (the four edges of the bottom face)

Run from the repository root:
  python3 tools/msh-fixtures/make_box.py crates/squeal-mesh/tests/data/msh
Gmsh 4.15.2 (pip install gmsh) wrote the committed files.
"""

import os
import sys

import gmsh

L, W, H = 0.10, 0.06, 0.02
SIZE = 0.015


def build():
    gmsh.model.add("box")
    gmsh.model.occ.addBox(0.0, 0.0, 0.0, L, W, H)
    gmsh.model.occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), SIZE)

    def surface_at_z(z):
        for dim, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
            if abs(z0 - z) < 1e-6 and abs(z1 - z) < 1e-6:
                return tag
        raise RuntimeError(f"no surface at z = {z}")

    def point_at(p):
        for dim, tag in gmsh.model.getEntities(0):
            x0, y0, z0, _, _, _ = gmsh.model.getBoundingBox(dim, tag)
            if max(abs(x0 - p[0]), abs(y0 - p[1]), abs(z0 - p[2])) < 1e-6:
                return tag
        raise RuntimeError(f"no point at {p}")

    top = surface_at_z(H)
    bottom = surface_at_z(0.0)
    bottom_edges = [abs(t) for _, t in gmsh.model.getBoundary([(2, bottom)], oriented=False)]

    gmsh.model.addPhysicalGroup(3, [1], 1, name="pad")
    gmsh.model.addPhysicalGroup(3, [1], 2, name="pad_again")
    gmsh.model.addPhysicalGroup(2, [top], 3, name="friction_face")
    gmsh.model.addPhysicalGroup(0, [point_at((0.0, 0.0, 0.0))], 4, name="corner")
    gmsh.model.addPhysicalGroup(1, bottom_edges, 7)

    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.model.mesh.generate(3)


def main(out_dir):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    build()
    for version, binary, name in [
        (2.2, 0, "box_v22_ascii.msh"),
        (2.2, 1, "box_v22_binary.msh"),
        (4.1, 0, "box_v41_ascii.msh"),
        (4.1, 1, "box_v41_binary.msh"),
    ]:
        gmsh.option.setNumber("Mesh.MshFileVersion", version)
        gmsh.option.setNumber("Mesh.Binary", binary)
        gmsh.write(os.path.join(out_dir, name))
    # MSH 4.1 with parametric coordinates (u on curves, u v on surfaces) in the node blocks.
    gmsh.option.setNumber("Mesh.SaveParametric", 1)
    for binary, name in [(0, "box_v41_parametric_ascii.msh"), (1, "box_v41_parametric_binary.msh")]:
        gmsh.option.setNumber("Mesh.Binary", binary)
        gmsh.write(os.path.join(out_dir, name))
    _, tets, _ = gmsh.model.mesh.getElements(3)
    nodes, _, _ = gmsh.model.mesh.getNodes()
    print(f"{len(nodes)} nodes, {sum(len(t) for t in tets)} tet10")
    gmsh.finalize()


if __name__ == "__main__":
    main(sys.argv[1])
