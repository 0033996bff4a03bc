# Builds the thin-wall scene in Blender, exports it with the stock glTF exporter at its default
# settings, and renders it with Cycles for slowlight's comparison (bench/blender/README.md).
#
#   blender -b --factory-startup -P bench/blender/thin_wall_scene.py -- [principled] OUT_DIR [SAMPLES] [SEED ...]
#
# Scene (Blender's Z up, metres): a 6 x 6 m floor, a zero-thickness sheet wall (one quad, x = 0,
# 3 m long, 1 m tall) standing on it, a 3 W/m^2 sun at 45 degrees from the +x side (the floor's
# shadow band is x in (-1, 0)), and a camera 2.5 m above the wall's foot looking straight down,
# 128 x 96. Both surfaces: Principled BSDF, base colour 0.5 (Diffuse BSDF for Cycles).
# Writes OUT_DIR/thin_wall.glb, OUT_DIR/thin_wall_cycles_seedN.exr per seed and
# OUT_DIR/thin_wall_regions.json (named pixel rectangles [x0, x1, y0, y1), rows from the top,
# from the camera's own projection).
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_common as sc  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
# "principled" first: Cycles renders the Principled BSDF itself (what a Blender user sees), into
# OUT_DIR/thin_wall_principled_cycles_seedN.exr; without it the surfaces are swapped for Diffuse BSDFs.
keep_principled = bool(argv) and argv[0] == "principled"
argv = argv[1:] if keep_principled else argv
out_dir = os.path.abspath(argv[0] if argv else "out")
samples = int(argv[1]) if len(argv) > 1 else 4096
seeds = [int(s) for s in argv[2:]] or [1, 2]
os.makedirs(out_dir, exist_ok=True)
W, H = 128, 96

sc.reset(W, H)
floor_mat, wall_mat = sc.principled("floor", 0.5), sc.principled("wall", 0.5)
sc.mesh("floor", [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)], [(0, 1, 2, 3)], floor_mat)
sc.mesh("wall", [(0, -1.5, 0), (0, 1.5, 0), (0, 1.5, 1), (0, -1.5, 1)], [(0, 1, 2, 3)], wall_mat)
# -z turned 45 degrees toward -x: the light travels down and toward -x.
sc.sun(3.0, (0, math.radians(45), 0), (3, 0, 3))
sc.camera((0, 0, 2.5), (0, 0, 0), 2 * math.atan(1.0 / 2.5))  # +-1 m of floor across the width
sc.export(os.path.join(out_dir, "thin_wall.glb"))

foot_x, _ = sc.pixel((0, 0, 0))
# The foot's line in the image: on a column boundary (the camera stands over it), else the
# column it crosses is left out of both sides.
boundary = round(foot_x)
on_edge = abs(foot_x - boundary) < 0.01
shadow_end = boundary if on_edge else int(math.floor(foot_x))
lit_begin = boundary if on_edge else int(math.floor(foot_x)) + 1
_, y_top = sc.pixel((0, 0.5, 0))
_, y_bot = sc.pixel((0, -0.5, 0))
r0, r1 = int(round(min(y_top, y_bot))), int(round(max(y_top, y_bot)))  # 1 m of the wall's length
metre_px = W / 2.0
column = lambda x: int(sc.pixel((x, 0, 0))[0])  # noqa: E731
regions = {
    "image": [0, W, 0, H],
    "foot_shadow_5px": [shadow_end - 5, shadow_end, r0, r1],
    "foot_shadow_4cm": [shadow_end - int(round(0.04 * metre_px)), shadow_end, r0, r1],
    "foot_lit_5px": [lit_begin, lit_begin + 5, r0, r1],
    "shadow_middle": [column(-0.6) - 3, column(-0.6) + 3, r0, r1],
    "lit_floor": [column(0.6) - 3, column(0.6) + 3, r0, r1],
}
with open(os.path.join(out_dir, "thin_wall_regions.json"), "w") as f:
    json.dump({"width": W, "height": H, "foot_x": foot_x, "regions": regions}, f, indent=1)

if not keep_principled:
    sc.swap_to_diffuse()
sc.render_cycles(out_dir, "thin_wall_principled" if keep_principled else "thin_wall", samples, seeds)
print("thin_wall: wrote", out_dir)
