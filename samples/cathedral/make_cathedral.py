#!/usr/bin/env python3
"""Writes the cathedral sample: OBJ geometry and the scene JSONs (constant and pulse).

A nave 14 m wide, 36 m long, walls 15 m high under a gabled roof (ridge at 20 m); two rows of
octagonal columns; six tall pointed windows down the left wall (x = -7) and a rose window in the
west front (z = 0); haze fills the nave up to the tops of its walls (a haze box reaching
into the gable would also hold haze outside the roof, which the beam estimate would gather
through it). The sun shines in through the windows and the rose, its
light travelling towards +x, +z and down at 30 degrees. The camera stands in the haze near the
east end, looking back down the nave towards the rose.

Python 3 standard library only. Run it from anywhere; it writes next to itself, or into the
folder given:

    python3 samples/cathedral/make_cathedral.py [OUT_DIR]

Each OBJ is one material (the scene JSON names it); cathedral.mtl carries the same materials
for tools that read OBJ+MTL.
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

W = 7.0        # half width (x in [-W, W])
L = 36.0       # length (z in [0, L])
H = 15.0       # wall height
RIDGE = 20.0   # roof ridge
WINDOWS_Z = [4.5, 9.5, 14.5, 19.5, 24.5, 29.5]
WIN_HALF = 0.8       # half width of a window
WIN_SILL, WIN_SPRING, WIN_APEX = 4.0, 11.0, 12.6
ROSE_C, ROSE_R, ROSE_SQ = (0.0, 11.0), 2.8, 3.0   # centre (x, y), radius, half side of its panel
COLUMNS_Z = [6.5, 13.0, 19.5, 26.0, 32.5]
COLUMN_X, COLUMN_R = 4.0, 0.45
SUN_DIR = (0.62, -0.5, 0.6)   # where the light goes


class Mesh:
    def __init__(self, name, material):
        self.name, self.material = name, material
        self.v, self.f = [], []

    def vert(self, p):
        self.v.append(tuple(round(c, 5) for c in p))
        return len(self.v)

    def tri(self, a, b, c):
        self.f.append((self.vert(a), self.vert(b), self.vert(c)))

    def quad(self, a, b, c, d):
        self.tri(a, b, c)
        self.tri(a, c, d)

    def write(self, path):
        with open(path, "w") as out:
            out.write("# slowlight cathedral: %s (written by make_cathedral.py)\n" % self.name)
            out.write("mtllib cathedral.mtl\no %s\nusemtl %s\n" % (self.name, self.material))
            for p in self.v:
                out.write("v %g %g %g\n" % p)
            for f in self.f:
                out.write("f %d %d %d\n" % f)


def rect_x(m, x, z0, z1, y0, y1):
    """A rectangle in the plane x = const."""
    m.quad((x, y0, z0), (x, y0, z1), (x, y1, z1), (x, y1, z0))


def rect_z(m, z, x0, x1, y0, y1):
    """A rectangle in the plane z = const."""
    m.quad((x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z))


def left_wall(m):
    """x = -W with pointed windows: strips between them, and the pieces below and above each."""
    x = -W
    edges = [0.0]
    for zc in WINDOWS_Z:
        z0, z1 = zc - WIN_HALF, zc + WIN_HALF
        rect_x(m, x, edges[-1], z0, 0, H)          # the pier before this window
        rect_x(m, x, z0, z1, 0, WIN_SILL)           # below the sill
        # above the pointed arch: (z0, spring) - (zc, apex) - (z1, spring), up to the wall top
        m.tri((x, WIN_SPRING, z0), (x, WIN_APEX, zc), (x, H, z0))
        m.tri((x, WIN_APEX, zc), (x, H, z1), (x, H, z0))
        m.tri((x, WIN_APEX, zc), (x, WIN_SPRING, z1), (x, H, z1))
        edges.append(z1)
    rect_x(m, x, edges[-1], L, 0, H)


def west_front(m):
    """z = 0 with the rose: the panel around the circle, the hub, spokes and a ring of tracery."""
    cx, cy = ROSE_C
    s = ROSE_SQ
    rect_z(m, 0, -W, cx - s, 0, H)
    rect_z(m, 0, cx + s, W, 0, H)
    rect_z(m, 0, cx - s, cx + s, 0, cy - s)
    rect_z(m, 0, cx - s, cx + s, cy + s, H)
    n = 48
    for k in range(n):
        a0, a1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        pts = []
        for a in (a0, a1):
            c, sn = math.cos(a), math.sin(a)
            edge = s / max(abs(c), abs(sn))
            pts.append(((cx + ROSE_R * c, cy + ROSE_R * sn, 0), (cx + edge * c, cy + edge * sn, 0)))
        (c0, q0), (c1, q1) = pts
        m.quad(c0, q0, q1, c1)
    hub = 0.6
    for k in range(24):
        a0, a1 = 2 * math.pi * k / 24, 2 * math.pi * (k + 1) / 24
        m.tri((cx, cy, 0), (cx + hub * math.cos(a0), cy + hub * math.sin(a0), 0),
              (cx + hub * math.cos(a1), cy + hub * math.sin(a1), 0))
    for k in range(12):  # spokes
        a = 2 * math.pi * (k + 0.5) / 12
        c, sn = math.cos(a), math.sin(a)
        tx, ty = -sn * 0.12, c * 0.12
        r0, r1 = hub * 0.9, ROSE_R * 1.01
        m.quad((cx + r0 * c - tx, cy + r0 * sn - ty, 0), (cx + r1 * c - tx, cy + r1 * sn - ty, 0),
               (cx + r1 * c + tx, cy + r1 * sn + ty, 0), (cx + r0 * c + tx, cy + r0 * sn + ty, 0))
    ring0, ring1 = 1.75, 1.9
    for k in range(n):
        a0, a1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        p = lambda r, a: (cx + r * math.cos(a), cy + r * math.sin(a), 0)
        m.quad(p(ring0, a0), p(ring1, a0), p(ring1, a1), p(ring0, a1))
    m.tri((-W, H, 0), (W, H, 0), (0, RIDGE, 0))   # gable


def shell(m):
    rect_x(m, W, 0, L, 0, H)                        # the right wall: no windows
    rect_z(m, L, -W, W, 0, H)                       # the east end
    m.tri((-W, H, L), (W, H, L), (0, RIDGE, L))
    m.quad((-W, H, 0), (0, RIDGE, 0), (0, RIDGE, L), (-W, H, L))   # roof
    m.quad((W, H, 0), (W, H, L), (0, RIDGE, L), (0, RIDGE, 0))


def columns(m):
    sides = 8
    for zc in COLUMNS_Z:
        for xc in (-COLUMN_X, COLUMN_X):
            for k in range(sides):
                a0, a1 = 2 * math.pi * k / sides, 2 * math.pi * (k + 1) / sides
                p0 = (xc + COLUMN_R * math.cos(a0), zc + COLUMN_R * math.sin(a0))
                p1 = (xc + COLUMN_R * math.cos(a1), zc + COLUMN_R * math.sin(a1))
                m.quad((p0[0], 0, p0[1]), (p1[0], 0, p1[1]), (p1[0], H, p1[1]), (p0[0], H, p0[1]))


def floor(m):
    m.quad((-W, 0, 0), (-W, 0, L), (W, 0, L), (W, 0, 0))


MATERIALS = {
    "stone": [0.62, 0.58, 0.52],
    "floor": [0.42, 0.40, 0.37],
    "column": [0.55, 0.52, 0.47],
}


def scene(pulse):
    n = math.sqrt(sum(c * c for c in SUN_DIR))
    s = {
        "camera": {"position": [1.0, 1.7, 35.2], "look_at": [-3.5, 6.0, 0.0], "up": [0, 1, 0],
                   "vfov_deg": 70.0, "width": 256, "height": 144},
        "materials": {k: {"type": "diffuse", "albedo": v} for k, v in MATERIALS.items()},
        "shapes": [
            {"type": "mesh", "file": "nave.obj", "material": "stone"},
            {"type": "mesh", "file": "floor.obj", "material": "floor"},
            {"type": "mesh", "file": "columns.obj", "material": "column"},
        ],
        "lights": [
            {"type": "sun", "direction": [round(c / n, 5) for c in SUN_DIR], "angle_deg": 0.53,
             "irradiance": [1000, 960, 880]},
        ],
        "medium": {"sigma_a": 0.001, "sigma_s": 0.05, "g": 0.5,
                   "bounds": {"min": [-W, 0, 0], "max": [W, H, L]}},
        "time": {"start_ns": 0, "end_ns": 192, "frames": 64, "fps": 24},
        "emission": {"mode": "pulse", "width_ns": 6.0} if pulse else {"mode": "constant"},
        # 50k photons a pass: the sun's are aimed where the camera sees (about half enter the
        # nave, not 1 in 22), so this costs what 200k unaimed did, with less noise.
        "render": {"passes": 32, "photons_per_pass": 50000, "max_depth": 3, "alpha": 0.7, "seed": 1},
    }
    return s


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else HERE
    os.makedirs(out_dir, exist_ok=True)
    nave = Mesh("nave", "stone")
    left_wall(nave)
    west_front(nave)
    shell(nave)
    fl = Mesh("floor", "floor")
    floor(fl)
    col = Mesh("columns", "column")
    columns(col)
    for m, name in ((nave, "nave.obj"), (fl, "floor.obj"), (col, "columns.obj")):
        m.write(os.path.join(out_dir, name))
    with open(os.path.join(out_dir, "cathedral.mtl"), "w") as out:
        out.write("# slowlight cathedral materials (written by make_cathedral.py)\n")
        for k, v in MATERIALS.items():
            out.write("newmtl %s\nKd %g %g %g\n" % (k, *v))
    for pulse, name in ((False, "cathedral.json"), (True, "cathedral_pulse.json")):
        with open(os.path.join(out_dir, name), "w") as out:
            json.dump(scene(pulse), out, indent=1)
            out.write("\n")


if __name__ == "__main__":
    main()
