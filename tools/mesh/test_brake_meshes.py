"""Tests of the mesh generator and of the checker (stdlib unittest; pytest also collects them).

Run from the repository root:  python3 -m unittest discover -s tools/mesh -v

The generator's coarse level is made once in a temporary directory (under a second). Besides
checking it, the tests corrupt it in the ways a writer could go wrong and require the checker to
notice: a checker that passes everything would pass a broken mesh.
"""

from __future__ import annotations

import copy
import filecmp
import math
import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import brake_geometry as geo  # noqa: E402
import brake_meshes  # noqa: E402
import check_meshes as cm  # noqa: E402

_TMP = tempfile.TemporaryDirectory()
_DIR = _TMP.name
_generated = False


def coarse_dir() -> str:
    global _generated
    if not _generated:
        brake_meshes.generate(["coarse"], ["disc", "pad"], _DIR)
        _generated = True
    return _DIR


def read(part: str) -> cm.InpMesh:
    return cm.read_inp(os.path.join(coarse_dir(), f"{part}_coarse.inp"))


def failures(part: str, mesh: cm.InpMesh) -> list[str]:
    rep = cm.Report(verbose=False)
    cm.check_inp(rep, f"{part}_test", part, mesh)
    return rep.failures


class GeometryTest(unittest.TestCase):
    def test_disc_volume_formula(self):
        # Pappus: volume = 2 pi * (area of the r-z profile) * (radius of its centroid); the
        # profile is three rectangles. A second route to the same number: 1e-15 is rounding.
        rects = [
            (geo.DISC_R_IN, geo.DISC_R_OUT, geo.DISC_Z_TOP - geo.DISC_Z_BOTTOM),
            (geo.DISC_R_IN, geo.HAT_R_OUT, geo.DISC_Z_BOTTOM - geo.FLANGE_Z_TOP),
            (geo.BORE_R, geo.HAT_R_OUT, geo.FLANGE_Z_TOP - geo.FLANGE_Z_BOTTOM),
        ]
        pappus = sum(2 * math.pi * (b - a) * h * 0.5 * (a + b) for a, b, h in rects)
        self.assertLess(abs(pappus - geo.disc_volume()) / pappus, 1e-15)

    def test_patch_centres_inside_their_patches(self):
        # every contact point lies strictly inside the patch of the same number (exact test)
        radii, angles = geo.patch_radii(), geo.patch_angles()
        for k, (x, y, _) in enumerate(geo.contact_points(geo.DISC_Z_TOP)):
            i, j = divmod(k, 3)
            r, a = math.hypot(x, y), math.atan2(y, x)
            self.assertTrue(radii[i] < r < radii[i + 1] and angles[j] < a < angles[j + 1])

    def test_piston_points_on_backplate(self):
        # each piston point lies inside the backplate's back face, on its piston's rim
        for x, y, z in geo.piston_points():
            r, a = math.hypot(x, y), math.atan2(y, x)
            self.assertEqual(z, geo.BACKPLATE_Z_TOP)
            self.assertTrue(geo.PAD_R_IN < r < geo.PAD_R_OUT)
            self.assertTrue(geo.PAD_ANGLE_MIN < a < geo.PAD_ANGLE_MAX)
            self.assertAlmostEqual(abs(r - geo.PISTON_CENTRE_R), geo.PISTON_RADIUS, delta=1e-15)


class GeneratedMeshTest(unittest.TestCase):
    def test_coarse_passes_all_checks(self):
        rep = cm.Report()
        disc = cm.check_part(rep, coarse_dir(), "disc", "coarse")
        pad = cm.check_part(rep, coarse_dir(), "pad", "coarse")
        self.assertEqual(rep.failures, [])
        self.assertGreater(rep.passed, 100)
        # the two parts' contact nodes coincide (the brief's 1e-9 m; they are in fact equal)
        self.assertLessEqual(np.abs(disc["contact_xyz"] - pad["contact_xyz"]).max(), 1e-9)

    def test_deterministic(self):
        # same command, same bytes
        with tempfile.TemporaryDirectory() as other:
            brake_meshes.generate(["coarse"], ["pad"], other)
            for ext in (".inp", ".msh"):
                a = os.path.join(coarse_dir(), "pad_coarse" + ext)
                b = os.path.join(other, "pad_coarse" + ext)
                self.assertTrue(filecmp.cmp(a, b, shallow=False), ext)


class CheckerCatchesFaultsTest(unittest.TestCase):
    """Each fault is one a writer could plausibly make; the checker must report it."""

    def test_gmsh_midside_order(self):
        mesh = read("pad")
        name = "LINING"
        ids, conn = mesh.elsets[name]
        mesh.elsets[name] = (ids, conn[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]])
        self.assertTrue(any("midside" in f for f in failures("pad", mesh)))

    def test_inverted_elements(self):
        mesh = read("disc")
        ids, conn = mesh.elsets["DISC"]
        # swap vertices 1 and 2 (and the midside nodes that follow them): a mirrored tet
        mesh.elsets["DISC"] = (ids, conn[:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]])
        self.assertTrue(any("Jacobian" in f for f in failures("disc", mesh)))

    def test_moved_contact_node(self):
        mesh = read("disc")
        k = int(np.flatnonzero(mesh.node_ids == mesh.nsets["CONTACT"][4])[0])
        mesh.coords = mesh.coords.copy()
        mesh.coords[k, 0] += 1e-9
        self.assertTrue(any("CONTACT nodes" in f for f in failures("disc", mesh)))

    def test_contact_in_wrong_order(self):
        mesh = read("pad")
        mesh.nsets["CONTACT"] = list(reversed(mesh.nsets["CONTACT"]))
        self.assertTrue(any("CONTACT" in f for f in failures("pad", mesh)))

    def test_incomplete_sets(self):
        for part, name in (("disc", "CLAMP"), ("pad", "ABUTMENT"), ("pad", "CONTACT_PATCH_5")):
            mesh = read(part)
            mesh.nsets[name] = mesh.nsets[name][1:]
            self.assertTrue(any(name in f for f in failures(part, mesh)), name)

    def test_lining_nodes_in_abutment(self):
        mesh = read("pad")
        on_end = (
            np.abs(
                mesh.coords[:, 0] * math.sin(geo.PAD_ANGLE_MIN)
                - mesh.coords[:, 1] * math.cos(geo.PAD_ANGLE_MIN)
            )
            < 1e-12
        )
        lining_end = mesh.node_ids[on_end & (mesh.coords[:, 2] < geo.LINING_Z_TOP - 1e-6)]
        mesh.nsets["ABUTMENT"] = sorted(
            set(mesh.nsets["ABUTMENT"]) | set(int(i) for i in lining_end)
        )
        self.assertTrue(any("ABUTMENT" in f for f in failures("pad", mesh)))

    def test_wrong_dimension(self):
        # a disc 0.1 mm too thick: every node above mid-thickness raised by 0.1 mm
        mesh = copy.deepcopy(read("disc"))
        top = mesh.coords[:, 2] > 0.5 * (geo.DISC_Z_TOP + geo.DISC_Z_BOTTOM)
        mesh.coords[top, 2] += 1e-4
        self.assertTrue(any("volume" in f for f in failures("disc", mesh)))

    def test_wrong_material(self):
        mesh = read("pad")
        mesh.materials["STEEL"] = (210.0e9, 0.3, 7800.0)
        self.assertTrue(any("STEEL" in f for f in failures("pad", mesh)))


if __name__ == "__main__":
    unittest.main()
