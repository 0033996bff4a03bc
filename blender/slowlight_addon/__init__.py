# slowlight for Blender: renders the open scene's slow-motion light video (haze included) with the
# slowlight program, run as a child process. See docs/blender.md in the slowlight repository.
bl_info = {
    "name": "slowlight",
    "author": "slowlight",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > slowlight",
    "description": "Slow-motion videos of light (transient photon mapping) from the open scene",
    "category": "Render",
}

if "bpy" in locals():  # reloaded (F3 > Reload Scripts)
    import importlib
    from . import properties, volume, scene_writer, runner, engine, ui
    for m in (properties, volume, scene_writer, runner, engine, ui):
        importlib.reload(m)
else:
    from . import properties, volume, scene_writer, runner, engine, ui

import bpy  # noqa: E402


def register():
    properties.register()
    engine.register()
    ui.register()


def unregister():
    ui.unregister()
    engine.unregister()
    properties.unregister()
