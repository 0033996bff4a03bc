#!/usr/bin/env bash
# What the Python module adds to a render against the command line, same scene and flags:
# whole-process wall time and peak RSS (/usr/bin/time), the program (--stats only: frames are
# assembled, nothing written) alternated with the module (render(): every frame kept in one
# array; frames(): the streaming loop), ROUNDS rounds, then a 1080p x 1000-frame render within
# --max-memory 2G by the program and by the streaming loop.
#   bash bench/python/run.sh [ROUNDS]     (from the checkout, after a build)
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-5}
out=${OUT:-/tmp/slowlight_bench_python}
mkdir -p "$out"
export PYTHONPATH=$PWD/build/python
py=/usr/bin/python3
scene=samples/cornell_box.json
small=(--width 256 --height 256 --frames 48 --passes 8 --photons 100000 --seed 1)
measure() {  # name, command...: appends "name seconds KiB" to $out/times.txt
  local name=$1; shift
  /usr/bin/time -f "$name %e %M" -o "$out/one.txt" "$@" > /dev/null 2>&1
  cat "$out/one.txt" >> "$out/times.txt"
}
: > "$out/times.txt"
for ((r = 1; r <= rounds; r++)); do
  measure cli ./build/slowlight render "$scene" "${small[@]}" --stats "$out/st.json" --no-progress
  measure render $py bench/python/module_run.py render "$scene" "${small[@]}"
  measure frames $py bench/python/module_run.py frames "$scene" "${small[@]}"
  measure import $py -c "import slowlight"
done
big=(--width 1920 --height 1080 --frames 1000 --passes 1 --photons 20000 --seed 1 --max-memory 2G)
measure big_cli ./build/slowlight render "$scene" "${big[@]}" --stats "$out/big.json" --no-progress
measure big_frames $py bench/python/module_run.py frames "$scene" "${big[@]}"
# Per kind: median seconds and peak KiB; the ratios to the program are per round (geometric mean).
$py - "$out/times.txt" <<'PY'
import collections, math, statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
by = collections.defaultdict(list)
for name, s, kib in rows:
    by[name].append((float(s), int(kib)))
for name, v in by.items():
    print(f"{name:10s} runs {len(v)}  median {statistics.median(s for s, _ in v):7.2f} s  "
          f"peak RSS median {statistics.median(k for _, k in v) / 1024:8.1f} MiB  max {max(k for _, k in v) / 1024:8.1f} MiB")
for name in ("render", "frames"):
    if name in by:
        t = [a[0] / b[0] for a, b in zip(by[name], by["cli"])]
        m = [a[1] / b[1] for a, b in zip(by[name], by["cli"])]
        g = lambda x: math.exp(sum(map(math.log, x)) / len(x))
        print(f"{name} / cli: time {g(t):.3f} ({min(t):.3f}-{max(t):.3f}), peak RSS {g(m):.3f} ({min(m):.3f}-{max(m):.3f})")
if "big_frames" in by:
    (tc, mc), (tf, mf) = by["big_cli"][0], by["big_frames"][0]
    print(f"1080p x 1000: frames / cli: time {tf / tc:.3f}, peak RSS {mf / mc:.3f} ({mf / 1024:.0f} / {mc / 1024:.0f} MiB)")
PY
