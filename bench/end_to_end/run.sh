#!/usr/bin/env bash
# End-to-end cost of frames: the real program at the demo's settings (the built-in Cornell box,
# 256x256, 64 passes x 100 000 photons) writing an .mp4 and --exr-dir, for F = 1, 48 and 192
# frames, interleaved round by round so that machine noise hits every F alike. Prints per F the
# median wall and CPU (user + sys) seconds and their ratio to F = 1.
#
#   bash bench/end_to_end/run.sh                       # uses build/slowlight, 3 rounds
#   ROUNDS=5 SLOWLIGHT=other/slowlight bash bench/end_to_end/run.sh
#   EXTRA="--passes 16" bash bench/end_to_end/run.sh   # any other render options
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${SLOWLIGHT:-$root/build/slowlight}
rounds=${ROUNDS:-3}
frames_list=${FRAMES:-"1 48 192"}
read -r -a extra <<<"${EXTRA:-}"
[[ $bin = /* ]] || bin=$PWD/$bin
[[ -x $bin ]] || { echo "run.sh: no program at $bin" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl_bench_e2e.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

for ((r = 1; r <= rounds; r++)); do
  for f in $frames_list; do
    rm -rf "$tmp/exr" "$tmp/v.mp4"
    /usr/bin/time -f "$f %e %U %S" -a -o "$tmp/times" \
      "$bin" render --frames "$f" -o "$tmp/v.mp4" --exr-dir "$tmp/exr" "${extra[@]}" 2>/dev/null
  done
done

python3 - "$tmp/times" <<'PY'
import sys, statistics
rows = {}
for line in open(sys.argv[1]):
    f, wall, user, sys_ = line.split()
    rows.setdefault(int(f), []).append((float(wall), float(user) + float(sys_)))
base_w = statistics.median(w for w, _ in rows[min(rows)])
base_c = statistics.median(c for _, c in rows[min(rows)])
print(f"{'frames':>6} {'wall s':>8} {'vs F=1':>7} {'cpu s':>8} {'vs F=1':>7}   (medians of {len(rows[min(rows)])} rounds)")
for f in sorted(rows):
    w = statistics.median(x for x, _ in rows[f]); c = statistics.median(x for _, x in rows[f])
    print(f"{f:>6} {w:>8.2f} {w / base_w:>7.3f} {c:>8.2f} {c / base_c:>7.3f}")
PY
