#!/usr/bin/env python3
"""The ventilated brake's convergence table (docs/reduction.md, "The ventilated brake under
refinement") from the outputs of `squeal stability` runs, one per mesh level and kept modes.

    python3 tools/study/ventilated_convergence.py LABEL=OUT_DIR [LABEL=OUT_DIR ...]

Each OUT_DIR is a `squeal stability SCENE -o OUT_DIR` folder (with its VTU files for the
shape columns; a run with --no-vtu leaves them empty). For each run it prints μ0, its frequency, the reduced size, the in-band crossings
of the sweep (branch, frequency, friction bracket), and of the unstable mode at μ0 (from
`stability/shapes_disc.vtu`): its nodal diameters (the axial motion of the disc nodes beyond
0.55 of the largest radius, in 72 angle bins, Fourier orders 0..12: the classification of
`crates/squeal-pipeline/src/pictures.rs`, `nodal_diameters`) with the share of the dominant
order, and its MAC against the previous run's on the disc's contact-face nodes (each node of
the previous run's faces paired with the nearest node of this run's faces: the study's
`face_mac`, crates/squeal-pipeline/src/study/convergence.rs). Then, for each consecutive
triple of runs given, the observed rate of μ0 (the ratio of its last two changes).
"""
import base64
import json
import math
import os
import re
import struct
import sys

import numpy as np


def arrays(path):
    """The VTU's binary (uncompressed, UInt64 header) data arrays by name."""
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="([^"]+)" NumberOfComponents="(\d+)"'
                         r' format="binary"[^>]*>\s*([A-Za-z0-9+/=]+)\s*</DataArray>', text):
        kind, name, ncomp, data = m.group(1), m.group(2), int(m.group(3)), m.group(4)
        raw = base64.b64decode(data)
        nbytes = struct.unpack("<Q", raw[:8])[0]
        dtype = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "UInt64": "<u8",
                 "Int32": "<i4", "UInt32": "<u4", "UInt8": "u1", "Int8": "i1"}[kind]
        a = np.frombuffer(raw[8:8 + nbytes], dtype=dtype)
        out[name] = a.reshape(-1, ncomp) if ncomp > 1 else a
    return out


def nodal_diameters(a):
    """(dominant order, its share) of the disc's axial motion on the outer annulus."""
    x = a["Points"]
    w = a["unstable_mode_real"][:, 2] + 1j * a["unstable_mode_imag"][:, 2]
    r = np.hypot(x[:, 0], x[:, 1])
    keep = r > 0.55 * r.max()
    th = np.arctan2(x[keep, 1], x[keep, 0])
    bins = np.floor((th + math.pi) / (2 * math.pi) * 72).astype(int) % 72
    mean = np.zeros(72, complex)
    for b in range(72):
        sel = bins == b
        if sel.any():
            mean[b] = w[keep][sel].mean()
    centres = -math.pi + (np.arange(72) + 0.5) * 2 * math.pi / 72
    power = []
    for n in range(13):
        c = np.sum(mean * np.cos(n * centres))
        s = np.sum(mean * np.sin(n * centres))
        power.append(abs(c) ** 2 + abs(s) ** 2 if n else abs(c) ** 2)
    power = np.array(power)
    k = int(power.argmax())
    return k, power[k] / power.sum()


def face(a):
    """Positions and complex displacements of the disc's contact-face nodes."""
    sel = np.zeros(len(a["Points"]), bool)
    for name in ("set:CONTACT_FACE", "set:CONTACT_FACE_OUTBOARD"):
        if name in a:
            sel |= a[name] != 0
    u = a["unstable_mode_real"] + 1j * a["unstable_mode_imag"]
    return a["Points"][sel], u[sel]


def mac(prev, this):
    (p, u), (q, v) = prev, this
    j = np.array([np.argmin(((q - x) ** 2).sum(axis=1)) for x in p])
    v = v[j]
    return abs(np.vdot(u, v)) ** 2 / (np.vdot(u, u).real * np.vdot(v, v).real)


def main():
    rows, prev, mu0s = [], None, []
    for arg in sys.argv[1:]:
        label, out = arg.split("=", 1)
        s = json.load(open(f"{out}/stability/summary.json"))
        ir = s.get("interface_reduction") or {}
        crossings = [c for c in s["crossings"] if c["in_band"]]
        vtu = f"{out}/stability/shapes_disc.vtu"
        if os.path.isfile(vtu):
            a = arrays(vtu)
            nd, share = nodal_diameters(a)
            f = face(a)
            m = mac(prev, f) if prev is not None else None
            shape = f"{nd} ({share:.2f})"
        else:
            # A run with --no-vtu: no shape, and no MAC with the next run.
            f, m, shape = None, None, "-"
        prev = f
        mu0s.append(s["mu0"])
        print(f"| {label} | {ir.get('dofs_before', '-')} -> {ir.get('dofs', '-')} | "
              f"{s['mu0']:.8f} | {s['frequency_hz']:.2f} | modes {s['pair_modes_1based']} | "
              f"{shape} | {'-' if m is None else f'{m:.4f}'} | "
              + "; ".join(f"b{c['branch']} {c['frequency_hz']:.0f} Hz [{c['mu_lo']:.3f}, {c['mu_hi']:.3f}]"
                          for c in crossings) + " |")
    for i in range(len(mu0s) - 2):
        d1, d2 = mu0s[i + 1] - mu0s[i], mu0s[i + 2] - mu0s[i + 1]
        print(f"runs {i + 1}-{i + 3}: changes {d1:+.3e}, {d2:+.3e}, ratio {d2 / d1:+.3f}")


if __name__ == "__main__":
    main()
