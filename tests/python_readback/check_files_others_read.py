#!/usr/bin/env python3
"""The files other tools read, read back as their users would (NumPy, h5py), against the EXR
frames of the same run: --cube --cube-layout mitransient (height, width, time, 3) with its time
axis in optical path length, and --hdf5 in tal's layout (time first, t_start and delta_t in
metres). Run by ctest: check_files_others_read.py SLOWLIGHT_BINARY SOURCE_DIR."""
import json
import os
import struct
import subprocess
import sys
import tempfile

import h5py
import numpy as np

C = 0.299792458  # metres per nanosecond
FRAMES, WIDTH, HEIGHT = 8, 24, 16


def read_exr(path):
    """(height, width, 3) float32 and the string attributes of an uncompressed float RGB EXR,
    as slowlight writes its linear frames (scanlines, channels B, G, R in the file)."""
    data = open(path, "rb").read()
    assert struct.unpack_from("<I", data, 0)[0] == 20000630, path
    at, attrs = 8, {}
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        name = data[at:name_end].decode()
        type_end = data.index(b"\0", name_end + 1)
        kind = data[name_end + 1:type_end].decode()
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        value = data[type_end + 5:type_end + 5 + size]
        attrs[name] = (kind, value)
        at = type_end + 5 + size
    at += 1
    assert attrs["compression"][1] == b"\0", "expected an uncompressed EXR"
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    chans, c = [], attrs["channels"][1]
    while c[0] != 0:
        end = c.index(b"\0")
        chans.append((c[:end].decode(), struct.unpack_from("<i", c, end + 1)[0]))
        c = c[end + 17:]
    assert all(t == 2 for _, t in chans), "float channels expected"
    offsets = struct.unpack_from("<%dQ" % h, data, at)
    img = np.zeros((h, w, 3), np.float32)
    for off in offsets:
        y = struct.unpack_from("<i", data, off)[0] - y0
        line = np.frombuffer(data, "<f4", len(chans) * w, off + 8).reshape(len(chans), w)
        for i, (name, _) in enumerate(chans):
            if name in "RGB":
                img[y, :, "RGB".index(name)] = line[i]
    text = {k: v.decode() for k, (t, v) in attrs.items() if t == "string"}
    return img, text


def main():
    slowlight, source = sys.argv[1], sys.argv[2]
    scene = os.path.join(source, "samples", "cornell_box.json")
    small = ["--width", str(WIDTH), "--height", str(HEIGHT), "--frames", str(FRAMES), "--passes", "2",
             "--photons", "5000", "--seed", "7", "--no-progress"]
    with tempfile.TemporaryDirectory(prefix="sl_py_readback_") as d:
        p = lambda name: os.path.join(d, name)
        subprocess.run([slowlight, "render", scene, *small, "--exr-dir", p("exr"), "--cube", p("ours.npy"),
                        "--hdf5", p("tal.h5")], check=True)
        subprocess.run([slowlight, "render", scene, *small, "--cube", p("mit.npy"), "--cube-layout", "mitransient"],
                       check=True)

        ours = np.load(p("ours.npy"))
        assert ours.shape == (FRAMES + 2, HEIGHT, WIDTH, 3) and ours.dtype == np.float32, ours.shape
        frames = [read_exr(os.path.join(p("exr"), "frame_%04d.exr" % k)) for k in range(FRAMES)]
        steady, _ = read_exr(os.path.join(p("exr"), "steady.exr"))
        starts = np.array([float(f[1]["slowlight:frame_start_ns"]) for f in frames])
        ends = np.array([float(f[1]["slowlight:frame_end_ns"]) for f in frames])
        # Constant emission: frame k is everything that arrived up to its end, the running sum of
        # the planes up to bin k; the steady image holds them all.
        running = np.cumsum(ours.astype(np.float64), axis=0)
        scale = max(float(steady.max()), 1e-30)
        for k, (img, _) in enumerate(frames):
            np.testing.assert_allclose(img, running[k + 1], rtol=1e-4, atol=1e-5 * scale, err_msg="frame %d" % k)
        np.testing.assert_allclose(steady, running[-1], rtol=1e-4, atol=1e-5 * scale)
        assert float(ours[1:-1].sum()) > 0, "light arrived within the frames"

        # mitransient's order: the frames' bins, (height, width, time, 3), time in optical path length.
        mit = np.load(p("mit.npy"))
        assert mit.shape == (HEIGHT, WIDTH, FRAMES, 3) and mit.dtype == np.float32, mit.shape
        assert np.array_equal(mit, ours[1:-1].transpose(1, 2, 0, 3)), "the same bins (same seed), transposed"
        side = json.load(open(p("mit.npy.json")))
        assert side["cube_layout"] == "mitransient", side
        np.testing.assert_allclose(side["start_opl"] + side["bin_width_opl"] * np.arange(FRAMES), C * starts, rtol=1e-12,
                                   atol=1e-12)
        np.testing.assert_allclose(side["start_opl"] + side["bin_width_opl"] * np.arange(1, FRAMES + 1), C * ends,
                                   rtol=1e-12)
        side_ours = json.load(open(p("ours.npy.json")))
        assert side_ours["cube_layout"] == "slowlight" and side_ours["bin_width_opl"] == side["bin_width_opl"]

        # tal's layout: time first, t_start and delta_t in metres, and our metadata.
        with h5py.File(p("tal.h5"), "r") as f:
            H = f["H"]
            assert H.shape == (FRAMES, HEIGHT, WIDTH, 3) and H.dtype == np.float32, H.shape
            assert H.chunks == (1, HEIGHT, WIDTH, 3), "one bin per chunk: written frame by frame"
            assert np.array_equal(H[()], ours[1:-1])
            assert np.array_equal(f["H_before"][()], ours[0]) and np.array_equal(f["H_after"][()], ours[-1])
            t_start, delta_t = float(f["t_start"][()]), float(f["delta_t"][()])
            np.testing.assert_allclose(t_start + delta_t * np.arange(FRAMES), C * starts, rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(f["frame_edges_ns"][()], np.append(starts, ends[-1]), rtol=0, atol=0)
            a = f.attrs
            assert a["seed"] == 7 and a["passes"] == 2 and a["photons_per_pass"] == 5000, dict(a)
            assert a["frames"] == FRAMES and a["start_ns"] == starts[0] and a["end_ns"] == ends[-1]
            assert a["slowlight:scene"].endswith("cornell_box.json")
            if "slowlight:exposure" in frames[0][1]:  # decided when a video or PNGs need it
                assert a["exposure"] == float(frames[0][1]["slowlight:exposure"]), dict(a)
            else:
                assert "exposure" not in a, dict(a)
            assert "metres" in a["t_units"] and H.attrs["axes"].startswith("time")
    print("files others read: cube in both orders and HDF5 match the EXR frames")


if __name__ == "__main__":
    main()
