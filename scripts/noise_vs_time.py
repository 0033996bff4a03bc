#!/usr/bin/env python3
"""Per-pixel noise against time for renders of one scene at several pass counts (docs/medium.md).

    scripts/noise_vs_time.py RUNS_DIR OUT.png [TITLE]

RUNS_DIR holds, for each version V (e.g. "before", "after"), scene S, pass count P and seeds 1
and 2: V_S_P_s1.npy, V_S_P_s2.npy (`slowlight render S.json --passes P --seed N --cube ...`)
and V_S_P_s1.time, V_S_P_s2.time (`/usr/bin/time -f "%e %U %S" -o ...`: wall, user, system
seconds). The noise of a pair is scripts/cube_noise.py's (median over the lit frames of the RMS
of (A - B) / sqrt(2) over the frame's mean; a scene whose name ends in "_pulse" is assembled as
a pulse one bucket wide), computed here with NumPy; the time is the mean of the two seeds'.
Plots noise against wall time and against CPU time (user + system), log-log, one colour per
scene, solid before, dashed after, and prints the table. Needs NumPy and Matplotlib (Debian's
python3-numpy, python3-matplotlib); the build does not use it.
"""
import glob
import os
import re
import sys

import numpy as np


def frames(cube, pulse):
    planes = cube.shape[0]
    if pulse == 0:
        return np.cumsum(cube, axis=0, dtype=np.float64)[1:planes - 1]
    return np.array([cube[max(1, k - pulse + 1):k + 1].sum(axis=0, dtype=np.float64) for k in range(1, planes - 1)])


def median_noise(a, b, pulse):
    fa, fb = frames(np.load(a), pulse), frames(np.load(b), pulse)
    n = fa[0].size
    means = (fa.reshape(len(fa), -1).sum(1) + fb.reshape(len(fb), -1).sum(1)) / (2 * n)
    top = means.max()
    vals = [np.sqrt(((fa[k] - fb[k]) ** 2).mean() / 2) / means[k] for k in range(len(fa)) if means[k] > 0.01 * top]
    return float(np.median(vals))


def read_time(path):
    with open(path) as f:
        wall, user, system = (float(x) for x in f.read().split()[-3:])
    return wall, user + system


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: noise_vs_time.py RUNS_DIR OUT.png [TITLE]")
    runs, out = sys.argv[1], sys.argv[2]
    points = {}  # (version, scene) -> [(passes, wall, cpu, noise)]
    for a in sorted(glob.glob(os.path.join(runs, "*_s1.npy"))):
        m = re.match(r"(.+?)_(.+)_(\d+)_s1\.npy$", os.path.basename(a))
        b = a.replace("_s1.npy", "_s2.npy")
        if not m or not os.path.exists(b):
            continue
        version, scene, passes = m.group(1), m.group(2), int(m.group(3))
        t1, t2 = read_time(a.replace(".npy", ".time")), read_time(b.replace(".npy", ".time"))
        noise = median_noise(a, b, 1 if scene.endswith("_pulse") else 0)
        points.setdefault((version, scene), []).append((passes, (t1[0] + t2[0]) / 2, (t1[1] + t2[1]) / 2, noise))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = {}
    print("version scene passes wall_s cpu_s median_noise")
    for (version, scene), pts in sorted(points.items()):
        pts.sort()
        colour = colours.setdefault(scene, f"C{len(colours)}")
        style = "--" if version == "after" else "-"
        for ax, col in zip(axes, (1, 2)):
            ax.loglog([p[col] for p in pts], [100 * p[3] for p in pts], style, marker="o", color=colour,
                      label=f"{scene} ({version})")
        for p in pts:
            print(f"{version} {scene} {p[0]} {p[1]:.1f} {p[2]:.1f} {100 * p[3]:.2f}%")
    for ax, what in zip(axes, ("wall time, s (2 cores, shared)", "CPU time (user + system), s")):
        ax.set_xlabel(what)
        ax.set_ylabel("per-pixel noise, median over lit frames (%)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    if len(sys.argv) == 4:
        fig.suptitle(sys.argv[3], fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
