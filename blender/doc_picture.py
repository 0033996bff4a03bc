# Makes docs/images/blender_addon_frames.png: the add-on's Render Animation of the tests' scripted
# scene (tests/blender/showcase_scene.py: a lamp, an emissive quad, a rough metal and a blue plastic
# sphere, a hazy box), Blender frames written as PNG through its Standard view transform; three of
# them side by side (8, 11 and 24 ns: constant light, the lamp switched on at 0).
#
#   nice -n 15 blender -b --factory-startup -P blender/doc_picture.py -- build/slowlight OUT_FOLDER
#   ffmpeg -i OUT_FOLDER/f0008.png -i OUT_FOLDER/f0011.png -i OUT_FOLDER/f0024.png \
#          -filter_complex hstack=inputs=3 docs/images/blender_addon_frames.png
import os
import sys

import bpy

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "tests", "blender")]
import showcase_scene  # noqa: E402

program, out = sys.argv[sys.argv.index("--") + 1:][:2]
scene = showcase_scene.build(192, 144)
import slowlight_addon  # noqa: E402
slowlight_addon.register()
scene.render.engine = 'SLOWLIGHT'
st = scene.slowlight
st.program, st.passes, st.photons = os.path.abspath(program), 64, 200000
st.frames, st.start_ns, st.end_ns, st.emission = 24, 0.0, 24.0, 'CONSTANT'
st.label_time = True
st.video_path = os.path.join(os.path.abspath(out), "showcase.mp4")
scene.frame_start, scene.frame_end = 1, 24
scene.view_settings.view_transform = "Standard"
scene.view_settings.exposure = 1.0
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = os.path.join(os.path.abspath(out), "f")
bpy.ops.render.render(animation=True)
