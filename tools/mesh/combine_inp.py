#!/usr/bin/env python3
"""Writes several Abaqus .inp part files as one assembly file, each part an element set, as
CAE tools export an assembly (Abaqus' flattened input, Ansys' and Nastran's single deck).

    python3 tools/mesh/combine_inp.py OUT.inp DISC=meshes/disc_coarse.inp PAD=meshes/pad_coarse.inp

Each part keeps its nodes, elements, node sets, element sets, materials and sections, in its
file's order; the parts follow each other in the order given. The node and element ids of
each part after the first are offset by a power of ten above the largest id so far, so that
no two parts share an id. A node set or element set of the same name in several parts is
written once, as the union of the parts' members (a CONTACT_FACE set then holds the disc's
and the pad's face nodes; cut out by element set, each part gets its own share back). Each
part also becomes an element set of its name (NAME=file), holding all its elements.

Only the keywords the bundled meshes use are handled (*HEADING, *NODE, *ELEMENT, *NSET,
*ELSET, *MATERIAL, *ELASTIC, *DENSITY, *SOLID SECTION and comments); anything else is an
error, so that nothing is dropped silently. GENERATE sets are refused for the same reason.
"""

import sys


def keyword(line):
    return line.split(",")[0].strip().upper()


def param(line, name):
    for p in line.split(",")[1:]:
        if "=" in p:
            k, v = p.split("=", 1)
            if k.strip().upper() == name:
                return v.strip()
    return None


def read_part(path):
    """Nodes, element blocks, sets and material text of one .inp file, ids as ints."""
    part = {"nodes": [], "blocks": [], "nsets": {}, "elsets": {}, "materials": [], "order": []}
    current = None
    with open(path) as f:
        lines = f.read().splitlines()
    for number, raw in enumerate(lines, 1):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            kw = keyword(line)
            if "GENERATE" in line.upper():
                sys.exit(f"{path}:{number}: GENERATE sets are not handled")
            if kw == "*HEADING":
                current = ("heading", None)
            elif kw == "*NODE":
                current = ("node", None)
            elif kw == "*ELEMENT":
                block = {"type": param(line, "TYPE"), "elset": param(line, "ELSET"), "rows": []}
                part["blocks"].append(block)
                current = ("element", block)
            elif kw == "*NSET":
                name = param(line, "NSET")
                part["nsets"].setdefault(name, [])
                current = ("nset", name)
            elif kw == "*ELSET":
                name = param(line, "ELSET")
                part["elsets"].setdefault(name, [])
                current = ("elset", name)
            elif kw in ("*MATERIAL", "*ELASTIC", "*DENSITY", "*SOLID SECTION"):
                part["materials"].append(line)
                current = ("material", None)
            else:
                sys.exit(f"{path}:{number}: keyword {kw} is not handled")
            continue
        what, target = current if current else (None, None)
        fields = [x.strip() for x in line.split(",") if x.strip()]
        if what == "heading":
            continue
        if what == "node":
            part["nodes"].append((int(fields[0]), fields[1:]))
        elif what == "element":
            target["rows"].append([int(x) for x in fields])
        elif what == "nset":
            part["nsets"][target].extend(int(x) for x in fields)
        elif what == "elset":
            part["elsets"][target].extend(int(x) for x in fields)
        elif what == "material":
            part["materials"].append(line)
        else:
            sys.exit(f"{path}:{number}: data line outside a keyword")
    return part


def rows(ids, per_line=16):
    return [", ".join(str(i) for i in ids[k:k + per_line]) for k in range(0, len(ids), per_line)]


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, specs = argv[1], argv[2:]
    parts = []
    for spec in specs:
        name, path = spec.split("=", 1)
        parts.append((name.upper(), path, read_part(path)))
    node_offset = element_offset = 0
    text = ["*HEADING", "squeal assembly: " + ", ".join(f"{n} from {p}" for n, p, _ in parts)]
    text.append("** Written by tools/mesh/combine_inp.py; each part is an element set of its name.")
    nsets, elsets, materials, seen_materials = {}, {}, [], set()
    for name, path, part in parts:
        text.append(f"** part {name}: {path}, node ids + {node_offset}, element ids + {element_offset}")
        text.append("*NODE")
        for i, xyz in part["nodes"]:
            text.append(", ".join([str(i + node_offset)] + xyz))
        all_elements = []
        for block in part["blocks"]:
            head = f"*ELEMENT, TYPE={block['type']}"
            if block["elset"]:
                head += f", ELSET={block['elset']}"
            text.append(head)
            for r in block["rows"]:
                e = r[0] + element_offset
                all_elements.append(e)
                if block["elset"]:
                    elsets.setdefault(block["elset"], [])
                text.append(", ".join([str(e)] + [str(n + node_offset) for n in r[1:]]))
        if name not in {b["elset"].upper() for b in part["blocks"] if b["elset"]}:
            elsets.setdefault(name, []).extend(all_elements)
        for s, ids in part["nsets"].items():
            nsets.setdefault(s, []).extend(i + node_offset for i in ids)
        for s, ids in part["elsets"].items():
            elsets.setdefault(s, []).extend(i + element_offset for i in ids)
        # Materials (with their *ELASTIC and *DENSITY) and sections once each; a material of
        # the same name in two parts is written once (the parts must agree on it).
        block = []
        for line in part["materials"] + ["*END"]:
            if keyword(line) in ("*MATERIAL", "*SOLID SECTION", "*END") and block:
                head = block[0]
                duplicate = (keyword(head) == "*MATERIAL"
                             and param(head, "NAME").upper() in seen_materials)
                if not duplicate:
                    materials.extend(block)
                if keyword(head) == "*MATERIAL":
                    seen_materials.add(param(head, "NAME").upper())
                block = []
            block.append(line)
        max_node = max(i for i, _ in part["nodes"]) + node_offset
        max_element = max(all_elements)
        node_offset = 10 ** len(str(max_node))
        element_offset = 10 ** len(str(max_element))
    for s, ids in nsets.items():
        text.append(f"*NSET, NSET={s}")
        text.extend(rows(sorted(set(ids))))
    for s, ids in elsets.items():
        if ids:
            text.append(f"*ELSET, ELSET={s}")
            text.extend(rows(sorted(set(ids))))
    text.extend(materials)
    with open(out, "w") as f:
        f.write("\n".join(text) + "\n")


if __name__ == "__main__":
    main(sys.argv)
