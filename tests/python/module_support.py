"""What the Python module's tests share: the program, the samples, running the command line, and
reading its EXR frames back through OpenImageIO's oiiotool (an independent reader: EXR -> PFM,
32-bit floats both, so nothing is rounded on the way)."""
import os
import subprocess
import sys
import tempfile

import numpy as np

SOURCE = os.environ.get("SLOWLIGHT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("SLOWLIGHT_BINARY", os.path.join(SOURCE, "build", "slowlight"))
SAMPLES = os.path.join(SOURCE, "samples")
BOX = os.path.join(SAMPLES, "cornell_box.json")

# Small enough for a shared 2-core machine, big enough that every frame has light in it.
SMALL = dict(frames=6, passes=3, photons=4000, width=40, height=32, seed=7)


def flags(options):
    """The command line's flags for the module's keyword arguments (the test's own translation)."""
    out = []
    for key, value in options.items():
        if key == "camera_tof":
            out.append("--camera-tof" if value else "--no-camera-tof")
        else:
            out += ["--" + key.replace("_", "-"), str(value)]
    return out


def run_cli(*args):
    """(exit status, stdout, stderr) of the program."""
    p = subprocess.run([BINARY, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def error_line(stderr):
    lines = [l for l in stderr.splitlines() if l.startswith("error: ")]
    assert len(lines) == 1, stderr
    return lines[0][len("error: "):]


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.fromfile(f, dtype="<f4" if scale < 0 else ">f4")
    channels = 3 if kind == b"PF" else 1
    return data.reshape(h, w, channels)[::-1].astype(np.float32)  # PFM rows run bottom to top


def read_exr(path):
    with tempfile.TemporaryDirectory() as d:
        pfm = os.path.join(d, "x.pfm")
        subprocess.run(["oiiotool", path, "-o", pfm], check=True, capture_output=True)
        return read_pfm(pfm)


def cli_exr_frames(scene, options, extra=()):
    """The program's frames and steady image for the same scene and flags, from its EXRs."""
    with tempfile.TemporaryDirectory() as d:
        status, _, err = run_cli("render", scene, "--exr-dir", d, "--no-progress", *flags(options), *extra)
        assert status == 0, err
        names = sorted(n for n in os.listdir(d) if n.startswith("frame_") and n.endswith(".exr"))
        frames = np.stack([read_exr(os.path.join(d, n)) for n in names])
        return frames, read_exr(os.path.join(d, "steady.exr"))


def main():
    import unittest
    unittest.main(module="__main__", verbosity=2, exit=True, argv=sys.argv[:1])
