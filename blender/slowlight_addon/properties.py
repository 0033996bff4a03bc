# The render settings a slowlight video needs and Blender has no place for (time window, emission,
# passes, sections, ...), kept on the scene as scene.slowlight and shown in Render Properties.
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty


class SlowlightSettings(bpy.types.PropertyGroup):
    use_timeline: BoolProperty(name="Frames from the timeline", default=True,
                               description="The video has one frame per frame of Blender's frame range "
                                           "(Start to End), so Render Animation fills the timeline")
    frames: IntProperty(name="Frames", default=48, min=1, max=100000,
                        description="Frames of the video (time.frames) when not taken from the timeline")
    start_ns: FloatProperty(name="Start (ns)", default=0.0, min=0.0,
                            description="Arrival time at the first frame's start, in nanoseconds")
    end_ns: FloatProperty(name="End (ns)", default=12.0, min=0.001,
                          description="Arrival time at the last frame's end, in nanoseconds")
    emission: EnumProperty(name="Emission", default='CONSTANT', items=[
        ('CONSTANT', "Constant", "The lamps switch on at t = 0 and stay on"),
        ('PULSE', "Pulse", "The lamps flash at t = 0 for the pulse width")])
    pulse_width_ns: FloatProperty(name="Pulse width (ns)", default=0.0, min=0.0,
                                  description="A whole multiple of the frame width; 0: one frame")
    passes: IntProperty(name="Passes", default=64, min=1, max=1000000,
                        description="Photon passes (the upper bound when a time limit is set)")
    photons: IntProperty(name="Photons per pass", default=200000, min=1, max=100000000)
    use_time_limit: BoolProperty(name="Time limit", default=False,
                                 description="Render as many passes as fit in the time limit")
    time_limit_min: FloatProperty(name="Minutes", default=10.0, min=0.05,
                                  description="Time limit in minutes (--time-limit)")
    split: EnumProperty(name="Sections", default='AUTO', items=[
        ('AUTO', "Automatic", "One section unless memory runs short"),
        ('SECTIONS', "Sections", "Split the frames into K sections (--sections)"),
        ('MEMORY', "Memory bound", "The fewest sections that keep the process within a size (--max-memory)")])
    sections: IntProperty(name="K", default=1, min=1, max=100000)
    max_memory: StringProperty(name="Max memory", default="2G", description="e.g. 512M, 2G")
    camera_tof: BoolProperty(name="Camera time of flight", default=False,
                             description="Add the way back to the camera to every arrival time")
    label_time: BoolProperty(name="Time label", default=False,
                             description="Print each frame's time on the video (--label time)")
    video_path: StringProperty(name="Video", default="//slowlight.mp4", subtype='FILE_PATH',
                               description="The video (.mp4, .mkv, .mov, .webm); its EXR frames go beside it")
    program: StringProperty(name="Program", default="slowlight", subtype='FILE_PATH',
                            description="The slowlight program (a path, or a name found on PATH)")


def video_frames(scene):
    """The video's number of frames: Blender's frame range, or the panel's own number."""
    st = scene.slowlight
    if st.use_timeline:
        return max(1, scene.frame_end - scene.frame_start + 1)
    return st.frames


def register():
    bpy.utils.register_class(SlowlightSettings)
    bpy.types.Scene.slowlight = bpy.props.PointerProperty(type=SlowlightSettings)


def unregister():
    del bpy.types.Scene.slowlight
    bpy.utils.unregister_class(SlowlightSettings)
