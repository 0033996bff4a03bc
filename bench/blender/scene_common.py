# Shared by the scene builders here: a fresh scene, quads with Blender's default Principled
# material, an Emission-only material, a sun, a camera, a black world, the stock glTF export at
# its default settings, the swap to Lambertian Diffuse BSDFs (slowlight draws these surfaces
# diffuse), and Cycles set up for reference images (Standard view transform, no denoising, high
# bounce limits, box filter, float EXR). Imported by the builders after they put this folder on
# sys.path.
import os

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def reset(width, height):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    world = bpy.data.worlds.new("black")  # slowlight has no sky
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    return scene


def principled(name, grey):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (grey, grey, grey, 1)
    return m


def emission(name, strength):
    """A material whose surface is an Emission shader alone (strength: radiance, W sr^-1 m^-2)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    e = nodes.new("ShaderNodeEmission")
    e.inputs["Strength"].default_value = strength
    m.node_tree.links.new(e.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    return m


def mesh(name, verts, faces, material):
    data = bpy.data.meshes.new(name)
    data.from_pydata(verts, [], faces)
    data.materials.append(material)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def sun(strength, rotation, location=(0, 0, 5)):
    data = bpy.data.lights.new("sun", "SUN")
    data.energy = strength  # W/m^2
    data.angle = 0.0        # parallel light, as slowlight's glTF sun
    obj = bpy.data.objects.new("sun", data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def camera(location, rotation, fov):
    data = bpy.data.cameras.new("camera")
    data.lens_unit = "FOV"
    data.angle = fov  # across the wider side of the image
    obj = bpy.data.objects.new("camera", data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    return obj


def export(path):
    # The stock exporter at its default settings (Lighting Mode "Standard": lights in candela and
    # lux), but for Include -> Cameras and Punctual Lights, which are off by default and which
    # docs/scenes.md asks for: without them the file has neither the sun nor the camera.
    bpy.ops.export_scene.gltf(filepath=path, export_cameras=True, export_lights=True)


def pixel(point):
    """Image position of a world point: (x, y) in pixels, y from the top."""
    scene = bpy.context.scene
    v = world_to_camera_view(scene, scene.camera, Vector(point))
    return v.x * scene.render.resolution_x, (1 - v.y) * scene.render.resolution_y


def swap_to_diffuse(names=None):
    """names: only these materials (all when None)."""
    for mat in bpy.data.materials:
        if not mat.use_nodes or "Principled BSDF" not in mat.node_tree.nodes:
            continue
        if names is not None and mat.name not in names:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        colour = nodes["Principled BSDF"].inputs["Base Color"].default_value[:]
        nodes.remove(nodes["Principled BSDF"])
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = colour
        diffuse.inputs["Roughness"].default_value = 0.0  # Lambertian
        links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])


def render_cycles(out_dir, stem, samples, seeds):
    """SAMPLES 0: export only."""
    if samples <= 0:
        return
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = cy.diffuse_bounces = 128
    cy.glossy_bounces = cy.transmission_bounces = cy.transparent_max_bounces = 128
    cy.caustics_reflective = cy.caustics_refractive = True
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0  # no "Filter Glossy" (it blurs glossy surfaces met after a diffuse bounce)
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    for seed in seeds:
        cy.seed = seed
        scene.render.filepath = os.path.join(out_dir, "%s_cycles_seed%d.exr" % (stem, seed))
        bpy.ops.render.render(write_still=True)
