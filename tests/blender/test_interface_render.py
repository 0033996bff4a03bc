# F12 and Render Animation as Blender's interface runs them (INVOKE: the engine on the render
# thread, the interface live), in a virtual display (xvfb-run): the scene is handed to the main
# loop for writing, the steady image matches the same render run on the main thread, the video is
# written and shown in a Movie Clip Editor (the render window's editor, turned into one). Run by run_blender_test.sh with BLENDER_UI set.
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import exr_image  # noqa: E402
import showcase_scene  # noqa: E402

zip_path, program, work = addon_env.args()
state = {"step": "start", "complete": 0}


def finish(code, message):
    print(("ok: " if code == 0 else "FAILED: ") + message, flush=True)
    sys.stdout.flush()
    os._exit(code)


def on_complete(*_):
    state["complete"] += 1


def override():
    win = bpy.context.window_manager.windows[0]
    return bpy.context.temp_override(window=win, screen=win.screen, area=win.screen.areas[0])


def save(name):
    path = os.path.join(work, name)
    bpy.data.images["Render Result"].save_render(path)
    return exr_image.mean(exr_image.load(path))


def tick():
    try:
        return step()
    except Exception as e:  # any failure ends the test, never a hung interface
        import traceback
        traceback.print_exc()
        finish(1, "exception: %s" % e)


def step():
    if state["step"] == "start":
        scene = showcase_scene.build(96, 72)
        addon_env.install(zip_path)
        scene.render.engine = 'SLOWLIGHT'
        st = scene.slowlight
        st.program, st.passes, st.photons, st.end_ns = program, 8, 50000, 30.0
        st.video_path = os.path.join(work, "ui.mp4")
        scene.render.filepath = os.path.join(work, "frames", "f")
        scene.frame_start, scene.frame_end = 1, 3  # a video of 3 frames, from the timeline
        bpy.app.handlers.render_complete.append(on_complete)
        with override():
            bpy.ops.render.render('INVOKE_DEFAULT')  # F12
        state["step"] = "f12"
    elif state["step"] == "f12" and state["complete"] == 1:
        state["ui_mean"] = save("ui.exr")
        bpy.ops.render.render()  # the same on the main thread, as headless
        main_mean = save("main.exr")
        print("steady image mean: interface %.6f, main thread %.6f" % (state["ui_mean"], main_mean), flush=True)
        if abs(state["ui_mean"] / main_mean - 1) > 0.001:
            finish(1, "F12 in the interface gives the main thread's image")
        print("ok: F12 in the interface gives the main thread's image", flush=True)
        with override():
            bpy.ops.render.render('INVOKE_DEFAULT', animation=True)
        state["step"] = "video"
    elif state["step"] == "video" and state["complete"] >= 3:
        video = os.path.join(work, "ui.mp4")
        if not (os.path.exists(video) and os.path.getsize(video) > 0):
            finish(1, "Render Animation in the interface wrote the video")
        shown = [a for w in bpy.context.window_manager.windows for a in w.screen.areas
                 if a.type == 'CLIP_EDITOR' and a.spaces.active.clip is not None and
                 os.path.realpath(bpy.path.abspath(a.spaces.active.clip.filepath)) == os.path.realpath(video)]
        if not shown:
            state["waits"] = state.get("waits", 0) + 1
            if state["waits"] > 60:
                finish(1, "the video is shown in a Movie Clip Editor within 30 s of the render")
            return 0.5  # the clip is opened by a timer after the render
        clip = shown[0].spaces.active.clip
        if clip.frame_duration != 3:
            finish(1, "the clip has the timeline's 3 frames (it has %d)" % clip.frame_duration)
        finish(0, "Render Animation in the interface wrote the video and showed it in a Movie Clip Editor")
    return 0.5


bpy.app.timers.register(tick, first_interval=1.0, persistent=True)  # survives the new scene
