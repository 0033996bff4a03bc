#!/usr/bin/env python3
"""Per-pixel noise of a time-resolved render from two seeds (docs/medium.md, "Measured").

    scripts/cube_noise.py A.npy B.npy [--pulse M]

A and B are `slowlight render --cube` stacks of the same scene with two seeds. Frames are
assembled as the renderer does (constant emission: everything that arrived before the frame's
end; --pulse M: the M buckets ending there). For each frame: the RMS over pixels and channels of
(A - B) / sqrt(2), relative to the frame's mean (of A and B). Printed: the median and the worst
over the lit frames (mean above 1% of the brightest frame's), and the frame-by-frame values.
Only the standard library: reads float32 .npy files of shape (frames + 2, height, width, 3).
"""
import array
import ast
import math
import sys


def read_npy(path):
    with open(path, "rb") as f:
        if f.read(6) != b"\x93NUMPY":
            sys.exit(f"error: {path}: not a .npy file")
        major = f.read(2)[0]
        hlen = int.from_bytes(f.read(2 if major == 1 else 4), "little")
        header = ast.literal_eval(f.read(hlen).decode("latin1"))
        if header["descr"] != "<f4" or header["fortran_order"]:
            sys.exit(f"error: {path}: expected little-endian float32 in C order")
        data = array.array("f")
        data.frombytes(f.read())
    shape = header["shape"]
    return shape, data


def frames(shape, data, pulse):
    planes, h, w, c = shape
    n = h * w * c
    plane = [data[k * n:(k + 1) * n] for k in range(planes)]
    out = []
    if pulse == 0:
        run = [0.0] * n
        for i, v in enumerate(plane[0]):
            run[i] = v
        for k in range(1, planes - 1):
            p = plane[k]
            for i in range(n):
                run[i] += p[i]
            out.append(list(run))
    else:
        for k in range(1, planes - 1):
            acc = [0.0] * n
            for b in range(max(1, k - pulse + 1), k + 1):
                p = plane[b]
                for i in range(n):
                    acc[i] += p[i]
            out.append(acc)
    return out


def main():
    args = sys.argv[1:]
    pulse = 0
    if "--pulse" in args:
        i = args.index("--pulse")
        pulse = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit("usage: cube_noise.py A.npy B.npy [--pulse M]")
    sa, da = read_npy(args[0])
    sb, db = read_npy(args[1])
    if sa != sb:
        sys.exit("error: the cubes differ in shape")
    fa, fb = frames(sa, da, pulse), frames(sb, db, pulse)
    means = [(sum(a) + sum(b)) / (2 * len(a)) for a, b in zip(fa, fb)]
    top = max(means)
    noise = []
    for k, (a, b) in enumerate(zip(fa, fb)):
        if means[k] <= 0.01 * top:
            continue
        rms = math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / len(a)) / math.sqrt(2)
        noise.append((k, rms / means[k]))
    vals = sorted(v for _, v in noise)
    med = vals[len(vals) // 2] if len(vals) % 2 else 0.5 * (vals[len(vals) // 2 - 1] + vals[len(vals) // 2])
    print(f"lit frames {len(vals)}: median noise {100 * med:.2f}%, worst {100 * vals[-1]:.2f}%")
    print("per frame:", " ".join(f"{k}:{100 * v:.1f}" for k, v in noise))


if __name__ == "__main__":
    main()
