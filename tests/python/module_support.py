"""What the Python module's tests share: the program, the samples, running the command line, and
reading its EXR frames back with a reader of the file format written here (not the program's)."""
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


def read_exr(path):
    """An uncompressed scanline EXR of float R, G, B channels (what the program writes), read
    here from the file format itself (openexr.com's layout), not by the program's reader."""
    import struct
    with open(path, "rb") as f:
        data = f.read()
    assert data[:4] == b"\x76\x2f\x31\x01", path
    pos, attrs = 8, {}
    while data[pos] != 0:  # attributes: name\0 type\0 size value
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        tend = data.index(b"\0", end + 1)
        kind = data[end + 1:tend].decode()
        size = struct.unpack_from("<i", data, tend + 1)[0]
        attrs[name] = (kind, data[tend + 5:tend + 5 + size])
        pos = tend + 5 + size
    pos += 1
    assert attrs["compression"][1] == b"\0", "compressed EXR: the test reads only uncompressed files"
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    channels, raw = [], attrs["channels"][1]
    while raw[0] != 0:  # name\0, pixel type int (2 = float), then 12 more bytes
        end = raw.index(b"\0")
        channels.append((raw[:end].decode(), struct.unpack_from("<i", raw, end + 1)[0]))
        raw = raw[end + 17:]
    assert [t for _, t in channels] == [2] * len(channels), channels
    offsets = struct.unpack_from(f"<{h}Q", data, pos)  # one scanline per block when uncompressed
    image = np.empty((h, w, len(channels)), dtype=np.float32)
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        row = np.frombuffer(data, dtype="<f4", count=size // 4, offset=off + 8).reshape(len(channels), w)
        image[y - ymin] = row.T
    names = [n for n, _ in channels]
    return image[:, :, [names.index(c) for c in "RGB"]]


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
