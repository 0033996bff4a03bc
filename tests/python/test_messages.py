"""The module says what the command line says: bad input raises ValueError with the text of the
program's `error:` line, its `warning:` lines arrive through Python's warnings module, info()
holds the figures `slowlight info` prints, and Ctrl-C ends the pass in flight and leaves the
frames written so far on the KeyboardInterrupt."""
import json
import os
import re
import signal
import tempfile
import unittest
import warnings

import numpy as np

import module_support as ms
import slowlight


class BadInput(unittest.TestCase):
    def same_error(self, scene, options):
        status, _, err = ms.run_cli("render", scene, "--exr-dir", tempfile.gettempdir() + "/sl_never", *ms.flags(options))
        self.assertEqual(status, 2, err)
        with self.assertRaises(ValueError) as raised:
            slowlight.render(scene, **options)
        self.assertEqual(str(raised.exception), ms.error_line(err))
        return str(raised.exception)

    def test_an_override_out_of_range(self):
        text = self.same_error(ms.BOX, dict(frames=0))
        self.assertIn("--frames", text)
        self.same_error(ms.BOX, dict(emission="pulse:0.3", frames=7))
        self.same_error(ms.BOX, dict(max_memory="lots"))

    def test_a_misspelt_key_in_a_scene_file(self):
        with open(ms.BOX) as f:
            scene = json.load(f)
        scene["render"]["pases"] = scene["render"].pop("passes")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bad.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            text = self.same_error(path, {})
        self.assertIn("pases", text)
        with self.assertRaises(ValueError) as raised:  # as a dict: the same message, naming <dict>
            slowlight.render(scene)
        self.assertEqual(str(raised.exception), text.replace(path, "<dict>"))

    def test_render_refuses_frames_larger_than_the_machine(self):
        # 100000 frames of 4096 x 4096: 20 TB of frames (and of buckets, which the program refuses
        # in its own words); render() would keep them all.
        with self.assertRaises(ValueError) as raised:
            slowlight.render(ms.BOX, frames=100000, width=4096, height=4096, sections=100000)
        self.assertIn("slowlight.frames()", str(raised.exception))

    def test_a_missing_file_and_an_unknown_keyword(self):
        self.same_error("/nonexistent/scene.json", {})
        with self.assertRaisesRegex(TypeError, "did you mean 'frames'"):
            slowlight.render(ms.BOX, frmes=3)


