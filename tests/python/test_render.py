"""slowlight.render and slowlight.frames against the command line: the same frames bit for bit
(read back from its EXR files by another reader), the same scene from a dict, the streamed frames
equal to the whole array, in order and before the render ends."""
import json
import os
import sys
import threading
import time
import unittest

import numpy as np

import module_support as ms
import slowlight


class RenderEqualsTheCommandLine(unittest.TestCase):
    def check_same(self, scene, options):
        r = slowlight.render(scene, **options)
        cli, steady = ms.cli_exr_frames(scene, options)
        self.assertEqual(r.frames.dtype, np.float32)
        self.assertEqual(r.frames.shape, (options["frames"], options["height"], options["width"], 3))
        self.assertEqual(cli.shape, r.frames.shape)
        self.assertTrue((r.frames > 0).any(), "the frames are black: the comparison would prove nothing")
        self.assertTrue(np.array_equal(r.frames, cli), f"largest difference {np.abs(r.frames - cli).max()}")
        self.assertTrue(np.array_equal(r.steady, steady))
        return r

    def test_constant_light_bit_for_bit(self):
        r = self.check_same(ms.BOX, ms.SMALL)
        # The time axis: frame edges of the scene's 0..24 ns window, and as optical path length.
        np.testing.assert_allclose(r.edges_ns, np.linspace(0, 24, 7))
        np.testing.assert_allclose(r.edges_m, r.edges_ns * 0.299792458)
        self.assertEqual(r.stats["frames"], 6)
        self.assertEqual(r.stats["passes_per_section"], [3])
        self.assertGreater(r.exposure, 0)
        self.assertFalse(r.interrupted)

    def test_pulse_in_two_sections_bit_for_bit(self):
        options = dict(ms.SMALL, emission="pulse", sections=2, seed=11)
        r = self.check_same(os.path.join(ms.SAMPLES, "cornell_box_pulse.json"), options)
        self.assertEqual(r.stats["sections"], 2)

    def test_a_dict_is_the_same_scene_as_its_file(self):
        with open(ms.BOX) as f:
            scene = json.load(f)
        a = slowlight.render(scene, base_dir=ms.SAMPLES, **ms.SMALL)
        b = slowlight.render(ms.BOX, **ms.SMALL)
        self.assertTrue(np.array_equal(a.frames, b.frames))
        scene["render"]["seed"] = 8  # and the dict is what is rendered
        c = slowlight.render(scene, base_dir=ms.SAMPLES, **dict(ms.SMALL, seed=None))
        self.assertFalse(np.array_equal(a.frames, c.frames))

    def test_threads_change_no_pixel(self):
        one = slowlight.render(ms.BOX, threads=1, **ms.SMALL)
        self.assertEqual(one.stats["threads"], 1)
        self.assertTrue(np.array_equal(one.frames, slowlight.render(ms.BOX, **ms.SMALL).frames))

    def test_a_model_file_renders_as_on_the_command_line(self):
        models = os.path.join(ms.SAMPLES, "models")
        model = next(os.path.join(models, n) for n in sorted(os.listdir(models)) if n.endswith((".glb", ".gltf", ".obj")))
        options = dict(frames=3, passes=2, photons=3000, width=24, height=24)
        r = slowlight.render(model, **options)
        cli, _ = ms.cli_exr_frames(model, options)
        self.assertTrue(np.array_equal(r.frames, cli))

    def test_gltf_principled_reaches_the_render_as_on_the_command_line(self):
        # The red plastic cube of bench/blender: its base drawn capped (energy-conserving) is another
        # image than drawn uncapped (Blender 3.x), which Blender 3.4's export gets unless told.
        model = os.path.join(ms.SOURCE, "bench", "blender", "reference", "glossy_plastic.glb")
        options = dict(frames=1, passes=2, photons=3000, width=24, height=18, gltf_principled="energy_conserving")
        r = slowlight.render(model, **options)
        cli, _ = ms.cli_exr_frames(model, options)
        self.assertTrue(np.array_equal(r.frames, cli))
        blender3 = slowlight.render(model, **dict(options, gltf_principled="blender3"))
        self.assertFalse(np.array_equal(r.frames, blender3.frames))
        default = slowlight.render(model, **dict(options, gltf_principled=None))
        self.assertTrue(np.array_equal(blender3.frames, default.frames))


class Streaming(unittest.TestCase):
    def test_frames_come_in_order_each_as_its_section_ends(self):
        options = dict(ms.SMALL, sections=3)
        whole = slowlight.render(ms.BOX, **options)
        events = []
        stream = slowlight.frames(ms.BOX, progress=lambda s, p, S, P: events.append(("pass", s)), **options)
        for frame in stream:
            events.append(("frame", frame.index))
            self.assertTrue(np.array_equal(np.asarray(frame), whole.frames[frame.index]))
            self.assertAlmostEqual(frame.start_ns, whole.edges_ns[frame.index])
            self.assertAlmostEqual(frame.end_m, whole.edges_m[frame.index + 1])
        self.assertEqual([i for kind, i in events if kind == "frame"], list(range(6)))
        # Section 0's frames reach the loop before the last section's passes are done.
        first_frame = events.index(("frame", 0))
        last_pass = max(i for i, e in enumerate(events) if e == ("pass", 2))
        self.assertLess(first_frame, last_pass, events)
        self.assertTrue(np.array_equal(stream.steady, whole.steady))
        self.assertEqual(stream.exposure, whole.exposure)
        self.assertEqual(stream.stats["sections"], 3)

    def test_leaving_the_loop_stops_the_render(self):
        stream = slowlight.frames(ms.BOX, **dict(ms.SMALL, sections=3, passes=50))
        first = next(stream)
        self.assertEqual(first.index, 0)
        stream.close()
        self.assertTrue(stream.interrupted)
        self.assertLess(stream.stats["sections_done"], 3)


class TheGilIsFree(unittest.TestCase):
    def test_python_threads_run_while_it_renders(self):
        # With a switch interval far longer than the render, another thread gets the GIL only
        # when the render gives it up: a render holding it would leave the counter where it was.
        ticks, stop = [0], threading.Event()

        def count():
            while not stop.is_set():
                ticks[0] += 1
                time.sleep(0.0005)  # gives the GIL back each time, so the main thread gets it

        before_interval = sys.getswitchinterval()
        t = threading.Thread(target=count)
        t.start()
        sys.setswitchinterval(100)
        seen = []
        try:
            slowlight.render(ms.BOX, progress=lambda *a: seen.append(ticks[0]), **dict(ms.SMALL, passes=20))
        finally:
            sys.setswitchinterval(before_interval)
            stop.set()
            t.join()
        # Between the first pass and the last (the rendering itself, not the scene's set-up).
        self.assertEqual(len(seen), 20)
        self.assertGreater(seen[-1] - seen[0], 10, seen)


if __name__ == "__main__":
    ms.main()
