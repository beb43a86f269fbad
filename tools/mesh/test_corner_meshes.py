"""Tests of the brake corner generator (corner_meshes.py) and of the bundled coarse corner."""

from __future__ import annotations

import math
import os
import tempfile
import unittest

import corner_meshes as cm
import inp_to_bdf_cdb

HERE = os.path.dirname(os.path.abspath(__file__))
BUNDLED = os.path.join(HERE, "..", "..", "meshes", "corner")


def signed_volume(x):
    a, b, c, d = x[:4]
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0


class CornerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.model, _ = cm.build(cm.LEVELS["coarse"])
        cls.coords = {v[0]: v[1] for v in cls.model.nodes.values()}

    def test_the_bundled_files_are_what_the_generator_writes(self):
        # Byte for byte: the bundled corner is reproducible from this script.
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "corner_coarse.inp")
            cm.write_inp(self.model, path, "coarse")
            inp_to_bdf_cdb.write_bdf(inp_to_bdf_cdb.read_inp(path), os.path.join(d, "corner_coarse.bdf"), "corner_coarse.inp")
            for name in ("corner_coarse.inp", "corner_coarse.bdf"):
                with open(os.path.join(d, name), "rb") as a, open(os.path.join(BUNDLED, name), "rb") as b:
                    self.assertEqual(a.read(), b.read(), name)

    def test_every_element_is_positively_oriented(self):
        # The corner tetrahedron of each element (tets: the element; hexahedra: corners 1, 2,
        # 4, 5; wedges: 1, 2, 3, 4) has a positive volume.
        for eid, ty, ns, _ in self.model.elements:
            x = [self.coords[n] for n in ns]
            corners = {"C3D10": [0, 1, 2, 3], "C3D20": [0, 1, 3, 4], "C3D15": [0, 1, 2, 3]}[ty]
            self.assertGreater(signed_volume([x[k] for k in corners]), 0.0, (eid, ty))

    def test_element_counts_and_types(self):
        kinds = {}
        for _, ty, _, s in self.model.elements:
            kinds[(s, ty)] = kinds.get((s, ty), 0) + 1
        # Disc: 4 rings x 36 sectors x 3 layers, the channel's odd sectors empty (18 vanes);
        # the bore ring in wedges (two per cell).
        self.assertEqual(kinds[("DISC", "C3D20")], 3 * 36 * 2 + 3 * 18)
        self.assertEqual(kinds[("DISC", "C3D15")], 2 * (36 * 2 + 18))
        # Pads: 2 x 6 cells per layer, six tetrahedra each.
        for part in ("LINING", "BACKPLATE", "SHIM"):
            self.assertEqual(kinds[("INBOARD_" + part, "C3D10")], 2 * 6 * 6)

    def test_the_tet10_disc_fills_the_same_cells_on_the_same_map(self):
        # --disc tet10: every disc cell of the hex20 corner split in six positive tetrahedra,
        # the other parts unchanged, and every node the hex20 disc has placed at the same point
        # (the tetrahedra add only the face- and cell-diagonal midside nodes), so the two
        # meshes describe one geometry.
        tet, _ = cm.build(cm.LEVELS["coarse"], "tet10")
        coords = {v[0]: v[1] for v in tet.nodes.values()}
        hexes = sum(1 for _, ty, _, s in self.model.elements if s == "DISC" and ty == "C3D20")
        wedges = sum(1 for _, ty, _, s in self.model.elements if s == "DISC" and ty == "C3D15")
        disc = [e for e in tet.elements if e[3] == "DISC"]
        self.assertTrue(all(ty == "C3D10" for _, ty, _, _ in disc))
        self.assertEqual(len(disc), 6 * (hexes + wedges // 2))
        for eid, _, ns, _ in disc:
            self.assertGreater(signed_volume([coords[n] for n in ns[:4]]), 0.0, eid)
        # Node ids follow the order nodes are made in; compare by the generator's node keys.
        def disc_nodes(model):
            key = {v[0]: (k, v[1]) for k, v in model.nodes.items()}
            return dict(key[n] for _, _, ns, s in model.elements if s == "DISC" for n in ns)
        hex_disc, tet_disc = disc_nodes(self.model), disc_nodes(tet)
        self.assertLess(len(hex_disc), len(tet_disc))
        for k, x in hex_disc.items():
            self.assertEqual(tet_disc[k], x, k)
        def others(model):
            key = {v[0]: k for k, v in model.nodes.items()}
            return [(ty, [key[n] for n in ns], s) for _, ty, ns, s in model.elements if s != "DISC"]
        self.assertEqual(others(self.model), others(tet))

    def test_tied_faces_and_contact_faces_coincide(self):
        # Each shim's front face lies on its backplate's back face, node for node (a matching
        # tie); each friction face lies on the disc's face under it (within 1e-12 m).
        sets = self.model.node_sets

        def points(name):
            return sorted(tuple(round(c, 12) for c in self.coords[n]) for n in sets[name])

        for side in ("INBOARD", "OUTBOARD"):
            self.assertEqual(points(side + "_SHIM_FRONT"), points(side + "_BACK"))
            z_face = {self.coords[n][2] for n in sets[side + "_FRICTION"]}
            z_disc = {self.coords[n][2] for n in sets["DISC_FACE_" + side]}
            self.assertEqual(len(z_face), 1)
            self.assertAlmostEqual(z_face.pop(), z_disc.pop(), delta=1e-12)
            self.assertEqual(len(sets[side + "_PISTON"]), 18)

    def test_the_caliper_and_bracket_sets_face_the_pads(self):
        # The caliper's piston face lies on the inboard shim's back (z = 46 mm); the bracket's
        # inboard abutments on the inboard backplate's ends (theta = 60 and 120 degrees).
        sets = self.model.node_sets
        for n in sets["CALIPER_PISTON"]:
            self.assertAlmostEqual(self.coords[n][2], 0.046, delta=1e-12)
        for n in sets["BRACKET_ABUTMENT_INBOARD"]:
            x, y, _ = self.coords[n]
            t = math.degrees(math.atan2(y, x))
            self.assertTrue(abs(t - 60.0) < 1e-9 or abs(t - 120.0) < 1e-9, t)
        self.assertTrue(sets["BRACKET_MOUNT"] and sets["CALIPER_GUIDE"])


if __name__ == "__main__":
    unittest.main()
