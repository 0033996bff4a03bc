# The scene the add-on writes, checked against values worked out here from Blender's own data:
# the camera (glTF axes, the vertical field of view from the horizontal one), each lamp type in
# Blender's watts, the medium from a Principled Volume on a box and from other volume nodes, the
# glTF holding every mesh but the volume box, and the report of what is not carried. The program
# must accept the scene (`slowlight info`).
import json
import math
import os
import subprocess
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import showcase_scene  # noqa: E402

zip_path, program, work = addon_env.args()
scene = showcase_scene.build(96, 72)
addon = addon_env.install(zip_path)
check = addon_env.check


def close(a, b, tol=1e-5):
    a = a if isinstance(a, (list, tuple)) else [a]
    b = b if isinstance(b, (list, tuple)) else [b]
    return len(a) == len(b) and all(abs(x - y) <= tol * max(1, abs(y)) for x, y in zip(a, b))


def lamp(name, kind, location, rotation=(0, 0, 0), **props):
    data = bpy.data.lights.new(name, kind)
    for k, v in props.items():
        setattr(data, k, v)
    obj = bpy.data.objects.new(name, data)
    obj.location, obj.rotation_euler = location, rotation
    scene.collection.objects.link(obj)
    return obj


# A spot pointing straight down, a sun from 45 degrees, a square area lamp facing -x.
lamp("spot", "SPOT", (0, 0, 3), energy=100.0, spot_size=math.radians(60), spot_blend=0.15, shadow_soft_size=0)
lamp("sun", "SUN", (0, 0, 5), (math.radians(45), 0, 0), energy=3.0, angle=math.radians(0.53))
lamp("area", "AREA", (2, 0, 1), (0, math.radians(90), 0), energy=50.0, size=0.5)
glossy = bpy.data.materials.new("glossy node")
glossy.use_nodes = True
nodes = glossy.node_tree.nodes
nodes.remove(nodes["Principled BSDF"])
g = nodes.new("ShaderNodeBsdfGlossy")
glossy.node_tree.links.new(g.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
bpy.data.objects["wall"].data.materials[0] = glossy
scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.5
bpy.context.view_layer.update()

path, warnings = addon.scene_writer.write_scene(scene, os.path.join(work, "scene"))
doc = json.load(open(path))
print(json.dumps(doc, indent=1)[:1500])
print("warnings:", warnings)


def gltf(v):  # Blender (x, y, z) -> glTF +Y up (x, z, -y)
    return [v[0], v[2], -v[1]]


cam = doc["camera"]
check(close(cam["position"], gltf(showcase_scene.CAMERA)), "camera position in glTF axes")
forward = (Vector((0.0, 0.9, 0.7)) - showcase_scene.CAMERA).normalized()
seen = (Vector(cam["look_at"]) - Vector(cam["position"])).normalized()
check(close(list(seen), gltf(forward)), "camera direction")
check(cam["up"][1] > 0.7, "camera up is glTF's +y side")
vfov = 2 * math.degrees(math.atan(math.tan(math.radians(55) / 2) * 72 / 96))
check(close(cam["vfov_deg"], vfov), "vfov %.4f from 55 deg across the 96 px side (sensor fit Auto)" % vfov)
check((cam["width"], cam["height"]) == (96, 72), "render resolution")

lights = {l["type"]: l for l in doc["lights"]}
check(close(lights["point"]["power"], [200.0] * 3) and close(lights["point"]["position"], gltf(showcase_scene.LAMP)),
      "point lamp: 200 W at its place")
spot_power = 100.0 / (4 * math.pi) * 2 * math.pi * (1 - math.cos(math.radians(30)))
check(close(lights["spot"]["power"], [spot_power] * 3) and close(lights["spot"]["cone_deg"], 60.0)
      and close(lights["spot"]["direction"], [0, -1, 0]),
      "spot: Blender's 100 W intensity (100/4pi W/sr) over its 60 deg cone = %.4f W, pointing down" % spot_power)
check(close(lights["sun"]["irradiance"], [3.0] * 3) and close(lights["sun"]["angle_deg"], 0.53),
      "sun: 3 W/m^2 and its 0.53 deg angle")
d = lights["sun"]["direction"]
check(close(d, gltf([0, math.sin(math.radians(45)), -math.cos(math.radians(45))])), "sun direction")
q = lights["quad"]
n = Vector(q["edge1"]).cross(Vector(q["edge2"]))
check(close(q["radiance"], [50 / (math.pi * 0.25)] * 3), "area lamp: 50 W over 0.25 m^2 -> 50 / (pi A) W/sr/m^2")
check(close(list(n.normalized()), gltf([-1, 0, 0])) and close(n.length, 0.25), "area lamp faces its -z (here -x)")
centre = Vector(q["corner"]) + (Vector(q["edge1"]) + Vector(q["edge2"])) / 2
check(close(list(centre), gltf([2, 0, 1])), "area lamp centred on its object")

med = doc["medium"]
check(close(med["sigma_s"], 0.1) and close(med["sigma_a"], 0.1) and "g" not in med,
      "Principled Volume, density 0.2, colour 0.5: sigma_s = sigma_a = 0.1 per metre")
lo, hi = showcase_scene.HAZE_MIN, showcase_scene.HAZE_MAX
check(close(med["bounds"]["min"], [lo.x, lo.z, -hi.y]) and close(med["bounds"]["max"], [hi.x, hi.z, -lo.y]),
      "the medium fills the box")

# Other volume nodes, evaluated as Cycles adds closures.
mat = bpy.data.materials.new("mix")
mat.use_nodes = True
nt = mat.node_tree
nt.nodes.remove(nt.nodes["Principled BSDF"])
sc, ab, add = nt.nodes.new("ShaderNodeVolumeScatter"), nt.nodes.new("ShaderNodeVolumeAbsorption"), nt.nodes.new("ShaderNodeAddShader")
sc.inputs["Color"].default_value = (0.8, 0.4, 0.2, 1)
sc.inputs["Density"].default_value = 0.5
sc.inputs["Anisotropy"].default_value = 0.3
ab.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1)
ab.inputs["Density"].default_value = 0.2
nt.links.new(sc.outputs[0], add.inputs[0])
nt.links.new(ab.outputs[0], add.inputs[1])
nt.links.new(add.outputs[0], nt.nodes["Material Output"].inputs["Volume"])
w = []
m = addon.volume.from_socket(nt.nodes["Material Output"].inputs["Volume"], "test", w)
check(close(m.sigma_s, [0.4, 0.2, 0.1]) and close(m.sigma_a, [0.1] * 3) and close(m.g, 0.3) and not w,
      "Scatter (0.8/0.4/0.2 x 0.5, g 0.3) + Absorption ((1 - 0.5) x 0.2)")
