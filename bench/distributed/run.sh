#!/usr/bin/env bash
# Two MPI ranks of one thread against one process of two threads, the same render, on this
# machine: A (1 rank x 2 threads) and B (2 ranks x 1 thread) run alternately, ROUNDS times each,
# and the ratio of their median wall times is the parallel efficiency of the ranks relative to
# threads (1.0: as fast). Also prints the ratio of the CPU time the two used (user + system, all
# processes, mpirun's included: on a busy machine, where wall times follow the share of the cores
# each run gets, this is the steadier figure) and the bytes the ranks exchanged per pass and frame.
# A third run, M (`mpirun -np 1` of 2 threads: one rank under the launcher), separates what the
# launcher and MPI's start and end cost once per job from what dividing the work costs: A / B is
# the figure to judge, M / B the ranks' efficiency against a rank of threads.
#   bash bench/distributed/run.sh [ROUNDS] [extra render options...]
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-5}; shift || true
bin=./build/slowlight
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
# A rank waiting in a collective yields its core instead of spinning: this machine is shared.
export OMPI_MCA_mpi_yield_when_idle=1
# One machine, shared memory: the ob1 layer, without the UCX probe (no such devices here), which
# costs each rank about 0.3 s of MPI_Init. On an InfiniBand cluster UCX is the right choice.
# SLOWLIGHT_BENCH_UCX=1 keeps Open MPI's default, to measure the probe itself.
if [[ "${SLOWLIGHT_BENCH_UCX:-0}" != 1 ]]; then export OMPI_MCA_pml=ob1 OMPI_MCA_osc=^ucx; fi
render=(render samples/cornell_box.json --width 192 --height 192 --frames 48 --passes 24 --photons 200000
        --no-progress --exr-dir "$out/exr" "$@")
# Prints "wall cpu" (seconds) of one run.
timed() {
  /usr/bin/time -f "%e %U %S" -o "$out/t" "$@" >/dev/null 2>"$out/err" || { cat "$out/err" >&2; exit 1; }
  awk '{ printf "%s %.2f\n", $1, $2 + $3 }' "$out/t"
}
a=(); b=(); m=(); ca=(); cb=(); cm=()
for ((i = 0; i < rounds; ++i)); do
  read -r w c < <(timed "$bin" "${render[@]}" --threads 2 --stats "$out/a.json"); a+=("$w"); ca+=("$c")
  read -r w c < <(timed mpirun -np 2 --bind-to none "$bin" "${render[@]}" --threads 1 --stats "$out/b.json"); b+=("$w"); cb+=("$c")
  read -r w c < <(timed mpirun -np 1 --bind-to none "$bin" "${render[@]}" --threads 2); m+=("$w"); cm+=("$c")
  echo "round $((i + 1)): 1 rank x 2 threads ${a[-1]} s (CPU ${ca[-1]} s), 2 ranks x 1 thread ${b[-1]} s (CPU ${cb[-1]} s)," \
       "mpirun -np 1 x 2 threads ${m[-1]} s (CPU ${cm[-1]} s)" >&2
done
python3 - "$out/b.json" "${a[*]}" "${b[*]}" "${ca[*]}" "${cb[*]}" "${m[*]}" "${cm[*]}" <<'PY'
import json, statistics, sys
s = json.load(open(sys.argv[1]))
a = [float(x) for x in sys.argv[2].split()]
b = [float(x) for x in sys.argv[3].split()]
ca = [float(x) for x in sys.argv[4].split()]
cb = [float(x) for x in sys.argv[5].split()]
m = [float(x) for x in sys.argv[6].split()]
cm = [float(x) for x in sys.argv[7].split()]
ma, mb = statistics.median(a), statistics.median(b)
e = s["exchanged_bytes"]
frames = s["frames"] + 1  # and steady.exr
print(f"1 rank x 2 threads: median {ma:.2f} s of {a}")
print(f"2 ranks x 1 thread: median {mb:.2f} s of {b}")
print(f"efficiency (A / B): {ma / mb:.3f}")
print(f"CPU seconds: A median {statistics.median(ca):.2f} of {ca}, B median {statistics.median(cb):.2f} of {cb};"
      f" A / B {statistics.median(ca) / statistics.median(cb):.3f}")
mm = statistics.median(m)
print(f"M, one rank under mpirun x 2 threads: median {mm:.2f} s of {m} (CPU {statistics.median(cm):.2f});"
      f" the launcher and MPI's start and end cost {mm - ma:+.2f} s; M / B {mm / mb:.3f}")
print(f"per pass, rank 0 received {e['passes_received'] / e['passes'] / 2**20:.2f} MiB and sent {e['passes_sent'] / e['passes'] / 2**20:.2f} MiB"
      f" ({e['passes']} passes); per frame it received {e['frames_received'] / frames / 2**10:.1f} KiB")
PY
