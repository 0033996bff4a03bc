# Render Animation through the SLOWLIGHT engine (the whole video rendered once, as a child
# process, its EXR frames beside it): with a one-frame pulse and the camera's time of flight, a
# floor pixel lit by the lamp is brightest in the frame holding lamp -> floor -> camera over c,
# to within one frame. The video takes its frames from Blender's frame range (1 to 40), and
# each Blender frame receives the video frame of the same place in the range.
import math
import os
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import exr_image  # noqa: E402
import showcase_scene  # noqa: E402

C = 0.299792458  # m/ns
W, H = 48, 36
zip_path, program, work = addon_env.args()
scene = showcase_scene.build(W, H)
addon = addon_env.install(zip_path)
check = addon_env.check

scene.render.engine = 'SLOWLIGHT'
st = scene.slowlight
st.program, st.passes, st.photons = program, 16, 50000
st.start_ns, st.end_ns = 0.0, 40.0
st.emission, st.camera_tof = 'PULSE', True
st.video_path = os.path.join(work, "tof.mp4")
scene.frame_start, scene.frame_end = 1, 40  # 40 frames of 1 ns, from the timeline
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.filepath = os.path.join(work, "blender_frames", "f")
bpy.ops.render.render(animation=True)
exr_dir = os.path.join(work, "tof_exr")
check(os.path.getsize(st.video_path) > 0, "Render Animation wrote the video")
check(os.path.exists(os.path.join(exr_dir, "frame_0039.exr")), "and its 40 EXR frames beside it")
blender_frames = sorted(os.listdir(os.path.join(work, "blender_frames")))
check(len(blender_frames) == 40, "Blender got one frame from the engine per timeline frame (%d)" % len(blender_frames))

# The floor point under the lamp, the pixel that sees it, and the floor point at that pixel's centre.
cam = scene.camera
under = Vector((showcase_scene.LAMP.x, showcase_scene.LAMP.y, 0.0))
v = world_to_camera_view(scene, cam, under)
px, py = int(v.x * W), int((1 - v.y) * H)  # py from the top
tr, br, bl, tl = cam.data.view_frame(scene=scene)
u, w = (px + 0.5) / W, 1 - (py + 0.5) / H
d = cam.matrix_world.to_3x3() @ (bl + u * (br - bl) + w * (tl - bl))
origin = cam.matrix_world.translation
floor = origin + d * (-origin.z / d.z)
t = ((showcase_scene.LAMP - floor).length + (floor - origin).length) / C
expected = int(t // 1.0)  # frames of 1 ns from 0

values = [exr_image.load(os.path.join(exr_dir, "frame_%04d.exr" % k))[py][px] for k in range(40)]
brightest = max(range(40), key=lambda k: values[k])
print("pixel (%d, %d), floor point %s, lamp->floor->camera %.3f ns: frame %d expected, brightest %d"
      % (px, py, tuple(round(c, 3) for c in floor), t, expected, brightest))
print("values around it: %s" % ["%.3g" % x for x in values[max(0, expected - 3):expected + 4]])
check(values[brightest] > 0, "the pixel is lit")
check(abs(brightest - expected) <= 1, "the lit floor pixel's time of flight is right to within one frame")

# Blender's frame k holds the video's frame k - 1 (its own output of the engine's result).
blender_value = exr_image.load(os.path.join(work, "blender_frames", "f%04d.exr" % (brightest + 1)))[py][px]
check(abs(blender_value / values[brightest] - 1) < 1e-3,
      "Blender frame %d is video frame %d (%.4g against %.4g)" % (brightest + 1, brightest, blender_value,
                                                                  values[brightest]))
