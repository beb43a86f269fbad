"""Makes a big-endian copy of a little-endian binary Gmsh file (MSH 2.2 or 4.1).

Gmsh only writes its machine's native (little-endian) order; the format states the order by the
int 1 written after the `$MeshFormat` line, so a reader must also handle big-endian files. This
script walks the binary sections field by field (its own implementation of the layout, from the
Gmsh reference manual, "MSH file format") and byte-swaps every int, size_t and double; the ASCII
parts (section names, counts of MSH 2.2, $PhysicalNames) stay as they are.

  python3 tools/msh-fixtures/swap_endian.py IN.msh OUT.msh
"""

import struct
import sys

TYPE_NODES = {}  # Gmsh element type -> number of nodes, from the Gmsh API (element_types.py)


def element_nodes(t):
    if not TYPE_NODES:
        import gmsh

        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        for code in range(1, 140):
            try:
                props = gmsh.model.mesh.getElementProperties(code)
            except Exception:
                continue
            TYPE_NODES[code] = props[3]
        gmsh.finalize()
    return TYPE_NODES[t]


class Swapper:
    def __init__(self, data):
        self.data = data
        self.pos = 0
        self.out = bytearray()

    def line(self):
        end = self.data.index(b"\n", self.pos) + 1
        text = self.data[self.pos:end]
        self.out += text
        self.pos = end
        return text.decode().strip()

    def field(self, fmt):
        """Reads one little-endian field, writes it big-endian, returns its value."""
        size = struct.calcsize("<" + fmt)
        (value,) = struct.unpack("<" + fmt, self.data[self.pos:self.pos + size])
        self.out += struct.pack(">" + fmt, value)
        self.pos += size
        return value

    def ints(self, n):
        return [self.field("i") for _ in range(n)]

    def sizes(self, n):
        return [self.field("Q") for _ in range(n)]

    def doubles(self, n):
        return [self.field("d") for _ in range(n)]


def swap_v2(s, section):
    if section == "Nodes":
        n = int(s.line())
        for _ in range(n):
            s.ints(1)
            s.doubles(3)
    elif section == "Elements":
        total = int(s.line())
        done = 0
        while done < total:
            etype, count, ntags = s.ints(3)
            for _ in range(count):
                s.ints(1 + ntags + element_nodes(etype))
            done += count
    else:
        raise ValueError(f"unexpected section ${section}")


def swap_v4(s, section):
    if section == "Entities":
        npts, ncur, nsur, nvol = s.sizes(4)
        for _ in range(npts):
            s.ints(1)
            s.doubles(3)
            s.ints(s.sizes(1)[0])
        for count in (ncur, nsur, nvol):
            for _ in range(count):
                s.ints(1)
                s.doubles(6)
                s.ints(s.sizes(1)[0])  # physical tags
                s.ints(s.sizes(1)[0])  # bounding entities
    elif section == "Nodes":
        nblocks, _, _, _ = s.sizes(4)
        for _ in range(nblocks):
            dim, _, parametric = s.ints(3)
            n = s.sizes(1)[0]
            s.sizes(n)
            s.doubles(n * (3 + (dim if parametric else 0)))
    elif section == "Elements":
        nblocks, _, _, _ = s.sizes(4)
        for _ in range(nblocks):
            _, _, etype = s.ints(3)
            n = s.sizes(1)[0]
            s.sizes(n * (1 + element_nodes(etype)))
    else:
        raise ValueError(f"unexpected section ${section}")


def main(src, dst):
    s = Swapper(open(src, "rb").read())
    assert s.line() == "$MeshFormat"
    version, file_type, _ = s.line().split()
    assert file_type == "1", "not a binary file"
    assert s.field("i") == 1, "not a little-endian file"
    while s.line() != "$EndMeshFormat":
        pass
    binary_sections = {"Nodes", "Elements"} | ({"Entities"} if version.startswith("4") else set())
    while s.pos < len(s.data):
        header = s.line()
        if not header:
            continue
        assert header.startswith("$"), header
        section = header[1:]
        if section in binary_sections:
            (swap_v4 if version.startswith("4") else swap_v2)(s, section)
        # Copy the rest of the section (the newline after binary data, or ASCII lines).
        while s.line() != "$End" + section:
            pass
    open(dst, "wb").write(bytes(s.out))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
