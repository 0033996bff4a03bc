# The child process as the engine runs it (runner.run, with the command line the panel's settings
# make): progress parsed from the program's progress line rises to 1; a stop request sends SIGINT,
# the program exits 130 and keeps the frames so far (the video plays: it has its frames); a bad
# setting gives the program's own error: line, which the engine reports as a Blender error.
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import showcase_scene  # noqa: E402

zip_path, program, work = addon_env.args()
scene = showcase_scene.build(64, 48)
addon = addon_env.install(zip_path)
check = addon_env.check
runner, writer = addon.runner, addon.scene_writer

st = scene.slowlight
st.program, st.passes, st.photons, st.frames, st.end_ns = program, 16, 200000, 8, 30.0
st.use_timeline = False  # the panel's own number of frames, not the factory timeline's 250
check(runner.program_path(st) == os.path.realpath(program) or runner.program_path(st) == program,
      "the program is found at its path")
scene_json, _ = writer.write_scene(scene, os.path.join(work, "a"))

# A whole render: progress rising pass by pass, never falling (the program redraws its line at
# most every 0.1 s, so the last pass may not be drawn: the engine sets 1 at the end itself).
progress, lines = [], []
status = runner.run(runner.command(st, program, scene_json, os.path.join(work, "a", "exr"),
                                   video=os.path.join(work, "a", "a.mp4")),
                    on_progress=progress.append, on_line=lines.append)
print("progress values:", ["%.3f" % p for p in progress][:20], "... lines:", lines)
check(status == 0, "the render ends with status 0")
check(progress and progress == sorted(progress) and 0 < progress[0] and progress[-1] <= 1,
      "progress rises within (0, 1] (%d updates)" % len(progress))
check(len(set(progress)) >= 3 and progress[-1] >= 0.5, "progress moves with the passes, to %.3f" % progress[-1])
check(any("wrote" in x and "a.mp4" in x for x in lines), "the program's last line is reported")
check(not any(runner.PROGRESS.search(x) for x in lines), "no progress redraw is reported as a line")

# Stopped after two passes, as Esc does: SIGINT, exit 130, the frames so far kept.
st.passes = 100000
st.photons = 200000
scene_json, _ = writer.write_scene(scene, os.path.join(work, "b"))
exr = os.path.join(work, "b", "exr")
progress, lines = [], []
status = runner.run(runner.command(st, program, scene_json, exr, video=os.path.join(work, "b", "b.mp4")),
                    on_progress=progress.append, should_stop=lambda: len(progress) >= 2,
                    on_line=lines.append)
print("lines:", lines)
check(status == runner.INTERRUPTED, "a stop request ends the program with 130 (got %d)" % status)
check(all(os.path.exists(os.path.join(exr, "frame_%04d.exr" % k)) for k in range(8)),
      "every frame so far is kept")
check(os.path.getsize(os.path.join(work, "b", "b.mp4")) > 0, "and the video is closed with them")
check(any("--resume" in x for x in lines), "the program's continue command is reported")

# A bad setting: the program's error line, as the engine shows it.
st.passes, st.split, st.max_memory = 4, 'MEMORY', "lots"
lines = []
status = runner.run(runner.command(st, program, scene_json, os.path.join(work, "c")), on_line=lines.append)
errors = [x for x in lines if runner.kind(x) == 'ERROR']
print("lines:", lines)
check(status == 2 and len(errors) == 1 and "lots" in errors[0],
      "a bad --max-memory gives the program's one error: line and status 2")
check(runner.kind("warning: scene.json: the time window ends before any light arrives") == 'WARNING',
      "warning: lines become Blender warnings")