class Warnings(unittest.TestCase):
    def test_the_command_lines_warning_lines(self):
        # The window ends before any reflected light can arrive: a warning, and still a render.
        options = dict(ms.SMALL, frames=2)
        with open(ms.BOX) as f:
            scene = json.load(f)
        scene["time"] = {"start_ns": 0, "end_ns": 0.5, "frames": 2}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "early.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            status, _, err = ms.run_cli("render", path, "--exr-dir", d, "--no-progress", *ms.flags(options))
            self.assertEqual(status, 0, err)
            expected = [l[len("warning: "):] for l in err.splitlines() if l.startswith("warning: ")]
            self.assertTrue(expected, err)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                r = slowlight.render(path, **options)
        got = [str(w.message) for w in caught if issubclass(w.category, slowlight.SlowlightWarning)]
        self.assertEqual(got, expected)
        self.assertEqual(r.frames.shape[0], 2)


    def test_an_imported_files_warnings_come_first(self):
        options = dict(ms.SMALL, frames=2, passes=1)
        with open(ms.BOX) as f:
            scene = json.load(f)
        scene["shapes"].append({"type": "mesh", "file": "odd.obj", "scale": 0.2, "translate": [0, 0.5, 0]})
        scene["time"] = {"start_ns": 0, "end_ns": 0.5, "frames": 2}  # and a warning of the scene's
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "odd.obj"), "w") as f:
                f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\nfoo 1\n")
            path = os.path.join(d, "odd.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            status, _, err = ms.run_cli("render", path, "--exr-dir", d, "--no-progress", *ms.flags(options))
            self.assertEqual(status, 0, err)
            expected = [l[len("warning: "):] for l in err.splitlines() if l.startswith("warning: ")]
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                slowlight.render(path, **options)
                info = slowlight.info(path, frames=2)
        got = [str(w.message) for w in caught if issubclass(w.category, slowlight.SlowlightWarning)]
        self.assertEqual(len(expected), 3, err)  # two of the OBJ file's, then the time window's
        self.assertIn("unknown statement 'foo'", expected[1])
        self.assertEqual(got, expected + expected)  # render(), then info()
        self.assertEqual(info["warnings"], ["warning: " + w for w in expected])


class Info(unittest.TestCase):
    def test_the_figures_info_prints(self):
        path = os.path.join(ms.SAMPLES, "spot_mesh_haze.json")
        status, out, _ = ms.run_cli("info", path, "--frames", "40")
        self.assertEqual(status, 0)
        d = slowlight.info(path, frames=40)
        self.assertEqual(f"image:      {d['width']} x {d['height']}", re.search(r"image: .*", out).group(0))
        self.assertIn(f"geometry:   {d['triangles']} triangles", out)
        self.assertEqual(d["time"]["frames"], 40)
        self.assertIn(f"{d['time']['frames']} frames of {d['time']['frame_ns']:g} ns", out)
        self.assertIn(f"arrives from {d['first_arrival_ns']:.2f} ns", out)
        self.assertTrue(d["medium"])
        # The buckets per K, which info prints to the byte.
        printed = [int(b) for b in re.findall(r"\((\d+) bytes\)", out)]
        self.assertEqual(printed, [row["bucket_bytes"] for row in d["memory"]["by_sections"]])
        self.assertEqual(len(d["light_powers"]), 1)
        self.assertIn(f"{d['light_powers'][0]['watts']:.4g} W", out)

    def test_max_memory_picks_the_k_info_prints(self):
        status, out, _ = ms.run_cli("info", ms.BOX, "--max-memory", "300M", "--width", "512", "--height", "512")
        d = slowlight.info(ms.BOX, max_memory="300M", width=512, height=512)
        self.assertEqual(status, 0)
        self.assertIn(f": K = {d['memory']['planned']['sections']} (", out)


class CtrlC(unittest.TestCase):
    def test_ctrl_c_keeps_the_frames_written(self):
        options = dict(ms.SMALL, sections=2, passes=40)
        sent = []

        def progress(section, done, sections, passes):
            if section == 0 and done == 2 and not sent:
                sent.append(1)
                os.kill(os.getpid(), signal.SIGINT)  # what Ctrl-C does: Python's handler raises

        with self.assertRaises(KeyboardInterrupt) as raised:
            slowlight.render(ms.BOX, progress=progress, **options)
        result = raised.exception.result
        self.assertTrue(result.interrupted)
        # The section in progress (section 0 of 2) is written from the passes it completed; the
        # second section never started.
        written = raised.exception.frames
        self.assertIs(written, result.frames)
        self.assertEqual(written.shape[1:], (32, 40, 3))
        self.assertTrue(0 < written.shape[0] < 6, written.shape)
        self.assertIsNone(result.steady)
        reached = result.stats["passes_per_section"]
        self.assertEqual(reached[1], 0)
        self.assertGreaterEqual(reached[0], 2)
        self.assertLess(reached[0], 40)
        # Those frames are what a render of that many passes gives.
        fewer = slowlight.render(ms.BOX, **dict(options, passes=reached[0]))
        self.assertTrue(np.array_equal(written, fewer.frames[: written.shape[0]]))

    def test_ctrl_c_while_streaming(self):
        options = dict(ms.SMALL, sections=3, passes=40)
        sent = []

        def progress(section, done, sections, passes):
            if section == 1 and done == 2 and not sent:
                sent.append(1)
                os.kill(os.getpid(), signal.SIGINT)  # lands while the loop waits for a frame

        stream = slowlight.frames(ms.BOX, progress=progress, **options)
        got = []
        with self.assertRaises(KeyboardInterrupt) as raised:
            for frame in stream:
                got.append(frame.index)
        rest = [f.index for f in raised.exception.frames]
        # Sections 0 and 1 (frames 0-3) were written, section 1 from the passes it had; what the
        # loop did not get yet is on the exception, in order.
        self.assertEqual(got + rest, list(range(len(got) + len(rest))))
        self.assertGreaterEqual(len(got) + len(rest), 4)
        self.assertTrue(stream.interrupted)
        self.assertLess(min(n for n in stream.stats["passes_per_section"] if n > 0), 40)

    def test_ctrl_c_in_the_loops_body(self):
        stream = slowlight.frames(ms.BOX, **dict(ms.SMALL, sections=3, passes=40))
        got = []
        try:
            for frame in stream:
                got.append(frame.index)
                if frame.index == 0:
                    os.kill(os.getpid(), signal.SIGINT)
                    for _ in range(1000):  # Python raises at a bytecode boundary
                        pass
        except KeyboardInterrupt:
            rest = [f.index for f in stream.stop()]
        self.assertEqual(got, [0])
        self.assertEqual(got + rest, list(range(len(got) + len(rest))))
        self.assertGreaterEqual(len(got + rest), 2)
        self.assertLess(len(got + rest), 6)
        self.assertTrue(stream.interrupted)


if __name__ == "__main__":
    ms.main()
