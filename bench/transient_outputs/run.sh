#!/usr/bin/env bash
# What the files other tools read and the sensor images add to a render (docs/transient-outputs.md):
# the real program on the Cornell box, the same render with --exr-dir alone and then with each of
# --cube (our order), --cube --cube-layout mitransient, --hdf5, the sensor images (three phasor
# frequencies, a gate, first arrival), and all of them at once; runs interleaved, REPS times each.
# Prints per variant the median wall time, its ratio to the plain run's median, the median of
# the writers' stage time (--stats) and the peak resident memory (GNU time's %M).
#
#   bash bench/transient_outputs/run.sh
#
# Settings (environment, defaults in brackets): SLOWLIGHT [build/slowlight], WIDTH [256],
# HEIGHT [256], FRAMES [192], PASSES [8], PHOTONS [100000], REPS [3].
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${SLOWLIGHT:-$root/build/slowlight}
[[ $bin = /* ]] || bin=$PWD/$bin
reps=${REPS:-3}
common=(render "$root/samples/cornell_box.json" --width "${WIDTH:-256}" --height "${HEIGHT:-256}"
        --frames "${FRAMES:-192}" --passes "${PASSES:-8}" --photons "${PHOTONS:-100000}" --no-progress)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

declare -A extra=(
  [plain]=""
  [cube]="--cube o.npy"
  [cube_mitransient]="--cube o.npy --cube-layout mitransient"
  [hdf5]="--hdf5 o.h5"
  [sensors]="--phasor 20MHz,100MHz,300MHz --gate 6:3 --first-arrival"
  [all]="--cube o.npy --cube-layout mitransient --hdf5 o.h5 --phasor 20MHz,100MHz,300MHz --gate 6:3 --first-arrival"
)
order=(plain cube cube_mitransient hdf5 sensors all)
for ((r = 0; r < reps; r++)); do
  for v in "${order[@]}"; do
    rm -rf exr o.npy o.npy.json o.h5
    # shellcheck disable=SC2086
    /usr/bin/time -f "%e %M" -o time.txt "$bin" "${common[@]}" --exr-dir exr --stats stats.json ${extra[$v]}
    python3 - "$v" >>results.txt <<'PY'
import json, sys
wall, rss = open("time.txt").read().split()[-2:]
print(sys.argv[1], wall, rss, json.load(open("stats.json"))["stage_seconds"]["writers"])
PY
  done
done
python3 - "${order[@]}" <<'PY'
import statistics, sys
rows = [l.split() for l in open("results.txt")]
med = lambda v, i: statistics.median(float(r[i]) for r in rows if r[0] == v)
base = med("plain", 1)
print("%-18s %9s %7s %11s %10s" % ("variant", "wall (s)", "ratio", "writers (s)", "peak MiB"))
for v in sys.argv[1:]:
    print("%-18s %9.2f %7.2f %11.2f %10.0f" % (v, med(v, 1), med(v, 1) / base, med(v, 3), med(v, 2) / 1024))
PY
