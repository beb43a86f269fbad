"""Dimensions of squeal's bundled brake (SI units: m, rad) and the points derived from them.

Shared by the generator (brake_meshes.py) and the checker (check_meshes.py) so that the disc's
and the pad's contact points are computed by the same expressions and coincide bit for bit.
"""

from __future__ import annotations

import math

# Disc: braking annulus, hat wall (inside the annulus' inner edge, going down), hub flange.
DISC_R_IN = 0.080  # annulus inner radius = hat wall inner radius
DISC_R_OUT = 0.140
DISC_Z_BOTTOM = 0.000
DISC_Z_TOP = 0.020  # braking face under the pad
DISC_Z_MID = 0.010  # internal mesh face at mid-thickness (two element layers)
HAT_R_OUT = 0.086  # hat wall 6 mm thick: r = 0.080 .. 0.086
FLANGE_Z_TOP = -0.029  # hub flange 6 mm thick: z = -0.035 .. -0.029
FLANGE_Z_BOTTOM = -0.035  # the face seated on the hub (CLAMP)
BORE_R = 0.033  # hub pilot bore, 66 mm diameter

# Pad: annular sector of 50 degrees centred on +y.
PAD_R_IN = 0.085
PAD_R_OUT = 0.135
PAD_ANGLE_MIN = math.radians(65.0)
PAD_ANGLE_MAX = math.radians(115.0)
LINING_Z_BOTTOM = DISC_Z_TOP  # friction face lies on the disc's top face
LINING_Z_TOP = 0.030  # 10 mm lining
LINING_Z_MID = 0.025  # internal mesh face at mid-thickness (two element layers)
BACKPLATE_Z_TOP = 0.035  # 5 mm steel backplate

# Twin-piston caliper: two 40 mm pistons on the pad's mean radius, 25 degrees apart; each
# cup piston touches the backplate on its rim, represented by the rim's inner and outer points.
PISTON_CENTRE_R = 0.5 * (PAD_R_IN + PAD_R_OUT)  # 0.110
PISTON_RADIUS = 0.020
PISTON_ANGLES = (math.radians(77.5), math.radians(102.5))


def patch_radii() -> list[float]:
    """The 4 radii bounding the 3 radial thirds of the pad footprint, inner to outer."""
    return [PAD_R_IN + (PAD_R_OUT - PAD_R_IN) * i / 3.0 for i in range(4)]


def patch_angles() -> list[float]:
    """The 4 angles bounding the 3 angular thirds of the pad footprint, smallest first."""
    return [PAD_ANGLE_MIN + (PAD_ANGLE_MAX - PAD_ANGLE_MIN) * j / 3.0 for j in range(4)]


def patch_index(i_radius: int, j_angle: int) -> int:
    """1-based patch number, radius-major: 1..3 on the inner third from the smallest angle."""
    return 3 * i_radius + j_angle + 1


def _on_circle(r: float, a: float, z: float) -> tuple[float, float, float]:
    """(r cos a, r sin a, z), with the rounding residue of cos(pi/2) written as an exact 0."""
    x, y = r * math.cos(a), r * math.sin(a)
    return (0.0 if abs(x) < 1e-15 else x, 0.0 if abs(y) < 1e-15 else y, z)


def contact_points(z: float) -> list[tuple[float, float, float]]:
    """Centre (mid radius, mid angle) of each patch at height z, in patch order 1..9."""
    radii = patch_radii()
    angles = patch_angles()
    pts = []
    for i in range(3):
        r = 0.5 * (radii[i] + radii[i + 1])
        for j in range(3):
            a = 0.5 * (angles[j] + angles[j + 1])
            pts.append(_on_circle(r, a, z))
    return pts


def piston_points() -> list[tuple[float, float, float]]:
    """Piston rim points on the backplate's back face, radius-major like the patches:
    1 inner/smaller angle, 2 inner/larger angle, 3 outer/smaller angle, 4 outer/larger angle."""
    pts = []
    for r in (PISTON_CENTRE_R - PISTON_RADIUS, PISTON_CENTRE_R + PISTON_RADIUS):
        for a in PISTON_ANGLES:
            pts.append(_on_circle(r, a, BACKPLATE_Z_TOP))
    return pts


def annulus_volume(r_in: float, r_out: float, height: float) -> float:
    return math.pi * (r_out**2 - r_in**2) * height


def disc_volume() -> float:
    """Analytic disc volume: annulus + hat wall + hub flange (three disjoint annular cylinders)."""
    return (
        annulus_volume(DISC_R_IN, DISC_R_OUT, DISC_Z_TOP - DISC_Z_BOTTOM)
        + annulus_volume(DISC_R_IN, HAT_R_OUT, DISC_Z_BOTTOM - FLANGE_Z_TOP)
        + annulus_volume(BORE_R, HAT_R_OUT, FLANGE_Z_TOP - FLANGE_Z_BOTTOM)
    )


def sector_volume(r_in: float, r_out: float, height: float) -> float:
    return 0.5 * (PAD_ANGLE_MAX - PAD_ANGLE_MIN) * (r_out**2 - r_in**2) * height


def lining_volume() -> float:
    return sector_volume(PAD_R_IN, PAD_R_OUT, LINING_Z_TOP - LINING_Z_BOTTOM)


def backplate_volume() -> float:
    return sector_volume(PAD_R_IN, PAD_R_OUT, BACKPLATE_Z_TOP - LINING_Z_TOP)
