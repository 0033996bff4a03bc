# The slowlight panel in Render Properties (shown when slowlight is the render engine) and the
# operator that fills in the time window from the scene's size.
import bpy

from . import properties, scene_writer


class SLOWLIGHT_OT_suggest_time(bpy.types.Operator):
    """Set the time window to three crossings of the scene's diagonal (as slowlight info gives)"""
    bl_idname = "slowlight.suggest_time"
    bl_label = "Suggest from the scene's size"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        diagonal, end_ns = scene_writer.suggested_end_ns(context.scene)
        if end_ns is None:
            self.report({'WARNING'}, "slowlight: the scene has no objects to measure")
            return {'CANCELLED'}
        st = context.scene.slowlight
        st.start_ns, st.end_ns = 0.0, float("%.3g" % end_ns)
        self.report({'INFO'}, "slowlight: the diagonal is %.3g m, light crosses it in %.3g ns"
                    % (diagonal, end_ns / 3))
        return {'FINISHED'}


class RENDER_PT_slowlight(bpy.types.Panel):
    bl_label = "slowlight"
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'
    bl_context = "render"
    COMPAT_ENGINES = {'SLOWLIGHT'}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        st = context.scene.slowlight
        layout = self.layout
        layout.use_property_split = True
        col = layout.column(heading="Time")
        col.prop(st, "use_timeline")
        if st.use_timeline:
            col.label(text="%d frames (Blender frames %d to %d)" % (properties.video_frames(context.scene),
                                                                     context.scene.frame_start,
                                                                     context.scene.frame_end))
        else:
            col.prop(st, "frames")
        col.prop(st, "start_ns")
        col.prop(st, "end_ns")
        diagonal, end_ns = scene_writer.suggested_end_ns(context.scene)
        if end_ns is not None:
            col.label(text="Light crosses the scene (%.3g m) in %.3g ns" % (diagonal, end_ns / 3))
        col.operator("slowlight.suggest_time")
        col = layout.column(heading="Emission")
        col.prop(st, "emission")
        if st.emission == 'PULSE':
            col.prop(st, "pulse_width_ns")
        col = layout.column(heading="Quality")
        col.prop(st, "passes")
        col.prop(st, "photons")
        col.prop(st, "use_time_limit")
        if st.use_time_limit:
            col.prop(st, "time_limit_min")
        col = layout.column(heading="Memory")
        col.prop(st, "split")
        if st.split == 'SECTIONS':
            col.prop(st, "sections")
        elif st.split == 'MEMORY':
            col.prop(st, "max_memory")
        col = layout.column(heading="Video")
        col.prop(st, "camera_tof")
        col.prop(st, "label_time")
        col.prop(st, "video_path")
        col.prop(st, "program")


classes = (SLOWLIGHT_OT_suggest_time, RENDER_PT_slowlight)


def register():
    for c in classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
