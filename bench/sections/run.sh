#!/usr/bin/env bash
# Sections benchmark (issue 3): the real program, F = 192 frames at 512x512 of the Cornell box,
# once per K = 1, 2, 4, 8 (--sections K, --stats, -o a temporary .mp4), then with --max-bucket-memory at
# a few budgets. Prints two tables (and the stage times per K); the numbers come from each run's
# --stats JSON, parsed with python3's standard library.
#
#   bash bench/sections/run.sh                    # uses build/slowlight
#   SLOWLIGHT=build-pipe/slowlight bash bench/sections/run.sh
#
# Settings (environment, defaults in brackets): SLOWLIGHT [build/slowlight], SCENE
# [samples/cornell_box.json], FRAMES [192], WIDTH [512], HEIGHT [512], PASSES [8], PHOTONS [50000],
# THREADS [0 = all cores], KS ["1 2 4 8"], BUDGETS ["700M 400M 256M 160M 100M"].
# Modest passes and photons keep the whole script to a few minutes on 2 cores; the memory
# numbers do not depend on them (buffers scale with frames x pixels), the time ratios do (more
# passes make rendering, which K multiplies, a larger share of the time).
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${SLOWLIGHT:-$root/build/slowlight}
scene=${SCENE:-$root/samples/cornell_box.json}
frames=${FRAMES:-192}
width=${WIDTH:-512}
height=${HEIGHT:-512}
passes=${PASSES:-8}
photons=${PHOTONS:-50000}
threads=${THREADS:-0}
ks=${KS:-"1 2 4 8"}
budgets=${BUDGETS:-"700M 400M 256M 160M 100M"}

