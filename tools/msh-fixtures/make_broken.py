"""Writes the broken-file corpus of the .msh reader tests (tests/data/broken/msh/).

Each file breaks one thing; crates/squeal-mesh/tests/mesh/msh.rs lists, for each, the location and the
message fragment the reader must report. Most are small edits of ONE_TET_V22 / ONE_TET_V41 (one
10-node tetrahedron and one 6-node triangle), whose line numbers the expectations refer to; the
binary truncations cut Gmsh's own box fixtures at a field boundary found from the layout.

  python3 tools/msh-fixtures/make_broken.py crates/squeal-mesh/tests/data/msh \
      crates/squeal-mesh/tests/data/broken/msh
"""

import os
import random
import struct
import sys

# Line numbers: 1 $MeshFormat, 2 version, 9 $Nodes, 10 count, 11-20 nodes, 21 $EndNodes,
# 22 $Elements, 23 count, 24 triangle, 25 tet10, 26 $EndElements.
ONE_TET_V22 = """$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "face"
3 2 "solid"
$EndPhysicalNames
$Nodes
10
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 0.5 0 0
6 0.5 0.5 0
7 0 0.5 0
8 0 0 0.5
9 0 0.5 0.5
10 0.5 0 0.5
$EndNodes
$Elements
2
1 9 2 1 1 1 2 3 5 6 7
2 11 2 2 1 1 2 3 4 5 6 7 8 9 10
$EndElements
"""

