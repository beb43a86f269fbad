"""Dimensions of squeal's bundled brakes (SI units: m, rad) and the points derived from them.

Shared by the generator (brake_meshes.py) and the checker (check_meshes.py) so that the disc's
and the pads' contact points are computed by the same expressions and coincide bit for bit.

Two brakes: the one-pad brake (the disc and the inboard pad on its top face, pushed by the
pistons) and the two-pad brake (a disc carrying both footprints, the same inboard pad, and an
outboard pad on the disc's bottom face, pulled on by a floating caliper's fingers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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

# Pad (the inboard pad): annular sector of 50 degrees centred on +y.
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

# Outboard pad of the two-pad brake, on the disc's bottom face (z = 0), over the same angles.
# Its footprint is 3 mm further out than the inboard pad's: the hat wall (r = 80 .. 86 mm)
# occupies the bottom face's inner edge, and 88 mm leaves 2 mm of clearance.
OUTBOARD_R_IN = 0.088
OUTBOARD_R_OUT = 0.138
OUTBOARD_LINING_Z_TOP = DISC_Z_BOTTOM  # friction face lies on the disc's bottom face
OUTBOARD_LINING_Z_MID = -0.005
OUTBOARD_LINING_Z_BOTTOM = -0.010  # 10 mm lining
OUTBOARD_BACKPLATE_Z_BOTTOM = -0.015  # 5 mm steel backplate

# Floating caliper: two fingers bear on the outboard backplate's back face opposite the
# pistons, represented like the pistons by the innermost and outermost point of each contact,
# 20 mm either side of the outboard pad's mean radius.
FINGER_CENTRE_R = 0.5 * (OUTBOARD_R_IN + OUTBOARD_R_OUT)  # 0.113
FINGER_RADIUS = 0.020
FINGER_ANGLES = PISTON_ANGLES


@dataclass(frozen=True)
class PadGeometry:
    """One pad: an annular sector PAD_ANGLE_MIN..PAD_ANGLE_MAX, r_in..r_out, whose friction
    face lies on a disc face; going away from the disc (direction +1 upwards, -1 downwards),
    the lining, then the backplate. Its z values are given, not summed from thicknesses, so
    each is exactly the double of the constant it names."""

    name: str  # "inboard" or "outboard"
    r_in: float
    r_out: float
    face_z: float  # friction face, on the disc
    lining_mid_z: float  # internal mesh face at the lining's mid-thickness (two element layers)
    lining_back_z: float  # lining/backplate interface
    back_z: float  # the backplate's back face, where the load points are
    load_set: str  # node set of the load points
    load_centre_r: float  # the load contacts' centre radius ...
    load_radius: float  # ... and the distance of their innermost and outermost points from it
    load_angles: tuple[float, float]  # the two contacts' angles
    disc_suffix: str  # suffix of the disc's set names for this footprint ("" or "_OUTBOARD")

    @property
    def direction(self) -> int:
        """+1 if the pad lies above its friction face (on the disc's top face), -1 below."""
        return 1 if self.back_z > self.face_z else -1


INBOARD = PadGeometry(
    name="inboard",
    r_in=PAD_R_IN,
    r_out=PAD_R_OUT,
    face_z=LINING_Z_BOTTOM,
    lining_mid_z=LINING_Z_MID,
    lining_back_z=LINING_Z_TOP,
    back_z=BACKPLATE_Z_TOP,
    load_set="PISTON",
    load_centre_r=PISTON_CENTRE_R,
    load_radius=PISTON_RADIUS,
    load_angles=PISTON_ANGLES,
    disc_suffix="",
)

OUTBOARD = PadGeometry(
    name="outboard",
    r_in=OUTBOARD_R_IN,
    r_out=OUTBOARD_R_OUT,
    face_z=OUTBOARD_LINING_Z_TOP,
    lining_mid_z=OUTBOARD_LINING_Z_MID,
    lining_back_z=OUTBOARD_LINING_Z_BOTTOM,
    back_z=OUTBOARD_BACKPLATE_Z_BOTTOM,
    load_set="FINGERS",
    load_centre_r=FINGER_CENTRE_R,
    load_radius=FINGER_RADIUS,
    load_angles=FINGER_ANGLES,
    disc_suffix="_OUTBOARD",
)


@dataclass(frozen=True)
class Part:
    """One mesh of a bundled brake: its file stem (relative to meshes/, without _<level>) and
    the pads whose footprints it carries (a disc) or that it is (a pad, one)."""

    stem: str
    is_disc: bool
    pads: tuple[PadGeometry, ...]
    reused: bool = False  # the file belongs to another brake and is not written for this one


BRAKES = {
    "one-pad": {
        "disc": Part("disc", True, (INBOARD,)),
        "pad": Part("pad", False, (INBOARD,)),
    },
    "two-pad": {
        "disc": Part("two_pad/disc", True, (INBOARD, OUTBOARD)),
        "pad": Part("pad", False, (INBOARD,), reused=True),
        "outboard": Part("two_pad/outboard", False, (OUTBOARD,)),
    },
}


def patch_radii(pad: PadGeometry = INBOARD) -> list[float]:
    """The 4 radii bounding the 3 radial thirds of a pad footprint, inner to outer."""
    return [pad.r_in + (pad.r_out - pad.r_in) * i / 3.0 for i in range(4)]


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


def contact_points(pad: PadGeometry = INBOARD) -> list[tuple[float, float, float]]:
    """Centre (mid radius, mid angle) of each patch of a pad's footprint on its friction face,
    in patch order 1..9: the pad's contact nodes and those of the disc under it."""
    radii = patch_radii(pad)
    angles = patch_angles()
    pts = []
    for i in range(3):
        r = 0.5 * (radii[i] + radii[i + 1])
        for j in range(3):
            a = 0.5 * (angles[j] + angles[j + 1])
            pts.append(_on_circle(r, a, pad.face_z))
    return pts


def load_points(pad: PadGeometry = INBOARD) -> list[tuple[float, float, float]]:
    """Load points on a pad's back face, radius-major like the patches: 1 inner/smaller angle,
    2 inner/larger angle, 3 outer/smaller angle, 4 outer/larger angle."""
    pts = []
    for r in (pad.load_centre_r - pad.load_radius, pad.load_centre_r + pad.load_radius):
        for a in pad.load_angles:
            pts.append(_on_circle(r, a, pad.back_z))
    return pts


def piston_points() -> list[tuple[float, float, float]]:
    """The inboard pad's piston rim points (its load points)."""
    return load_points(INBOARD)


def finger_points() -> list[tuple[float, float, float]]:
    """The outboard pad's finger points (its load points)."""
    return load_points(OUTBOARD)


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


def lining_volume(pad: PadGeometry = INBOARD) -> float:
    return sector_volume(pad.r_in, pad.r_out, abs(pad.lining_back_z - pad.face_z))


def backplate_volume(pad: PadGeometry = INBOARD) -> float:
    return sector_volume(pad.r_in, pad.r_out, abs(pad.back_z - pad.lining_back_z))
