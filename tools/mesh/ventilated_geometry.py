"""Dimensions of squeal's ventilated two-pad brake (SI units: m, rad) and its closed forms.

Shared by the generator (ventilated_meshes.py) and the checker (check_ventilated.py). The
brake: a hat disc of two friction rings (cheeks) joined by straight radial vanes, the hat wall
and a hub flange with a pilot bore and five bolt holes below the outboard cheek; an inboard pad
on the top cheek (pushed by two pistons) and an outboard pad on the bottom cheek (pulled on by
a floating caliper's two fingers), each a 60-degree sector of friction lining on a steel
backplate. Disc and pads are meshed separately: nothing of a pad's outline is imprinted on the
disc (see meshes/README.md, "Ventilated brake").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

# Disc: the outboard cheek z = 0 .. 7 mm, the vane channel 7 .. 16 mm, the inboard cheek
# 16 .. 23 mm; both cheeks and the vanes span r = 80 .. 140 mm (the channel is open at both
# radii: air enters at the inner radius and leaves at the outer).
R_IN = 0.080
R_OUT = 0.140
Z_BOTTOM = 0.000  # the outboard cheek's friction face
Z_CHANNEL_BOTTOM = 0.007
Z_CHANNEL_TOP = 0.016
Z_TOP = 0.023  # the inboard cheek's friction face
VANES = 21
VANE_WIDTH = 0.006  # tangential, constant along the vane (straight radial vanes)
VANE_ANGLE_0 = math.radians(90.0)  # the first vane's centre plane, on the pads' centre line

# Hat: wall r = 80 .. 86 mm going down from the outboard cheek, hub flange r = 33 .. 86 mm
# (66 mm pilot bore) z = -35 .. -29 mm, five M14 bolt holes (14 mm) on a 114.3 mm circle.
HAT_R_OUT = 0.086
FLANGE_Z_TOP = -0.029
FLANGE_Z_BOTTOM = -0.035
BORE_R = 0.033
BOLTS = 5
BOLT_CIRCLE_R = 0.05715
BOLT_R = 0.007
BOLT_ANGLE_0 = math.radians(90.0)


@dataclass(frozen=True)
class VentPad:
    """One pad: an annular sector angle_min..angle_max, r_in..r_out, its friction face on a disc
    face; going away from the disc (direction +1 upwards, -1 downwards), the 10 mm lining then
    the 5 mm steel backplate."""

    name: str  # "inboard" or "outboard"
    stem: str  # file stem under meshes/
    face_z: float  # friction face, on the disc
    lining_back_z: float  # lining/backplate interface
    back_z: float  # the backplate's back face, where the load points are
    load_set: str  # node set of the load points (PISTON or FINGERS)
    disc_face_set: str  # the disc's face under this pad (CONTACT_FACE, CONTACT_FACE_OUTBOARD)
    r_in: float = 0.090
    r_out: float = 0.138
    angle_min: float = math.radians(60.0)
    angle_max: float = math.radians(120.0)
    load_radius: float = 0.020  # the load contacts' rim points, either side of the mean radius
    load_angles: tuple[float, float] = (math.radians(77.5), math.radians(102.5))

    @property
    def direction(self) -> int:
        return 1 if self.back_z > self.face_z else -1

    @property
    def load_centre_r(self) -> float:
        return 0.5 * (self.r_in + self.r_out)


INBOARD = VentPad(
    name="inboard",
    stem="ventilated/inboard",
    face_z=Z_TOP,
    lining_back_z=0.033,
    back_z=0.038,
    load_set="PISTON",
    disc_face_set="CONTACT_FACE",
)
OUTBOARD = VentPad(
    name="outboard",
    stem="ventilated/outboard",
    face_z=Z_BOTTOM,
    lining_back_z=-0.010,
    back_z=-0.015,
    load_set="FINGERS",
    disc_face_set="CONTACT_FACE_OUTBOARD",
)
PADS = (INBOARD, OUTBOARD)
DISC_STEM = "ventilated/disc"


def _on_circle(r: float, a: float, z: float) -> tuple[float, float, float]:
    """(r cos a, r sin a, z), with the rounding residue of cos(pi/2) written as an exact 0."""
    x, y = r * math.cos(a), r * math.sin(a)
    return (0.0 if abs(x) < 1e-15 else x, 0.0 if abs(y) < 1e-15 else y, z)


def load_points(pad: VentPad) -> list[tuple[float, float, float]]:
    """Load points on a pad's back face, radius-major: inner/smaller angle, inner/larger,
    outer/smaller, outer/larger (as the bundled brakes' PISTON and FINGERS)."""
    return [
        _on_circle(r, a, pad.back_z)
        for r in (pad.load_centre_r - pad.load_radius, pad.load_centre_r + pad.load_radius)
        for a in pad.load_angles
    ]


def vane_angles() -> list[float]:
    return [VANE_ANGLE_0 + 2.0 * math.pi * k / VANES for k in range(VANES)]


def bolt_centres() -> list[tuple[float, float]]:
    return [
        (BOLT_CIRCLE_R * math.cos(a), BOLT_CIRCLE_R * math.sin(a))
        for a in (BOLT_ANGLE_0 + 2.0 * math.pi * k / BOLTS for k in range(BOLTS))
    ]


def annulus_volume(r_in: float, r_out: float, height: float) -> float:
    return math.pi * (r_out**2 - r_in**2) * height


def _strip_area(radius: float, half_width: float) -> float:
    """Area of {|y| <= a, x > 0, x^2 + y^2 <= R^2}: the integral of sqrt(R^2 - y^2) over |y| <= a."""
    a = half_width
    return a * math.sqrt(radius**2 - a**2) + radius**2 * math.asin(a / radius)


def vane_volume() -> float:
    """One vane: the strip of width VANE_WIDTH along a ray, between the two cylinders, times
    the channel's height."""
    a = 0.5 * VANE_WIDTH
    area = _strip_area(R_OUT, a) - _strip_area(R_IN, a)
    return area * (Z_CHANNEL_TOP - Z_CHANNEL_BOTTOM)


def disc_volume() -> float:
    """Two cheeks + vanes + hat wall + hub flange - bolt holes (disjoint pieces)."""
    cheeks = annulus_volume(R_IN, R_OUT, Z_CHANNEL_BOTTOM - Z_BOTTOM) + annulus_volume(
        R_IN, R_OUT, Z_TOP - Z_CHANNEL_TOP
    )
    hat = annulus_volume(R_IN, HAT_R_OUT, Z_BOTTOM - FLANGE_Z_TOP)
    flange = annulus_volume(BORE_R, HAT_R_OUT, FLANGE_Z_TOP - FLANGE_Z_BOTTOM)
    holes = BOLTS * math.pi * BOLT_R**2 * (FLANGE_Z_TOP - FLANGE_Z_BOTTOM)
    return cheeks + VANES * vane_volume() + hat + flange - holes


def sector_volume(pad: VentPad, height: float) -> float:
    return 0.5 * (pad.angle_max - pad.angle_min) * (pad.r_out**2 - pad.r_in**2) * height


def lining_volume(pad: VentPad) -> float:
    return sector_volume(pad, abs(pad.lining_back_z - pad.face_z))


def backplate_volume(pad: VentPad) -> float:
    return sector_volume(pad, abs(pad.back_z - pad.lining_back_z))


def friction_area(pad: VentPad) -> float:
    return sector_volume(pad, 1.0)


def distance_to_footprint(pad: VentPad, x: float, y: float) -> float:
    """Distance in the disc plane from (x, y) to the pad's footprint (0 inside)."""
    r, a = math.hypot(x, y), math.atan2(y, x)
    if pad.angle_min <= a <= pad.angle_max:
        return max(pad.r_in - r, r - pad.r_out, 0.0)
    best = math.inf
    for edge in (pad.angle_min, pad.angle_max):
        ux, uy = math.cos(edge), math.sin(edge)
        t = min(max(x * ux + y * uy, pad.r_in), pad.r_out)
        best = min(best, math.hypot(x - t * ux, y - t * uy))
    return best
