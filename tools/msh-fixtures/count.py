"""Counts what the .msh reader tests expect, with the Gmsh Python API as the independent reader.

For each file: number of nodes, of 10-node tetrahedra (type 11) and of other elements by type,
and per physical group (dim, tag, name): its tet10 (dimension 3) or the distinct nodes of its
elements (dimensions 0-2) - the reader's set semantics computed by Gmsh's own reader. Also the
sum of all node coordinates, a checksum of the coordinates read.

  python3 tools/msh-fixtures/count.py FILE.msh...
"""

import sys

import gmsh


def count(path):
    gmsh.clear()
    gmsh.open(path)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    print(f"{path}")
    print(f"  nodes {len(tags)}, coordinate sum {sum(coords):.15g}")
    types, elem_tags, _ = gmsh.model.mesh.getElements()
    for t, e in zip(types, elem_tags):
        name = gmsh.model.mesh.getElementProperties(t)[0]
        print(f"  type {t} ({name}): {len(e)}")
    for dim, tag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, tag)
        tets = set()
        nodes = set()
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            etypes, etags, enodes = gmsh.model.mesh.getElements(dim, entity)
            for t, e, n in zip(etypes, etags, enodes):
                if t == 11:
                    tets.update(e)
                nodes.update(n)
        if dim == 3:
            print(f"  group ({dim}, {tag}) \"{name}\": {len(tets)} tet10")
        else:
            print(f"  group ({dim}, {tag}) \"{name}\": {len(nodes)} nodes")


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
for p in sys.argv[1:]:
    count(p)
gmsh.finalize()
