#!/usr/bin/env bash
# Is the suite flaky? Runs the whole test suite (each test once, as `setup.sh test` does) N times
# in a row while a second copy of the suite loops beside it for load, and stops at the first
# failing run. Usage: bash scripts/soak-tests.sh [N=30] [LOG=soak.log] (after a build).
set -uo pipefail
cd "$(dirname "$0")/.."
n=${1:-30}
log=${2:-soak.log}
[[ -x build/slowlight ]] || { echo "soak: build first (bash scripts/setup.sh build)" >&2; exit 2; }

# The load: the same suite, over and over, until the measured runs are done. Its own results are
# kept apart (a failure there is reported too: it is the same suite under the same load).
load_log=$log.load
: >"$load_log"
(
  while :; do
    ctest --test-dir build -j"$(nproc)" >>"$load_log" 2>&1 || echo "soak: the load copy failed a run" >>"$load_log"
  done
) &
load_pid=$!
trap 'pkill -P $load_pid 2>/dev/null; kill $load_pid 2>/dev/null' EXIT

: >"$log"
passed=0
for ((i = 1; i <= n; i++)); do
  start=$(date +%s)
  if ctest --test-dir build -j"$(nproc)" --output-on-failure >"$log.run" 2>&1; then
    passed=$((passed + 1))
    echo "soak: run $i/$n passed ($(tail -n 3 "$log.run" | grep -o '[0-9]* tests passed.*' | head -n1), $(( $(date +%s) - start )) s)" | tee -a "$log"
  else
    echo "soak: run $i/$n FAILED after $(( $(date +%s) - start )) s:" | tee -a "$log"
    grep -E "Failed|\*\*\*" "$log.run" | tee -a "$log"
    cat "$log.run" >>"$log"
    break
  fi
done
echo "soak: $passed of $n runs passed in a row; the load copy's failures: $(grep -c 'load copy failed' "$load_log")" | tee -a "$log"
[[ $passed -eq $n ]]
