"""Tests of the mesh generator and of the checker (stdlib unittest; pytest also collects them).

Run from the repository root:  python3 -m unittest discover -s tools/mesh -v

The generator's coarse level of both brakes is made once in a temporary directory (about a
second). Besides checking it, the tests corrupt it in the ways a writer could go wrong and
require the checker to notice: a checker that passes everything would pass a broken mesh.
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
import check_ventilated as cv  # noqa: E402
import ventilated_geometry as vg  # noqa: E402
import ventilated_meshes  # noqa: E402

_TMP = tempfile.TemporaryDirectory()
_DIR = _TMP.name
_generated = False


_BUNDLED = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", "..", "meshes"))


def coarse_dir() -> str:
    global _generated
    if not _generated:
        brake_meshes.generate(["coarse"], ["disc", "pad"], _DIR)
        brake_meshes.generate(["coarse"], ["disc", "outboard"], _DIR, brake="two-pad")
        ventilated_meshes.generate(["coarse"], list(ventilated_meshes.PARTS), _DIR)
        _generated = True
    return _DIR


def read(part: str, brake: str = "one-pad") -> cm.InpMesh:
    stem = geo.BRAKES[brake][part].stem
    return cm.read_inp(os.path.join(coarse_dir(), f"{stem}_coarse.inp"))


def failures(part: str, mesh: cm.InpMesh, brake: str = "one-pad") -> list[str]:
    rep = cm.Report(verbose=False)
    cm.check_inp(rep, f"{part}_test", part, mesh, brake)
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
        # every contact point lies strictly inside the patch of the same number (exact test),
        # on its pad's friction face: the disc's top face (inboard) or bottom face (outboard)
        for pad, z in ((geo.INBOARD, geo.DISC_Z_TOP), (geo.OUTBOARD, geo.DISC_Z_BOTTOM)):
            radii, angles = geo.patch_radii(pad), geo.patch_angles()
            for k, (x, y, zk) in enumerate(geo.contact_points(pad)):
                i, j = divmod(k, 3)
                r, a = math.hypot(x, y), math.atan2(y, x)
                self.assertTrue(radii[i] < r < radii[i + 1] and angles[j] < a < angles[j + 1])
                self.assertEqual(zk, z)

    def test_outboard_volumes_formula(self):
        # the brief's closed form: pi (r_out^2 - r_in^2) (50/360) thickness
        for got, h in (
            (geo.lining_volume(geo.OUTBOARD), 0.010),
            (geo.backplate_volume(geo.OUTBOARD), 0.005),
        ):
            exact = math.pi * (0.138**2 - 0.088**2) * (50.0 / 360.0) * h
            self.assertLess(abs(got - exact) / exact, 1e-14)

    def test_outboard_pad_geometry(self):
        # below the disc, clear of the hat wall, lining then backplate going down
        pad = geo.OUTBOARD
        self.assertEqual(pad.direction, -1)
        self.assertEqual(geo.INBOARD.direction, 1)
        self.assertEqual(pad.face_z, geo.DISC_Z_BOTTOM)
        self.assertGreaterEqual(pad.r_in - geo.HAT_R_OUT, 0.002 - 1e-15)
        self.assertLessEqual(pad.r_out, geo.DISC_R_OUT)
        self.assertTrue(pad.back_z < pad.lining_back_z < pad.lining_mid_z < pad.face_z)

    def test_finger_points_on_backplate(self):
        # (93, 77.5), (93, 102.5), (133, 77.5), (133, 102.5) on the back face z = -15 mm,
        # resultant at the centre of the friction face (mean radius, 90 degrees)
        expect = [(0.093, 77.5), (0.093, 102.5), (0.133, 77.5), (0.133, 102.5)]
        pts = geo.finger_points()
        for (x, y, z), (r0, a0) in zip(pts, expect):
            self.assertEqual(z, -0.015)
            self.assertAlmostEqual(math.hypot(x, y), r0, delta=1e-15)
            self.assertAlmostEqual(math.degrees(math.atan2(y, x)), a0, delta=1e-12)
        self.assertAlmostEqual(sum(p[0] for p in pts), 0.0, delta=1e-15)
        mean_r = 0.25 * sum(math.hypot(x, y) for x, y, _ in pts)
        self.assertAlmostEqual(mean_r, 0.5 * (geo.OUTBOARD_R_IN + geo.OUTBOARD_R_OUT), delta=1e-15)

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
        self.assertTrue(
            np.array_equal(disc["contact_xyz"]["inboard"], pad["contact_xyz"]["inboard"])
        )

    def test_two_pad_coarse_passes_all_checks(self):
        rep = cm.Report()
        infos = {
            "disc": cm.check_part(rep, coarse_dir(), "disc", "coarse", "two-pad"),
            "pad": cm.check_part(rep, coarse_dir(), "pad", "coarse", "two-pad"),
            "outboard": cm.check_part(rep, coarse_dir(), "outboard", "coarse", "two-pad"),
        }
        cm.check_pairs(rep, "two-pad", "coarse", infos)
        self.assertEqual(rep.failures, [])
        self.assertGreater(rep.passed, 200)
        # both pads' contact nodes are the disc's bit for bit
        disc = infos["disc"]["contact_xyz"]
        self.assertTrue(np.array_equal(disc["inboard"], infos["pad"]["contact_xyz"]["inboard"]))
        self.assertTrue(
            np.array_equal(disc["outboard"], infos["outboard"]["contact_xyz"]["outboard"])
        )

    def test_deterministic(self):
        # same command, same bytes
        with tempfile.TemporaryDirectory() as other:
            brake_meshes.generate(["coarse"], ["pad"], other)
            brake_meshes.generate(["coarse"], ["outboard"], other, brake="two-pad")
            for stem in ("pad_coarse", "two_pad/outboard_coarse"):
                for ext in (".inp", ".msh"):
                    a = os.path.join(coarse_dir(), stem + ext)
                    b = os.path.join(other, stem + ext)
                    self.assertTrue(filecmp.cmp(a, b, shallow=False), stem + ext)

    @unittest.skipUnless(
        brake_meshes.gmsh.__version__ == brake_meshes.GMSH_VERSION, "another Gmsh meshes otherwise"
    )
    def test_bundled_coarse_files_reproduced(self):
        # the committed coarse files are what the generator makes: the one-pad ones were not
        # changed by the two-pad brake's parametrization
        for stem in ("disc_coarse", "pad_coarse", "two_pad/disc_coarse", "two_pad/outboard_coarse"):
            for ext in (".inp", ".msh"):
                committed = os.path.join(_BUNDLED, stem + ext)
                if not os.path.exists(committed):
                    self.skipTest(f"{committed} not generated yet")
                made = os.path.join(coarse_dir(), stem + ext)
                self.assertTrue(filecmp.cmp(committed, made, shallow=False), stem + ext)


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

    def test_moved_outboard_contact_node(self):
        # the disc's bottom footprint: a centre node off by 1 nm
        mesh = read("disc", "two-pad")
        k = int(np.flatnonzero(mesh.node_ids == mesh.nsets["CONTACT_OUTBOARD"][4])[0])
        mesh.coords = mesh.coords.copy()
        mesh.coords[k, 1] += 1e-9
        found = failures("disc", mesh, "two-pad")
        self.assertTrue(any("CONTACT_OUTBOARD nodes" in f for f in found), found)

    def test_hat_wall_node_in_outboard_face(self):
        # a node at z = 0 but on the hat wall's top (r < 88 mm) is outside the footprint
        mesh = read("disc", "two-pad")
        r = np.hypot(mesh.coords[:, 0], mesh.coords[:, 1])
        hat = mesh.node_ids[(np.abs(mesh.coords[:, 2]) < 1e-12) & (r < geo.HAT_R_OUT + 1e-9)]
        self.assertGreater(hat.size, 0)
        mesh.nsets["CONTACT_FACE_OUTBOARD"] = sorted(
            mesh.nsets["CONTACT_FACE_OUTBOARD"] + [int(hat[0])]
        )
        found = failures("disc", mesh, "two-pad")
        self.assertTrue(any("inside the footprint" in f for f in found), found)

    def test_outboard_sets_missing(self):
        # a two-pad disc written with the top footprint only fails
        mesh = read("disc", "one-pad")
        found = failures("disc", mesh, "two-pad")
        self.assertTrue(any("CONTACT_OUTBOARD" in f for f in found))
        self.assertTrue(any("CONTACT_FACE_OUTBOARD" in f for f in found))

    def test_fingers_off_back_face(self):
        mesh = read("outboard", "two-pad")
        k = int(np.flatnonzero(mesh.node_ids == mesh.nsets["FINGERS"][0])[0])
        mesh.coords = mesh.coords.copy()
        mesh.coords[k, 2] += 1e-9
        found = failures("outboard", mesh, "two-pad")
        self.assertTrue(any("FINGERS nodes not at z" in f for f in found), found)

    def test_outboard_lining_nodes_in_abutment(self):
        # the outboard backplate is below the lining: its ABUTMENT is z = -15 .. -10 mm
        mesh = read("outboard", "two-pad")
        ang = geo.PAD_ANGLE_MAX
        x, y, z = mesh.coords[:, 0], mesh.coords[:, 1], mesh.coords[:, 2]
        on_end = np.abs(x * math.sin(ang) - y * math.cos(ang)) < 1e-12
        lining_end = mesh.node_ids[on_end & (z > geo.OUTBOARD_LINING_Z_BOTTOM + 1e-6)]
        self.assertGreater(lining_end.size, 0)
        mesh.nsets["ABUTMENT"] = sorted(
            set(mesh.nsets["ABUTMENT"]) | set(int(i) for i in lining_end)
        )
        self.assertTrue(any("ABUTMENT" in f for f in failures("outboard", mesh, "two-pad")))

    def test_outboard_pad_too_narrow(self):
        # the outboard pad meshed with the inboard radii (85..135) is caught by its volume
        mesh = read("outboard", "two-pad")
        scale = geo.PAD_R_OUT / geo.OUTBOARD_R_OUT
        mesh.coords = mesh.coords * np.array([scale, scale, 1.0])
        found = failures("outboard", mesh, "two-pad")
        self.assertTrue(any("volume" in f for f in found))

    def test_pairs_compared_bit_for_bit(self):
        # a pad's contact nodes 1e-15 m off the disc's are reported (no tolerance)
        rep = cm.Report(verbose=False)
        xyz = np.array(geo.contact_points(geo.OUTBOARD))
        moved = xyz.copy()
        moved[3, 0] = np.nextafter(moved[3, 0], 1.0)
        infos = {
            "disc": {"contact_xyz": {"inboard": np.array(geo.contact_points()), "outboard": xyz}},
            "pad": {"contact_xyz": {"inboard": np.array(geo.contact_points())}},
            "outboard": {"contact_xyz": {"outboard": moved}},
        }
        cm.check_pairs(rep, "two-pad", "coarse", infos)
        self.assertEqual(len(rep.failures), 1)
        self.assertIn("outboard", rep.failures[0])

    def test_wrong_material(self):
        mesh = read("pad")
        mesh.materials["STEEL"] = (210.0e9, 0.3, 7800.0)
        self.assertTrue(any("STEEL" in f for f in failures("pad", mesh)))


class VentilatedTest(unittest.TestCase):
    """The ventilated two-pad brake (ventilated_meshes.py, check_ventilated.py)."""

    def read(self, part: str) -> cm.InpMesh:
        return cm.read_inp(os.path.join(coarse_dir(), f"{cv.stem(part)}_coarse.inp"))

    def failures(self, part: str, mesh: cm.InpMesh) -> list[str]:
        rep = cm.Report(verbose=False)
        cv.check_inp(rep, f"{part}_test", part, mesh)
        return rep.failures

    def infos(self) -> dict:
        rep = cm.Report(verbose=False)
        infos = {p: cv.check_part(rep, coarse_dir(), p, "coarse") for p in cv.PARTS}
        self.assertEqual(rep.failures, [])
        return infos

    def test_vane_volume_formula(self):
        # a second route: the area of the strip |y| <= a between the two circles is the integral
        # over r of the arc 2 r asin(a / r) inside the strip; 40-point Gauss-Legendre on a
        # smooth integrand is exact to round-off (1e-13 relative)
        a = 0.5 * vg.VANE_WIDTH
        g, w = np.polynomial.legendre.leggauss(40)
        r = vg.R_IN + (vg.R_OUT - vg.R_IN) * 0.5 * (g + 1.0)
        area = 0.5 * (vg.R_OUT - vg.R_IN) * float(w @ (2.0 * r * np.arcsin(a / r)))
        exact = area * (vg.Z_CHANNEL_TOP - vg.Z_CHANNEL_BOTTOM)
        self.assertLess(abs(vg.vane_volume() - exact) / exact, 1e-13)

    def test_geometry(self):
        # the outboard pad clears the hat wall; pads inside the cheeks; bolt holes in the flange
        for pad in vg.PADS:
            self.assertGreaterEqual(pad.r_in - vg.HAT_R_OUT, 0.004 - 1e-15)
            self.assertLessEqual(pad.r_out, vg.R_OUT)
            self.assertAlmostEqual(math.degrees(pad.angle_max - pad.angle_min), 60.0, delta=1e-12)
        for x, y in vg.bolt_centres():
            r = math.hypot(x, y)
            self.assertTrue(vg.BORE_R < r - vg.BOLT_R and r + vg.BOLT_R < vg.HAT_R_OUT)
        self.assertTrue(21 <= vg.VANES <= 36)

    def test_coarse_passes_all_checks_and_pairs(self):
        rep = cm.Report(verbose=False)
        infos = {p: cv.check_part(rep, coarse_dir(), p, "coarse") for p in cv.PARTS}
        pairs = cv.check_pairs(rep, "coarse", infos)
        self.assertEqual(rep.failures, [])
        self.assertGreater(rep.passed, 60)
        for pad in vg.PADS:
            # non-matching: no pad face node is a disc node (measured 0 of 106)
            self.assertEqual(pairs[pad.name]["shared"], 0)

    def test_deterministic(self):
        with tempfile.TemporaryDirectory() as other:
            ventilated_meshes.generate(["coarse"], list(ventilated_meshes.PARTS), other)
            for part in cv.PARTS:
                for ext in (".inp", ".msh"):
                    name = f"{cv.stem(part)}_coarse{ext}"
                    a, b = os.path.join(coarse_dir(), name), os.path.join(other, name)
                    self.assertTrue(filecmp.cmp(a, b, shallow=False), name)

    @unittest.skipUnless(
        brake_meshes.gmsh.__version__ == brake_meshes.GMSH_VERSION, "another Gmsh meshes otherwise"
    )
    def test_bundled_coarse_files_reproduced(self):
        for part in cv.PARTS:
            for ext in (".inp", ".msh"):
                name = f"{cv.stem(part)}_coarse{ext}"
                committed = os.path.join(_BUNDLED, name)
                if not os.path.exists(committed):
                    self.skipTest(f"{committed} not generated yet")
                made = os.path.join(coarse_dir(), name)
                self.assertTrue(filecmp.cmp(committed, made, shallow=False), name)

    def test_pad_lifted_off_the_disc(self):
        # the outboard pad moved 1 nm away from the disc: its face no longer on the disc face
        infos = self.infos()
        mesh = infos["outboard"]["mesh"]
        mesh.coords = mesh.coords - np.array([0.0, 0.0, 1e-9])
        rep = cm.Report(verbose=False)
        cv.check_pairs(rep, "coarse", infos)
        self.assertTrue(any("off the disc face" in f for f in rep.failures), rep.failures)

    def test_disc_face_not_covering_the_pad(self):
        # the disc face cut to the nodes inside the footprint leaves pad nodes uncovered
        infos = self.infos()
        disc = infos["disc"]["mesh"]
        table = cm.node_table(disc)
        disc.nsets["CONTACT_FACE"] = [
            i
            for i in disc.nsets["CONTACT_FACE"]
            if vg.distance_to_footprint(vg.INBOARD, table[i][0], table[i][1]) == 0.0
        ]
        rep = cm.Report(verbose=False)
        cv.check_pairs(rep, "coarse", infos)
        self.assertTrue(any("outside the disc's CONTACT_FACE" in f for f in rep.failures))

    def test_pad_turned_away(self):
        # the inboard pad turned 90 degrees about the axis: it faces no part of its disc face
        infos = self.infos()
        mesh = infos["inboard"]["mesh"]
        x, y = mesh.coords[:, 0].copy(), mesh.coords[:, 1].copy()
        mesh.coords = np.stack([y, -x, mesh.coords[:, 2]], axis=1)
        rep = cm.Report(verbose=False)
        cv.check_pairs(rep, "coarse", infos)
        self.assertTrue(any("inboard pad face nodes outside" in f for f in rep.failures))

    def test_clamp_incomplete_and_vane_missing(self):
        mesh = self.read("disc")
        mesh.nsets["CLAMP"] = mesh.nsets["CLAMP"][1:]
        self.assertTrue(any("bolt holes" in f for f in self.failures("disc", mesh)))
        # the elements of one vane (centroid in the channel, within 5 mm of the first vane's
        # plane, beyond the inner radius) dropped: the volume check fails
        mesh = self.read("disc")
        ids, conn = mesh.elsets["DISC"]
        cen = cm.element_coords(mesh, conn)[:, :4].mean(axis=1)
        in_channel = (cen[:, 2] > vg.Z_CHANNEL_BOTTOM) & (cen[:, 2] < vg.Z_CHANNEL_TOP)
        vane0 = in_channel & (np.abs(cen[:, 0]) < 0.005) & (cen[:, 1] > 0)
        self.assertGreater(int(vane0.sum()), 0)
        mesh.elsets["DISC"] = (ids[~vane0], conn[~vane0])
        self.assertTrue(any("volume" in f for f in self.failures("disc", mesh)))

    def test_wrong_piston_point(self):
        mesh = self.read("inboard")
        k = int(np.flatnonzero(mesh.node_ids == mesh.nsets["PISTON"][2])[0])
        mesh.coords = mesh.coords.copy()
        mesh.coords[k, 0] += 1e-9
        self.assertTrue(any("PISTON nodes" in f for f in self.failures("inboard", mesh)))


if __name__ == "__main__":
    unittest.main()
