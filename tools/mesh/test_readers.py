"""The coarse pad in three formats, read by readers that are not squeal's (stdlib unittest).

Run from the repository root:  python3 -m unittest tools/mesh/test_readers.py -v

crates/squeal-mesh/tests/data/formats/pad_coarse.{bdf,cdb} are written from
meshes/pad_coarse.inp by tools/mesh/inp_to_bdf_cdb.py. squeal's own test
(crates/squeal-mesh/tests/mesh/formats.rs) reads the three files to the same bits. Here:

- pyNastran reads the .bdf, meshio reads the .inp and the .bdf, mapdl-archive (Ansys's
  reader) reads the .cdb: the same node ids and coordinates (exactly: every file carries 17
  significant digits), the same element ids and connectivity (in each format's own node
  order, so a writer that permuted a node would show), the same sets;
- `squeal mesh info` on each file gives the counts these readers give (skipped, with the
  reason printed, when target/release/squeal has not been built).

A package that is not installed skips its tests with the reason printed; CI installs them
from tools/mesh/requirements.txt.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import inp_to_bdf_cdb as conv  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
INP = os.path.join(ROOT, "meshes", "pad_coarse.inp")
FORMATS = os.path.join(ROOT, "crates", "squeal-mesh", "tests", "data", "formats")
BDF = os.path.join(FORMATS, "pad_coarse.bdf")
CDB = os.path.join(FORMATS, "pad_coarse.cdb")
SQUEAL = os.path.join(ROOT, "target", "release", "squeal")


def _have(module: str) -> str | None:
    """None if the module imports, else the reason to skip."""
    try:
        __import__(module)
        return None
    except Exception as e:  # noqa: BLE001 - any failure to import is a reason to skip
        reason = f"{module} is not importable ({e}); pip install -r tools/mesh/requirements.txt"
        print(f"skipped: {reason}", file=sys.stderr)
        return reason


def _meshio_inp():
    import meshio

    return meshio.read(INP, file_format="abaqus")


class FilesAreCurrent(unittest.TestCase):
    def test_the_converter_writes_the_committed_files(self):
        """The committed .bdf and .cdb are what the converter writes from the .inp now."""
        import tempfile

        with tempfile.TemporaryDirectory() as d:
            stem = os.path.join(d, "pad_coarse")
            conv.main(["inp_to_bdf_cdb.py", INP, stem])
            for ext in ("bdf", "cdb"):
                with open(stem + "." + ext, encoding="utf-8") as a, open(
                    os.path.join(FORMATS, "pad_coarse." + ext), encoding="utf-8"
                ) as b:
                    self.assertEqual(a.read().replace(INP, ""), b.read(), ext)


@unittest.skipIf(_have("pyNastran") is not None, "pyNastran is not installed")
class PyNastranReadsTheBdf(unittest.TestCase):
    def setUp(self):
        from pyNastran.bdf.bdf import BDF as Reader

        self.model = Reader(debug=None, mode="msc")
        self.model.read_bdf(BDF, xref=False, validate=False)
        self.inp = conv.read_inp(INP)

    def test_nodes_elements_sets_materials(self):
        m, inp = self.model, self.inp
        self.assertEqual(sorted(m.nodes), [i for i, _ in sorted(inp.nodes)])
        for nid, x in inp.nodes:
            self.assertEqual(tuple(m.nodes[nid].xyz), x, f"GRID {nid}")
        self.assertEqual(len(m.elements), len(inp.elements))
        for eid, ty, nodes, _ in inp.elements:
            e = m.elements[eid]
            self.assertEqual(e.type, conv.NASTRAN_CARD[ty])
            # pyNastran keeps Nastran's own grid order: map the .inp's (Abaqus) order to it.
            self.assertEqual(list(e.node_ids), [nodes[k] for k in conv.NASTRAN_FROM_ABAQUS[ty]])
        self.assertEqual(len(m.sets), len(inp.node_sets))
        sizes = sorted(len(s.ids) for s in m.sets.values())
        self.assertEqual(sizes, sorted(len(set(v)) for v in inp.node_sets.values()))
        by_e = {round(mat.e): mat for mat in m.materials.values()}
        for name, (e, nu, rho) in inp.materials.items():
            self.assertEqual((by_e[round(e)].nu, by_e[round(e)].rho), (nu, rho), name)


@unittest.skipIf(_have("meshio") is not None, "meshio is not installed")
class MeshioReadsTheInpAndTheBdf(unittest.TestCase):
    def test_same_points_and_cells(self):
        import meshio
        import numpy as np

        a = _meshio_inp()
        b = meshio.read(BDF, file_format="nastran")
        np.testing.assert_array_equal(a.points, b.points)
        ca = np.concatenate([c.data for c in a.cells])
        cb = np.concatenate([c.data for c in b.cells])
        # Both are tetra10 in meshio's (VTK's) order, whatever the file's.
        self.assertEqual(ca.shape, cb.shape)
        np.testing.assert_array_equal(np.sort(ca, axis=0), np.sort(cb, axis=0))


@unittest.skipIf(_have("mapdl_archive") is not None, "mapdl-archive is not installed")
class AnsysArchiveReadsTheCdb(unittest.TestCase):
    def test_nodes_elements_components(self):
        import mapdl_archive
        import numpy as np

        arch = mapdl_archive.Archive(CDB, parse_vtk=False)
        inp = conv.read_inp(INP)
        ids = [i for i, _ in inp.nodes]
        np.testing.assert_array_equal(arch.nnum, ids)
        # mapdl-archive converts the 17-digit reals with its own parser, which is not
        # correctly rounded: measured, 959 of 4269 coordinates differ by 1 or 2 ulp (relative
        # 2.8e-16 at most) from Python's float(), which is. Two ulp is the tolerance; squeal's
        # own test requires the exact bits.
        np.testing.assert_allclose(arch.nodes, np.array([x for _, x in inp.nodes]), rtol=4.5e-16, atol=0)
        self.assertEqual(len(arch.enum), len(inp.elements))
        np.testing.assert_array_equal(arch.ekey, [[1, 187], [2, 186]])
        np.testing.assert_array_equal(arch.enum, [e[0] for e in inp.elements])
        for (eid, ty, nodes, _), elem in zip(inp.elements, arch.elem):
            # elem: 8 attributes (material, type, ...), the element number, one more field,
            # then the nodes in Ansys's order (SOLID187 = C3D10's).
            self.assertEqual(int(elem[8]), eid)
            self.assertEqual(list(elem[10:]), nodes if ty != "C3D15" else conv.solid186_prism(nodes))
        elems = {k.upper(): v for k, v in arch.element_components.items()}
        for name in {s for *_, s in inp.elements}:
            ids = sorted(e[0] for e in inp.elements if e[3] == name)
            np.testing.assert_array_equal(np.sort(elems[name]), ids, name)
        comps = {k.upper(): v for k, v in arch.node_components.items()}
        for name, members in inp.node_sets.items():
            np.testing.assert_array_equal(np.sort(comps[name]), np.unique(members), name)


def _squeal_info(path: str) -> str:
    out = subprocess.run([SQUEAL, "mesh", "info", path], capture_output=True, text=True, timeout=120)
    if out.returncode != 0:
        raise AssertionError(f"squeal mesh info {path}: {out.stderr}")
    return out.stdout


def _count(text: str, label: str) -> int:
    m = re.search(rf"^\s*{label}\s+(\d+)", text, re.M)
    if m is None:
        raise AssertionError(f"no '{label}' in {text}")
    return int(m.group(1))


@unittest.skipIf(not os.path.exists(SQUEAL), "target/release/squeal is not built (cargo build --release)")
class SquealAgrees(unittest.TestCase):
    def test_counts_sets_and_volume_of_the_three_files(self):
        inp = conv.read_inp(INP)
        infos = {p: _squeal_info(p) for p in (INP, BDF, CDB)}
        for p, text in infos.items():
            self.assertEqual(_count(text, "nodes"), len(inp.nodes), p)
            self.assertEqual(_count(text, "elements"), len(inp.elements), p)
            for name, members in inp.node_sets.items():
                self.assertRegex(text, rf"\n\s+{name}\s+{len(set(members))} nodes", p)
            volume = re.search(r"volume\s+(\S+) m\^3", text).group(1)
            self.assertEqual(volume, re.search(r"volume\s+(\S+) m\^3", infos[INP]).group(1), p)


if __name__ == "__main__":
    unittest.main()
