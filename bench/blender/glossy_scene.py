# Builds a glossy scene in Blender, exports it with the stock glTF exporter at its default
# settings, and renders it with Cycles for slowlight's comparison (bench/blender/README.md).
#
#   blender -b --factory-startup -P bench/blender/glossy_scene.py -- KIND OUT_DIR [SAMPLES] [SEED ...]
#
# KIND: metal (the cube a Principled metal: base 0.8, metallic 1, roughness 0.3), plastic (a
# Principled dielectric: base (0.8, 0.1, 0.1), metallic 0, roughness 0.2, specular 0.5) or glass
# (Principled, transmission 1, roughness 0.2 for reflection and refraction, ior 1.45; the cube
# 5 cm above the floor). The glass scene is lit by a 1 x 1 m
# emissive quad 3 m up (Emission shader, strength 20) rather than the sun: Cycles cannot carry a
# parallel sun's light through rough glass to the floor, photons can.
# Scene (Blender's Z up, metres): a 6 x 6 m floor (Principled, base 0.5, specular 0: a Lambertian
# base alone in the exported file; Cycles gets a Diffuse BSDF), a 1 m cube standing on it turned 30 degrees
# (its Principled distribution set to single-scattering GGX in Cycles, as slowlight's), a 3 W/m^2 sun 45 degrees high, a camera 3.5 m away, 128 x 96.
# Cycles renders the cube's Principled BSDF itself. Writes OUT_DIR/glossy_KIND.glb,
# OUT_DIR/glossy_KIND_cycles_seedN.exr and OUT_DIR/glossy_KIND_regions.json.
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import scene_common as sc  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
kind = argv[0] if argv else "metal"
assert kind in ("metal", "plastic", "glass"), kind
stem = "glossy_" + kind
out_dir = os.path.abspath(argv[1] if len(argv) > 1 else "out")
samples = int(argv[2]) if len(argv) > 2 else 1024
seeds = [int(s) for s in argv[3:]] or [1, 2]
os.makedirs(out_dir, exist_ok=True)
W, H = 128, 96

sc.reset(W, H)
floor_mat = sc.principled("floor", 0.5)
floor_mat.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
metal = sc.principled(kind, 0.8)
bsdf = metal.node_tree.nodes["Principled BSDF"]
if kind == "metal":
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = 0.3
elif kind == "plastic":
    bsdf.inputs["Base Color"].default_value = (0.8, 0.1, 0.1, 1)
    bsdf.inputs["Roughness"].default_value = 0.2
else:
    bsdf.inputs["Base Color"].default_value = (1, 1, 1, 1)
    bsdf.inputs["Roughness"].default_value = 0.2
    bsdf.inputs["Transmission"].default_value = 1.0
    # Principled v1 refracts with roughness 1 - (1 - Roughness)(1 - Transmission Roughness): its
    # default Transmission Roughness 0 gives the 0.2 that glTF's one roughness means.
bsdf.distribution = "GGX"
sc.mesh("floor", [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)], [(0, 1, 2, 3)], floor_mat)
c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
corners = [(x * c - y * s, x * s + y * c) for x, y in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]]
lift = 0.05 if kind == "glass" else 0.0  # no glass face on the floor's plane
verts = [(x, y, lift) for x, y in corners] + [(x, y, 1 + lift) for x, y in corners]
faces = [(3, 2, 1, 0), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
sc.mesh("cube", verts, faces, metal)
if kind == "glass":
    lamp = sc.emission("lamp", 20.0)
    sc.mesh("lamp", [(-1.5, 0.5, 3), (-1.5, -0.5, 3), (-0.5, -0.5, 3), (-0.5, 0.5, 3)], [(0, 1, 2, 3)], lamp)
else:
    sc.sun(3.0, (math.radians(45), 0, math.radians(-60)), (3, -3, 4))
sc.camera((0, -3.5, 1.6), (math.radians(72), 0, 0), math.radians(50))
sc.export(os.path.join(out_dir, stem + ".glb"))


def box(point, half):
    x, y = sc.pixel(point)
    return [int(x) - half, int(x) + half, int(y) - half, int(y) + half]


regions = {
    "image": [0, W, 0, H],
    "cube_front_face": box((0.5 * s * 0 + 0.0, -0.5 / c * 0.9, 0.5), 3),
    "cube_top": box((0, 0, 1), 3),
    "floor_left_of_cube": box((-1.4, -0.3, 0), 4),
    "floor_right_of_cube": box((1.4, -0.3, 0), 4),
    "floor_behind_cube": box((0.9, 0.9, 0), 3),
}
with open(os.path.join(out_dir, stem + "_regions.json"), "w") as f:
    json.dump({"width": W, "height": H, "regions": regions}, f, indent=1)

# Principled v1's diffuse is Burley's, not Lambert's: the floor is swapped for a Diffuse BSDF of its
# colour (the exported file keeps it Principled with no specular layer: a Lambertian base).
sc.swap_to_diffuse(["floor"])
sc.render_cycles(out_dir, stem, samples, seeds)
print(stem + ": wrote", out_dir)
