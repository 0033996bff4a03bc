# The scripted scene of the add-on's tests: a floor and a back wall (Blender's Principled BSDF,
# grey), a 200 W point lamp, an emissive quad (an Emission shader), two glossy spheres and a hazy
# box (a Principled Volume on a cube) around them, seen by a camera at a small resolution. The
# spheres exercise both ways slowlight draws a GGX surface (docs/materials.md, "In the renderer"):
# a Principled metal of roughness 0.35 (below 0.5: camera paths follow it) and a blue Principled
# plastic of roughness 0.4 (a specular layer over a coloured base: gathered). The plastic's base
# is far from white so that slowlight's cap on the diffuse albedo (<= 1) does not decide the
# comparison with Cycles. Blender units are metres; the world is black (slowlight has no sky).
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
# (centre, radius) of the spheres; the tests project them into the image for their regions.
METAL_SPHERE = (Vector((1.1, 1.0, 0.5)), 0.5)
METAL_ROUGHNESS = 0.35
PLASTIC_SPHERE = (Vector((-0.55, 0.3, 0.4)), 0.4)
PLASTIC_COLOUR = (0.2, 0.4, 0.7)
PLASTIC_ROUGHNESS = 0.4
# Principled "Specular" of the plastic: Blender's default 0.5 (F0 = 4 %); 0 leaves its Burley/
# Lambertian base alone (docs/blender.md uses it to tell the gather's bias from the layer's).
PLASTIC_SPECULAR = float(os.environ.get("SLOWLIGHT_TEST_PLASTIC_SPECULAR", "0.5"))


def principled(name, colour, metallic=0.0, roughness=0.5):
    """colour: a grey level or an (r, g, b) triple."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    rgb = colour if isinstance(colour, tuple) else (colour, colour, colour)
    p.inputs["Base Color"].default_value = rgb + (1,)
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


def sphere(name, centre_radius, material):
    centre, radius = centre_radius
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=radius, location=centre)
    obj = bpy.context.view_layer.objects.active
    for poly in obj.data.polygons:
        poly.use_smooth = True
    obj.name = name
    obj.data.materials.append(material)
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
    sphere("metal sphere", METAL_SPHERE, principled("rough metal", 0.9, metallic=1.0, roughness=METAL_ROUGHNESS))
    plastic = principled("blue plastic", PLASTIC_COLOUR, roughness=PLASTIC_ROUGHNESS)
    plastic.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = PLASTIC_SPECULAR
    sphere("plastic sphere", PLASTIC_SPHERE, plastic)
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