pv = nt.nodes.new("ShaderNodeVolumePrincipled")
pv.inputs["Color"].default_value = (0.6, 0.6, 0.6, 1)
pv.inputs["Absorption Color"].default_value = (0.25, 0.25, 0.25, 1)
pv.inputs["Density"].default_value = 2.0
pv.inputs["Emission Strength"].default_value = 1.0
nt.links.new(pv.outputs[0], nt.nodes["Material Output"].inputs["Volume"])
w = []
m = addon.volume.from_socket(nt.nodes["Material Output"].inputs["Volume"], "test", w)
check(close(m.sigma_s, [1.2] * 3) and close(m.sigma_a, [2 * 0.4 * 0.5] * 3),
      "Principled: sigma_a = density (1 - colour)(1 - sqrt(absorption colour))")
check(len(w) == 1 and "emits" in w[0], "a glowing volume is reported")

joined = "\n".join(warnings)
check("world" in joined and "background" in joined, "the world's light is reported")
check("glossy node" in joined and "ShaderNodeBsdfGlossy" in joined, "a non-Principled surface is reported")
check("spot" in joined and "blend" in joined, "the spot's blend is reported")
check("haze" not in joined, "the haze box (a volume, no surface) needs no warning")

# The glTF: every mesh but the haze box.
tris = sum(len(o.data.loop_triangles) for o in scene.objects
           if o.type == 'MESH' and o.name != "haze" and (o.data.calc_loop_triangles() or True))
# Blender 3.x: its Principled v1 base as Cycles draws it (uncapped); 4.x: the default.
shape = {"type": "gltf", "file": "scene.glb"}
if bpy.app.version < (4, 0, 0):
    shape["principled"] = "blender3"
check(doc["shapes"] == [shape], "the meshes come through one glTF, drawn as this Blender's Principled BSDF")
info = subprocess.run([program, "info", path], capture_output=True, text=True)
print(info.stdout, info.stderr)
check(info.returncode == 0, "slowlight info accepts the scene")
check("%d imported triangles" % tris in info.stdout, "the glTF holds the %d triangles of the meshes, not the box" % tris)
check("with a medium" in info.stdout and "lights: 4" in info.stdout, "the medium and the four lamps are there")
check("(2 emissive" in info.stdout, "the emissive quad is an area light")
