# The scripted scene of the add-on's tests: a floor and a back wall (Blender's Principled BSDF,
# grey), a 200 W point lamp, an emissive quad (an Emission shader), a polished metal sphere (the
# glossy object) and a hazy box (a Principled Volume on a cube) around them, seen by a camera at
# a small resolution. Blender units are metres; the world is black (slowlight has no sky).
import math
import os

import bpy
from mathutils import Vector

LAMP = Vector((0.5, 0.6, 2.0))
LAMP_WATTS = 200.0
EMISSION_STRENGTH = 6.0
HAZE_DENSITY = float(os.environ.get("SLOWLIGHT_TEST_HAZE", "0.2"))  # Principled Volume, colour 0.5, no absorption colour: sigma_s = sigma_a = 0.1 /m
# The box reaches 10 cm below the floor: where its face coincides with the floor, Cycles' volume
# stack is ambiguous (that version gave Cycles' floor 0.62x slowlight's; both draw this one alike).
HAZE_MIN, HAZE_MAX = Vector((-2.5, -1.5, -0.1)), Vector((2.5, 2.5, 2.5))
CAMERA = Vector((0.0, -5.0, 2.0))


def principled(name, grey, metallic=0.0, roughness=0.5):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (grey, grey, grey, 1)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    return m


def emission(name, strength):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    e = nodes.new("ShaderNodeEmission")
    e.inputs["Strength"].default_value = strength
    m.node_tree.links.new(e.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    return m


def haze(name, density):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    v = nodes.new("ShaderNodeVolumePrincipled")
    v.inputs["Density"].default_value = density
    m.node_tree.links.new(v.outputs["Volume"], nodes["Material Output"].inputs["Volume"])
    return m


def add(name, verts, faces, material):
    data = bpy.data.meshes.new(name)
    data.from_pydata(verts, [], faces)
    data.materials.append(material)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def build(width=96, height=72):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    grey = principled("grey", 0.6)
    add("floor", [(-4, -3, 0), (4, -3, 0), (4, 4, 0), (-4, 4, 0)], [(0, 1, 2, 3)], grey)
    add("wall", [(-4, 3, 0), (4, 3, 0), (4, 3, 4), (-4, 3, 4)], [(0, 1, 2, 3)], grey)
    add("panel", [(-1.9, 1.2, 0.4), (-1.3, 1.2, 0.4), (-1.3, 1.2, 1.0), (-1.9, 1.2, 1.0)], [(0, 1, 2, 3)],
        emission("glow", EMISSION_STRENGTH))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.5, location=(1.1, 1.0, 0.5))
    sphere = bpy.context.view_layer.objects.active
    for poly in sphere.data.polygons:
        poly.use_smooth = True
    sphere.name = "sphere"
    sphere.data.materials.append(principled("polished metal", 0.9, metallic=1.0, roughness=0.05))
    c, h = (HAZE_MIN + HAZE_MAX) / 2, (HAZE_MAX - HAZE_MIN) / 2
    bpy.ops.mesh.primitive_cube_add(size=2, location=c, scale=h)
    box = bpy.context.view_layer.objects.active
    box.name = "haze"
    box.data.materials.append(haze("haze", HAZE_DENSITY))

    lamp = bpy.data.lights.new("lamp", "POINT")
    lamp.energy = LAMP_WATTS
    lamp.shadow_soft_size = 0.0
    obj = bpy.data.objects.new("lamp", lamp)
    obj.location = LAMP
    scene.collection.objects.link(obj)

    cam = bpy.data.cameras.new("camera")
    cam.lens_unit = "FOV"
    cam.angle = math.radians(55)  # across the wider side (sensor fit Auto)
    cobj = bpy.data.objects.new("camera", cam)
    cobj.location = CAMERA
    direction = Vector((0.0, 0.9, 0.7)) - CAMERA
    cobj.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()
    scene.collection.objects.link(cobj)
    scene.camera = cobj
    bpy.context.view_layer.update()
    return scene