[[ $bin = /* ]] || bin=$PWD/$bin
if [[ ! -x $bin ]]; then
  echo "run.sh: no program at $bin (build it, or set SLOWLIGHT=path/to/slowlight)" >&2
  exit 1
fi
command -v python3 >/dev/null || { echo "run.sh: python3 is needed to read the stats" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl_bench_sections.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

common=(render "$scene" --frames "$frames" --width "$width" --height "$height"
        --passes "$passes" --photons "$photons" --threads "$threads" --no-progress)

echo "slowlight sections benchmark: $(basename "$scene"), $frames frames at ${width}x${height}," \
     "$passes passes x $photons photons, $(nproc) cores, $("$bin" --version)"
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg) (other work on the machine inflates the times)"
echo "command per K: $bin ${common[*]} --sections K --stats K.json -o K.mp4"
echo

# `slowlight info` with the same overrides: what it promises (buffers per K, fixed overhead).
"$bin" info "$scene" --frames "$frames" --width "$width" --height "$height" \
  --passes "$passes" --photons "$photons" > "$tmp/info.txt"
sed -n '/^memory:/,$p' "$tmp/info.txt"
echo

run() {  # run NAME ARGS...: one render, its stats in $tmp/NAME.json, its stderr in $tmp/NAME.log
  local name=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  # GNU time, where present, adds CPU seconds (less disturbed than wall time by other work on a
  # shared machine) and the kernel's max RSS as a cross-check of the stats' peak_rss_bytes.
  local timer=()
  [[ -x /usr/bin/time ]] && timer=(/usr/bin/time -f "%e %U %S %M" -o "$tmp/$name.time")
  if ! "${timer[@]}" "$bin" "${common[@]}" "$@" --stats "$tmp/$name.json" -o "$tmp/$name.mp4" 2> "$tmp/$name.log"; then
    echo "run.sh: run $name failed:" >&2
    cat "$tmp/$name.log" >&2
    exit 1
  fi
  t1=$(date +%s.%N)
  echo "  $name done in $(python3 -c "print(f'{$t1 - $t0:.1f}')") s" >&2
}

for k in $ks; do run "k$k" --sections "$k"; done
for b in $budgets; do run "mem_$b" --max-bucket-memory "$b"; done

python3 - "$tmp" "$ks" "$budgets" <<'EOF'
import json, sys

tmp, ks, budgets = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
MiB = 1024 * 1024

def load(name):
    with open(f"{tmp}/{name}.json") as f:
        s = json.load(f)
    try:  # GNU time: elapsed, user, system seconds, max RSS KiB
        with open(f"{tmp}/{name}.time") as f:
            e, u, sy, m = f.read().split()[-4:]
        s["cpu_seconds"] = float(u) + float(sy)
        s["time_max_rss_bytes"] = int(m) * 1024
    except (OSError, ValueError):
        s["cpu_seconds"] = float("nan")
        s["time_max_rss_bytes"] = 0
    return s

def parse_size(text):  # as --max-bucket-memory reads it: K, M, G, T are powers of 1024
    units = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}
    t = text.upper().removesuffix("IB").removesuffix("B")
    u = t[-1] if t and t[-1] in "KMGT" else ""
    return int(float(t[: len(t) - len(u)]) * units[u])

runs = {k: load(f"k{k}") for k in ks}
base = runs[ks[0]]
print(f"Table 1: sections (ratios against K = {ks[0]})")
print(f"{'K':>3} {'sections':>8} {'wall s':>8} {'CPU s':>7} {'peak RSS MiB':>13} {'buffers/section MiB':>20} "
      f"{'overlap':>7} {'RSS-buffers MiB':>15} {'RSS ratio':>9} {'time ratio':>10} {'CPU ratio':>9}")
for k in ks:
    s = runs[k]
    in_flight = s["buffer_bytes_per_section"] * (2 if s.get("sections_overlap") else 1)
    print(f"{k:>3} {s['sections']:>8} {s['wall_seconds']:>8.2f} {s['cpu_seconds']:>7.1f} "
          f"{s['peak_rss_bytes'] / MiB:>13.1f} "
          f"{s['buffer_bytes_per_section'] / MiB:>20.1f} {str(s.get('sections_overlap', '-')):>7} "
          f"{(s['peak_rss_bytes'] - in_flight) / MiB:>15.1f} "
          f"{s['peak_rss_bytes'] / base['peak_rss_bytes']:>9.3f} {s['wall_seconds'] / base['wall_seconds']:>10.3f} "
          f"{s['cpu_seconds'] / base['cpu_seconds']:>9.3f}")
print("(RSS-buffers: peak RSS minus the buffers alive at once, i.e. two sections' with overlap;")
print(" CPU s: user + system seconds from GNU time; its max RSS agrees with peak RSS: "
      + ", ".join(f"K={k} {runs[k]['time_max_rss_bytes'] / MiB:.1f}" for k in ks) + " MiB)")
print()

stages = list(base["stage_seconds"].keys())
print("Stage seconds per K (stages overlap in time, so they need not add up to wall)")
print(f"{'K':>3} " + " ".join(f"{st:>19}" for st in stages) + f" {'photons traced':>15} {'rays traced':>12}")
for k in ks:
    s = runs[k]
    print(f"{k:>3} " + " ".join(f"{s['stage_seconds'].get(st, 0):>19.2f}" for st in stages)
          + f" {s['photons_traced']:>15} {s['rays_traced']:>12}")
print()

if budgets:
    print("Table 2: --max-bucket-memory (limit = budget + fixed overhead that info/stats state)")
    print(f"{'budget':>7} {'K chosen':>8} {'buffers/section MiB':>20} {'overlap':>7} {'in flight MiB':>13} "
          f"{'fixed MiB':>9} {'limit MiB':>9} {'peak RSS MiB':>12} {'wall s':>7} {'within':>6}")
    all_within = True
    for b in budgets:
        s = load(f"mem_{b}")
        budget = parse_size(b)
        fixed = s["fixed_overhead_bytes"]
        in_flight = s["buffer_bytes_per_section"] * (2 if s.get("sections_overlap") else 1)
        limit = budget + fixed
        ok = s["peak_rss_bytes"] <= limit
        all_within &= ok and in_flight <= budget
        print(f"{b:>7} {s['sections']:>8} {s['buffer_bytes_per_section'] / MiB:>20.1f} "
              f"{str(s.get('sections_overlap', '-')):>7} {in_flight / MiB:>13.1f} {fixed / MiB:>9.1f} "
              f"{limit / MiB:>9.1f} {s['peak_rss_bytes'] / MiB:>12.1f} {s['wall_seconds']:>7.2f} {'yes' if ok else 'NO':>6}")
    print()

if "1" in runs and "4" in runs:
    r = runs["4"]["peak_rss_bytes"] / runs["1"]["peak_rss_bytes"]
    t = runs["4"]["wall_seconds"] / runs["1"]["wall_seconds"]
    print(f"target peak RSS K=4 <= 0.35 x K=1: {r:.3f} -> {'met' if r <= 0.35 else 'NOT met'}")
    c = runs["4"]["cpu_seconds"] / runs["1"]["cpu_seconds"]
    print(f"target wall time K=4 <= 3 x K=1:   {t:.3f} -> {'met' if t <= 3 else 'NOT met'} (CPU time ratio {c:.3f})")
if budgets:
    print(f"target peak RSS <= --max-bucket-memory + fixed overhead at every budget: {'met' if all_within else 'NOT met'}")
EOF
