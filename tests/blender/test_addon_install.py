# The zip the build makes installs and registers in a fresh factory-startup Blender: the render
# engine, its panel and settings exist, and unregistering removes them again.
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402

zip_path, program, work = addon_env.args()
addon = addon_env.install(zip_path)
check = addon_env.check

check(addon.bl_info["blender"] <= (3, 4, 0), "bl_info asks for Blender 3.4 or later: %s" % (addon.bl_info["blender"],))
check("slowlight_addon" in bpy.context.preferences.addons, "the add-on is enabled in the preferences")
scene = bpy.context.scene
scene.render.engine = 'SLOWLIGHT'
check(scene.render.engine == 'SLOWLIGHT', "slowlight is a render engine")
check(hasattr(bpy.types, "RENDER_PT_slowlight"), "its panel is registered")
check('SLOWLIGHT' in bpy.types.RENDER_PT_format.COMPAT_ENGINES, "Blender's format panel shows for it")
st = scene.slowlight
for name in ("use_timeline", "frames", "start_ns", "end_ns", "emission", "pulse_width_ns", "passes", "photons",
             "use_time_limit", "time_limit_min", "split", "sections", "max_memory", "camera_tof",
             "label_time", "video_path", "program"):
    check(hasattr(st, name), "scene.slowlight.%s exists" % name)
# The time window suggestion: the default cube (2 m) and the camera and lamp of the factory scene.
res = bpy.ops.slowlight.suggest_time()
diagonal, end_ns = addon.scene_writer.suggested_end_ns(scene)
check(res == {'FINISHED'} and abs(st.end_ns - end_ns) < 0.01 * end_ns,
      "the suggested window ends at three crossings of the diagonal (%.3g ns, set %.3g)" % (end_ns, st.end_ns))
check(abs(end_ns - 3 * diagonal / 0.299792458) < 1e-6, "the suggestion is 3 x diagonal / c")
bpy.ops.preferences.addon_disable(module="slowlight_addon")
check(not hasattr(bpy.types, "RENDER_PT_slowlight"), "disabling unregisters the panel")
check('SLOWLIGHT' not in bpy.types.RENDER_PT_format.COMPAT_ENGINES, "and takes the engine off Blender's panels")
