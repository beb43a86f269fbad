"""Checks of tools/mesh/hex_pad.py: node and element counts of the serendipity grid, the sets
the scene reads, positive element volumes, and the bundled coarse file written by it."""

from __future__ import annotations

import math
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hex_pad  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def signed_volume(x):
    """Six times the volume of the tetrahedron (a, b, c, d)."""
    a, b, c, d = x
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]))


class HexPad(unittest.TestCase):
    def test_counts_sets_and_orientation(self):
        for nr, nt, nl in hex_pad.LEVELS.values():
            nodes, elements, sets = hex_pad.build(nr, nt, nl)
            nz = nl + 1
            grid = (2 * nr + 1) * (2 * nt + 1) * (2 * nz + 1)
            # Less the face centres (two odd indices) and the cell centres (three).
            centres = (nr * nt * (nz + 1) + nr * (nt + 1) * nz + (nr + 1) * nt * nz + nr * nt * nz)
            self.assertEqual(len(nodes), grid - centres)
            self.assertEqual(len(elements), nr * nt * nz)
            self.assertEqual(len(sets["CONTACT_FACE"]), (2 * nr + 1) * (2 * nt + 1) - nr * nt)
            xyz = {n: x for n, x in nodes.values()}
            for n in sets["CONTACT_FACE"]:
                self.assertEqual(xyz[n][2], 0.020)
            for n, (r, t) in zip(sets["PISTON"], hex_pad.PISTONS):
                x = xyz[n]
                self.assertAlmostEqual(math.hypot(x[0], x[1]), r, delta=1e-15)
                self.assertAlmostEqual(math.degrees(math.atan2(x[1], x[0])), t, delta=1e-12)
                self.assertEqual(x[2], 0.035)
            for n in sets["ABUTMENT"]:
                self.assertGreaterEqual(xyz[n][2], 0.030)
            # The corner tetrahedron (1, 2, 4, 5) of every element has a positive volume.
            for _, ns, _ in elements:
                self.assertGreater(signed_volume([xyz[ns[i]] for i in (0, 1, 3, 4)]), 0.0)

    def test_bundled_coarse_file_is_the_generators(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "pad.inp")
            nodes, elements, sets = hex_pad.build(*hex_pad.LEVELS["coarse"])
            hex_pad.write(path, nodes, elements, sets, "cells 5 x 4 x 1")
            with open(path, encoding="ascii") as f, open(
                os.path.join(ROOT, "meshes", "hex_pad", "pad_coarse.inp"), encoding="ascii"
            ) as g:
                self.assertEqual(f.read(), g.read())


if __name__ == "__main__":
    unittest.main()
