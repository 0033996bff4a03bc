# Blender's factory scene (the default cube with the default Principled BSDF) plus a plane with an
# Emission-only material (strength 10), exported by the stock glTF exporter at its default settings
# but for Include -> Cameras and Punctual Lights: the file for checking that slowlight warns about
# neither material (issue 28, item 6; bench/blender/README.md).
#
#   blender -b --factory-startup -P bench/blender/default_export.py -- OUT.glb
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import scene_common as sc  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out = argv[0] if argv else "default_export.glb"
bpy.ops.wm.read_factory_settings()
bpy.ops.mesh.primitive_plane_add(location=(0, 0, 3))
bpy.context.object.data.materials.append(sc.emission("lamp", 10.0))
sc.export(out)
