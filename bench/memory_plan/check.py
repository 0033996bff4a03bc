#!/usr/bin/env python3
"""The memory plan against measured peaks: real renders at a few sizes and section counts K,
each run's peak RSS (--stats peak_rss_bytes, getrusage's ru_maxrss) against what the plan said
the whole process needs (fixed_overhead_bytes + the buffers in flight, from the same --stats).

    python3 bench/memory_plan/check.py                 # uses build/slowlight
    SLOWLIGHT=path/to/slowlight python3 bench/memory_plan/check.py
    python3 bench/memory_plan/check.py --quick         # the smaller cases only

Prints a table and exits 1 when any run's peak / plan is outside [1 - TOL, 1] (TOL = 0.10:
the plan must not be below the peak, since --max-memory promises the process stays within it,
and not more than 10 % above it)."""
import json, os, subprocess, sys, tempfile

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
binary = os.environ.get("SLOWLIGHT", os.path.join(root, "build", "slowlight"))
scene = os.path.join(root, "samples", "cornell_box.json")
TOL = 0.10

# (width, height, frames, passes, photons, K, output)
cases = [
    (512, 512, 192, 2, 50000, 1, "mp4"),
    (512, 512, 192, 2, 50000, 4, "mp4"),
    (512, 512, 192, 2, 50000, 8, "mp4"),
    (256, 256, 96, 2, 50000, 1, "mp4"),
    (256, 256, 96, 2, 50000, 4, "mp4"),
    (384, 384, 64, 2, 50000, 2, "mkv"),
    (384, 384, 64, 2, 50000, 2, "webm"),
    (256, 256, 96, 2, 50000, 2, "exr"),
]
if "--quick" in sys.argv:
    cases = [c for c in cases if c[0] <= 256]

print(f"{'size':>9} {'frames':>6} {'photons':>7} {'K':>2} {'out':>4} {'buffers MiB':>11} {'fixed MiB':>9} "
      f"{'plan MiB':>8} {'peak MiB':>8} {'peak/plan':>9}")
bad = 0
with tempfile.TemporaryDirectory(prefix="sl_memplan.") as tmp:
    for (w, h, frames, passes, photons, k, out) in cases:
        stats = os.path.join(tmp, "s.json")
        cmd = [binary, "render", scene, "--frames", str(frames), "--width", str(w), "--height", str(h),
               "--passes", str(passes), "--photons", str(photons), "--no-progress", "--sections", str(k),
               "--stats", stats]
        cmd += ["--exr-dir", os.path.join(tmp, "exr")] if out == "exr" else ["-o", os.path.join(tmp, "out." + out)]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        s = json.load(open(stats))
        in_flight = s["buffer_bytes_per_section"] * (2 if s["sections_overlap"] else 1)
        plan = s["fixed_overhead_bytes"] + in_flight
        peak = s["peak_rss_bytes"]
        ratio = peak / plan
        ok = 1 - TOL <= ratio <= 1.0
        bad += not ok
        mib = 1 << 20
        print(f"{w:>4}x{h:<4} {frames:>6} {photons:>7} {k:>2} {out:>4} {in_flight / mib:>11.1f} "
              f"{s['fixed_overhead_bytes'] / mib:>9.1f} {plan / mib:>8.1f} {peak / mib:>8.1f} {ratio:>9.3f}"
              + ("" if ok else "  <- outside"), flush=True)
sys.exit(1 if bad else 0)
