# Shared by the add-on tests (run by run_blender_test.sh in a factory-startup Blender): installs
# and enables the add-on from the zip into the temporary user folder, and reads the arguments.
import os
import sys

import bpy


def args():
    """(zip, slowlight program, a scratch folder)."""
    argv = sys.argv[sys.argv.index("--") + 1:]
    return argv[0], argv[1], os.environ["SLOWLIGHT_TEST_WORK"]


def install(zip_path):
    scripts = os.environ["BLENDER_USER_SCRIPTS"]
    assert bpy.utils.user_resource('SCRIPTS') == scripts, (bpy.utils.user_resource('SCRIPTS'), scripts)
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    installed = os.path.join(scripts, "addons", "slowlight_addon", "__init__.py")
    assert os.path.exists(installed), "the zip did not install " + installed
    bpy.ops.preferences.addon_enable(module="slowlight_addon")
    import slowlight_addon
    assert os.path.realpath(slowlight_addon.__file__) == os.path.realpath(installed), slowlight_addon.__file__
    return slowlight_addon


def check(cond, message):
    if not cond:
        print("FAILED: " + message)
        sys.exit(1)
    print("ok: " + message)
