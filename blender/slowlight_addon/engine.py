# The render engine "SLOWLIGHT": F12 writes the scene, runs `slowlight render --exr-dir` for the
# steady image (one frame) and loads steady.exr into the render result; Render Animation renders
# the whole video once, at the first frame, into the panel's video path (EXR frames beside it),
# then hands Blender the EXR frame of each of its frames. Progress, Esc and the program's
# messages go through the engine (update_progress, test_break, report).
import os
import shutil
import tempfile
import threading

import bpy

from . import properties, runner, scene_writer

# One video per Render Animation: the first frame renders it, the others read its frames.
_video = {"exr_dir": None, "frames": 0}


def video_paths(settings):
    video = bpy.path.abspath(settings.video_path or "//slowlight.mp4")
    stem = os.path.splitext(video)[0]
    return video, stem + "_exr"


class SlowlightRenderEngine(bpy.types.RenderEngine):
    bl_idname = "SLOWLIGHT"
    bl_label = "slowlight"
    bl_use_preview = False
    bl_use_eevee_viewport = True
    bl_use_shading_nodes_custom = False

    def render(self, depsgraph):
        scene = depsgraph.scene
        settings = scene.slowlight
        r = scene.render
        width = max(1, r.resolution_x * r.resolution_percentage // 100)
        height = max(1, r.resolution_y * r.resolution_percentage // 100)
        if self.is_animation:
            index = scene.frame_current - scene.frame_start
            if index == 0 or _video["exr_dir"] is None:
                if not self._render_video(scene, depsgraph):
                    return
            frame = os.path.join(_video["exr_dir"], "frame_%04d.exr" % index)
            if index >= _video["frames"]:
                self.report({'WARNING'}, "slowlight: the video has %d frames; Blender frame %d is past them"
                            % (_video["frames"], scene.frame_current))
            self._load(frame, width, height)
            return
        folder = tempfile.mkdtemp(prefix="slowlight_still_")
        try:
            exr = os.path.join(folder, "exr")
            status = self._run(scene, depsgraph, folder, exr, still=True)
            if status == 0 or (status == runner.INTERRUPTED and os.path.exists(os.path.join(exr, "steady.exr"))):
                self._load(os.path.join(exr, "steady.exr"), width, height)
        finally:
            if not os.environ.get("SLOWLIGHT_KEEP_TEMP"):
                shutil.rmtree(folder, ignore_errors=True)

    def _render_video(self, scene, depsgraph):
        video, exr = video_paths(scene.slowlight)
        # The scene is kept beside the video, so that the command the program prints after Esc
        # (--resume) still finds it.
        folder = os.path.splitext(video)[0] + "_scene"
        os.makedirs(os.path.dirname(video) or ".", exist_ok=True)
        status = self._run(scene, depsgraph, folder, exr, video=video)
        _video["exr_dir"], _video["frames"] = exr, properties.video_frames(scene)
        if status == 0:
            self.report({'INFO'}, "slowlight: wrote %s" % video)
            if not bpy.app.background:
                _open_clip_when_done(video)
        return status == 0

    def _run(self, scene, depsgraph, folder, exr, still=False, video=None):
        settings = scene.slowlight
        program = runner.program_path(settings)
        if program is None:
            self.report({'ERROR'}, "slowlight: the program '%s' was not found (Render Properties > "
                        "slowlight > Program)" % settings.program)
            return 2
        self.update_stats("slowlight", "writing the scene")
        try:
            scene_json, warnings = _write_on_main_thread(scene, folder, depsgraph, self.test_break)
        except Exception as e:  # the scene cannot be written: say why, render nothing
            self.report({'ERROR'}, "slowlight: %s" % e)
            return 2
        if scene_json is None:  # Esc while waiting for the interface
            return runner.INTERRUPTED
        for w in warnings:
            self.report({'WARNING'}, "slowlight: " + w)
        cmd = runner.command(settings, program, scene_json, exr, video=video, still=still)
        self.update_stats("slowlight", "rendering the steady image" if still else "rendering the video")
        errors = []

        def line(text):
            k = runner.kind(text)
            if k == 'ERROR':
                errors.append(text)
            self.report({k}, text)

        status = runner.run(cmd, on_progress=self.update_progress, should_stop=self.test_break, on_line=line)
        if status == 0:
            self.update_progress(1.0)
        if status == runner.INTERRUPTED:
            self.report({'WARNING'}, "slowlight: stopped; the frames so far are kept in %s" % exr)
        elif status != 0 and not errors:
            self.report({'ERROR'}, "slowlight: the program exited with status %d" % status)
        return status

    def _load(self, path, width, height):
        result = self.begin_result(0, 0, width, height)
        try:
            if os.path.exists(path):
                result.layers[0].load_from_file(path)
            else:
                self.report({'ERROR'}, "slowlight: %s was not written" % path)
        finally:
            self.end_result(result)


def _write_on_main_thread(scene, folder, depsgraph, should_stop):
    """write_scene on Blender's main thread. Headless, a render runs there; in the interface F12
    runs the engine on the render thread, whose context the glTF exporter cannot work in: the
    writing is handed to the main loop through a timer, with the render's view layer."""
    if threading.current_thread() is threading.main_thread():
        return scene_writer.write_scene(scene, folder, depsgraph)
    layer = depsgraph.view_layer.name
    done, box = threading.Event(), {}

    def job():
        try:
            wm = bpy.context.window_manager
            win = wm.windows[0] if wm and wm.windows else None
            with bpy.context.temp_override(window=win, scene=scene, view_layer=scene.view_layers[layer]):
                box["result"] = scene_writer.write_scene(scene, folder)
        except Exception as e:  # handed back to the render thread
            box["error"] = e
        done.set()
        return None

    bpy.app.timers.register(job, first_interval=0.0)
    while not done.wait(0.1):
        if should_stop():
            # The job may still run; its result is simply not used.
            return None, []
    if "error" in box:
        raise box["error"]
    return box["result"]


def _open_clip_when_done(path):
    """Opens the video once Blender has finished the whole Render Animation (its later frames
    still use the render window)."""
    def handler(*_):
        for hs in (bpy.app.handlers.render_complete, bpy.app.handlers.render_cancel):
            if handler in hs:
                hs.remove(handler)
        bpy.app.timers.register(lambda: _open_clip(path), first_interval=0.1)
    bpy.app.handlers.render_complete.append(handler)
    bpy.app.handlers.render_cancel.append(handler)


def _open_clip(path):
    """Shows the finished video in a Movie Clip Editor: one already open, else the render window's
    image editor (where the render was shown) turned into one, else a new window."""
    try:
        clip = bpy.data.movieclips.load(path, check_existing=True)
    except RuntimeError:
        return None
    wm = bpy.context.window_manager
    areas = [a for w in wm.windows for a in w.screen.areas]
    target = next((a for a in areas if a.type == 'CLIP_EDITOR'), None)
    if target is None:
        target = next((a for a in areas if a.type == 'IMAGE_EDITOR' and a.spaces.active.image is not None
                       and a.spaces.active.image.type == 'RENDER_RESULT'), None)
    if target is None and wm.windows:
        with bpy.context.temp_override(window=wm.windows[0]):
            bpy.ops.wm.window_new()
        target = max(wm.windows[-1].screen.areas, key=lambda a: a.width * a.height)
    if target is not None:
        target.type = 'CLIP_EDITOR'
        target.spaces.active.clip = clip
    return None


# Eevee's engine name: BLENDER_EEVEE in 3.x and 4.0-4.1, BLENDER_EEVEE_NEXT in 4.2-4.4.
EEVEE_IDS = {'BLENDER_EEVEE', 'BLENDER_EEVEE_NEXT'}


def compatible_panels():
    """Blender's own panels that show for Eevee and fit any engine (format, output, lamps, ...)."""
    skip = ("RENDER_PT_eevee", "EEVEE_", "RENDER_PT_gpencil", "RENDER_PT_simplify", "RENDER_PT_hair",
            "MATERIAL_PT_viewport", "RENDER_PT_color_management", "RENDER_PT_freestyle")
    for name in dir(bpy.types):
        cls = getattr(bpy.types, name)
        engines = getattr(cls, "COMPAT_ENGINES", None)
        if isinstance(engines, set) and engines & EEVEE_IDS and not name.startswith(skip):
            yield cls


def register():
    bpy.utils.register_class(SlowlightRenderEngine)
    for cls in compatible_panels():
        cls.COMPAT_ENGINES.add(SlowlightRenderEngine.bl_idname)


def unregister():
    for cls in compatible_panels():
        cls.COMPAT_ENGINES.discard(SlowlightRenderEngine.bl_idname)
    bpy.utils.unregister_class(SlowlightRenderEngine)
