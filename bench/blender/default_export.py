# Blender's factory scene (the default cube with the default Principled BSDF) plus a plane with an
# Emission-only material (strength 10), exported by the stock glTF exporter at its default settings
# but for Include -> Cameras and Punctual Lights: the file for checking that slowlight warns about
# neither material (issue 28, item 6; bench/blender/README.md).
#
#   blender -b --factory-startup -P bench/blender/default_export.py -- OUT.glb
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out = argv[0] if argv else "default_export.glb"
bpy.ops.wm.read_factory_settings()
bpy.ops.mesh.primitive_plane_add(location=(0, 0, 3))
lamp = bpy.data.materials.new("lamp")
lamp.use_nodes = True
nodes = lamp.node_tree.nodes
nodes.remove(nodes["Principled BSDF"])
emission = nodes.new("ShaderNodeEmission")
emission.inputs["Strength"].default_value = 10.0
lamp.node_tree.links.new(emission.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
bpy.context.object.data.materials.append(lamp)
bpy.ops.export_scene.gltf(filepath=out, export_cameras=True, export_lights=True)