# Line numbers: 8 $Entities, 13 $Nodes, 14 header, 15 block header, 16-25 tags, 26-35
# coordinates, 36 $EndNodes, 37 $Elements, 38 header, 39 block (triangle), 40 triangle,
# 41 block (tet10), 42 tet10, 43 $EndElements.
ONE_TET_V41 = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
3 2 "solid"
$EndPhysicalNames
$Entities
0 0 1 1
1 0 0 0 1 1 0 0 0
1 0 0 0 1 1 1 1 2 1 1
$EndEntities
$Nodes
1 10 1 10
3 1 0 10
1
2
3
4
5
6
7
8
9
10
0 0 0
1 0 0
0 1 0
0 0 1
0.5 0 0
0.5 0.5 0
0 0.5 0
0 0 0.5
0 0.5 0.5
0.5 0 0.5
$EndNodes
$Elements
2 2 1 2
2 1 9 1
1 1 2 3 5 6 7
3 1 11 1
2 1 2 3 4 5 6 7 8 9 10
$EndElements
"""


def edit(text, old, new):
    assert text.count(old) == 1, old
    return text.replace(old, new)


def drop_line(text, line):
    lines = text.split("\n")
    del lines[line - 1]
    return "\n".join(lines)


def section_start(data, name):
    """Offset just after the line `$name`."""
    i = data.index(b"$" + name + b"\n")
    return i + len(name) + 2


def main(fixtures, out):
    os.makedirs(out, exist_ok=True)
    files = {}
    # ASCII edits.
    files["bad_number.msh"] = edit(ONE_TET_V22, "8 0 0 0.5\n", "8 0 0 0.5x\n")
    files["nan_coordinate.msh"] = edit(ONE_TET_V22, "8 0 0 0.5\n", "8 0 0 nan\n")
    files["wrong_node_count.msh"] = edit(ONE_TET_V22, " 8 9 10\n", " 8 9\n")
    files["wrong_node_count_v41.msh"] = edit(ONE_TET_V41, "2 1 2 3 4 5 6 7 8 9 10\n", "2 1 2 3 4 5 6 7 8 9\n")
    files["unknown_element_type.msh"] = edit(ONE_TET_V22, "2 11 2 2 1", "2 200 2 2 1")
    files["missing_end_nodes.msh"] = drop_line(ONE_TET_V22, 21)
    files["missing_end_elements.msh"] = ONE_TET_V22.replace("$EndElements\n", "")
    files["version_3.msh"] = edit(ONE_TET_V22, "2.2 0 8", "3.0 0 8")
    files["version_4_0.msh"] = edit(ONE_TET_V41, "4.1 0 8", "4 0 8")
    files["huge_count.msh"] = edit(ONE_TET_V41, "1 10 1 10\n", "1 18446744073709551615 1 10\n")
    files["huge_count_v22.msh"] = edit(ONE_TET_V22, "$Nodes\n10\n", "$Nodes\n4000000000\n")
    files["truncated_ascii.msh"] = "\n".join(ONE_TET_V22.split("\n")[:24]) + "\n"  # no tet10 line
    files["duplicate_node.msh"] = edit(ONE_TET_V22, "7 0 0.5 0\n", "6 0 0.5 0\n")
    files["node_total_mismatch.msh"] = edit(ONE_TET_V41, "1 10 1 10\n", "1 11 1 11\n")
    files["dimension_mismatch.msh"] = edit(ONE_TET_V41, "3 1 11 1\n", "2 1 11 1\n")
    files["unclosed_comments.msh"] = ONE_TET_V22 + "$Comments\nwritten by hand\n"
    files["stray_end.msh"] = edit(ONE_TET_V22, "$EndPhysicalNames\n", "$EndPhysicalNames\n$EndNodes\n")
    files["unquoted_name.msh"] = edit(ONE_TET_V22, '2 1 "face"', "2 1 face")
    files["not_msh.msh"] = "*HEADING\nan Abaqus file with the wrong extension\n"
    files["msh_version_1.msh"] = "$NOD\n1\n1 0 0 0\n$ENDNOD\n"

    # Binary truncations. In the node data of MSH 2.2, after 100 nodes: the count of 694 nodes
    # (28 bytes each) no longer fits, reported at the count line, byte 141.
    v22 = open(os.path.join(fixtures, "box_v22_binary.msh"), "rb").read()
    count_line = section_start(v22, b"Nodes")
    assert count_line == 141
    files["truncated_binary_v22.msh"] = v22[: count_line + len(b"694\n") + 100 * 28]
    # In the middle of the $Nodes header of MSH 4.1 (after 2 of its 4 size_t): reported at the
    # third, byte 2025 + 16.
    v41 = open(os.path.join(fixtures, "box_v41_binary.msh"), "rb").read()
    nodes = section_start(v41, b"Nodes")
    assert nodes == 2025
    files["truncated_binary_v41.msh"] = v41[: nodes + 2 * 8]
    # After 100 of the 310 tet10 of the last element block (header: 3 int + 1 size_t = 20 bytes,
    # then 11 size_t per element), which starts 20 + 310 * 88 bytes before "\n$EndElements\n":
    # reported at that block header, byte 29954.
    tet_block = len(v41) - len(b"\n$EndElements\n") - 310 * 88 - 20
    assert tet_block == 29954
    files["truncated_binary_v41_elements.msh"] = v41[: tet_block + 20 + 100 * 88]

    # Binary garbage: a valid binary header, then random bytes where the node header should be.
    rng = random.Random(20240601)
    header = b"$MeshFormat\n4.1 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n$Nodes\n"
    files["binary_garbage.msh"] = header + bytes(rng.randrange(256) for _ in range(200))
    files["bad_byte_order_mark.msh"] = b"$MeshFormat\n4.1 1 8\n" + struct.pack("<i", 7) + b"\n$EndMeshFormat\n"
    files["binary_data_size_4.msh"] = b"$MeshFormat\n4.1 1 4\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n"
    # A 2.2 binary element block declaring 2^31 - 1 elements of 10 nodes.
    block = struct.pack("<3i", 11, 2**31 - 1, 2)
    files["huge_count_binary.msh"] = (
        b"$MeshFormat\n2.2 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n"
        b"$Elements\n2147483647\n" + block + bytes(64)
    )
    # 3 elements whose block declares 2^31 - 1 tags each.
    block = struct.pack("<3i", 11, 3, 2**31 - 1)
    files["huge_tags_binary.msh"] = (
        b"$MeshFormat\n2.2 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n$Elements\n3\n" + block + bytes(64)
    )
    files["garbage.msh"] = bytes(rng.randrange(1, 256) for _ in range(300)).replace(b"\n", b" ")

    for name, content in sorted(files.items()):
        data = content.encode() if isinstance(content, str) else content
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    with open(os.path.join(fixtures, "one_tet_v22.msh"), "w") as f:
        f.write(ONE_TET_V22)
    with open(os.path.join(fixtures, "one_tet_v41.msh"), "w") as f:
        f.write(ONE_TET_V41)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
