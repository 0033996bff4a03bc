# Builds a closed room with a window opening, lit by a sun through it, exports it with the stock
# glTF exporter at its default settings, and renders it with Cycles: slowlight's boundary bias
# around the opening (a visible point on the wall beside it has part of its gather disc over
# the hole, where no photon lands) is measured against it (bench/blender/README.md).
#
#   blender -b --factory-startup -P bench/blender/window_scene.py -- [principled] OUT_DIR [SAMPLES] [SEED ...]
#
# Scene (Z up, metres): a 4 x 3 x 2.5 m room of zero-thickness quads (Principled, base colour
# 0.6); in the wall y = 1.5 a 1 x 1 m opening (x in (-0.5, 0.5), z in (0.8, 1.8)); a 3 W/m^2
# sun 40 degrees above the horizon shining in through it; a camera inside at (0, -1.4, 1.3)
# looking at the window wall, 128 x 96. Writes OUT_DIR/window.glb,
# OUT_DIR/window_cycles_seedN.exr and OUT_DIR/window_regions.json.
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_common as sc  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
# "principled" first: Cycles renders the Principled BSDF itself (what a Blender user sees), into
# OUT_DIR/window_principled_cycles_seedN.exr; without it the surfaces are swapped for Diffuse BSDFs.
keep_principled = bool(argv) and argv[0] == "principled"
argv = argv[1:] if keep_principled else argv
out_dir = os.path.abspath(argv[0] if argv else "out")
samples = int(argv[1]) if len(argv) > 1 else 2048
seeds = [int(s) for s in argv[2:]] or [1, 2]
os.makedirs(out_dir, exist_ok=True)
W, H = 128, 96

sc.reset(W, H)
m = sc.principled("white", 0.6)
X, Y, Z = 2.0, 1.5, 2.5
q = lambda name, v: sc.mesh(name, v, [(0, 1, 2, 3)], m)  # noqa: E731
q("floor", [(-X, -Y, 0), (X, -Y, 0), (X, Y, 0), (-X, Y, 0)])
q("ceiling", [(-X, -Y, Z), (-X, Y, Z), (X, Y, Z), (X, -Y, Z)])
q("wall_back", [(-X, -Y, 0), (-X, -Y, Z), (X, -Y, Z), (X, -Y, 0)])
q("wall_left", [(-X, -Y, 0), (-X, Y, 0), (-X, Y, Z), (-X, -Y, Z)])
q("wall_right", [(X, -Y, 0), (X, -Y, Z), (X, Y, Z), (X, Y, 0)])
# The window wall y = Y around the opening, in four pieces.
x0, x1, z0, z1 = -0.5, 0.5, 0.8, 1.8
q("window_left", [(-X, Y, 0), (x0, Y, 0), (x0, Y, Z), (-X, Y, Z)])
q("window_right", [(x1, Y, 0), (X, Y, 0), (X, Y, Z), (x1, Y, Z)])
q("window_below", [(x0, Y, 0), (x1, Y, 0), (x1, Y, z0), (x0, Y, z0)])
q("window_above", [(x0, Y, z1), (x1, Y, z1), (x1, Y, Z), (x0, Y, Z)])
# -z turned about x by -50 degrees: the light travels toward -y, 40 degrees below the horizon.
sc.sun(3.0, (math.radians(-50), 0, 0), (0, 4, 4))
sc.camera((0, -1.4, 1.3), (math.radians(90), 0, 0), math.radians(70))
sc.export(os.path.join(out_dir, "window.glb"))

# The opening's rectangle in the image (the wall faces the camera squarely).
(ax, ay), (bx, by) = sc.pixel((x0, Y, z1)), sc.pixel((x1, Y, z0))
X0, X1, Y0, Y1 = math.floor(ax), math.ceil(bx), math.floor(ay), math.ceil(by)  # covers the opening
px_per_m = (bx - ax) / (x1 - x0)
ring = 3  # pixels of wall beside each edge
away = int(round(0.3 * px_per_m))
regions = {
    "image": [0, W, 0, H],
    "ring_left": [X0 - ring, X0, Y0, Y1],
    "ring_right": [X1, X1 + ring, Y0, Y1],
    "ring_above": [X0, X1, Y0 - ring, Y0],
    "ring_below": [X0, X1, Y1, Y1 + ring],
    "wall_left_away": [X0 - away - ring, X0 - away, Y0, Y1],
    "wall_right_away": [X1 + away, X1 + away + ring, Y0, Y1],
}
with open(os.path.join(out_dir, "window_regions.json"), "w") as f:
    json.dump({"width": W, "height": H, "opening_px": [ax, bx, ay, by], "regions": regions}, f, indent=1)

if not keep_principled:
    sc.swap_to_diffuse()
sc.render_cycles(out_dir, "window_principled" if keep_principled else "window", samples, seeds)
print("window: wrote", out_dir)
